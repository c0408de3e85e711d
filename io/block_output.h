#pragma once
/// Files of the `blocks` stage: blocks.csv, blocks.vtu and summary.json.
#include <string>
#include <vector>

#include "blocks/block_model.h"
#include "geometry/fracture_network.h"
#include "io/scene.h"
#include "io/summary.h"

namespace rockmass::io {

/// blocks.csv: id,volume,cx,cy,cz,material,pieces (the shared contract), then
/// xmin,ymin,zmin,xmax,ymax,zmax (bounding box, m). material is the material's name.
std::string formatBlocksCsv(const blocks::BlockModel& model,
                            const std::vector<Material>& materials);

/// blocks.vtu: one VTK polyhedron cell (type 42) per convex piece, with cell data id (block
/// id), material (index), volume (the block's, m3) and piece_volume (m3). A block is the set
/// of cells with its id (threshold on `id` in ParaView).
std::string formatBlocksVtu(const blocks::BlockModel& model);

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
