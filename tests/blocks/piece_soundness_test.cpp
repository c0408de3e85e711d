// Sound pieces (piece_soundness.h): degenerate inputs that make slivers and near-duplicate
// vertices give, through both cutters, pieces with no volume, vertex distance or face area
// below the tolerances (findDegeneratePieces), the same blocks in both cutters, and
// conserved volume; soundPiece itself on hand-made pieces.
#include "blocks/piece_soundness.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "blocks/block_validation.h"
#include "blocks/exact_cutter.h"
#include "blocks/fast_cutter.h"
#include "geometry/disc.h"
#include "scenarios/disc_scenes.h"
#include "tests/blocks/block_test_support.h"

namespace rockmass::blocks {
namespace {

using geometry::Disc;
using geometry::FractureNetwork;
using geometry::Polyhedron;
using geometry::Vec3;

using test::circle;
using test::cubeNetwork;
using test::sortedVolumes;
using test::totalVolume;

/// Both cuts of a network, with their soundness reports.
struct BothCuts {
  BlockModel exact;
  BlockModel fast;
  ExactCutReport exact_report;
  FastCutReport fast_report;
  explicit BothCuts(const FractureNetwork& network) {
    const CutInput input = boxCutInput(network);
    exact = cutExact(input, {}, &exact_report);
    fast = cutFast(input, &fast_report);
  }
};

/// Every emitted piece is sound and valid, in both cutters; they give the same blocks.
void expectSoundAndAgreeing(const BothCuts& cuts) {
  const SoundnessTolerances tolerances = soundnessTolerances(cuts.exact.domain);
  for (const BlockModel* model : {&cuts.exact, &cuts.fast}) {
    for (const BlockProblem& p : findDegeneratePieces(*model, tolerances)) {
      ADD_FAILURE() << "block " << p.block << " piece " << p.piece << ": " << p.message;
    }
    for (const BlockProblem& p : validateBlocks(*model)) {
      ADD_FAILURE() << "block " << p.block << " piece " << p.piece << ": " << p.message;
    }
    const PieceMeasures m = measurePieces(*model);
    EXPECT_GE(m.min_volume, tolerances.volume);
    EXPECT_GE(m.min_vertex_distance, tolerances.distance);
    EXPECT_GE(m.min_face_area, tolerances.area);
  }
  ASSERT_EQ(cuts.exact.blocks.size(), cuts.fast.blocks.size());
  const std::vector<double> e = sortedVolumes(cuts.exact);
  const std::vector<double> f = sortedVolumes(cuts.fast);
  // Issue 3: the two cutters agree on volumes within 1e-9 relative.
  for (std::size_t i = 0; i < e.size(); ++i) EXPECT_NEAR(e[i], f[i], 1e-9 * f[i]) << i;
}

TEST(PieceSoundness, PlaneGrazingACornerOfThreePlanesFoldsTheSliver) {
  // x = 5, y = 5, z = 5 make 8 octants; x + y + z = 15 + eps passes eps / sqrt(3) from their
  // common corner. It cuts 6 of the 7 octants it meets in two (the octant x, y, z < 5 lies
  // below it), and from the octant x, y, z > 5 only the tetrahedron with legs eps: volume
  // eps^3 / 6 = 1.7e-13 m3, below the volume tolerance 1e-15 x 1000 m3, a block of its own.
  // Sound: it is folded away, 1 + 6 x 2 + 1 = 14 blocks remain.
  const double eps = 1e-4;
  const BothCuts cuts(
      cubeNetwork({circle({5, 5, 5}, Vec3::UnitX()), circle({5, 5, 5}, Vec3::UnitY()),
                   circle({5, 5, 5}, Vec3::UnitZ()), circle({5, 5, 5 + eps}, Vec3(1, 1, 1))}));
  expectSoundAndAgreeing(cuts);
  EXPECT_EQ(cuts.exact.blocks.size(), 14u);
  EXPECT_EQ(cuts.exact_report.soundness.folded_pieces, 1);
  EXPECT_EQ(cuts.fast_report.soundness.folded_pieces, 1);
  // The folded tetrahedron, computed from coordinates near 5 m: 1e-15 m of round-off on
  // 1e-4 m legs is 1e-11 relative per leg.
  EXPECT_NEAR(cuts.exact_report.soundness.folded_volume, eps * eps * eps / 6.0, 1e-9 * 1.7e-13);
  // Volume conservation: the blocks miss exactly the folded sliver (its block vanished),
  // up to the round-off of summing 14 volumes of 100 m3 (1e-12 relative).
  EXPECT_NEAR(totalVolume(cuts.exact) + cuts.exact_report.soundness.folded_volume, 1000.0, 1e-10);
  EXPECT_NEAR(totalVolume(cuts.fast) + cuts.fast_report.soundness.folded_volume, 1000.0, 1e-10);
}

TEST(PieceSoundness, NearlyCoplanarDiscsLeaveNoWedgeSliver) {
  // z = 5 and a plane through (5, 5, 5) tilted by 1e-15 rad about the y axis: between them,
  // two wedges 5 m long and at most 5e-15 m thick (volume 10 x 5 x 5e-15 / 2 = 1.25e-13 m3
  // each, below the 1e-12 m3 tolerance). The exact cutter makes them (rationally); the fast
  // cutter puts both discs in one plane. Sound, both give the two halves only, each 500 m3
  // within the wedges' volume.
  const double angle = 1e-15;
  const BothCuts cuts(cubeNetwork({circle({5, 5, 5}, Vec3::UnitZ()),
                                   circle({5, 5, 5}, Vec3(std::sin(angle), 0, std::cos(angle)))}));
  expectSoundAndAgreeing(cuts);
  ASSERT_EQ(cuts.exact.blocks.size(), 2u);
  for (const Block& b : cuts.exact.blocks) EXPECT_NEAR(b.mass.volume, 500.0, 1e-9);
  EXPECT_NEAR(totalVolume(cuts.exact) + cuts.exact_report.soundness.folded_volume, 1000.0, 1e-10);
}

TEST(PieceSoundness, FoldedSliverInsideABlockKeepsTheBlockMass) {
  // As the corner case, but the grazing plane is a disc of radius 2 m centred on the far
  // side of the corner: it covers the sliver's face but leaves the x, y, z > 5 octant's
  // rest whole around it, so the sliver is glued to its octant. Folding it must keep the
  // octant's block volume 125 m3 (block.folded_volume), not lose the sliver.
  const double eps = 1e-4;
  const Vec3 n = Vec3(1, 1, 1).normalized();
  const Vec3 corner(5, 5, 5 + eps);
  // A disc in the grazing plane whose edge passes through the sliver's inside: it covers the
  // corner region partly, so the sliver's face is fictitious there.
  Disc partial = circle(corner + 0.5 * n.unitOrthogonal(), n, 0.5 + 0.5 * eps);
  const BothCuts cuts(
      cubeNetwork({circle({5, 5, 5}, Vec3::UnitX()), circle({5, 5, 5}, Vec3::UnitY()),
                   circle({5, 5, 5}, Vec3::UnitZ()), partial}));
  expectSoundAndAgreeing(cuts);
  ASSERT_EQ(cuts.exact.blocks.size(), 8u);  // the partial disc separates nothing
  EXPECT_GE(cuts.exact_report.soundness.folded_pieces, 1);
  double folded = 0.0;
  for (const Block& b : cuts.exact.blocks) {
    // Each octant keeps its 125 m3 (the cube's round-off, 1e-12 relative).
    EXPECT_NEAR(b.mass.volume, 125.0, 1e-10) << b.id;
    folded += b.folded_volume;
  }
  EXPECT_NEAR(folded, cuts.exact_report.soundness.folded_volume, 1e-20);
  EXPECT_NEAR(totalVolume(cuts.exact), 1000.0, 1e-10);
}

/// The unit cube with corner (1, 1, 1) cut off by the plane x + y + z = 3 - t: 10
/// vertices, 7 faces (the last one the small triangle).
Piece truncatedCube(double t) {
  Piece piece;
  Polyhedron& p = piece.shape;
  p.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0},     {0, 1, 0},     {0, 0, 1},
                {1, 0, 1}, {0, 1, 1}, {1, 1, 1 - t}, {1, 1 - t, 1}, {1 - t, 1, 1}};
  p.faces = {{0, 3, 2, 1}, {4, 5, 8, 9, 6}, {0, 1, 5, 4}, {3, 6, 9, 7, 2},
             {0, 4, 6, 3}, {1, 2, 7, 8, 5}, {7, 9, 8}};
  for (int f = 0; f < 7; ++f) piece.face_sources.push_back({FaceKind::Disc, f});
  return piece;
}

TEST(PieceSoundness, TinyCornerFaceIsMergedBackIntoTheCorner) {
  // A corner cut off 1e-12 m deep in a 1 m piece: its three new vertices lie 1.4e-12 m
  // apart, below the distance tolerance of a 1 m domain (1.7e-7 m). They merge into one,
  // the triangle disappears, the other faces keep their order and provenance.
  const Piece piece = truncatedCube(1e-12);
  ASSERT_NEAR(geometry::massProperties(piece.shape).volume, 1.0, 1e-12);
  const SoundnessTolerances tolerances = soundnessTolerances({Vec3::Zero(), Vec3::Ones()});
  SoundPieceReport report;
  const std::optional<SoundPiece> sound = soundPiece(piece, tolerances, &report);
  ASSERT_TRUE(sound);
  EXPECT_EQ(report.merged_vertices, 2);
  EXPECT_EQ(report.removed_faces, 1);
  EXPECT_FALSE(report.unrepaired);
  EXPECT_EQ(sound->piece.shape.vertices.size(), 8u);
  ASSERT_EQ(sound->piece.shape.faces.size(), 6u);
  EXPECT_EQ(sound->face_origin, (std::vector<int>{0, 1, 2, 3, 4, 5}));
  for (std::size_t f = 0; f < 6; ++f)
    EXPECT_EQ(sound->piece.face_sources[f].id, static_cast<int>(f));
  // The corner returns to within 1e-12 m of (1, 1, 1): the volume is the cube's.
  EXPECT_NEAR(geometry::massProperties(sound->piece.shape).volume, 1.0, 1e-11);
}

TEST(PieceSoundness, TinyPieceIsFoldedAndThinSlabIsKept) {
  const SoundnessTolerances tolerances = soundnessTolerances({Vec3::Zero(), Vec3::Constant(10)});
  // A tetrahedron with legs 1e-5 m: 1.7e-16 m3, below 1e-15 x 1000 m3: folded.
  Piece tiny;
  tiny.shape.vertices = {{5, 5, 5}, {5 + 1e-5, 5, 5}, {5, 5 + 1e-5, 5}, {5, 5, 5 + 1e-5}};
  tiny.shape.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  tiny.face_sources.assign(4, {});
  EXPECT_FALSE(soundPiece(tiny, tolerances));
  // A 10 x 10 x 1e-9 m slab (issue 3: two discs 1e-9 m apart): its vertices lie 1e-9 m
  // apart, but merging them would flatten it (volume 1e-7 m3 -> 0), so it stays as it is.
  Piece slab;
  slab.shape = geometry::boxPolyhedron({Vec3(0, 0, 5), Vec3(10, 10, 5 + 1e-9)});
  slab.face_sources.assign(6, {});
  SoundPieceReport report;
  const std::optional<SoundPiece> kept = soundPiece(slab, tolerances, &report);
  ASSERT_TRUE(kept);
  EXPECT_TRUE(report.unrepaired);
  EXPECT_EQ(kept->piece.shape.vertices, slab.shape.vertices);
  EXPECT_EQ(kept->piece.shape.faces, slab.shape.faces);
}

}  // namespace
}  // namespace rockmass::blocks
