// Merging the convex pieces of a block where their union is convex (blocks::coarsenPieces).
#include "blocks/piece_coarsening.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>
#include <tuple>

#include "blocks/block_merge.h"
#include "blocks/fast_cutter.h"
#include "geometry/polyhedron.h"
#include "scenarios/disc_scenes.h"
#include "tests/blocks/block_test_support.h"

namespace rockmass::blocks {
namespace {

using geometry::Box;
using geometry::Vec3;

Piece boxPiece(const Vec3& lo, const Vec3& hi, FaceSource source = {FaceKind::Disc, 7}) {
  Piece p;
  p.shape = geometry::boxPolyhedron({lo, hi});
  p.face_sources.assign(6, source);
  return p;
}

/// True when `p` lies in the closed convex piece (within `tolerance` m of its faces).
bool inPiece(const Piece& piece, const Vec3& p, double tolerance) {
  for (std::size_t f = 0; f < piece.shape.faces.size(); ++f) {
    const Vec3 n = geometry::faceNormal(piece.shape, static_cast<int>(f));
    const Vec3& a = piece.shape.vertices[static_cast<std::size_t>(piece.shape.faces[f][0])];
    if (n.dot(p - a) > tolerance) return false;
  }
  return true;
}

using test::expectValidPiece;

TEST(ConvexUnion, TwoHalvesOfABoxAreTheBoxWithTheirOwnVertices) {
  const Piece lower = boxPiece(Vec3(0, 0, 0), Vec3(2, 1, 0.5), {FaceKind::Disc, 1});
  Piece upper = boxPiece(Vec3(0, 0, 0.5), Vec3(2, 1, 1), {FaceKind::Disc, 2});
  const std::optional<Piece> u = convexUnion(lower, upper, 1e-12);
  ASSERT_TRUE(u.has_value());
  // The box: 8 corners, 6 faces, volume 2 (exact: the corners are inputs' corners).
  EXPECT_EQ(u->shape.vertices.size(), 8u);
  EXPECT_EQ(u->shape.faces.size(), 6u);
  EXPECT_DOUBLE_EQ(geometry::massProperties(u->shape).volume, 2.0);
  expectValidPiece(*u, 1e-12);
  // The vertices are copies of the inputs' (conforming with neighbours), never recomputed.
  for (const Vec3& v : u->shape.vertices) {
    const bool from_lower = std::find(lower.shape.vertices.begin(), lower.shape.vertices.end(),
                                      v) != lower.shape.vertices.end();
    const bool from_upper = std::find(upper.shape.vertices.begin(), upper.shape.vertices.end(),
                                      v) != upper.shape.vertices.end();
    EXPECT_TRUE(from_lower || from_upper);
  }
  // The bottom face comes from the lower piece, the top from the upper one.
  for (std::size_t f = 0; f < u->shape.faces.size(); ++f) {
    const Vec3 n = geometry::faceNormal(u->shape, static_cast<int>(f));
    if (n.z() < -0.5) {
      EXPECT_EQ(u->face_sources[f].id, 1);
    }
    if (n.z() > 0.5) {
      EXPECT_EQ(u->face_sources[f].id, 2);
    }
  }
}

TEST(ConvexUnion, AnLShapeOrPiecesApartHaveNone) {
  const Piece base = boxPiece(Vec3(0, 0, 0), Vec3(2, 1, 1));
  // On top of half of the base: the union is an L, not convex.
  EXPECT_FALSE(convexUnion(base, boxPiece(Vec3(0, 0, 1), Vec3(1, 1, 2)), 1e-12).has_value());
  // Side by side but 1 mm apart: no common plane.
  EXPECT_FALSE(convexUnion(base, boxPiece(Vec3(2.001, 0, 0), Vec3(3, 1, 1)), 1e-12).has_value());
  // Touching along an edge only (diagonal neighbours).
  EXPECT_FALSE(convexUnion(base, boxPiece(Vec3(2, 0, 1), Vec3(3, 1, 2)), 1e-12).has_value());
  // Two boxes on one plane whose shared faces do not overlap and leave a gap between them.
  EXPECT_FALSE(convexUnion(boxPiece(Vec3(0, 0, 0), Vec3(1, 1, 1)),
                           boxPiece(Vec3(1.5, 0, 1), Vec3(2, 1, 2)), 1e-12)
                   .has_value());
  // Equal faces, side by side: the union is a 3 x 1 x 1 box.
  const std::optional<Piece> row = convexUnion(base, boxPiece(Vec3(2, 0, 0), Vec3(3, 1, 1)), 1e-12);
  ASSERT_TRUE(row.has_value());
  EXPECT_DOUBLE_EQ(geometry::massProperties(row->shape).volume, 3.0);
  EXPECT_EQ(row->shape.vertices.size(), 8u);
}

TEST(ConvexUnion, AWedgeOnABoxIsAPrism) {
  // A wedge on the full top face of a box, its sloping side leaning inward: one convex
  // prism. The box's top corners at x = 0 lie inside the merged side x = 0 and go away.
  Piece box = boxPiece(Vec3(0, 0, 0), Vec3(1, 1, 1));
  Piece wedge;  // x from 0 to 1 at z = 1, x from 0 to 0.5 at z = 2 (side x + z/2 <= 1.5)
  wedge.shape.vertices = {Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0.5, 0, 2), Vec3(0, 0, 2),
                          Vec3(0, 1, 1), Vec3(1, 1, 1), Vec3(0.5, 1, 2), Vec3(0, 1, 2)};
  wedge.shape.faces = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1},
                       {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}};
  wedge.face_sources.assign(6, {FaceKind::Disc, 3});
  ASSERT_NEAR(geometry::massProperties(wedge.shape).volume, 0.75, 1e-15);
  // Its sloping side leans inward over the box's side x = 1: the union is convex.
  const std::optional<Piece> u = convexUnion(box, wedge, 1e-12);
  ASSERT_TRUE(u.has_value());
  EXPECT_NEAR(geometry::massProperties(u->shape).volume, 1.75, 1e-14);
  expectValidPiece(*u, 1e-12);
  // 4 bottom corners, the 2 corners of the crease at x = 1, z = 1, and the wedge's 4 top
  // corners; (0, y, 1) lie inside the side x = 0 and are gone.
  EXPECT_EQ(u->shape.vertices.size(), 10u);
  EXPECT_EQ(u->shape.faces.size(), 7u);
  // Overhanging the other way (sloping side leaning out past x = 1): not convex.
  Piece overhang = wedge;
  overhang.shape.vertices[2] = Vec3(1.5, 0, 2);
  overhang.shape.vertices[6] = Vec3(1.5, 1, 2);
  EXPECT_FALSE(convexUnion(box, overhang, 1e-12).has_value());
}

TEST(CoarsenPieces, AStackOfSlabsBecomesOnePiece) {
  Block block;
  for (int k = 0; k < 10; ++k) {
    block.pieces.push_back(boxPiece(Vec3(0, 0, 0.1 * k), Vec3(1, 1, 0.1 * (k + 1))));
  }
  const CoarseningReport r = coarsenPieces(block, 1e-12);
  EXPECT_EQ(r.pieces_before, 10);
  EXPECT_EQ(r.pieces_after, 1);
  EXPECT_EQ(r.vertices_before, 80);
  EXPECT_EQ(r.vertices_after, 8);
  ASSERT_EQ(block.pieces.size(), 1u);
  EXPECT_NEAR(geometry::massProperties(block.pieces[0].shape).volume, 1.0, 1e-14);
}

TEST(CoarsenPieces, CutAndGluedBlocksKeepTheirSolidWithFewerPieces) {
  // Fast cut of 30 random discs in a 10 m cube, glued below 20 m3 (non-convex clusters of
  // many pieces, like the Xiangjiaba blocks), then coarsened.
  DiscSceneSpec spec;
  spec.discs = 30;
  spec.seed = 3;
  const geometry::FractureNetwork network = randomDiscNetwork(spec);
  BlockModel model = cutFast(boxCutInput(network, 12));
  mergeSmallBlocks(model, 20.0);
  const BlockModel before = model;
  const CoarseningReport r = coarsenPieces(model);
  EXPECT_LT(r.pieces_after, r.pieces_before);
  EXPECT_LT(r.vertices_after, r.vertices_before);
  ASSERT_EQ(model.blocks.size(), before.blocks.size());
  const double tolerance = 1e-9 * model.domain.diagonal();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> coordinate(0.0, 10.0);
  int pieces_before = 0;
  for (std::size_t b = 0; b < model.blocks.size(); ++b) {
    const Block& old_block = before.blocks[b];
    const Block& new_block = model.blocks[b];
    pieces_before += static_cast<int>(old_block.pieces.size());
    // Volume: the pieces still add up to the block's volume (1e-9 relative: round-off of
    // the per-piece sums; the pieces themselves are checked to 1e-9 when merged).
    double volume = 0.0;
    std::set<std::tuple<double, double, double>> old_vertices;
    for (const Piece& p : old_block.pieces) {
      for (const Vec3& v : p.shape.vertices) old_vertices.insert({v.x(), v.y(), v.z()});
    }
    for (const Piece& p : new_block.pieces) {
      volume += geometry::massProperties(p.shape).volume;
      // Closed, planar faces, convex and outward within the tolerance.
      expectValidPiece(p, tolerance);
      // Every vertex is an old vertex, bit for bit.
      for (const Vec3& v : p.shape.vertices) {
        EXPECT_EQ(old_vertices.count({v.x(), v.y(), v.z()}), 1u);
      }
    }
    EXPECT_NEAR(volume, old_block.mass.volume, 1e-9 * old_block.mass.volume);
    // The same solid: random points of the block's box are in the old pieces exactly when
    // they are in the new ones (points within 1e-6 m of a face are skipped: on a face, the
    // tolerance decides).
    for (int k = 0; k < 200; ++k) {
      const Vec3 p(coordinate(rng), coordinate(rng), coordinate(rng));
      const auto in = [&](const Block& block, double slack) {
        return std::any_of(block.pieces.begin(), block.pieces.end(),
                           [&](const Piece& piece) { return inPiece(piece, p, slack); });
      };
      const bool surely_in = in(old_block, -1e-6);
      const bool maybe_in = in(old_block, 1e-6);
      if (surely_in != maybe_in) continue;
      EXPECT_EQ(in(new_block, 0.0), surely_in);
    }
  }
  EXPECT_EQ(pieces_before, r.pieces_before);
}

}  // namespace
}  // namespace rockmass::blocks
