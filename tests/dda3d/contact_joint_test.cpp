// The joint of a contact from the joints of the faces it lies on (dda3d/contact_joint.h):
// a vertex on a disc face, a vertex on a face that carries none, an edge-edge contact between
// faces of two joints, the order of "weaker", the validation of DdaBlock::face_joints, and
// the joints the Simulation gives the contacts it detects. Two boxes: a fixed base
// [0, 2] x [0, 2] x [-1, 0] and a unit cube [0.5, 1.5]^2 x [0, 1] resting on it.
#include "dda3d/contact_joint.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "dda3d/simulation.h"
#include "scenarios/dda_scenes.h"

namespace rockmass::dda3d {
namespace {

using geometry::Vec3;

// Box faces (geometry::boxPolyhedron): 0 x min, 1 x max, 2 y min, 3 y max, 4 z min, 5 z max;
// vertex k has x, y, z at the max side where bit 0, 1, 2 of k is set.
constexpr int kZMin = 4, kZMax = 5;

/// Joints: 0 default (f 0.6), 1 fault (f 0.3), 2 (f 0.3, c 1e5), 3 (f 0.5), 4 (f 0.1).
DdaModel baseAndCube() {
  DdaModel model;
  scenes::setRock(model, 30.0);
  model.joints = {
      {0.6, 0.0, 0.0}, {0.3, 0.0, 0.0}, {0.3, 1e5, 0.0}, {0.5, 0.0, 0.0}, {0.1, 0.0, 0.0}};
  model.blocks.push_back(scenes::boxBlock({0, 0, -1}, {2, 2, 0}, 0, true));
  model.blocks.push_back(scenes::boxBlock({0.5, 0.5, 0}, {1.5, 1.5, 1}, 0, false));
  return model;
}

/// The block states of the model's blocks (geometry and topology only).
std::vector<BlockState> statesOf(const DdaModel& model) {
  std::vector<BlockState> states;
  for (const DdaBlock& block : model.blocks) {
    BlockState s;
    s.pieces = block.pieces;
    for (const geometry::Polyhedron& p : s.pieces) s.topology.push_back(pieceTopology(p));
    states.push_back(std::move(s));
  }
  return states;
}

/// Sets the joint of face `face` of the one piece of block `block`.
void setFace(DdaModel& model, int block, int face, int joint) {
  DdaBlock& b = model.blocks[static_cast<std::size_t>(block)];
  if (b.face_joints.empty()) b.face_joints = {std::vector<int>(6, -1)};
  b.face_joints[0][static_cast<std::size_t>(face)] = joint;
}

/// Vertex 0 of the cube (its corner at x, y, z min) on the base's top face.
Contact vertexOnBase() {
  Contact c;
  c.kind = ContactKind::VertexFace;
  c.block_i = 1;
  c.piece_i = 0;
  c.vertex = 0;
  c.block_j = 0;
  c.piece_j = 0;
  c.face = kZMax;
  c.normal = Vec3::UnitZ();
  return c;
}

/// Index of the edge (a, b) of a piece's topology.
int edgeIndex(const PieceTopology& topology, int a, int b) {
  for (std::size_t e = 0; e < topology.edges.size(); ++e) {
    const auto& ends = topology.edges[e];
    if ((ends[0] == a && ends[1] == b) || (ends[0] == b && ends[1] == a)) {
      return static_cast<int>(e);
    }
  }
  return -1;
}

TEST(ContactJoint, AVertexOnADiscFaceTakesTheDiscsJoint) {
  DdaModel model = baseAndCube();
  setFace(model, 0, kZMax, 1);  // the base's top is a fault face
  std::vector<BlockState> states = statesOf(model);
  EXPECT_EQ(contactJoint(model, states, vertexOnBase()), 1);
  // The cube's faces around the vertex carry joint 4 on its sides and none below: the face
  // of i that counts is the one most opposed to n (its bottom), which carries none.
  setFace(model, 1, 0, 4);
  setFace(model, 1, 2, 4);
  EXPECT_EQ(contactJoint(model, states, vertexOnBase()), 1);
  // Both candidate faces carry a joint, different ones: the weaker (f 0.3 < 0.5).
  setFace(model, 1, kZMin, 3);
  EXPECT_EQ(contactJoint(model, states, vertexOnBase()), 1);
}

TEST(ContactJoint, AVertexOnAFaceWithoutAJointTakesTheJointOfItsOwnFace) {
  DdaModel model = baseAndCube();
  std::vector<BlockState> states = statesOf(model);
  // No face carries a joint: -1, the default joint.
  EXPECT_EQ(contactJoint(model, states, vertexOnBase()), -1);
  // The base's top carries none (a domain boundary face); the cube's bottom carries joint 3,
  // its two sides at the vertex the weaker joint 4: the bottom decides, being the face of i
  // around the vertex whose outward normal (-z) is most opposed to n (+z).
  setFace(model, 1, kZMin, 3);
  setFace(model, 1, 0, 4);
  setFace(model, 1, 2, 4);
  EXPECT_EQ(contactJoint(model, states, vertexOnBase()), 3);
}

TEST(ContactJoint, AnEdgeEdgeContactBetweenTwoJointsTakesTheWeaker) {
  DdaModel model = baseAndCube();
  // The cube's bottom edge along x at y min (vertices 0-1; faces y min and z min) against
  // the base's top edge along y at x min (vertices 4-6; faces x min and z max), n = +z out
  // of the base. (Only the edges and n matter to the rule, not where they cross.)
  std::vector<BlockState> states = statesOf(model);
  Contact c;
  c.kind = ContactKind::EdgeEdge;
  c.block_i = 1;
  c.piece_i = 0;
  c.edge_i = edgeIndex(states[1].topology[0], 0, 1);
  c.block_j = 0;
  c.piece_j = 0;
  c.edge_j = edgeIndex(states[0].topology[0], 4, 6);
  ASSERT_GE(c.edge_i, 0);
  ASSERT_GE(c.edge_j, 0);
  c.normal = Vec3::UnitZ();
  // Base top: joint 2 (f 0.3, c 1e5); cube bottom: joint 1 (f 0.3, c 0): the same friction,
  // so the smaller cohesion decides: 1. The other faces of the two edges (the base's x min
  // side and the cube's y min side, joint 4, f 0.1) look away from the contact: no
  // candidates.
  setFace(model, 0, kZMax, 2);
  setFace(model, 1, kZMin, 1);
  setFace(model, 0, 0, 4);
  setFace(model, 1, 2, 4);
  EXPECT_EQ(contactJoint(model, states, c), 1);
  // Swapped: still the weaker one.
  setFace(model, 0, kZMax, 1);
  setFace(model, 1, kZMin, 2);
  EXPECT_EQ(contactJoint(model, states, c), 1);
  // Friction first: f 0.5 (joint 3) against f 0.3 with cohesion (joint 2): 2.
  setFace(model, 0, kZMax, 3);
  EXPECT_EQ(contactJoint(model, states, c), 2);
  // One side carries none: the other's joint.
  setFace(model, 0, kZMax, -1);
  EXPECT_EQ(contactJoint(model, states, c), 2);
}

TEST(ContactJoint, WeakerOrder) {
  const std::vector<DdaJoint> joints = {
      {0.6, 0.0, 0.0}, {0.3, 0.0, 0.0}, {0.3, 1e5, 0.0}, {0.3, 1e5, 1e4}, {0.3, 0.0, 0.0}};
  EXPECT_EQ(weakerJoint(joints, 0, 1), 1);   // friction
  EXPECT_EQ(weakerJoint(joints, 2, 1), 1);   // then cohesion
  EXPECT_EQ(weakerJoint(joints, 3, 2), 2);   // then tensile strength
  EXPECT_EQ(weakerJoint(joints, 4, 1), 1);   // equal strength: the lower index
  EXPECT_EQ(weakerJoint(joints, -1, 3), 3);  // none: the other
  EXPECT_EQ(weakerJoint(joints, 3, -1), 3);
  EXPECT_EQ(weakerJoint(joints, -1, -1), -1);
}

/// The message of the std::invalid_argument the Simulation constructor throws.
std::string constructorError(const DdaModel& model) {
  try {
    Simulation sim(model, DdaSettings{});
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(ContactJoint, FaceJointsAreValidated) {
  DdaModel model = baseAndCube();
  model.blocks[1].face_joints = {std::vector<int>(6, -1), std::vector<int>(6, -1)};
  EXPECT_EQ(constructorError(model), "block 1 has face joints for 2 pieces but 1 pieces");
  model.blocks[1].face_joints = {std::vector<int>(5, -1)};
  EXPECT_EQ(constructorError(model), "block 1 piece 0 has 5 face joints but 6 faces");
  model.blocks[1].face_joints = {{-1, -1, -1, 5, -1, -1}};
  EXPECT_EQ(constructorError(model),
            "block 1 piece 0 face 3 has joint 5, which is neither -1 nor an index into the 5 "
            "joints");
  model.blocks[1].face_joints = {{-1, -1, -1, -2, -1, -1}};
  EXPECT_NE(constructorError(model).find("face 3 has joint -2"), std::string::npos);
  model.blocks[1].face_joints = {{-1, -1, -1, 4, -1, -1}};
  EXPECT_EQ(constructorError(model), "no error");
}

// Through the engine: the cube resting on the base, whose top is a fault face of joint 1.
// Every contact the first step detects lies on that face and takes joint 1; without face
// joints, every one takes -1 (the default joint).
TEST(ContactJoint, TheSimulationGivesEveryDetectedContactItsJoint) {
  DdaModel model = baseAndCube();
  model.gravity = Vec3(0, 0, -9.81);
  DdaSettings settings;
  settings.kinematics = Kinematics::Rigid;
  settings.time_step = 1e-3;
  Simulation plain(model, settings);
  plain.step();
  ASSERT_GE(plain.contacts().size(), 4u);  // at least the cube's four bottom corners
  for (const Contact& c : plain.contacts()) EXPECT_EQ(c.joint, -1);
  setFace(model, 0, kZMax, 1);
  Simulation fault(model, settings);
  fault.step();
  ASSERT_EQ(fault.contacts().size(), plain.contacts().size());
  for (const Contact& c : fault.contacts()) EXPECT_EQ(c.joint, 1);
}

}  // namespace
}  // namespace rockmass::dda3d
