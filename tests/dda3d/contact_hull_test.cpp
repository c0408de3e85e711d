// A face of a block lying on a face of another is carried by the corners of the convex hull of
// its vertex entries (keepHullCorners, DdaSettings::detection.hull_corners): the vertices of
// the block's pieces inside its faces and along their edges take no part, so the contact is
// the one a block of a single piece of the same shape has (formulation doc, "Point-to-face
// contact": a face-to-face contact is its corners' entries; Shi 1988, ch. 4).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "dda3d/contact_detection.h"
#include "dda3d/contact_hull.h"
#include "dda3d/simulation.h"
#include "geometry/polyhedron.h"
#include "scenarios/dda_scenes.h"
#include "tests/dda3d/cut_pieces.h"

namespace rockmass::dda3d {
namespace {

using geometry::Polyhedron;
using geometry::Vec3;
using testing::blocksOf;
using testing::cutCube;
using testing::kNoPrevious;

/// Twice the signed area of the triangle (a, b, c) in the xy plane.
double cross(const Vec3& a, const Vec3& b, const Vec3& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

/// True when p (xy) lies in the triangle (a, b, c) or on its boundary, within `slack` (twice an
/// area).
bool inTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, double slack) {
  const double d1 = cross(a, b, p), d2 = cross(b, c, p), d3 = cross(c, a, p);
  const bool some_negative = d1 < -slack || d2 < -slack || d3 < -slack;
  const bool some_positive = d1 > slack || d2 > slack || d3 > slack;
  return !(some_negative && some_positive);
}

/// True when p (xy) lies in the convex hull of `others` within `slack`: in a triangle of
/// three of them (Caratheodory), a brute-force check for a few points.
bool inHullOf(const Vec3& p, const std::vector<Vec3>& others, double slack) {
  for (std::size_t a = 0; a < others.size(); ++a) {
    for (std::size_t b = a + 1; b < others.size(); ++b) {
      for (std::size_t c = b + 1; c < others.size(); ++c) {
        if (inTriangle(p, others[a], others[b], others[c], slack)) return true;
      }
    }
  }
  return false;
}

/// The points of `contacts` of block i against block j whose vertex lies on a face facing j.
std::vector<Vec3> facingPoints(const std::vector<Contact>& contacts, int i, int j) {
  std::vector<Vec3> points;
  for (const Contact& c : contacts) {
    if (c.kind == ContactKind::VertexFace && c.facing_face >= 0 && c.block_i == i &&
        c.block_j == j) {
      points.push_back(c.point);
    }
  }
  return points;
}

// A cube cut into pieces by random planes, standing inside the top of another cut cube: the
// upper block's base is carried by its four corners, whatever the pieces (without the
// reduction, 9-23 of its pieces' vertices lie on it); the lower block's piece vertices under
// the upper's base keep the extreme points of their group and drop the others, each dropped
// one inside the kept ones' hull; the contact area is the whole footprint still (the area
// samples go to the nearest kept entry).
TEST(ContactHull, ACutBlockOnACutBlockStandsOnTheCornersOfItsBase) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    std::vector<Polyhedron> upper = cutCube(seed, 6), lower = cutCube(seed + 500, 6);
    for (Polyhedron& p : upper) {
      for (Vec3& v : p.vertices) v = Vec3(0.1 + 0.8 * v.x(), 0.1 + 0.8 * v.y(), v.z() + 1.0 - 1e-6);
    }
    const std::vector<BlockState> blocks = blocksOf({upper, lower});
    const std::vector<double> reach{1e-4, 1e-4};
    const std::vector<Contact> all = findContacts(blocks, reach, 1e-3, kNoPrevious);
    const std::vector<Contact> hull =
        findContacts(blocks, reach, 1e-3, kNoPrevious, nullptr, nullptr, {}, true);
    const std::vector<Vec3> base_all = facingPoints(all, 0, 1);
    const std::vector<Vec3> base = facingPoints(hull, 0, 1);
    // The cuts put vertices of the upper's pieces inside its base or on its edges.
    EXPECT_GT(base_all.size(), 4u) << "seed " << seed;
    ASSERT_EQ(base.size(), 4u) << "seed " << seed;
    for (const Vec3& p : base) {
      // The footprint's corners (0.1 or 0.9 each way; the cuts' round-off is 1e-9 m).
      EXPECT_NEAR(std::min(std::abs(p.x() - 0.1), std::abs(p.x() - 0.9)), 0.0, 1e-8);
      EXPECT_NEAR(std::min(std::abs(p.y() - 0.1), std::abs(p.y() - 0.9)), 0.0, 1e-8);
    }
    // The lower block's entries against the upper's base: the kept ones are extreme points
    // of the group, and each dropped one lies in their hull (slack: 1e-9 m on 1 m).
    const std::vector<Vec3> top_all = facingPoints(all, 1, 0);
    const std::vector<Vec3> top = facingPoints(hull, 1, 0);
    EXPECT_LE(top.size(), top_all.size());
    for (std::size_t k = 0; k < top.size(); ++k) {
      std::vector<Vec3> others = top;
      others.erase(others.begin() + static_cast<std::ptrdiff_t>(k));
      EXPECT_FALSE(inHullOf(top[k], others, -1e-9)) << "seed " << seed << " kept " << k;
    }
    for (const Vec3& p : top_all) {
      const bool kept = std::any_of(top.begin(), top.end(),
                                    [&](const Vec3& q) { return (q - p).norm() < 1e-12; });
      if (!kept) {
        EXPECT_TRUE(inHullOf(p, top, 1e-9)) << "seed " << seed;
      }
    }
    // Entries that are no face's vertices (edge crossings) are kept as they were.
    const auto crossings = [](const std::vector<Contact>& contacts) {
      return std::count_if(contacts.begin(), contacts.end(),
                           [](const Contact& c) { return c.kind == ContactKind::EdgeEdge; });
    };
    EXPECT_EQ(crossings(hull), crossings(all)) << "seed " << seed;
    double area = 0.0;
    for (const Contact& c : hull) area += c.area;
    EXPECT_NEAR(area, 0.64, 1e-6) << "seed " << seed;
  }
}

/// A vertex entry of block 0's box piece (its base, face 4, facing down) on a plane z = 0 of
/// block 1, at `p`.
Contact baseEntry(const Vec3& p, int vertex, int joint = -1) {
  Contact c;
  c.kind = ContactKind::VertexFace;
  c.block_i = 0;
  c.piece_i = 0;
  c.block_j = 1;
  c.piece_j = 0;
  c.vertex = vertex;
  c.face = 5;
  c.facing_face = 4;
  c.joint = joint;
  c.point = p;
  c.normal = Vec3::UnitZ();
  c.gap0 = p.z();
  c.foot = Vec3(p.x(), p.y(), 0.0);
  return c;
}

// Points along the base's edges a round-off (1e-12 m) outside or inside the straight edge
// are on it: each drops, whichever side its round-off put it on (an exact hull keeps those
// outside, and which of them stayed would change from search to search as the blocks' round-off
// did). Points of another joint form their own group, and a parallel plane 1 cm above is not
// the same plane.
TEST(ContactHull, RoundOffAlongAnEdgeDoesNotDecideWhichPointsStay) {
  std::vector<BlockState> blocks =
      blocksOf({{geometry::boxPolyhedron({Vec3(0, 0, 0), Vec3(2, 1, 1)})},
                {geometry::boxPolyhedron({Vec3(-1, -1, -1), Vec3(3, 2, 0)})}});
  for (const double offset : {1e-12, -1e-12}) {
    std::vector<Contact> contacts;
    const std::vector<Vec3> corners{Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(0, 1, 0)};
    for (const Vec3& p : corners) contacts.push_back(baseEntry(p, 0));
    // Along the edges, off them by the round-off; one inside the base.
    for (const double x : {0.5, 1.0, 1.5}) {
      contacts.push_back(baseEntry(Vec3(x, -offset, 0), 1));
      contacts.push_back(baseEntry(Vec3(x, 1.0 + offset, 0), 1));
    }
    contacts.push_back(baseEntry(Vec3(2.0 + offset, 0.5, 0), 1));
    contacts.push_back(baseEntry(Vec3(1.0, 0.5, 0), 1));
    const std::size_t dropped = keepHullCorners(contacts, blocks);
    EXPECT_EQ(dropped, 8u) << "offset " << offset;
    ASSERT_EQ(contacts.size(), 4u) << "offset " << offset;
    for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(contacts[k].point, corners[k]);
  }
  // Another joint's points on the same plane: their own hull.
  std::vector<Contact> joints;
  for (const double x : {0.0, 0.5, 1.0}) {
    for (const double y : {0.0, 0.5, 1.0}) joints.push_back(baseEntry(Vec3(x, y, 0), 0, 0));
  }
  for (const double x : {1.0, 1.5, 2.0}) {
    for (const double y : {0.0, 0.5, 1.0}) joints.push_back(baseEntry(Vec3(x, y, 0), 0, 1));
  }
  EXPECT_EQ(keepHullCorners(joints, blocks), 10u);  // 9 - 4 in each
  EXPECT_EQ(joints.size(), 8u);
  // Points on a plane 1 cm above (a step in block 1's surface): their own hull too.
  std::vector<Contact> step;
  for (const double x : {0.0, 0.5, 1.0}) {
    for (const double y : {0.0, 1.0}) step.push_back(baseEntry(Vec3(x, y, 0), 0));
  }
  for (const double x : {1.0, 1.5, 2.0}) {
    for (const double y : {0.0, 1.0}) {
      Contact c = baseEntry(Vec3(x, y, 0.0), 0);
      c.foot.z() = 0.01;
      c.gap0 = -0.01;
      step.push_back(c);
    }
  }
  EXPECT_EQ(keepHullCorners(step, blocks), 4u);  // the middle pair of each
}

/// A 1 m cube on a fixed slab, as one piece or cut into pieces by `cuts` random planes, under
/// gravity tilted 35 degrees (friction 30 degrees): the cube slides down the slab.
DdaModel cubeOnSlab(std::uint64_t seed, int cuts) {
  DdaModel model;
  scenes::setRock(model, 30.0);
  model.blocks.push_back(scenes::boxBlock(Vec3(-3, -3, -1), Vec3(3, 3, 0), 0, true));
  DdaBlock cube = scenes::boxBlock(Vec3(0, 0, 0), Vec3(1, 1, 1), 0, false);
  if (cuts > 0) cube.pieces = cutCube(seed, cuts);
  model.blocks.push_back(cube);
  const double a = scenes::radians(35.0);
  model.gravity = Vec3(9.81 * std::sin(a), 0.0, -9.81 * std::cos(a));
  return model;
}

// The same cube as one piece and cut into 8-14 pieces by four random planes slides the same
// way. The whole cube's centroid moves 4.94 mm in 0.1 s, 1/2 g (sin 35 - cos 35 tan 30) t^2.
// With the hull's corners the cut cubes' bases are the same four corner springs, and they
// follow it within 1e-9 m (the cuts' round-off in the corners; measured 6e-17 m at most).
// With every vertex of the pieces an entry (the default), their bases have 8-10 springs that
// share the load otherwise, and some may open in the first steps: the friction, paired with
// each step's normal force (friction_tolerance), gives the same slide within 0.1 %, as the
// whole cube's own check (measured 0.003-0.045 %; a round-off floor on each contact's friction
// check, since replaced by its block's measure, left seed 5 0.31 % short). Solved with the normal
// force of the iteration before (friction_tolerance 1), the whole cube slid 0.2 % too far and
// the cut ones 0.3 % short to 8.5 % too far: the friction of their first steps, a load of f
// times the last normal force while that force rose to 1.5 weights and fell back, was a
// different impulse from f times the normal one, by whichever springs changed state.
TEST(ContactHull, ACubeCutIntoPiecesSlidesAsTheWholeCube) {
  DdaSettings settings;
  settings.kinematics = Kinematics::Rigid;
  settings.time_step = 2e-3;
  const auto slide = [&](std::uint64_t seed, int cuts, bool hull, double friction_tolerance) {
    DdaSettings s = settings;
    s.detection.hull_corners = hull;
    s.friction_tolerance = friction_tolerance;
    Simulation sim(cubeOnSlab(seed, cuts), s);
    const Vec3 start = sim.blocks()[1].centroid;
    for (int k = 0; k < 50; ++k) sim.step();
    return Vec3(sim.blocks()[1].centroid - start);
  };
  const double tolerance = DdaSettings{}.friction_tolerance;
  const Vec3 whole = slide(0, 0, false, tolerance);
  const double expected = 0.5 * 9.81 *
                          (std::sin(scenes::radians(35.0)) -
                           std::cos(scenes::radians(35.0)) * std::tan(scenes::radians(30.0))) *
                          0.1 * 0.1;
  // Limit equilibrium of a block on a plane (the slide's acceleration): within 0.1 % as the
  // incline's sliding test at 0.3 s (measured 0.003 %).
  EXPECT_NEAR(whole.x(), expected, 1e-3 * expected);
  EXPECT_LE((slide(0, 0, true, tolerance) - whole).norm(), 1e-12);  // one piece: no reduction
  double largest_every = 0.0, largest_lagged = 0.0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const Vec3 hull = slide(seed, 4, true, tolerance);
    EXPECT_LE((hull - whole).norm(), 1e-9)
        << "seed " << seed << ": " << hull.transpose() << " against " << whole.transpose();
    const Vec3 every = slide(seed, 4, false, tolerance);
    EXPECT_LE((every - whole).norm(), 1e-3 * expected)
        << "seed " << seed << ": " << every.transpose() << " against " << whole.transpose();
    largest_every = std::max(largest_every, (every - whole).norm());
    largest_lagged = std::max(largest_lagged, (slide(seed, 4, false, 1.0) - whole).norm());
  }
  // The test would see the pieces' springs: without the reduction the cut cubes move
  // differently (measured up to 2.2e-6 m, seed 6), and the friction one iteration late
  // (measured 1.7e-5 to 4.1e-4 m).
  EXPECT_GT(largest_every, 1e-6);
  EXPECT_GT(largest_lagged, 3e-3 * expected);
}

}  // namespace
}  // namespace rockmass::dda3d
