// Scene + blocks -> DDA model: materials, joints and the joint of every piece face, gravity present
// or absent, supports.fixed by face provenance or by geometry, monitors located by
// point-in-convex-polyhedron, and the errors a user can cause. Blocks are hand-built boxes.
#include "scene_model/dda_model.h"

#include <gtest/gtest.h>

#include <string>

#include "io/input_error.h"

namespace rockmass::scene_model {
using namespace io;  // NOLINT: the scene's types
namespace {

using geometry::Box;
using geometry::Vec3;

/// A block made of one box piece; faces on the domain box boundary are tagged Boundary with
/// the box face id (what the cutters do), the others Disc 1.
blocks::Block boxBlock(int id, const Box& box, const Box& domain, int material = 0) {
  blocks::Piece piece;
  piece.shape = geometry::boxPolyhedron(box);
  for (int f = 0; f < 6; ++f) {
    const int axis = f / 2;
    const bool max_side = f % 2 == 1;
    const double at = max_side ? box.max[axis] : box.min[axis];
    const double bound = max_side ? domain.max[axis] : domain.min[axis];
    piece.face_sources.push_back(at == bound ? blocks::FaceSource{blocks::FaceKind::Boundary, f}
                                             : blocks::FaceSource{blocks::FaceKind::Disc, 1});
  }
  blocks::Block block;
  block.id = id;
  block.material = material;
  block.mass = geometry::massProperties(piece.shape);
  block.bounds = box;
  block.pieces.push_back(piece);
  return block;
}

/// The domain [0, 2] x [0, 1] x [0, 2] cut into four unit-wide columns of blocks:
/// block 1 (x < 1, z < 1), 2 (x > 1, z < 1), 3 (x < 1, z > 1), 4 (x > 1, z > 1, soft).
blocks::BlockModel fourBlocks() {
  blocks::BlockModel model;
  model.domain = Box{{0, 0, 0}, {2, 1, 2}};
  model.domain_volume = 4.0;
  model.blocks.push_back(boxBlock(1, {{0, 0, 0}, {1, 1, 1}}, model.domain));
  model.blocks.push_back(boxBlock(2, {{1, 0, 0}, {2, 1, 1}}, model.domain));
  model.blocks.push_back(boxBlock(3, {{0, 0, 1}, {1, 1, 2}}, model.domain));
  model.blocks.push_back(boxBlock(4, {{1, 0, 1}, {2, 1, 2}}, model.domain, 1));
  return model;
}

/// The network the blocks above were cut with: disc 1 (their inner faces), of joint 1
/// (`weak` in scene() below).
geometry::FractureNetwork discOne() {
  geometry::FractureNetwork network;
  geometry::Disc disc;
  disc.id = 1;
  disc.joint = 1;
  network.discs.push_back(disc);
  return network;
}

/// A scene over that domain; `extra` adds top-level keys.
Scene scene(const std::string& extra) {
  return parseScene(
      "version: 1\n"
      "domain: {box: {min: [0, 0, 0], max: [2, 1, 2]}}\n"
      "materials:\n"
      "  rock: {density: 2600, young: 10.0e9, poisson: 0.25}\n"
      "  soft: {unit_weight: 20.0e3, young: 0.75e9, poisson: 0.4}\n"
      "  concrete: {density: 2446.5, young: 17.6e9, poisson: 0.167}\n"
      "rock_material: rock\n"
      "joints: {rock_joint: {friction: 0.86, cohesion: 0.8e6}, weak: {friction: 0.35}}\n"
      "default_joint: rock_joint\n" +
          extra,
      "tiny.yaml");
}

TEST(SceneModel, MaterialsJointsAndGravity) {
  const dda3d::DdaModel model = buildDdaModel(
      scene("loads: {gravity: 9.81}\n"
            "interlayers:\n"
            "  - {name: P1, profile: [[0, 1], [2, 1]], sweep: y, thickness: 0.2, material: soft,"
            " joint: weak}\n"
            "structures:\n"
            "  - name: dam\n"
            "    prism: {profile: [[0, 2], [1, 2], [0, 3]], sweep: y, from: 0, to: 1}\n"
            "    material: concrete\n"
            "    joint: {friction: 1.2, cohesion: 1.4e6}\n"),
      fourBlocks(), discOne());
  ASSERT_EQ(model.materials.size(), 3u);
  EXPECT_EQ(model.materials[0].density, 2600.0);
  EXPECT_EQ(model.materials[1].young, 0.75e9);
  EXPECT_EQ(model.materials[2].poisson, 0.167);
  // unit_weight / 9.81 (the scene reader's conversion)
  EXPECT_DOUBLE_EQ(model.materials[1].density, 20.0e3 / 9.81);
  ASSERT_EQ(model.joints.size(), 3u);  // rock_joint, weak, then the dam's inline joint
  EXPECT_EQ(model.joints[model.default_joint].friction, 0.86);
  // Each piece face carries the joint of what made it: the inner faces (disc 1) the disc's
  // joint, the faces on the domain boundary none.
  const std::vector<std::vector<int>> block1 = {{-1, 1, -1, -1, -1, 1}};  // x max, z max inner
  EXPECT_EQ(model.blocks[0].face_joints, block1);
  const std::vector<std::vector<int>> block4 = {{1, -1, -1, -1, 1, -1}};  // x min, z min inner
  EXPECT_EQ(model.blocks[3].face_joints, block4);
  EXPECT_EQ(model.joints[2].cohesion, 1.4e6);
  EXPECT_EQ(model.gravity, Vec3(0, 0, -9.81));
  ASSERT_EQ(model.blocks.size(), 4u);
  EXPECT_EQ(model.blocks[3].material, 1);
  EXPECT_EQ(model.blocks[2].pieces[0].vertices.size(), 8u);
}

TEST(SceneModel, JointModelIsPassedOn) {
  // `model` of a joint reaches the engine's DdaJoint; plastic is the default.
  const Scene brittle = parseScene(
      "version: 1\n"
      "domain: {box: {min: [0, 0, 0], max: [2, 1, 2]}}\n"
      "materials: {rock: {density: 2600, young: 10.0e9, poisson: 0.25},"
      " soft: {density: 2000, young: 1.0e9, poisson: 0.4}}\n"
      "rock_material: rock\n"
      "joints: {rj: {friction: 0.86}, weak: {friction: 0.35, cohesion: 1e5, model: brittle}}\n"
      "default_joint: rj\n",
      "tiny.yaml");
  const dda3d::DdaModel model = buildDdaModel(brittle, fourBlocks(), discOne());
  ASSERT_EQ(model.joints.size(), 2u);
  EXPECT_EQ(model.joints[0].model, dda3d::JointModel::Plastic);
  EXPECT_EQ(model.joints[1].model, dda3d::JointModel::Brittle);
  EXPECT_EQ(model.joints[1].cohesion, 1e5);
}

TEST(SceneModel, NoGravityMeansNoBodyForce) {
  // Absent loads.gravity: zero vector, which the engine reads as "no body force term".
  EXPECT_EQ(buildDdaModel(scene(""), fourBlocks(), discOne()).gravity, Vec3::Zero());
  EXPECT_EQ(
      buildDdaModel(scene("loads: {gravity: [0.5, 0, -9.8]}\n"), fourBlocks(), discOne()).gravity,
      Vec3(0.5, 0, -9.8));
}

TEST(SceneModel, FixedFacesHoldTheBlocksTouchingThem) {
  const blocks::BlockModel blocks = fourBlocks();
  EXPECT_EQ(blocksOnDomainFaces(blocks, {"bottom"}, true),
            (std::vector<bool>{true, true, false, false}));
  EXPECT_EQ(blocksOnDomainFaces(blocks, {"west"}, true),
            (std::vector<bool>{true, false, true, false}));
  EXPECT_EQ(blocksOnDomainFaces(blocks, {"top", "east"}, true),
            (std::vector<bool>{false, true, true, true}));
  // Every block touches south and north (the domain is one block deep).
  EXPECT_EQ(blocksOnDomainFaces(blocks, {"south"}, true), std::vector<bool>(4, true));
  EXPECT_EQ(blocksOnDomainFaces(blocks, {}, true), std::vector<bool>(4, false));
  const dda3d::DdaModel model =
      buildDdaModel(scene("supports: {fixed: [bottom]}\n"), blocks, discOne());
  EXPECT_TRUE(model.blocks[0].fixed && model.blocks[1].fixed);
  EXPECT_FALSE(model.blocks[2].fixed || model.blocks[3].fixed);
}

TEST(SceneModel, RollerFacesHoldTheirBlocksNormalToTheFaceAtItsVertices) {
  // Bottom fixed, west on rollers: of the two west blocks only the upper one (2; the lower,
  // 0, is held by the bottom) gets rollers, one per vertex of its face on x = x_min (4
  // corners), all along the face's outward normal -x.
  const blocks::BlockModel blocks = fourBlocks();
  const dda3d::DdaModel model =
      buildDdaModel(scene("supports: {fixed: [bottom], rollers: [west]}\n"), blocks, discOne());
  ASSERT_EQ(model.fixed_points.size(), 4u);
  for (const dda3d::DdaFixedPoint& p : model.fixed_points) {
    EXPECT_EQ(p.block, 2);
    EXPECT_EQ(p.direction, geometry::Vec3(-1, 0, 0));
    EXPECT_DOUBLE_EQ(p.point.x(), blocks.domain.min.x());
  }
  EXPECT_FALSE(model.blocks[2].fixed);
}

TEST(SceneModel, FixedFacesByGeometryWithoutProvenance) {
  // A mesh domain (or a cutter that lost the tags): every face Fictitious; the block is still
  // held when a face lies in the bottom plane, within the tolerance (1e-6 of the diagonal
  // 3 m = 3e-6 m: 1e-7 m is inside it, 1e-4 m is not).
  blocks::BlockModel blocks = fourBlocks();
  for (blocks::Block& block : blocks.blocks) {
    for (blocks::Piece& piece : block.pieces) {
      for (blocks::FaceSource& s : piece.face_sources) s = {};
    }
  }
  blocks.blocks[0].pieces[0].shape.vertices[0].z() = 1e-7;
  blocks.blocks[1].pieces[0].shape.vertices[0].z() = 1e-4;
  EXPECT_EQ(blocksOnDomainFaces(blocks, {"bottom"}, false),
            (std::vector<bool>{true, false, false, false}));
}

TEST(SceneModel, AnEdgeOnTheFaceDoesNotHoldABlock) {
  // A tetrahedron standing on one edge on the bottom plane: its bounding box touches the
  // bottom, but none of its faces lies on it.
  blocks::BlockModel blocks = fourBlocks();
  blocks::Piece wedge;
  wedge.shape.vertices = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 1}, {0.5, 0, 1}};
  wedge.shape.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  wedge.face_sources.assign(4, {blocks::FaceKind::Disc, 1});
  ASSERT_GT(geometry::massProperties(wedge.shape).volume, 0.0) << "faces must point outward";
  blocks.blocks[0].pieces = {wedge};
  EXPECT_FALSE(blocksOnDomainFaces(blocks, {"bottom"}, true)[0]);
  EXPECT_TRUE(blocksOnDomainFaces(blocks, {"south"}, true)[0]);  // face {0, 1, 3} is at y = 0
}

TEST(SceneModel, AFaceInTheSidePlaneButAboveTheBoxDoesNotHold) {
  // A dam standing on the top (z 2..5) across the whole slice (y 0..1): its y = 0 face lies
  // in the south face's plane, and the cutter tags it Boundary 2, but at z in [2, 5] it is
  // outside the south face's rectangle (z in [0, 2]): it touches the rectangle along an
  // edge only (zero area), so south and north do not hold it. A block reaching 0.5 m into
  // the box (z 1.5..5) overlaps it with 1 x 0.5 m2 and is held.
  blocks::BlockModel blocks = fourBlocks();
  blocks.blocks.push_back(boxBlock(5, {{0.5, 0, 2}, {1.5, 1, 5}}, blocks.domain));
  blocks.blocks.push_back(boxBlock(6, {{0.5, 0, 1.5}, {1.5, 1, 5}}, blocks.domain));
  for (const std::size_t b : {std::size_t{4}, std::size_t{5}}) {
    blocks.blocks[b].pieces[0].face_sources[2] = {blocks::FaceKind::Boundary, 2};
    blocks.blocks[b].pieces[0].face_sources[3] = {blocks::FaceKind::Boundary, 3};
  }
  const std::vector<bool> held = blocksOnDomainFaces(blocks, {"south", "north"}, true);
  EXPECT_FALSE(held[4]);
  EXPECT_TRUE(held[5]);
  // By geometry alone (no provenance) the same.
  EXPECT_FALSE(blocksOnDomainFaces(blocks, {"south"}, false)[4]);
  EXPECT_TRUE(blocksOnDomainFaces(blocks, {"south"}, false)[5]);
}

TEST(SceneModel, MonitorsAttachToTheBlockThatContainsThem) {
  const blocks::BlockModel blocks = fourBlocks();
  EXPECT_EQ(findContainingBlock(blocks, Vec3(1.5, 0.5, 1.5)), 3);
  EXPECT_EQ(findContainingBlock(blocks, Vec3(0.25, 0.5, 0.75)), 0);
  // On the domain top: inside block 4's closed piece.
  EXPECT_EQ(findContainingBlock(blocks, Vec3(1.5, 0.5, 2.0)), 3);
  // On the joint between blocks 1 and 3 (z = 1), 1e-9 m into block 3: block 3 (deeper);
  // exactly on it: both are at depth 0, the lower index wins.
  EXPECT_EQ(findContainingBlock(blocks, Vec3(0.5, 0.5, 1.0 + 1e-9)), 2);
  EXPECT_EQ(findContainingBlock(blocks, Vec3(0.5, 0.5, 1.0)), 0);
  // Outside the domain by more than the tolerance.
  EXPECT_EQ(findContainingBlock(blocks, Vec3(0.5, 0.5, 2.001)), -1);

  const dda3d::DdaModel model =
      buildDdaModel(scene("monitors:\n  - {name: P4, point: [1.5, 0.5, 1.5]}\n"
                          "  - {name: toe, point: [0.1, 0.1, 0.1]}\n"),
                    blocks, discOne());
  ASSERT_EQ(model.monitors.size(), 2u);
  EXPECT_EQ(model.monitors[0].name, "P4");
  EXPECT_EQ(model.monitors[0].block, 3);
  EXPECT_EQ(model.monitors[1].block, 0);
  EXPECT_EQ(model.monitors[1].point, Vec3(0.1, 0.1, 0.1));
}

TEST(SceneModel, PointLoadsActOnTheBlockThatContainsThem) {
  const dda3d::DdaModel model = buildDdaModel(
      scene("loads:\n  point_loads:\n    - {point: [1.5, 0.5, 2], force: [0, 0, -1.0e6]}\n"
            "    - {point: [0.5, 0.5, 0.5], force: [10, 0, 0]}\n"),
      fourBlocks(), discOne());
  ASSERT_EQ(model.point_loads.size(), 2u);
  EXPECT_EQ(model.point_loads[0].block, 3);  // on the top face of block 4
  EXPECT_EQ(model.point_loads[0].force, Vec3(0, 0, -1.0e6));
  EXPECT_EQ(model.point_loads[1].block, 0);
  EXPECT_EQ(model.point_loads[1].point, Vec3(0.5, 0.5, 0.5));
}

TEST(SceneModel, WaterWetsTheDomainTopInItsRegion) {
  // Domain top z = 2 under a level of 3: the top faces (box face 5) of blocks 3 and 4; the
  // region x <= 1 keeps block 3's (centre x = 0.5) only. A level of 2 wets nothing (the faces
  // lie at the water line).
  const dda3d::DdaModel wet =
      buildDdaModel(scene("loads: {water: [{level: 3, unit_weight: 10000, on: {domain_top: true,"
                          " region: {x_max: 1}}}]}\n"),
                    fourBlocks(), discOne());
  ASSERT_EQ(wet.pressures.size(), 1u);
  EXPECT_EQ(wet.pressures[0].block, 2);
  EXPECT_EQ(wet.pressures[0].piece, 0);
  EXPECT_EQ(wet.pressures[0].face, 5);
  EXPECT_EQ(wet.pressures[0].level, 3.0);
  EXPECT_EQ(wet.pressures[0].unit_weight, 10000.0);
  EXPECT_EQ(buildDdaModel(scene("loads: {water: [{level: 3, on: {domain_top: true}}]}\n"),
                          fourBlocks(), discOne())
                .pressures.size(),
            2u);
  EXPECT_TRUE(buildDdaModel(scene("loads: {water: [{level: 2, on: {domain_top: true}}]}\n"),
                            fourBlocks(), discOne())
                  .pressures.empty());
}

TEST(SceneModel, WaterWetsTheStructureFacesThatFaceIt) {
  // A structure block of two glued box pieces, x in [0, 1] and [1, 2], standing on z = 2.
  // Water from +x (facing [1, 0, 0]) wets the outer x = 2 face only: piece 0's x = 1 face
  // also faces +x but is glued to piece 1 (internal).
  blocks::BlockModel blocks = fourBlocks();
  blocks::Block dam = boxBlock(5, {{0, 0, 2}, {1, 1, 3}}, blocks.domain, 2);
  dam.pieces.push_back(boxBlock(5, {{1, 0, 2}, {2, 1, 3}}, blocks.domain, 2).pieces[0]);
  for (blocks::Piece& piece : dam.pieces) {
    piece.face_sources.assign(6, {blocks::FaceKind::Structure, 0});
  }
  blocks.blocks.push_back(dam);
  const std::string dam_scene =
      "structures:\n"
      "  - {name: dam, prism: {profile: [[0, 2], [2, 2], [2, 3], [0, 3]], sweep: y, from: 0,"
      " to: 1}, material: concrete}\n";
  const dda3d::DdaModel model = buildDdaModel(
      scene(dam_scene +
            "loads: {water: [{level: 2.5, on: {structure: dam, facing: [1, 0, 0]}}]}\n"),
      blocks, discOne());
  ASSERT_EQ(model.pressures.size(), 1u);
  EXPECT_EQ(model.pressures[0].block, 4);
  EXPECT_EQ(model.pressures[0].piece, 1);
  EXPECT_EQ(model.pressures[0].face, 1);  // x_max
  // Facing -z: the bottom faces (n = -z) of both pieces, which reach below 2.5 m.
  EXPECT_EQ(buildDdaModel(scene(dam_scene + "loads: {water: [{level: 2.5, on: {structure: dam,"
                                            " facing: [0, 0, -1]}}]}\n"),
                          blocks, discOne())
                .pressures.size(),
            2u);
}

TEST(SceneModel, UpliftWetsBothSidesOfTheStructureRockInterface) {
  // The two-piece dam of the test above on the rock top z = 2 (blocks 3 and 4 below it):
  // uplift wets the dam's two bottom faces (n = -z, rock beyond) and the rock's two top
  // faces (n = +z, the dam beyond), all flagged uplift; the upstream face (facing -x) is
  // ordinary water. The reservoir floor (domain_top) is all under the dam: nothing wet.
  blocks::BlockModel blocks = fourBlocks();
  blocks::Block dam = boxBlock(5, {{0, 0, 2}, {1, 1, 3}}, blocks.domain, 2);
  dam.pieces.push_back(boxBlock(5, {{1, 0, 2}, {2, 1, 3}}, blocks.domain, 2).pieces[0]);
  for (blocks::Piece& piece : dam.pieces) {
    piece.face_sources.assign(6, {blocks::FaceKind::Structure, 0});
  }
  dam.bounds = Box{{0, 0, 2}, {2, 1, 3}};
  blocks.blocks.push_back(dam);
  const std::string dam_scene =
      "structures:\n"
      "  - {name: dam, prism: {profile: [[0, 2], [2, 2], [2, 3], [0, 3]], sweep: y, from: 0,"
      " to: 1}, material: concrete}\n";
  const dda3d::DdaModel model = buildDdaModel(
      scene(dam_scene + "loads: {water: [{level: 2.5, uplift: true, on: {structure: dam, "
                        "facing: [-1, 0, 0]}}, {level: 2.5, on: {domain_top: true}}]}\n"),
      blocks, discOne());
  int upstream = 0, dam_base = 0, rock_top = 0;
  for (const dda3d::DdaPressure& p : model.pressures) {
    const Vec3 n = geometry::faceNormal(blocks.blocks[static_cast<std::size_t>(p.block)]
                                            .pieces[static_cast<std::size_t>(p.piece)]
                                            .shape,
                                        p.face);
    if (!p.uplift) {
      upstream += p.block == 4 && n.x() < -0.5;
    } else if (p.block == 4) {
      dam_base += n.z() < -0.5;
    } else {
      rock_top += (p.block == 2 || p.block == 3) && n.z() > 0.5;
    }
  }
  EXPECT_EQ(upstream, 1);
  EXPECT_EQ(dam_base, 2);
  EXPECT_EQ(rock_top, 2);
  EXPECT_EQ(model.pressures.size(), 5u);  // nothing else, in particular no reservoir floor
}

/// The message of the InputError that buildDdaModel throws ("no error" otherwise).
std::string errorOf(const Scene& s, const blocks::BlockModel& blocks) {
  try {
    buildDdaModel(s, blocks, discOne());
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SceneModel, ErrorsNameWhatIsWrong) {
  EXPECT_EQ(errorOf(scene("monitors:\n  - {name: lost, point: [5, 0.5, 1]}\n"), fourBlocks()),
            "tiny.yaml:11: monitors: lost at (5, 0.5, 1) lies in no block; a monitor must be "
            "inside the rock or a structure");
  EXPECT_EQ(errorOf(scene("loads: {point_loads: [{point: [0.5, 0.5, -3], force: [0, 0, 1]}]}\n"),
                    fourBlocks()),
            "tiny.yaml: loads.point_loads[0] at (0.5, 0.5, -3) lies in no block; a point load must "
            "act on the rock or a structure");
  blocks::BlockModel no_material = fourBlocks();
  no_material.blocks[2].material = -1;
  EXPECT_EQ(errorOf(scene(""), no_material),
            "tiny.yaml: block 3 has no material: give `rock_material` (the material of the "
            "rock outside every slab)");
  const Scene no_default = parseScene(
      "version: 1\n"
      "domain: {box: {min: [0, 0, 0], max: [2, 1, 2]}}\n"
      "materials: {rock: {density: 2600, young: 10.0e9, poisson: 0.25}}\n"
      "rock_material: rock\n",
      "tiny.yaml");
  EXPECT_EQ(errorOf(no_default, fourBlocks()),
            "tiny.yaml: analysis.dda needs the strength of the contacts between blocks: give "
            "`joints` and `default_joint`");
}

}  // namespace
}  // namespace rockmass::scene_model
