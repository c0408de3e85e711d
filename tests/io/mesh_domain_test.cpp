// Mesh domains: an L-shaped prism read with assimp and checked with CGAL, its convex
// decomposition (blocks::convexDecomposition), the blocks cut from it, and the errors that
// name a bad mesh; end to end through `rockmass blocks` with a mesh domain and a block mesh.
#include "io/mesh_domain.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "blocks/convex_decomposition.h"
#include "blocks/exact_cutter.h"
#include "blocks/fast_cutter.h"
#include "geometry/disc.h"
#include "io/block_mesh.h"
#include "io/input_error.h"
#include "tests/support/test_support.h"

namespace rockmass::io {
namespace {

namespace fs = std::filesystem;
using geometry::Vec3;

/// An L-shaped prism: profile (0,0) (20,0) (20,10) (10,10) (10,20) (0,20) in x-y, z from -10
/// to 0. Volume (400 - 100) m2 x 10 m = 3000 m3. With `top == false` the top face is missing
/// (6 border edges).
std::string lPrismObj(bool top = true) {
  std::string obj =
      "v 0 0 -10\nv 20 0 -10\nv 20 10 -10\nv 10 10 -10\nv 10 20 -10\nv 0 20 -10\n"
      "v 0 0 0\nv 20 0 0\nv 20 10 0\nv 10 10 0\nv 10 20 0\nv 0 20 0\n"
      "f 6 5 4 3 2 1\n";  // bottom, seen from below: clockwise from above
  if (top) obj += "f 7 8 9 10 11 12\n";
  for (int i = 0; i < 6; ++i) {
    const int a = i + 1, b = (i + 1) % 6 + 1;
    obj += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(b + 6) + " " +
           std::to_string(a + 6) + "\n";
  }
  return obj;
}

TEST(MeshDomain, LPrismReadsWithItsVolumeAndBounds) {
  test::TempDir dir("mesh_domain_l");
  const fs::path obj = test::writeFile(dir.path() / "l.obj", lPrismObj());
  const MeshDomain domain = readMeshDomain(obj, "scene.yaml");
  EXPECT_NEAR(domain.volume, 3000.0, 1e-9);  // closed form above; round-off only
  EXPECT_EQ(domain.bounds.min, Vec3(0, 0, -10));
  EXPECT_EQ(domain.bounds.max, Vec3(20, 20, 0));
  // Triangulated by CGAL: 2 hexagons x 4 + 6 quads x 2 triangles.
  EXPECT_EQ(domain.surface.faces.size(), 20u);
}

TEST(MeshDomain, ConvexDecompositionOfTheLIsConvexAndKeepsTheVolume) {
  test::TempDir dir("mesh_domain_cd");
  const MeshDomain domain =
      readMeshDomain(test::writeFile(dir.path() / "l.obj", lPrismObj()), "scene.yaml");
  const std::vector<geometry::Polyhedron> pieces = blocks::convexDecomposition(domain.surface);
  // An L is not convex: at least 2 pieces.
  EXPECT_GE(pieces.size(), 2u);
  double volume = 0.0;
  for (const geometry::Polyhedron& p : pieces) {
    const double v = geometry::massProperties(p).volume;
    EXPECT_GT(v, 0.0);  // outward, not degenerate
    volume += v;
    // Convex: every vertex on or behind every face plane (1e-9 m: the double rounding of
    // exact vertices of a 20 m solid is ~1e-15 m).
    for (std::size_t f = 0; f < p.faces.size(); ++f) {
      const Vec3 n = geometry::faceNormal(p, static_cast<int>(f));
      const Vec3& q = p.vertices[static_cast<std::size_t>(p.faces[f][0])];
      for (const Vec3& v2 : p.vertices) EXPECT_LE(n.dot(v2 - q), 1e-9);
    }
  }
  EXPECT_NEAR(volume, 3000.0, 1e-9);  // integer-coordinate pieces: round-off only
}

/// A large disc in the plane through `point` with normal `normal` (crosses the whole L).
geometry::Disc plane(const Vec3& point, const Vec3& normal) {
  geometry::Disc d;
  d.center = point;
  d.normal = normal.normalized();
  d.major = d.normal.unitOrthogonal();
  d.a = d.b = 100.0;
  return d;
}

TEST(MeshDomain, BlocksOfTheLSumToItsVolume) {
  test::TempDir dir("mesh_domain_cut");
  const MeshDomain domain =
      readMeshDomain(test::writeFile(dir.path() / "l.obj", lPrismObj()), "scene.yaml");
  geometry::FractureNetwork network;
  network.domain = domain.bounds;
  // x = 5 cuts both arms' stem; z = -4 cuts everything; an inclined plane through the
  // corner (10, 10) cuts the re-entrant part.
  network.discs = {plane({5, 5, -5}, {1, 0, 0}), plane({5, 5, -4}, {0, 0, 1}),
                   plane({10, 10, -5}, {1, 1, 0.3})};
  for (std::size_t i = 0; i < network.discs.size(); ++i) network.discs[i].id = i + 1;
  blocks::CutInput input;
  input.domain_box = domain.bounds;
  input.domain_surface = domain.surface;
  input.domain_pieces = blocks::convexDecomposition(domain.surface);
  input.network = &network;
  input.rock_material = 0;
  const blocks::BlockModel fast = blocks::cutFast(input);
  double total = 0.0;
  for (const blocks::Block& b : fast.blocks) total += b.mass.volume;
  // x = 5 splits the L in 2, z = -4 doubles that: 4. The inclined plane
  // x + y + 0.3 z = 18.5 cuts each of the 4 in two connected parts: in the L-shaped rest its
  // upper side reaches both arm ends, which meet through the corner (10,10), where
  // x + y = 20 > 18.5 - 0.3 z for z > -5, a height range both z parts reach. 8 blocks.
  EXPECT_EQ(fast.blocks.size(), 8u);
  EXPECT_NEAR(total, 3000.0, 1e-9 * 3000.0);  // the fast cutter's 1e-9 relative contract
  // The exact cutter on the triangulated surface (coplanar triangles are one plane), its Nef
  // referee an independent count.
  blocks::ExactCutOptions options;
  options.nef_referee = true;
  blocks::ExactCutReport report;
  const blocks::BlockModel exact = blocks::cutExact(input, options, &report);
  EXPECT_EQ(report.nef_agrees, std::optional<bool>(true));
  ASSERT_EQ(exact.blocks.size(), fast.blocks.size());
  double exact_total = 0.0;
  for (std::size_t i = 0; i < exact.blocks.size(); ++i) {
    // Same blocks in the same order (blockOrder), volumes within 1e-9 relative (issue 3).
    EXPECT_NEAR(exact.blocks[i].mass.volume, fast.blocks[i].mass.volume,
                1e-9 * fast.blocks[i].mass.volume);
    exact_total += exact.blocks[i].mass.volume;
  }
  EXPECT_NEAR(exact_total, 3000.0, 1e-9 * 3000.0);  // exact vertices rounded to double
}

/// The InputError text of readMeshDomain on `text` saved as `name` ("" when accepted).
std::string errorOf(const std::string& name, const std::string& text) {
  test::TempDir dir("mesh_domain_bad");
  try {
    readMeshDomain(test::writeFile(dir.path() / name, text), "scene.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MeshDomain, BadMeshesAreNamedWithTheirProblem) {
  EXPECT_EQ(errorOf("open.obj", lPrismObj(false)),
            "scene.yaml: domain.mesh: open.obj is not closed: 6 border edges");
  // The top face reversed: its 6 edges run the same way as in the side faces.
  std::string flipped = lPrismObj(false) + "f 12 11 10 9 8 7\n";
  EXPECT_EQ(errorOf("flipped.obj", flipped),
            "scene.yaml: domain.mesh: flipped.obj is not consistently oriented: 6 edges run "
            "the same way in both faces");
  // Every face reversed: closed and consistent but inward.
  std::string inward;
  for (const std::string& line : {std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"),
                                  std::string("f 1 2 3\nf 1 4 2\nf 2 4 3\nf 1 3 4\n")}) {
    inward += line;  // a tetrahedron with all faces facing in
  }
  EXPECT_EQ(errorOf("inward.obj", inward),
            "scene.yaml: domain.mesh: inward.obj is oriented inward (reverse its faces)");
  EXPECT_EQ(errorOf("empty.obj", "# nothing\n").rfind("scene.yaml: domain.mesh: empty.obj ", 0),
            0u);
}

}  // namespace
}  // namespace rockmass::io
