// Parts the scene -> DDA model adapters share (scene_model/dda_model.cpp, water.cpp):
// geometry of piece faces against the domain and the structures, and the water of a model.
// Internal to the scene_model module.
#pragma once

#include <string>
#include <vector>

#include "blocks/block_model.h"
#include "dda3d/model.h"
#include "io/scene.h"

namespace rockmass::scene_model::parts {

/// A face of the domain box: the axis it is normal to, which end, and its box face id
/// (blocks::FaceKind::Boundary ids 0..5: x_min, x_max, y_min, y_max, z_min, z_max).
struct DomainFace {
  int axis = 0;
  bool max_side = false;
  int box_id = 0;
};

/// The domain face called `name` (bottom, top, west, east, south, north).
DomainFace domainFace(const std::string& name);

/// Absolute tolerance (m) for a domain (kSceneModelRelativeTolerance of its diagonal).
double tolerance(const blocks::BlockModel& blocks);

/// True when face `f` of `piece` lies in the plane of `face` and faces outward.
bool liesOnDomainFace(const blocks::Piece& piece, int f, const DomainFace& face,
                      const geometry::Box& domain, double tol);

/// "(x, y, z)" for messages.
std::string pointText(const geometry::Vec3& p);

/// Mean of the face's vertices (m).
geometry::Vec3 faceCenter(const geometry::Polyhedron& shape, int f);

/// True when face `f` of piece `p` is glued to another piece of the same block (its centre
/// lies on that piece): an internal face, never wet.
bool internalFace(const blocks::Block& block, std::size_t p, int f, double tol);

/// True when the point's plan position lies in the region (open bounds ignored).
bool inRegion(const io::Region& region, const geometry::Vec3& p);

/// Index of the structure named `name` (the scene reader has checked that it exists).
int structureIndex(const io::Scene& scene, const std::string& name);

/// Index of the structure a block belongs to, or -1 for a rock block.
int structureOf(const blocks::Block& block);

/// Block indices by owner (structureOf): members[0] the rock blocks, members[s + 1] those of
/// structure s.
using Members = std::vector<std::vector<int>>;

/// True when `point` lies inside a block of `owner` (structure index, or -1 for rock): inside
/// one of its pieces by more than `depth` m, or on a face between two of its pieces.
bool insideOwnedBy(const blocks::BlockModel& blocks, const Members& members, int owner,
                   const geometry::Vec3& point, double depth);

/// True when the body of `owner` lies behind face `f` of `shape`: one of the face's centre
/// and the points halfway from it to each vertex, moved `probe` m outward, lies inside a
/// piece of `owner` by more than probe / 2. (One point alone misses a face whose centre
/// sits over a joint of the body behind it.)
bool backsOnto(const blocks::BlockModel& blocks, const Members& members, int owner,
               const geometry::Polyhedron& shape, int f, double probe);

/// The water of the scene on the model's pieces (water.cpp): loads.water on exposed faces and
/// in the structure-rock interface, loads.pore_pressure in the discontinuities, and
/// Westergaard's added pressure of loads.seismic. `owner`: structureOf per block.
void addWater(const io::Scene& scene, const blocks::BlockModel& blocks,
              const std::vector<int>& owner, const Members& members, dda3d::DdaModel& model);

}  // namespace rockmass::scene_model::parts
