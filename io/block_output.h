#pragma once
/// Files of the `blocks` stage: blocks.csv, blocks.vtu and summary.json.
#include <functional>
#include <string>
#include <vector>

#include "blocks/block_model.h"
#include "geometry/fracture_network.h"
#include "io/scene.h"
#include "io/summary.h"

namespace rockmass::io {

/// blocks.csv: id,volume,cx,cy,cz,material,pieces (the shared contract), then
/// xmin,ymin,zmin,xmax,ymax,zmax (bounding box, m) and structure (the name of the structure
/// the block belongs to, from `structure_names`; empty for a rock block). material is the
/// material's name.
std::string formatBlocksCsv(const blocks::BlockModel& model, const std::vector<Material>& materials,
                            const std::vector<std::string>& structure_names = {});

/// blocks.vtu: one VTK polyhedron cell (type 42) per convex piece, with cell data id (block
/// id), material (index), volume (the block's, m3) and piece_volume (m3). A block is the set
/// of cells with its id (threshold on `id` in ParaView).
std::string formatBlocksVtu(const blocks::BlockModel& model);

/// faces.vtu: one VTK polygon cell (type 7) per piece face that is not fictitious (internal
/// cuts between pieces of one block are left out), CCW seen from outside the piece, with
/// Int32 cell data block (block id), piece (index in the block), kind (0 disc, 1 domain
/// boundary, 2 structure), source (disc id, boundary face id, structure index) and joint
/// (index into Scene::joints as `joint_of` gives it, -1 none; scene_model::FaceJoints).
std::string formatFacesVtu(const blocks::BlockModel& model,
                           const std::function<int(const blocks::FaceSource&)>& joint_of);

/// What the blocks summary says about the cut itself.
struct CutInfo {
  std::string cutter;             ///< "fast" or "exact"
  int disc_segments = 24;         ///< polygon points per ellipse
  long long pieces = 0;           ///< convex pieces
  int inconsistent_contacts = 0;  ///< fast cutter diagnostic (0 in a sound cut)
};

/// summary.json of the blocks stage: discs and cutting discs, block count, total and domain
/// volume, volume_stats {min, max, mean}, weibull {shape, scale} (null when the volumes
/// cannot be fitted: fewer than 2 blocks or all equal), pieces, adjacency count, per-material
/// block counts and volumes, the cut settings, then the timings.
std::string formatBlocksSummary(const RunInfo& run, const geometry::FractureNetwork& network,
                                const blocks::BlockModel& model, const CutInfo& cut,
                                const std::vector<Material>& materials);

}  // namespace rockmass::io
