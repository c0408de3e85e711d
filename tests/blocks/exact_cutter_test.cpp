// The exact cutter on cases with known volumes, degenerate inputs and random scenes. Every
// case checks exact volume conservation (rational sum of the piece volumes == domain volume),
// agreement with the Nef-polyhedron referee and the CGAL validation of every piece.
#include "blocks/exact_cutter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "blocks/block_validation.h"
#include "geometry/random.h"

namespace rockmass::blocks {
namespace {

using geometry::Box;
using geometry::Disc;
using geometry::FractureNetwork;
using geometry::Vec3;

const Box kCube{Vec3(0, 0, 0), Vec3(10, 10, 10)};

/// A polygon-form disc (used exactly as given) with the next id.
Disc polygonDisc(FractureNetwork& network, std::vector<Vec3> polygon) {
  Disc disc = geometry::discFromPolygon(std::move(polygon));
  disc.id = static_cast<std::int64_t>(network.discs.size()) + 1;
  network.discs.push_back(disc);
  return disc;
}

/// A square of half-side h centred at c in the plane with unit normal n.
void square(FractureNetwork& network, const Vec3& c, const Vec3& n, double h) {
  const Vec3 u = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
  const Vec3 v = n.cross(u);
  polygonDisc(network,
              {c - h * u - h * v, c + h * u - h * v, c + h * u + h * v, c - h * u + h * v});
}

/// Cuts the network in the cube with every check on; returns the sorted block volumes.
std::vector<double> cutAndCheck(const FractureNetwork& network, BlockModel* out = nullptr,
                                int max_discs = 30) {
  CutInput input;
  input.domain_box = network.domain;
  input.domain_pieces = {geometry::boxPolyhedron(network.domain)};
  input.network = &network;
  input.rock_material = 0;
  ExactCutOptions options;
  options.check_exact_volume = true;
  options.nef_referee = true;
  options.max_discs_per_region = max_discs;
  ExactCutReport report;
  BlockModel model = cutExact(input, options, &report);
  EXPECT_EQ(report.volume_conserved, std::optional<bool>(true))
      << report.rock_volume_exact << " vs " << report.domain_volume_exact;
  EXPECT_EQ(report.nef_agrees, std::optional<bool>(true));
  EXPECT_EQ(report.nef_blocks, std::optional<int>(static_cast<int>(model.blocks.size())));
  for (const BlockProblem& p : validateBlocks(model)) {
    ADD_FAILURE() << "block " << p.block << " piece " << p.piece << ": " << p.message;
  }
  std::vector<double> volumes;
  for (const Block& b : model.blocks) volumes.push_back(b.mass.volume);
  std::sort(volumes.begin(), volumes.end());
  if (out != nullptr) *out = std::move(model);
  return volumes;
}

FractureNetwork cube() {
  FractureNetwork network;
  network.domain = kCube;
  return network;
}

// Volumes below come from elementary solid geometry (boxes, prisms, tetrahedra); the
// tolerance 1e-9 m3 covers rounding the exact vertices to double.
constexpr double kTol = 1e-9;

TEST(ExactCutter, ThreeOrthogonalPersistentPlanes) {
  FractureNetwork network = cube();
  square(network, Vec3(3, 5, 5), Vec3::UnitX(), 20);
  square(network, Vec3(5, 4, 5), Vec3::UnitY(), 20);
  square(network, Vec3(5, 5, 2), Vec3::UnitZ(), 20);
  const std::vector<double> v = cutAndCheck(network);
  // Boxes of sides {3,7} x {4,6} x {2,8}.
  std::vector<double> expected;
  for (double x : {3.0, 7.0})
    for (double y : {4.0, 6.0})
      for (double z : {2.0, 8.0}) expected.push_back(x * y * z);
  std::sort(expected.begin(), expected.end());
  ASSERT_EQ(v.size(), 8u);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_NEAR(v[i], expected[i], kTol);
}

TEST(ExactCutter, DiscTooSmallToSeparateLeavesOneBlock) {
  FractureNetwork network = cube();
  square(network, Vec3(5, 5, 5), Vec3(1, 2, 3).normalized(), 2);  // wholly inside
  square(network, Vec3(0, 5, 5), Vec3::UnitY(), 3);               // enters from a face
  BlockModel model;
  const std::vector<double> v = cutAndCheck(network, &model);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_NEAR(v[0], 1000.0, kTol);
  // The crack planes split the cube into pieces that glue back into the one block across
  // faces the cracks only partly cover.
  EXPECT_GT(model.blocks[0].pieces.size(), 1u);
}

TEST(ExactCutter, TwoDiscsTogetherSeparateABlock) {
  FractureNetwork network = cube();
  // z = 5 for x < 6, and x = 6 for z > 5: the box {x < 6, z > 5} comes loose (6*10*5).
  polygonDisc(network, {Vec3(-1, -1, 5), Vec3(6, -1, 5), Vec3(6, 11, 5), Vec3(-1, 11, 5)});
  polygonDisc(network, {Vec3(6, -1, 5), Vec3(6, -1, 11), Vec3(6, 11, 11), Vec3(6, 11, 5)});
  const std::vector<double> v = cutAndCheck(network);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_NEAR(v[0], 300.0, kTol);
  EXPECT_NEAR(v[1], 700.0, kTol);
}

TEST(ExactCutter, CornerWedge) {
  FractureNetwork network = cube();
  square(network, Vec3(1, 1, 1), Vec3(1, 1, 1).normalized(), 30);  // x + y + z = 3
  const std::vector<double> v = cutAndCheck(network);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_NEAR(v[0], 27.0 / 6.0, kTol);  // corner tetrahedron with legs 3
  EXPECT_NEAR(v[1], 1000.0 - 4.5, kTol);
}

TEST(ExactCutter, DiscCoplanarWithDomainFaceCutsNothing) {
  FractureNetwork network = cube();
  square(network, Vec3(5, 5, 10), Vec3::UnitZ(), 20);
  BlockModel model;
  const std::vector<double> v = cutAndCheck(network, &model);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_NEAR(v[0], 1000.0, kTol);
  for (const Piece& p : model.blocks[0].pieces) {
    for (const FaceSource& s : p.face_sources) EXPECT_NE(s.kind, FaceKind::Disc);
  }
}

TEST(ExactCutter, DiscThroughDomainEdgeAndVertex) {
  {
    // x + y = 10 runs along two vertical edges of the cube: two triangular prisms of 500.
    FractureNetwork network = cube();
    square(network, Vec3(5, 5, 5), Vec3(1, 1, 0).normalized(), 30);
    const std::vector<double> v = cutAndCheck(network);
    ASSERT_EQ(v.size(), 2u);
    EXPECT_NEAR(v[0], 500.0, kTol);
    EXPECT_NEAR(v[1], 500.0, kTol);
  }
  {
    // x - y + z = 0 passes through the vertices (0,0,0), (0,10,10) and (10,10,0) and cuts
    // off {y > x + z}: the integral of (10 - x - z) over x + z < 10 is 1000 / 6.
    FractureNetwork network = cube();
    square(network, Vec3(0, 0, 0), Vec3(1, -1, 1).normalized(), 40);
    const std::vector<double> v = cutAndCheck(network);
    ASSERT_EQ(v.size(), 2u);
    EXPECT_NEAR(v[0], 1000.0 / 6.0, kTol);
    EXPECT_NEAR(v[1], 5000.0 / 6.0, kTol);
  }
}

TEST(ExactCutter, TwoCoplanarOverlappingDiscsSeparateTogether) {
  FractureNetwork network = cube();
  polygonDisc(network, {Vec3(-1, -1, 5), Vec3(6, -1, 5), Vec3(6, 11, 5), Vec3(-1, 11, 5)});
  polygonDisc(network, {Vec3(4, -1, 5), Vec3(11, -1, 5), Vec3(11, 11, 5), Vec3(4, 11, 5)});
  const std::vector<double> v = cutAndCheck(network);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_NEAR(v[0], 500.0, kTol);
  EXPECT_NEAR(v[1], 500.0, kTol);
}

TEST(ExactCutter, DiscsOneNanometreApart) {
  FractureNetwork network = cube();
  square(network, Vec3(5, 5, 5), Vec3::UnitZ(), 20);
  square(network, Vec3(5, 5, 5 + 1e-9), Vec3::UnitZ(), 20);
  const std::vector<double> v = cutAndCheck(network);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_NEAR(v[0], 100.0 * 1e-9, 1e-14);  // the 1e-9 m slice, relative 1e-7 of its volume
}

TEST(ExactCutter, DiscTangentToAnExistingEdge) {
  FractureNetwork network = cube();
  square(network, Vec3(5, 5, 5), Vec3::UnitZ(), 20);
  // x = 5 for z in [5, 11]: its lower edge lies exactly in the first plane.
  polygonDisc(network, {Vec3(5, -1, 5), Vec3(5, 11, 5), Vec3(5, 11, 11), Vec3(5, -1, 11)});
  const std::vector<double> v = cutAndCheck(network);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_NEAR(v[0], 250.0, kTol);
  EXPECT_NEAR(v[1], 250.0, kTol);
  EXPECT_NEAR(v[2], 500.0, kTol);
}

TEST(ExactCutter, SliverOfAspectOneToThousand) {
  FractureNetwork network = cube();
  square(network, Vec3(5, 5, 5), Vec3::UnitZ(), 20);
  // z = 5 + x / 1000: a wedge 10 m long and 1 cm high at x = 10, volume 10 * 10 * 0.01 / 2.
  square(network, Vec3(0, 5, 5), Vec3(-1e-3, 0, 1).normalized(), 20);
  const std::vector<double> v = cutAndCheck(network);
  ASSERT_EQ(v.size(), 3u);
  EXPECT_NEAR(v[0], 0.5, kTol);
  EXPECT_NEAR(v[1], 499.5, kTol);
  EXPECT_NEAR(v[2], 500.0, kTol);
}

/// Random elliptical discs (radius 2-5 m, aspect 0.6) in the cube.
FractureNetwork randomScene(std::uint64_t seed, int count) {
  FractureNetwork network = cube();
  geometry::Rng rng = geometry::makeRng(seed, 0);
  const auto u = [&] { return geometry::uniformOpen01(rng); };
  for (int i = 0; i < count; ++i) {
    Disc d;
    d.id = i + 1;
    d.center = Vec3(10 * u(), 10 * u(), 10 * u());
    const double z = 2 * u() - 1;
    const double phi = 2 * M_PI * u();
    d.normal = Vec3(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z);
    d.major =
        d.normal.cross(std::abs(d.normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).normalized();
    d.a = 2 + 3 * u();
    d.b = 0.6 * d.a;
    network.discs.push_back(d);
  }
  return network;
}

TEST(ExactCutter, RandomScenesConserveVolumeExactlyAndKeepProvenance) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const FractureNetwork network = randomScene(seed, 12);
    BlockModel model;
    // A small region limit forces many regions, so gluing across them is exercised.
    cutAndCheck(network, &model, /*max_discs=*/4);
    for (const Block& block : model.blocks) {
      for (const Piece& piece : block.pieces) {
        for (std::size_t f = 0; f < piece.face_sources.size(); ++f) {
          const FaceSource& s = piece.face_sources[f];
          if (s.kind != FaceKind::Disc) continue;
          // Provenance: every vertex of the face lies in its disc's plane and inside its
          // 24-gon (the exact polygon rounded to double: tolerance 1e-9 m).
          const Disc& disc = network.discs[static_cast<std::size_t>(s.id - 1)];
          const std::vector<Vec3> outline = disc.outline(24);
          for (const int v : piece.shape.faces[f]) {
            const Vec3& p = piece.shape.vertices[static_cast<std::size_t>(v)];
            EXPECT_NEAR(disc.normal.dot(p - disc.center), 0.0, 1e-9);
            for (std::size_t k = 0; k < outline.size(); ++k) {
              const Vec3 edge = outline[(k + 1) % outline.size()] - outline[k];
              EXPECT_GE(disc.normal.dot(edge.cross(p - outline[k])) / edge.norm(), -1e-9);
            }
          }
        }
      }
    }
  }
}

TEST(ExactCutter, RegionSplitDoesNotChangeTheBlocks) {
  // The blocks must not depend on how the domain is split into regions.
  const FractureNetwork network = randomScene(9, 14);
  const std::vector<double> one = cutAndCheck(network, nullptr, /*max_discs=*/100);
  const std::vector<double> many = cutAndCheck(network, nullptr, /*max_discs=*/3);
  ASSERT_EQ(one.size(), many.size());
  for (std::size_t i = 0; i < one.size(); ++i) EXPECT_NEAR(one[i], many[i], 1e-9 * 1000.0);
}

TEST(ExactCutter, RejectsTooFewSegments) {
  const FractureNetwork network = cube();
  CutInput input;
  input.domain_box = kCube;
  input.domain_pieces = {geometry::boxPolyhedron(kCube)};
  input.network = &network;
  input.disc_segments = 2;
  EXPECT_THROW(cutExact(input), std::invalid_argument);
}

}  // namespace
}  // namespace rockmass::blocks
