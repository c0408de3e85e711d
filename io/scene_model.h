#pragma once
/// From a scene and its blocks to the DDA model: materials, the joint of every material
/// pair, gravity, the blocks held by `supports.fixed`, and the block each monitor is attached
/// to. Lives in io because it reads the scene; dda3d knows nothing of scenes.
#include <string>
#include <vector>

#include "blocks/block_model.h"
#include "dda3d/model.h"
#include "io/scene.h"

namespace rockmass::io {

/// Distances below this fraction of the domain diagonal count as contact: a point on a block
/// face, a block face on a domain face. Loose enough for the cutters' snapping, far below
/// any block size that matters.
constexpr double kSceneModelRelativeTolerance = 1e-6;

/// The DDA model of `blocks` (cut from `scene`); block i of the model is blocks.blocks[i].
/// - materials: density, Young's modulus, Poisson's ratio, in scene order;
/// - joints: the scene's joints; the joint of a contact between materials a and b is
///   default_joint, except between a fault/interlayer slab material and the rock material
///   (the slab's joint) and between a structure's material and any non-structure material
///   (the structure's joint, e.g. the dam-rock contact);
/// - gravity: loads.gravity, or none at all (no body force term) when absent;
/// - fixed: the blocks touching a face named in supports.fixed (blocksOnDomainFaces);
/// - monitors: each attached to the block that contains its point (findContainingBlock);
/// - point loads: each acting on the block that contains its point;
/// - water: one DdaPressure (level, unit weight) per wetted outer piece face that reaches
///   below the level: faces on the domain top (`domain_top`) not covered by a structure, or
///   faces of the named structure whose outward normal n has n . facing > 0; with `uplift`,
///   also both sides of that structure's (domain_top: every structure's) interface with the
///   rock (DdaPressure::uplift, not restricted by `region`): the
///   structure's faces whose far side lies in a rock block and the rock's faces whose far
///   side lies in the structure, at the full hydrostatic head; `region` selects faces by the
///   plan position of their centre; faces glued to another piece of the same block are
///   internal and stay dry. The engine clips each face at the water line.
/// Throws InputError naming the scene file (and the monitor's line) when a monitor or point
/// load lies in no block, a block has no material, or the scene gives no default_joint.
dda3d::DdaModel buildDdaModel(const Scene& scene, const blocks::BlockModel& blocks);

/// Index into blocks.blocks of the block with a piece containing `point` (within
/// kSceneModelRelativeTolerance of the domain diagonal); when several do (a point on a
/// joint), the one it lies deepest in, then the lowest index. -1 when none.
int findContainingBlock(const blocks::BlockModel& blocks, const geometry::Vec3& point);

/// Per block of `blocks`, whether it touches one of the domain faces named in `faces`
/// (bottom, top, west, east, south, north: z min, z max, x min, x max, y min, y max of the
/// domain box). A block touches a face when one of its piece faces came from it (FaceKind::
/// Boundary with that box face id; box domains only, `box_domain`) or lies in its plane
/// (every vertex within the tolerance, outward normal along the face's), and that piece face
/// overlaps the domain face's rectangle (within the box bounds) with positive area: a block
/// meeting the face along an edge or at a vertex only, or lying in its plane outside the
/// box (a dam standing on the top, its sides in the planes of the side faces), is not held.
std::vector<bool> blocksOnDomainFaces(const blocks::BlockModel& blocks,
                                      const std::vector<std::string>& faces, bool box_domain);

}  // namespace rockmass::io
