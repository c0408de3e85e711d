// Non-convex solids in the cutters: the convex decomposition of a block with concave faces
// (blocks::convexDecomposition), and both cutters on an L-shaped mesh domain, checked
// against the closed-form volumes of the L and against each other, with the exact cutter's
// Nef referee (rock minus discs as a CGAL Nef polyhedron, an independent count of blocks).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "blocks/convex_decomposition.h"
#include "blocks/exact_cutter.h"
#include "blocks/fast_cutter.h"
#include "geometry/polyhedron.h"
#include "scenarios/disc_scenes.h"

namespace rockmass::blocks {
namespace {

using geometry::Polyhedron;
using geometry::Vec3;

/// An L-shaped prism: profile (0,0) (20,0) (20,10) (10,10) (10,20) (0,20) in x-y (the
/// 20 x 20 square minus its 10 x 10 corner, 300 m2), z from 0 to `height`. Its top and bottom
/// are concave hexagons; the bottom starts at (0,20), from where a fan of triangles leaves
/// the polygon (the triangle (0,20) (10,10) (20,10) crosses the notch). With `split_edge`, the
/// profile also has the midpoint (10,0) of its first edge (a flat corner in three faces).
Polyhedron lPrism(double height, bool split_edge = false) {
  std::vector<Vec3> profile = {{0, 0, 0},   {20, 0, 0},  {20, 10, 0},
                               {10, 10, 0}, {10, 20, 0}, {0, 20, 0}};
  if (split_edge) profile.insert(profile.begin() + 1, Vec3(10, 0, 0));
  const int n = static_cast<int>(profile.size());
  Polyhedron solid;
  for (const Vec3& p : profile) solid.vertices.push_back(p);
  for (const Vec3& p : profile) solid.vertices.push_back(p + Vec3(0, 0, height));
  std::vector<int> bottom, top;
  for (int i = n - 1; i >= 0; --i) bottom.push_back(i);  // clockwise from above: outward -z
  for (int i = 0; i < n; ++i) top.push_back(n + i);
  solid.faces = {bottom, top};
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    solid.faces.push_back({i, j, n + j, n + i});
  }
  return solid;
}

/// Whether every vertex of `p` lies on or behind every face plane (1e-9 m: the pieces'
/// vertices are exact rationals rounded to double, ~1e-15 m off in a 20 m solid).
bool convex(const Polyhedron& p) {
  for (std::size_t f = 0; f < p.faces.size(); ++f) {
    const Vec3 n = geometry::faceNormal(p, static_cast<int>(f));
    const Vec3& q = p.vertices[static_cast<std::size_t>(p.faces[f][0])];
    for (const Vec3& v : p.vertices) {
      if (n.dot(v - q) > 1e-9) return false;
    }
  }
  return true;
}

TEST(ConvexDecomposition, LShapedBlockWithConcaveFacesGivesConvexPiecesOfItsVolume) {
  for (const bool split_edge : {false, true}) {
    const Polyhedron block = lPrism(10.0, split_edge);
    const std::vector<Polyhedron> pieces = convexDecomposition(block);
    // An L is not convex: at least 2 pieces (CGAL's decomposition gives 2 or 3 here).
    EXPECT_GE(pieces.size(), 2u) << split_edge;
    double volume = 0.0;
    for (const Polyhedron& p : pieces) {
      const double v = geometry::massProperties(p).volume;
      EXPECT_GT(v, 0.0);  // outward and not flat
      EXPECT_TRUE(convex(p));
      volume += v;
    }
    // 300 m2 x 10 m; integer coordinates, so round-off only.
    EXPECT_NEAR(volume, 3000.0, 1e-9 * 3000.0) << split_edge;
  }
}

/// A disc of radius `radius` through `point` with normal `normal`.
geometry::Disc disc(std::int64_t id, const Vec3& point, const Vec3& normal, double radius) {
  geometry::Disc d;
  d.id = id;
  d.center = point;
  d.normal = normal.normalized();
  d.major = d.normal.unitOrthogonal();
  d.a = d.b = radius;
  return d;
}

/// The L prism of height 20 (6000 m3) as a mesh domain cut by `network`: the surface as
/// given (concave hexagon faces) and its convex decomposition.
CutInput lDomainInput(const geometry::FractureNetwork& network, const Polyhedron& surface) {
  CutInput input;
  input.domain_box = geometry::bounds(surface);
  input.domain_surface = surface;
  input.domain_pieces = convexDecomposition(surface);
  input.network = &network;
  input.disc_segments = 16;
  input.rock_material = 0;
  return input;
}

/// Both cutters agree (issue 3: same count, volumes within 1e-9 relative, ids by blockOrder),
/// the Nef referee agrees with the exact cutter, and the blocks fill the domain (1e-9
/// relative: the fast cutter's contract; exact vertices are rounded to double).
/// `regions`: discs per region of the exact cutter (1000: one region, the referee is then
/// one Nef polyhedron of the whole L minus the discs). Returns the fast blocks.
BlockModel expectAgreement(const CutInput& input, int regions, const std::string& label) {
  ExactCutOptions options;
  options.nef_referee = true;
  options.max_discs_per_region = regions;
  ExactCutReport report;
  const BlockModel exact = cutExact(input, options, &report);
  const BlockModel fast = cutFast(input);
  EXPECT_EQ(report.nef_agrees, std::optional<bool>(true)) << label;
  EXPECT_EQ(report.nef_blocks, std::optional<int>(static_cast<int>(exact.blocks.size()))) << label;
  EXPECT_EQ(exact.blocks.size(), fast.blocks.size()) << label;
  const double domain = geometry::massProperties(input.domain_surface).volume;
  double exact_total = 0.0, fast_total = 0.0;
  for (std::size_t i = 0; i < std::min(exact.blocks.size(), fast.blocks.size()); ++i) {
    EXPECT_NEAR(exact.blocks[i].mass.volume, fast.blocks[i].mass.volume,
                1e-9 * fast.blocks[i].mass.volume)
        << label << " block " << fast.blocks[i].id;
  }
  for (const Block& b : exact.blocks) exact_total += b.mass.volume;
  for (const Block& b : fast.blocks) fast_total += b.mass.volume;
  EXPECT_NEAR(exact_total, domain, 1e-9 * domain) << label;
  EXPECT_NEAR(fast_total, domain, 1e-9 * domain) << label;
  return fast;
}

TEST(MeshDomainCut, TheLAloneIsOneBlock) {
  // The planes of the L's inner faces (x = 10, y = 10) split the exact cutter's cells inside
  // the L; nothing cuts there, so the L is one block of 6000 m3.
  geometry::FractureNetwork network;
  const Polyhedron l = lPrism(20.0);
  network.domain = geometry::bounds(l);
  const BlockModel fast = expectAgreement(lDomainInput(network, l), 1000, "no discs");
  ASSERT_EQ(fast.blocks.size(), 1u);
  EXPECT_NEAR(fast.blocks[0].mass.volume, 6000.0, 1e-9 * 6000.0);  // round-off only
}

TEST(MeshDomainCut, DiscsInTheInnerFacePlanes) {
  const Polyhedron l = lPrism(20.0);
  // A persistent disc in x = 10 (the plane of the inner face from (10,10) to (10,20)) cuts
  // off the arm [10,20] x [0,10]: 2000 and 4000 m3.
  {
    geometry::FractureNetwork network;
    network.domain = geometry::bounds(l);
    network.discs = {disc(1, {10, 10, 10}, {1, 0, 0}, 40.0)};
    const BlockModel fast = expectAgreement(lDomainInput(network, l), 1000, "x = 10");
    ASSERT_EQ(fast.blocks.size(), 2u);
    // Ids by centroid x: the [0,10] x [0,20] part first.
    EXPECT_NEAR(fast.blocks[0].mass.volume, 4000.0, 1e-9 * 4000.0);
    EXPECT_NEAR(fast.blocks[1].mass.volume, 2000.0, 1e-9 * 2000.0);
  }
  // A 3 m disc in that plane inside the L ends in the rock: it separates nothing.
  {
    geometry::FractureNetwork network;
    network.domain = geometry::bounds(l);
    network.discs = {disc(1, {10, 5, 10}, {1, 0, 0}, 3.0)};
    const BlockModel fast = expectAgreement(lDomainInput(network, l), 1000, "small x = 10");
    EXPECT_EQ(fast.blocks.size(), 1u);
  }
}

TEST(MeshDomainCut, ThreePlanesCutTheLIntoNineBlocks) {
  // x = 5 splits the L into the strip [0,5] x [0,20] and an L-shaped rest; z = 8 splits both
  // (4 blocks). The inclined plane x + y + 0.3 z = 23 (through (10,10,10)) cuts both convex
  // strip parts in two: 4 blocks from the strip. In the rest, its upper side holds the ends of
  // both arms (near (20,10) and (10,20)); they meet through the corner square
  // [5,10] x [0,10] only where x + y = 20 there exceeds 23 - 0.3 z, i.e. for z > 10. So the
  // upper rest (z in [8,20]) is cut in 2 and the lower rest (z in [0,8]) in 3: the two arm
  // ends and what lies below the plane. 4 + 2 + 3 = 9 blocks. (Where the exact cutter kept
  // the faces inside the L in the planes x = 10 and y = 10 as domain boundary, it gave more.)
  const Polyhedron l = lPrism(20.0);
  geometry::FractureNetwork network;
  network.domain = geometry::bounds(l);
  network.discs = {disc(1, {5, 5, 10}, {1, 0, 0}, 100.0), disc(2, {5, 5, 8}, {0, 0, 1}, 100.0),
                   disc(3, {10, 10, 10}, {1, 1, 0.3}, 100.0)};
  const BlockModel fast = expectAgreement(lDomainInput(network, l), 1000, "three planes");
  EXPECT_EQ(fast.blocks.size(), 9u);
}

TEST(MeshDomainCut, RandomDiscsInTheLAgree) {
  // Finite discs of radius 4-9 m in the 20 m cube around the L: many end inside the rock
  // and some straddle the notch, so blocks are non-convex and glue across the L's planes.
  const Polyhedron l = lPrism(20.0);
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    DiscSceneSpec spec;
    spec.discs = 8;
    spec.side = 20.0;
    spec.radius_min = 4.0;
    spec.radius_max = 9.0;
    spec.seed = seed;
    const geometry::FractureNetwork network = randomDiscNetwork(spec);
    const BlockModel fast =
        expectAgreement(lDomainInput(network, l), 4, "seed " + std::to_string(seed));
    EXPECT_GE(fast.blocks.size(), 1u);
  }
}

}  // namespace
}  // namespace rockmass::blocks
