#pragma once
/// From a scene and its blocks to the DDA model: materials, joints and the joint of every
/// piece face, gravity, the blocks held by `supports.fixed`, and the block each monitor is attached
/// to. Lives in io because it reads the scene; dda3d knows nothing of scenes.
#include <string>
#include <vector>

#include "blocks/block_model.h"
#include "dda3d/model.h"
#include "geometry/fracture_network.h"
#include "io/scene.h"
#include "io/summary.h"

namespace rockmass::scene_model {

/// Distances below this fraction of the domain diagonal count as contact: a point on a block
/// face, a block face on a domain face. Loose enough for the cutters' snapping, far below
/// any block size that matters.
constexpr double kSceneModelRelativeTolerance = 1e-6;

/// The joint (index into Scene::joints) of the piece faces of a scene's blocks, by what made
/// them (blocks::Piece::face_sources): a disc face takes its disc's joint
/// (geometry::Disc::joint: its joint set's, fault's, interlayer's or FAB file's `joint`), a
/// structure face its structure's `joint`; domain-boundary and fictitious (internal) faces
/// carry none (-1), nor do discs or structures without a joint (no default_joint).
class FaceJoints {
 public:
  /// `network`: the discs the blocks were cut with (ids 1..N).
  FaceJoints(const io::Scene& scene, const geometry::FractureNetwork& network);

  /// The joint of a face made by `source`, or -1. Throws std::invalid_argument for a disc id
  /// or structure index that the network or scene does not have.
  int of(const blocks::FaceSource& source) const;

  /// One list per piece of `block`, one joint per face (a face without a source: -1).
  std::vector<std::vector<int>> of(const blocks::Block& block) const;

 private:
  std::vector<int> disc_joints_;       ///< by disc id (entry 0 unused)
  std::vector<int> structure_joints_;  ///< by structure index
};

/// The DDA model of `blocks` (cut from `scene` with the discs of `network`); block i of the
/// model is blocks.blocks[i].
/// - materials: density, Young's modulus, Poisson's ratio, in scene order;
/// - joints: the scene's joints (friction, cohesion, tensile strength, model), default_joint;
///   every piece face gets the joint of what made it (FaceJoints, DdaBlock::face_joints),
///   and the engine gives each contact the joint of the faces it lies on
///   (dda3d/contact_joint.h);
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
dda3d::DdaModel buildDdaModel(const io::Scene& scene, const blocks::BlockModel& blocks,
                              const geometry::FractureNetwork& network);

/// The uplift on each structure of the scene: the resultant of the uplift and pore pressures
/// on its faces (DdaPressure::uplift) as the model starts. Empty when there are none.
std::vector<io::StructureUplift> structureUplift(const io::Scene& scene,
                                                 const dda3d::DdaModel& model);

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

}  // namespace rockmass::scene_model
