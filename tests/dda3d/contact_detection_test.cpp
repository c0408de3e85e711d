// Contact detection: the broad phase against an all-pairs reference, and the search
// distance (each block's step reach) against the displacement of the step.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "blocks/convex_split.h"
#include "dda3d/broad_phase.h"
#include "dda3d/contact_detection.h"
#include "dda3d/simulation.h"
#include "geometry/random.h"
#include "scenarios/dda_scenes.h"
#include "tests/dda3d/cut_pieces.h"

namespace rockmass::dda3d {
namespace {

using geometry::Box;
using geometry::Vec3;

/// The definition the broad phase must meet, by brute force: closed boxes sharing a point,
/// of different blocks, not both fixed; sorted.
std::vector<PiecePair> allPairs(const std::vector<PieceBox>& boxes) {
  std::vector<PiecePair> pairs;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for (std::size_t j = i + 1; j < boxes.size(); ++j) {
      const PieceBox& x = boxes[i];
      const PieceBox& y = boxes[j];
      if (x.block == y.block || (x.fixed && y.fixed)) continue;
      if ((x.box.min.array() > y.box.max.array()).any() ||
          (y.box.min.array() > x.box.max.array()).any()) {
        continue;
      }
      PiecePair p{x.block, x.piece, y.block, y.piece};
      if (std::tie(p.block_b, p.piece_b) < std::tie(p.block_a, p.piece_a)) {
        p = {y.block, y.piece, x.block, x.piece};
      }
      pairs.push_back(p);
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const PiecePair& x, const PiecePair& y) {
    return std::tie(x.block_a, x.piece_a, x.block_b, x.piece_b) <
           std::tie(y.block_a, y.piece_a, y.block_b, y.piece_b);
  });
  return pairs;
}

/// `count` boxes with corners on a 0.25 m grid in a 6 m cube (exactly representable, so
/// many boxes touch exactly: max of one == min of another), 1-3 pieces per block, every
/// fifth block fixed. A quarter of the boxes are flat (zero extent along one axis) and one
/// in twenty is a point.
std::vector<PieceBox> randomBoxes(std::uint64_t seed, int count) {
  geometry::Rng rng = geometry::makeRng(seed, 0);
  const auto grid = [&rng](int cells) { return 0.25 * static_cast<double>(rng() % cells); };
  std::vector<PieceBox> boxes;
  int block = 0, piece = 0;
  for (int k = 0; k < count; ++k) {
    PieceBox b;
    for (int axis = 0; axis < 3; ++axis) {
      b.box.min[axis] = grid(24);
      b.box.max[axis] = b.box.min[axis] + grid(5);  // 0 to 1 m
    }
    const unsigned kind = rng() % 20;
    if (kind < 5) b.box.max[kind % 3] = b.box.min[kind % 3];  // flat
    if (kind == 5) b.box.max = b.box.min;                     // a point
    b.block = block;
    b.piece = piece;
    b.fixed = block % 5 == 0;
    boxes.push_back(b);
    if (rng() % 3 == 0) {
      ++piece;  // the next box is another piece of the same block
    } else {
      ++block;
      piece = 0;
    }
  }
  return boxes;
}

TEST(BroadPhase, FindsExactlyTheAllPairsReferenceOnRandomBoxes) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const std::vector<PieceBox> boxes = randomBoxes(seed, 400);
    const std::vector<PiecePair> reference = allPairs(boxes);
    // The grid makes touching and degenerate overlaps frequent; check the sample has them,
    // so that the comparison below covers them.
    int touching = 0;
    for (const PiecePair& p : reference) {
      const auto boxOf = [&boxes](int block, int piece) {
        for (const PieceBox& b : boxes) {
          if (b.block == block && b.piece == piece) return b.box;
        }
        return Box{};
      };
      const Box x = boxOf(p.block_a, p.piece_a), y = boxOf(p.block_b, p.piece_b);
      touching += ((x.max.array() == y.min.array()) || (y.max.array() == x.min.array())).any();
    }
    ASSERT_GT(touching, 20) << "seed " << seed;
    ASSERT_GT(reference.size(), 200u) << "seed " << seed;
    EXPECT_EQ(overlappingPieces(boxes), reference) << "seed " << seed;
    // The order of the input does not change the (sorted) result.
    std::vector<PieceBox> reversed(boxes.rbegin(), boxes.rend());
    EXPECT_EQ(overlappingPieces(reversed), reference) << "seed " << seed;
  }
}

TEST(BroadPhase, EdgeCasesOfTheInput) {
  EXPECT_TRUE(overlappingPieces({}).empty());
  // Two fixed blocks overlapping, and two pieces of one block: never pairs.
  const Box unit{Vec3::Zero(), Vec3::Ones()};
  EXPECT_TRUE(overlappingPieces({{unit, 0, 0, true}, {unit, 1, 0, true}}).empty());
  EXPECT_TRUE(overlappingPieces({{unit, 3, 0, false}, {unit, 3, 1, false}}).empty());
  // A point on a corner of a box touches it; a point just off does not.
  const Box corner{Vec3::Ones(), Vec3::Ones()};
  const Box off{Vec3::Constant(1.0 + 1e-12), Vec3::Constant(1.0 + 1e-12)};
  EXPECT_EQ(overlappingPieces({{unit, 0, 0, true}, {corner, 1, 0, false}}),
            (std::vector<PiecePair>{{0, 0, 1, 0}}));
  EXPECT_TRUE(overlappingPieces({{unit, 0, 0, true}, {off, 1, 0, false}}).empty());
}

/// Two unit cubes 0.25 m apart along x.
std::vector<BlockState> twoCubes() {
  std::vector<BlockState> blocks(2);
  blocks[0].pieces.push_back(geometry::boxPolyhedron({Vec3::Zero(), Vec3::Ones()}));
  blocks[1].pieces.push_back(geometry::boxPolyhedron({Vec3(1.25, 0.0, 0.0), Vec3(2.25, 1.0, 1.0)}));
  for (BlockState& b : blocks) {
    b.topology.push_back(pieceTopology(b.pieces[0]));
    b.updateMassProperties();
  }
  return blocks;
}

TEST(BroadPhase, GrowsEachPieceByItsBlocksReach) {
  const std::vector<BlockState> blocks = twoCubes();
  // Reaches summing exactly to the gap (binary fractions): the grown boxes touch.
  EXPECT_EQ(broadPhase(blocks, {0.125, 0.125}).size(), 1u);
  EXPECT_EQ(broadPhase(blocks, {0.0, 0.25}).size(), 1u);
  EXPECT_TRUE(broadPhase(blocks, {0.125, 0.0625}).empty());
}

TEST(SearchDistance, IsTwiceThePredictedStepDisplacementWithinItsLimits) {
  std::vector<BlockState> blocks = twoCubes();
  BlockState& b = blocks[0];
  const ReachLimits limits{1e-4, 0.05};
  const double dt = 1e-3;
  EXPECT_EQ(stepReach(b, dt, dt, limits), limits.floor);  // at rest
  // Translation at 2 m/s: every vertex moves 2 mm in dt; reach = 2 x 2 mm.
  b.velocity.head<3>() = Vec3(2.0, 0.0, 0.0);
  EXPECT_NEAR(stepReach(b, dt, dt, limits), 4e-3, 1e-15);
  // Spin at 3 rad/s about z through the centroid: the corners (sqrt(0.5) m off the axis)
  // move fastest, 3 sqrt(0.5) m/s.
  b.velocity.setZero();
  b.velocity[5] = 3.0;
  EXPECT_NEAR(stepReach(b, dt, dt, limits), 2.0 * 3.0 * std::sqrt(0.5) * dt, 1e-15);
  // The last step's displacement, scaled to this dt (half the last one): 3 mm -> 1.5 mm.
  b.velocity.setZero();
  b.last_displacement.head<3>() = Vec3(0.0, 0.0, -3e-3);
  EXPECT_NEAR(stepReach(b, 0.5 * dt, dt, limits), 2.0 * 1.5e-3, 1e-15);
  // Free flight under gravity from rest: 1/2 g dt^2 = 4.905 um, reach twice that.
  b.last_displacement.setZero();
  const ReachLimits falling{1e-6, 0.05, 9.81};
  EXPECT_NEAR(stepReach(b, dt, dt, falling), 9.81 * dt * dt, 1e-18);
  // Never above the step control's own limit; a fixed block does not move.
  b.velocity.head<3>() = Vec3(100.0, 0.0, 0.0);
  EXPECT_EQ(stepReach(b, dt, dt, limits), limits.cap);
  blocks[1].fixed = true;
  EXPECT_EQ(stepReach(blocks[1], dt, dt, limits), 0.0);
}

// A cube at rest 3 mm above a fixed slab is pushed down by a point load that would move
// it 5-10 mm in the first 10 ms step: within the step control's 1.5 g2 l0 = 22.5 mm, but
// beyond its resting reach 0.1 g2 l0 = 1.5 mm, so the slab is not a contact candidate for
// that step. The step must be redone with a smaller dt rather than let the cube pass into
// the slab unseen; after every step the cube moved no farther than its reach.
TEST(SearchDistance, AStepThatWouldOutrunTheReachIsRedone) {
  DdaModel model;
  scenes::setRock(model, 30.0);
  model.blocks.push_back(scenes::boxBlock({-1, -1, -1}, {2, 2, 0}, 0, true));
  model.blocks.push_back(scenes::boxBlock({0, 0, 3e-3}, {1, 1, 1.003}, 0, false));
  // d = F dt^2 / (2 m) = 5 mm for m = 2600 kg (a dt^2 / 2 ... a dt^2 by scheme).
  model.point_loads.push_back({1, Vec3(0.5, 0.5, 0.5), Vec3(0.0, 0.0, -2.6e5)});
  DdaSettings settings;
  settings.kinematics = Kinematics::Rigid;
  settings.time_step = 1e-2;
  Simulation sim(model, settings);
  ASSERT_NEAR(sim.halfDomainSize(), 1.5, 1e-12);
  const double resting_reach = 0.1 * settings.max_displacement_ratio * sim.halfDomainSize();
  const StepReport first = sim.step();
  EXPECT_NEAR(sim.contactReach()[1], resting_reach, 1e-15);
  EXPECT_GE(first.redo_displacement, 1) << "the 5 mm step must not be accepted";
  const double allowed = settings.allowed_penetration_ratio * sim.halfDomainSize();
  for (int k = 0; k < 40; ++k) {
    if (k > 0) sim.step();  // the first step is `first`
    const BlockState& cube = sim.blocks()[1];
    EXPECT_LE(largestVertexDisplacement(cube, cube.last_displacement),
              sim.contactReach()[1] * (1.0 + 1e-12))
        << "step " << k;
    double lowest = 1.0;
    for (const Vec3& v : cube.pieces[0].vertices) lowest = std::min(lowest, v.z());
    // Geometric penetration into the slab top (z = 0), whether or not a contact saw it.
    ASSERT_LE(-lowest, allowed) << "step " << k;
  }
  // The load is resisted by the slab: the cube ends in contact.
  EXPECT_GT(sim.contactCounts().total - sim.contactCounts().open, 0);
}

/// Area of face f of p (Newell).
double faceArea(const geometry::Polyhedron& p, int f) {
  const std::vector<int>& face = p.faces[static_cast<std::size_t>(f)];
  Vec3 sum = Vec3::Zero();
  for (std::size_t k = 0; k < face.size(); ++k) {
    sum += p.vertices[static_cast<std::size_t>(face[k])].cross(
        p.vertices[static_cast<std::size_t>(face[(k + 1) % face.size()])]);
  }
  return 0.5 * sum.norm();
}

TEST(FacePoints, CellsTileEveryFaceWideEnoughAndSumToItsArea) {
  // A 4 x 2 x 1 m box with spacing 0.5 m: its 4 x 2 faces get 8 x 4 cells, its 4 x 1 faces
  // 8 x 2, its 2 x 1 faces 4 x 2, each of 0.25 m2; a triangular prism's faces are cut by the
  // same rule and clipped, the cells' areas summing to each face's area (round-off).
  const geometry::Polyhedron box = geometry::boxPolyhedron({Vec3(0, 0, 0), Vec3(4, 2, 1)});
  const std::vector<FacePoint> points = facePoints(box, 0.5).points;
  std::vector<int> count(box.faces.size(), 0);
  std::vector<double> area(box.faces.size(), 0.0);
  for (const FacePoint& p : points) {
    ++count[static_cast<std::size_t>(p.face)];
    area[static_cast<std::size_t>(p.face)] += p.area;
    EXPECT_NEAR(p.area, 0.25, 1e-12);
    // On its face's plane, inside the box's faces.
    const Vec3 n = geometry::faceNormal(box, p.face);
    const Vec3& v0 =
        box.vertices[static_cast<std::size_t>(box.faces[static_cast<std::size_t>(p.face)][0])];
    EXPECT_NEAR(n.dot(p.position - v0), 0.0, 1e-12);
    EXPECT_TRUE((p.position.array() > -1e-12).all() &&
                (p.position.array() < Vec3(4, 2, 1).array() + 1e-12).all());
  }
  std::vector<int> sorted = count;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, (std::vector<int>{8, 8, 16, 16, 32, 32}));
  for (std::size_t f = 0; f < box.faces.size(); ++f) {
    EXPECT_NEAR(area[f], faceArea(box, static_cast<int>(f)), 1e-12);
  }
  const DdaBlock prism = scenes::prismBlock({{0, 0}, {3, 0}, {0, 2}}, 0.0, 2.0, 0, false);
  const geometry::Polyhedron& p = prism.pieces[0];
  const std::vector<FacePoint> prism_points = facePoints(p, 0.4).points;
  std::vector<double> prism_area(p.faces.size(), 0.0);
  for (const FacePoint& q : prism_points) prism_area[static_cast<std::size_t>(q.face)] += q.area;
  for (std::size_t f = 0; f < p.faces.size(); ++f) {
    EXPECT_NEAR(prism_area[f], faceArea(p, static_cast<int>(f)), 1e-9) << "face " << f;
  }
  // A face narrower than two cells either way gets none (its corners carry it).
  EXPECT_TRUE(facePoints(box, 1.5).points.size() < points.size());
  for (const FacePoint& q : facePoints(box, 1.5).points) {
    EXPECT_GE(faceArea(box, q.face), 2.0);  // only the 4 x 2 and 4 x 1 faces
  }
  EXPECT_TRUE(facePoints(box, 0.0).points.empty());
}

TEST(FacePoints, ABlockOnASlabRestsOnItsPointsWithTheirAreasAndJoint) {
  // A 2 x 2 x 1 m block on a slab, spacing 0.5 m: its base carries 16 face-point contacts,
  // 0.25 m2 each (4 m2 in all, the corners none), with the slab's face joint; together they
  // carry the block's weight, and the block rests.
  DdaModel model;
  model.materials = {DdaMaterial{2600.0, 10e9, 0.25}};
  model.joints = {DdaJoint{0.6, 1e5, 0.0}, DdaJoint{0.3, 2e4, 0.0}};
  model.blocks.push_back(scenes::boxBlock({-3, -3, -1}, {3, 3, 0}, 0, true));
  model.blocks.push_back(scenes::boxBlock({-1, -1, 0}, {1, 1, 1}, 0, false));
  model.blocks[0].face_joints = {std::vector<int>(6, 1)};  // the slab's faces: joint 1
  model.gravity = Vec3(0, 0, -9.81);
  DdaSettings settings;
  settings.kinematics = Kinematics::Rigid;
  settings.contact_point_spacing = 0.5;
  Simulation sim(model, settings);
  for (int k = 0; k < 20; ++k) sim.step();
  int points = 0;
  double area = 0.0, normal = 0.0;
  for (const Contact& c : sim.contacts()) {
    if (c.kind == ContactKind::FacePoint) {
      ++points;
      area += c.area;
      EXPECT_EQ(c.joint, 1);
      EXPECT_EQ(c.block_i, 1);  // the block's face is the smaller one: its points
    } else {
      EXPECT_EQ(c.area, 0.0);
    }
    normal += c.normal_force;
  }
  EXPECT_EQ(points, 16);
  EXPECT_NEAR(area, 4.0, 1e-12);
  const double weight = 2600.0 * 9.81 * 4.0;
  EXPECT_NEAR(normal, weight, 1e-6 * weight);
  EXPECT_LT(sim.centroidDisplacement(1).norm(), 1e-6);
}

}  // namespace
}  // namespace rockmass::dda3d

namespace rockmass::dda3d {
namespace {

using geometry::Vec3;

using testing::blocksOf;
using testing::cutCube;

using testing::kNoPrevious;

// Pieces that only touch never penetrate: every entry found between the pieces of a cube cut
// by random planes has gap0 >= 0 up to round-off. The search reach (0.3 m) and depth are as
// large as the pieces, as with the small blocks of the Xiangjiaba model, where skew edges kept
// apart by another plane, and vertices on a piece's edge matched to a face far behind the
// nearest, were recorded as penetrations up to the depth (0.26 m) and threw blocks apart.
TEST(NarrowPhase, TouchingPiecesNeverReadAsPenetrating) {
  int entries = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    std::vector<std::vector<geometry::Polyhedron>> groups;
    for (const geometry::Polyhedron& p : cutCube(seed, 5)) groups.push_back({p});
    const std::vector<BlockState> blocks = blocksOf(groups);
    const std::vector<double> reach(blocks.size(), 0.15);
    const std::vector<Contact> contacts = findContacts(blocks, reach, 0.3, kNoPrevious);
    entries += static_cast<int>(contacts.size());
    for (const Contact& c : contacts) {
      // 1e-9 m: the round-off of the split vertices (tolerance 1e-9 of a 1 m cube).
      EXPECT_GT(c.gap0, -1e-9) << "seed " << seed << " blocks " << c.block_i << "/" << c.block_j
                               << " kind " << static_cast<int>(c.kind);
    }
  }
  EXPECT_GT(entries, 1000);  // the cut pieces do touch: many entries were examined
}

// A block of two pieces (a box split in half) resting on a box: each corner of its bottom face
// is one contact entry, also the two corners on the split, which belong to both pieces (each
// copy would be a full penalty spring, doubling the support there).
TEST(NarrowPhase, ASharedVertexOfAMultiPieceBlockIsOneEntry) {
  const geometry::Polyhedron left = geometry::boxPolyhedron({Vec3(0, 0, 1), Vec3(0.5, 1, 2)});
  const geometry::Polyhedron right = geometry::boxPolyhedron({Vec3(0.5, 0, 1), Vec3(1, 1, 2)});
  const geometry::Polyhedron base = geometry::boxPolyhedron({Vec3(-1, -1, 0), Vec3(2, 2, 1)});
  const std::vector<BlockState> blocks = blocksOf({{left, right}, {base}});
  const std::vector<Contact> contacts = findContacts(blocks, {0.01, 0.01}, 0.02, kNoPrevious);
  int vertex_entries = 0;
  for (const Contact& c : contacts) {
    if (c.kind != ContactKind::VertexFace || c.block_i != 0) continue;
    ++vertex_entries;
    EXPECT_NEAR(c.point.z(), 1.0, 1e-12);
    EXPECT_NEAR(c.normal.z(), 1.0, 1e-12);
  }
  EXPECT_EQ(vertex_entries, 6);  // 4 corners + the 2 ends of the split line
}

/// `pieces` moved by `shift`.
std::vector<geometry::Polyhedron> moved(std::vector<geometry::Polyhedron> pieces,
                                        const Vec3& shift) {
  for (geometry::Polyhedron& p : pieces) {
    for (Vec3& v : p.vertices) v += shift;
  }
  return pieces;
}

/// A 1 x 1 x 2 column cut by the planes of cutCube(seed, cuts) stretched to its height, then
/// split at z = 1: the upper and lower pieces meet on lines the cuts continue across, as
/// where joints cross an interlayer. Returns {upper, lower} pieces.
std::pair<std::vector<geometry::Polyhedron>, std::vector<geometry::Polyhedron>> splitColumn(
    std::uint64_t seed, int cuts) {
  std::pair<std::vector<geometry::Polyhedron>, std::vector<geometry::Polyhedron>> out;
  for (geometry::Polyhedron p : cutCube(seed, cuts)) {
    for (Vec3& v : p.vertices) v.z() *= 2.0;
    blocks::Piece piece;
    piece.shape = p;
    piece.face_sources.assign(p.faces.size(), {});
    const auto split =
        blocks::splitPiece(piece, blocks::Plane::through(Vec3(0, 0, 1), Vec3::UnitZ()), 1e-9, {});
    if (!split) {
      (p.vertices[0].z() > 1.0 ? out.first : out.second).push_back(p);
      continue;
    }
    out.first.push_back(split->above.shape);
    out.second.push_back(split->below.shape);
  }
  return out;
}

// Pieces pressed face to face read only the press. A column cut by random planes is split at
// mid-height, and its upper pieces are pressed 1e-7 m into the lower ones: the spring
// compression of a settled pile. One half is one block of many pieces, the other's pieces are
// blocks of their own. Every point of the
// upper pieces is then at most 1e-7 m inside the lower block, so no entry may read deeper. On
// the Xiangjiaba model two readings were far deeper: the crossing of a lower edge ending on
// the shared face with an upper edge lying in it (0.25 m sideways), and an upper vertex on the
// line where two lower pieces meet, whose foot fell a round-off beyond the top face and which
// was matched to a steep face (0.7 mm). Their penalty forces exceeded the model's weight.
TEST(NarrowPhase, PiecesPressedFaceToFaceReadOnlyThePress) {
  constexpr double kPress = 1e-7;
  int entries = 0, pressed = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    for (int variant = 0; variant < 4; ++variant) {
      // Bit 0: the cuts continue across the split (else the halves are cut independently).
      // Bit 1: the upper half is the one block of many pieces (else the lower half).
      auto [upper, lower] = splitColumn(seed, 6);
      if ((variant & 1) == 0) {
        upper = moved(cutCube(seed + 1000, 6), Vec3(0, 0, 1));
        lower = cutCube(seed + 2000, 6);
      }
      upper = moved(upper, Vec3(0, 0, -kPress));
      const bool upper_glued = (variant & 2) != 0;
      std::vector<std::vector<geometry::Polyhedron>> groups;
      for (const geometry::Polyhedron& p : upper_glued ? lower : upper) groups.push_back({p});
      groups.push_back(upper_glued ? upper : lower);
      const std::vector<BlockState> blocks = blocksOf(groups);
      const std::vector<double> reach(blocks.size(), 0.15);
      const std::vector<Contact> contacts = findContacts(blocks, reach, 0.3, kNoPrevious);
      const int glued = static_cast<int>(blocks.size()) - 1;
      for (const Contact& c : contacts) {
        if (c.block_i != glued && c.block_j != glued) continue;
        ++entries;
        pressed += c.gap0 < -0.5 * kPress;
        // The press, plus the round-off of the split vertices (1e-9 m on a 1 m cube).
        EXPECT_GT(c.gap0, -kPress - 2e-9)
            << "seed " << seed << " variant " << variant << " blocks " << c.block_i << "/"
            << c.block_j << " kind " << static_cast<int>(c.kind) << " normal "
            << c.normal.transpose();
      }
    }
  }
  EXPECT_GT(entries, 4000);  // many entries across the pressed face were examined
  EXPECT_GT(pressed, 800);   // and the press itself is read
}

/// The prism over a convex polygon of the x-z plane (counter-clockwise with x right, z up)
/// between y0 and y1.
geometry::Polyhedron prismXZ(const std::vector<std::pair<double, double>>& polygon, double y0,
                             double y1) {
  geometry::Polyhedron prism;
  const int n = static_cast<int>(polygon.size());
  for (double y : {y0, y1}) {
    for (const auto& [x, z] : polygon) prism.vertices.emplace_back(x, y, z);
  }
  std::vector<int> front, back;
  for (int k = 0; k < n; ++k) {
    front.push_back(k);             // y = y0, normal -y
    back.push_back(2 * n - 1 - k);  // y = y1, normal +y
    const int next = (k + 1) % n;
    prism.faces.push_back({k, n + k, n + next, next});
  }
  prism.faces.push_back(front);
  prism.faces.push_back(back);
  return prism;
}

// A vertex barely inside a piece is matched to the face it is least deep behind, even where
// its foot falls a round-off beyond that face's edge. Piece b is a 0.3 mm sliver whose bottom
// face meets an overhanging side at x = 0; a vertex of a, pressed 1.5e-7 m up into b, lies
// 1e-7 m beyond the bottom face's edge, where the overhang keeps it inside b. The overhang
// itself is ruled out (a's edge along +x would dive through it), and the old rule, a foot
// within 1e-9 of the pieces' size of its face, ruled out the bottom too and matched the vertex
// to the sliver's top face, 0.3 mm away: a false penetration 2000 times the press (seen on
// the Xiangjiaba model at 0.7 mm, where its spring force exceeded the model's weight).
TEST(NarrowPhase, AVertexBeyondAFaceEdgeByRoundOffKeepsThatFace) {
  constexpr double kSliver = 3e-4, kPress = 1.5e-7, kBeyond = 1e-7;
  const geometry::Polyhedron b = prismXZ({{0, 0}, {1, 0}, {1, kSliver}, {-kSliver, kSliver}}, 0, 1);
  // a: its top face pressed into b's bottom, its corner p = (-1e-7, y, 1.5e-7) beyond the
  // bottom's edge; its edges at p run along +x, along y, and down at 16 degrees.
  const geometry::Polyhedron a = prismXZ(
      {{-kBeyond, kPress}, {1.92 - kBeyond, kPress - 0.56}, {2, kPress - 0.56}, {2, kPress}}, 0.25,
      0.75);
  ASSERT_GT(geometry::massProperties(a).volume, 0.0);  // both prisms are outward-oriented
  ASSERT_GT(geometry::massProperties(b).volume, 0.0);
  const std::vector<BlockState> blocks = blocksOf({{a}, {b}});
  const std::vector<Contact> contacts = findContacts(blocks, {0.01, 0.01}, 0.02, kNoPrevious);
  int at_corner = 0;
  for (const Contact& c : contacts) {
    if (c.kind != ContactKind::VertexFace || c.block_i != 0) continue;
    if (std::abs(c.point.x() + kBeyond) > 1e-12 || c.point.z() < 0.0) continue;
    ++at_corner;  // the two corners of a at x = -1e-7 (y = 0.25 and 0.75)
    EXPECT_NEAR(c.normal.z(), -1.0, 1e-12);  // b's bottom face
    EXPECT_NEAR(c.gap0, -kPress, 1e-12);     // the press, not the sliver's thickness
  }
  EXPECT_EQ(at_corner, 2);
}

}  // namespace
}  // namespace rockmass::dda3d

namespace rockmass::dda3d {
namespace {

/// Sum of the contact areas (m2) of the entries between blocks a and b.
double areaBetween(const std::vector<Contact>& contacts, int a, int b) {
  double area = 0.0;
  for (const Contact& c : contacts) {
    if ((c.block_i == a && c.block_j == b) || (c.block_i == b && c.block_j == a)) area += c.area;
  }
  return area;
}

// Cohesion and tensile strength act on the contact area. Face-to-face, that is the overlap of
// the two faces, whatever the blocks' corners: a block on a larger base (the base's corners
// are outside), two equal boxes stacked (corners coincide: each corner's two entries, one
// each way, must not both carry it), a box straddling two boxes (the overlap's corners are
// edge crossings on one side, a vertex of either block on the other), and a block of two
// pieces. Each total is exact up to round-off, and the areas' first moment puts their centre
// at the overlap's centroid (what a moment of the cohesion needs).
TEST(ContactArea, IsTheOverlapOfTheFacingFaces) {
  const auto box = [](const Vec3& low, const Vec3& high) {
    return geometry::boxPolyhedron({low, high});
  };
  const std::vector<double> reach(3, 0.01);
  {
    // 2 x 3 base of a block resting on a 10 x 10 slab.
    const auto blocks = blocksOf({{box({0, 0, 1}, {2, 3, 2})}, {box({-4, -4, 0}, {6, 6, 1})}});
    const auto contacts = findContacts(blocks, reach, 0.02, kNoPrevious);
    EXPECT_NEAR(areaBetween(contacts, 0, 1), 6.0, 1e-9);
    Vec3 moment = Vec3::Zero();
    for (const Contact& c : contacts) moment += c.area * c.point;
    EXPECT_NEAR(moment.x() / 6.0, 1.0, 1e-9);
    EXPECT_NEAR(moment.y() / 6.0, 1.5, 1e-9);
    // A rectangle's corners take a quarter each (symmetric: no yaw from uneven cohesion).
    for (const Contact& c : contacts) {
      if (c.area > 0.0) {
        EXPECT_NEAR(c.area, 1.5, 1e-9);
      }
    }
  }
  {
    // Two equal 1 x 1 boxes stacked: 1 m2, not 2.
    const auto blocks = blocksOf({{box({0, 0, 1}, {1, 1, 2})}, {box({0, 0, 0}, {1, 1, 1})}});
    EXPECT_NEAR(areaBetween(findContacts(blocks, reach, 0.02, kNoPrevious), 0, 1), 1.0, 1e-9);
  }
  {
    // A 2 x 1 box straddling two 1.5 x 1 boxes 0.2 m apart: overlaps 0.9 and 0.9 m2.
    const auto blocks = blocksOf({{box({0.2, 0, 1}, {2.2, 1, 2})},
                                  {box({-0.6, 0, 0}, {1.1, 1, 1})},
                                  {box({1.3, 0, 0}, {3.0, 1, 1})}});
    const auto contacts = findContacts(blocks, reach, 0.02, kNoPrevious);
    EXPECT_NEAR(areaBetween(contacts, 0, 1), 0.9, 1e-9);
    EXPECT_NEAR(areaBetween(contacts, 0, 2), 0.9, 1e-9);
  }
  {
    // A block of two pieces on a base: the pieces' faces tile its 1 x 1 bottom.
    const auto blocks = blocksOf({{box({0, 0, 1}, {0.5, 1, 2}), box({0.5, 0, 1}, {1, 1, 2})},
                                  {box({-1, -1, 0}, {2, 2, 1})}});
    EXPECT_NEAR(areaBetween(findContacts(blocks, reach, 0.02, kNoPrevious), 0, 1), 1.0, 1e-9);
  }
  {
    // Apart by more than the reach: no area (no contact).
    const auto blocks = blocksOf({{box({0, 0, 1.5}, {1, 1, 2})}, {box({0, 0, 0}, {1, 1, 1})}});
    EXPECT_EQ(areaBetween(findContacts(blocks, reach, 0.02, kNoPrevious), 0, 1), 0.0);
  }
}

}  // namespace
}  // namespace rockmass::dda3d

namespace rockmass::dda3d {
namespace {

/// A hexahedron from its 8 corners in the prism order (front face 0 1 2 3 counter-clockwise
/// seen from the front, back face 4 5 6 7 behind them), faces oriented outwards.
geometry::Polyhedron hexahedron(const std::array<Vec3, 8>& corners) {
  geometry::Polyhedron p;
  p.vertices.assign(corners.begin(), corners.end());
  p.faces = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1}, {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 5, 6, 2}};
  if (geometry::massProperties(p).volume < 0.0) {
    for (std::vector<int>& f : p.faces) std::reverse(f.begin(), f.end());
  }
  return p;
}

// Two cubes of the top layer of a landing pile (../shared/repro/dynamic-pile, blocks 621 and
// 704), side by side, their facing sides tilted 1.1 deg against each other and closing at the
// top: the top corner of the left cube comes down and across onto the right cube's top-left
// edge. Three snapshots, 2-5 ms apart, from above and beside the edge (0.8 mm above its top,
// 0.9 mm beside its side) to inside the side's plane and just above the top. In each, the
// corner must have an entry across the right cube's side: its only support. With faces taken
// as touching only within 1 deg, no entry was found in any of them, the corner sank 2 mm into
// its neighbour unseen, and the spring that found it there threw the cubes apart at 7 m/s.
TEST(NarrowPhase, ACornerComingDownOntoTheEdgeOfASideBySideNeighbourHasAnEntry) {
  struct Snapshot {
    std::array<Vec3, 8> left, right;
  };
  const std::vector<Snapshot> snapshots = {
      {{Vec3(7.25248, 8.25511, 6.01048), Vec3(8.25239, 8.26832, 6.00912),
        Vec3(8.25370, 8.27219, 7.00911), Vec3(7.25379, 8.25898, 7.01047),
        Vec3(7.23927, 9.25502, 6.00662), Vec3(8.23918, 9.26823, 6.00526),
        Vec3(8.24048, 9.27210, 7.00526), Vec3(7.24057, 9.25889, 7.00661)},
       {Vec3(8.25517, 8.26140, 6.00755), Vec3(9.25517, 8.25961, 6.00642),
        Vec3(9.25629, 8.25591, 7.00641), Vec3(8.25630, 8.25770, 7.00754),
        Vec3(8.25696, 9.26139, 6.01125), Vec3(9.25696, 9.25960, 6.01012),
        Vec3(9.25808, 9.25590, 7.01011), Vec3(8.25809, 9.25769, 7.01124)}},
      {{Vec3(7.25112, 8.25483, 6.01284), Vec3(8.25103, 8.26678, 6.00755),
        Vec3(8.25627, 8.27157, 7.00752), Vec3(7.25635, 8.25962, 7.01281),
        Vec3(7.23915, 9.25475, 6.00811), Vec3(8.23906, 9.26670, 6.00282),
        Vec3(8.24430, 9.27148, 7.00280), Vec3(7.24438, 9.25954, 7.00809)},
       {Vec3(8.25796, 8.26003, 6.00670), Vec3(9.25796, 8.26063, 6.00749),
        Vec3(9.25716, 8.25699, 7.00749), Vec3(8.25717, 8.25639, 7.00669),
        Vec3(8.25735, 9.26002, 6.01034), Vec3(9.25735, 9.26062, 6.01113),
        Vec3(9.25656, 9.25698, 7.01112), Vec3(8.25656, 9.25638, 7.01033)}},
      {{Vec3(7.24967, 8.25465, 6.01493), Vec3(8.24957, 8.26514, 6.00587),
        Vec3(8.25857, 8.27082, 7.00582), Vec3(7.25866, 8.26034, 7.01487),
        Vec3(7.23913, 9.25458, 6.00934), Vec3(8.23903, 9.26507, 6.00029),
        Vec3(8.24803, 9.27075, 7.00023), Vec3(7.24813, 9.26026, 7.00928)},
       {Vec3(8.26080, 8.25864, 6.00566), Vec3(9.26079, 8.26170, 6.00833),
        Vec3(9.25814, 8.25813, 7.00832), Vec3(8.25815, 8.25507, 7.00566),
        Vec3(8.25773, 9.25863, 6.00923), Vec3(9.25772, 9.26169, 6.01190),
        Vec3(9.25507, 9.25812, 7.01189), Vec3(8.25507, 9.25505, 7.00922)}},
  };
  for (std::size_t k = 0; k < snapshots.size(); ++k) {
    SCOPED_TRACE("snapshot " + std::to_string(k));
    const geometry::Polyhedron left = hexahedron(snapshots[k].left);
    const geometry::Polyhedron right = hexahedron(snapshots[k].right);
    const Vec3 corner = left.vertices[2];
    // The corner's signed distance to the right cube's left side (negative: inside its plane).
    Vec3 side_normal = (right.vertices[7] - right.vertices[0])
                           .cross(right.vertices[3] - right.vertices[0])
                           .normalized();
    if (side_normal.x() > 0.0) side_normal = -side_normal;  // out of the right cube
    const double beside = side_normal.dot(corner - right.vertices[0]);
    const std::vector<BlockState> blocks = blocksOf({{left}, {right}});
    // The reaches of the run (4 and 3 mm), the search depth 3 g2 l0 of the pile's scene.
    const std::vector<Contact> contacts =
        findContacts(blocks, {0.00391, 0.00274}, 0.022, kNoPrevious);
    const Contact* at_corner = nullptr;
    for (const Contact& c : contacts) {
      if ((c.point - corner).norm() < 2e-3) at_corner = &c;
    }
    ASSERT_NE(at_corner, nullptr);
    // Across the right cube's side (its normal, -x within the tilt), the gap the corner's
    // distance from that side (an edge crossing up to 1.5 mm below the corner reads it to
    // 3e-5 m: the 1.1 deg between the sides over that length).
    EXPECT_LT(std::abs(std::abs(at_corner->normal.dot(side_normal)) - 1.0), 1e-3);
    EXPECT_NEAR(at_corner->gap0, beside, 5e-5);
  }
}

}  // namespace
}  // namespace rockmass::dda3d

namespace rockmass::dda3d {
namespace {

// A vertex of a face lying on a face of b, at b's convex edge, is that face's contact
// however little deeper it sits behind it than behind b's other face there. b is a dam's
// section (base on z = 0, toe at x = 4, its downstream face sloping back at 53 degrees),
// pressed 1e-6 m into a rock block a whose top (z = 0) starts at the toe, and moved 1.5e-6 m
// downstream: a's corner at the toe is 1e-6 m behind b's base and 6e-7 m behind its slope.
// Matched to the slope by the least depth, the rock's corner pushed the dam back up its
// slope: on the Xiangjiaba model two such corners held the dam against a strength reduction
// of 6, twice its limit-equilibrium factor (docs/stability.md, "Contact points").
TEST(NarrowPhase, AVertexLyingOnAFaceAtAConvexEdgeTakesThatFace) {
  constexpr double kPress = 1e-6, kMoved = 1.5e-6;
  const geometry::Polyhedron dam = prismXZ(
      {{kMoved, -kPress}, {4 + kMoved, -kPress}, {1 + kMoved, 4 - kPress}, {kMoved, 4 - kPress}}, 0,
      1);
  // The rock: top z = 0 from the toe downstream; its upstream face (a joint) runs down
  // downstream at 18 degrees: its edge does not dive into the dam's slope, so the slope is a
  // candidate face, and the joint does not face the slope (the slope is no face-to-face
  // contact of the corner).
  const geometry::Polyhedron rock = prismXZ({{7, -1}, {10, -1}, {10, 0}, {4, 0}}, 0, 1);
  ASSERT_GT(geometry::massProperties(dam).volume, 0.0);
  ASSERT_GT(geometry::massProperties(rock).volume, 0.0);
  const Vec3 slope_normal = Vec3(4, 0, 3).normalized();
  const Vec3 corner(4, 0, 0);
  // Behind the slope by less than behind the base: the case the rule is for.
  ASSERT_NEAR(slope_normal.dot(corner - Vec3(4 + kMoved, 0, -kPress)), -6e-7, 1e-12);
  const std::vector<BlockState> blocks = blocksOf({{rock}, {dam}});
  const std::vector<Contact> contacts = findContacts(blocks, {0.01, 0.01}, 0.02, kNoPrevious);
  int at_toe = 0;
  for (const Contact& c : contacts) {
    if (c.kind != ContactKind::VertexFace || c.block_i != 0) continue;
    if ((c.point - Vec3(4, c.point.y(), 0)).norm() > 1e-12) continue;
    ++at_toe;                                // the rock's two corners at the toe (y = 0 and 1)
    EXPECT_NEAR(c.normal.z(), -1.0, 1e-12);  // the dam's base, not its slope
    EXPECT_NEAR(c.gap0, -kPress, 1e-12);
  }
  EXPECT_EQ(at_toe, 2);
}

}  // namespace
}  // namespace rockmass::dda3d

namespace rockmass::dda3d {
namespace {

/// The edge-to-edge entries of `contacts`.
std::vector<Contact> crossings(const std::vector<Contact>& contacts) {
  std::vector<Contact> out;
  for (const Contact& c : contacts) {
    if (c.kind == ContactKind::EdgeEdge) out.push_back(c);
  }
  return out;
}

// A crossing of two blocks' edges is one entry however many pieces share those edges. Block
// a is a 1 x 2 x 1 box split into two wedges by a plane through its top edge at x = 1, so that
// edge belongs to both pieces (as where a convex split of a cut block meets its surface);
// block b is a bar lying on a's top across that edge, overhanging it: its bottom edge crosses
// a's at (1, 1, 0), the bar's support beyond its inner vertex. The narrow phase finds the
// crossing from each wedge. When the wedges' copies of the edge's ends are bit for bit equal
// the two finds coincide exactly; when they differ by round-off (1e-13 m here, as the
// cutter's copies of a shared corner do) they did not, and the crossing was two entries, two
// full penalty springs. On the Xiangjiaba region 7 700 of 24 000 crossings were such copies,
// and about 450 of them went from one entry to two or back at every search of the foundation
// at rest. Two crossings 1e-6 m apart (a second bar beside the first) stay two entries.
TEST(NarrowPhase, AnEdgeCrossingSharedByTwoPiecesIsOneEntry) {
  const auto wedges = [](double round_off) {
    // (x, z) cross-sections extruded along y from 0 to 2: above and below z = x - 1.
    geometry::Polyhedron upper = prismXZ({{0, -1}, {1, 0}, {0, 0}}, 0, 2);
    geometry::Polyhedron lower = prismXZ({{0, -1}, {1, -1}, {1, 0}}, 0, 2);
    for (Vec3& v : lower.vertices) {
      if (v.x() == 1.0 && v.z() == 0.0) v.x() += round_off;  // its copies of the shared edge
    }
    return std::vector<geometry::Polyhedron>{upper, lower};
  };
  // A bar of square section (diagonals 2 h) standing on its edge along x, from x = 0.5 to 1.5
  // at y = y0.
  const auto bar = [](double y0, double h) {
    std::array<Vec3, 8> corners;
    for (int end = 0; end < 2; ++end) {
      const double x = end == 0 ? 0.5 : 1.5;
      corners[static_cast<std::size_t>(4 * end)] = Vec3(x, y0, 0.0);
      corners[static_cast<std::size_t>(4 * end + 1)] = Vec3(x, y0 + h, h);
      corners[static_cast<std::size_t>(4 * end + 2)] = Vec3(x, y0, 2 * h);
      corners[static_cast<std::size_t>(4 * end + 3)] = Vec3(x, y0 - h, h);
    }
    return hexahedron(corners);
  };
  for (const double round_off : {0.0, 1e-13}) {
    SCOPED_TRACE("copies apart by " + std::to_string(round_off));
    const std::vector<BlockState> blocks = blocksOf({wedges(round_off), {bar(1.0, 0.1)}});
    const std::vector<Contact> found =
        crossings(findContacts(blocks, {0.01, 0.01}, 0.02, kNoPrevious));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_LT((found[0].point - Vec3(1, 1, 0)).norm(), 1e-12);
    EXPECT_NEAR(std::abs(found[0].normal.z()), 1.0, 1e-12);
    EXPECT_NEAR(found[0].gap0, 0.0, 1e-12);
    // The first find (the upper wedge's) is kept: the same entry from search to search.
    EXPECT_EQ(found[0].block_i == 0 ? found[0].piece_i : found[0].piece_j, 0);
  }
  // Two thin bars side by side (touching along a line), their bottom edges 1e-6 m apart: two
  // crossings of a's edge, both kept (the copies' tolerance is 1e-9 of the pieces' sizes).
  const std::vector<BlockState> two_bars =
      blocksOf({wedges(1e-13), {bar(1.0, 5e-7), bar(1.0 + 1e-6, 5e-7)}});
  EXPECT_EQ(crossings(findContacts(two_bars, {0.01, 0.01}, 0.02, kNoPrevious)).size(), 2u);
}

}  // namespace
}  // namespace rockmass::dda3d
