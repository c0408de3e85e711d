// Gluing small blocks to a neighbour before the DDA (blocks::mergeSmallBlocks).
#include "blocks/block_merge.h"

#include <gtest/gtest.h>

#include "geometry/polyhedron.h"

namespace rockmass::blocks {
namespace {

using geometry::Vec3;

/// A row of boxes along x, each `widths[i]` long, 1 x 1 in y and z, of `materials[i]`; the
/// adjacency of neighbours in the row has area 1 m2.
BlockModel row(const std::vector<double>& widths, const std::vector<int>& materials) {
  BlockModel model;
  double x = 0.0;
  for (std::size_t i = 0; i < widths.size(); ++i) {
    Block b;
    b.id = static_cast<int>(i) + 1;
    b.material = materials[i];
    Piece p;
    p.shape = geometry::boxPolyhedron({Vec3(x, 0, 0), Vec3(x + widths[i], 1, 1)});
    p.face_sources.assign(6, {});
    b.mass = geometry::massProperties(p.shape);
    b.bounds = geometry::bounds(p.shape);
    b.pieces.push_back(p);
    model.blocks.push_back(b);
    if (i > 0) model.adjacency.push_back({b.id - 1, b.id, 1.0, {FaceKind::Disc, 0}});
    x += widths[i];
  }
  model.domain_volume = x;
  return model;
}

TEST(MergeSmallBlocks, GluesEachSmallBlockToItsNeighbourAndKeepsTheVolume) {
  // 0.1 is glued to 2 (its only neighbour); 0.3 shares 1 m2 with both 2 and 5 (ties: the
  // lower index, 2); the glued 2 + 0.1 + 0.3 = 2.4 is above the threshold.
  BlockModel model = row({0.1, 2.0, 0.3, 5.0, 0.2}, {0, 0, 0, 0, 0});
  const MergeReport r = mergeSmallBlocks(model, 1.0);
  EXPECT_EQ(r.merged, 3);
  EXPECT_EQ(r.blocks_after, 2);
  EXPECT_EQ(r.left_small, 0);
  EXPECT_NEAR(r.merged_volume, 0.6, 1e-12);
  ASSERT_EQ(model.blocks.size(), 2u);
  EXPECT_NEAR(model.blocks[0].mass.volume, 2.4, 1e-12);  // 0.1 + 2.0 + 0.3
  EXPECT_NEAR(model.blocks[1].mass.volume, 5.2, 1e-12);  // 5.0 + 0.2
  EXPECT_EQ(model.blocks[0].pieces.size(), 3u);
  EXPECT_EQ(model.blocks[0].id, 1);
  EXPECT_EQ(model.blocks[1].id, 2);
  // The bounds are the union: x from 0 to 2.4.
  EXPECT_DOUBLE_EQ(model.blocks[0].bounds.min.x(), 0.0);
  EXPECT_DOUBLE_EQ(model.blocks[0].bounds.max.x(), 2.4);
  // One adjacency left, between the two glued groups, with the 1 m2 of their shared face.
  ASSERT_EQ(model.adjacency.size(), 1u);
  EXPECT_EQ(model.adjacency[0].block_a, 1);
  EXPECT_EQ(model.adjacency[0].block_b, 2);
  EXPECT_DOUBLE_EQ(model.adjacency[0].area, 1.0);
}

TEST(MergeSmallBlocks, KeepsEveryFacesSource) {
  // Each face remembers what made it (the DDA takes a contact's joint from it): after gluing,
  // every piece of a glued block has the face sources it had, face by face, including the
  // faces now inside the glued block.
  BlockModel model = row({0.1, 2.0, 0.3}, {0, 0, 0});
  for (std::size_t b = 0; b < model.blocks.size(); ++b) {
    std::vector<FaceSource>& sources = model.blocks[b].pieces[0].face_sources;
    for (std::size_t f = 0; f < sources.size(); ++f) {
      sources[f] = {
          f % 3 == 0 ? FaceKind::Disc : (f % 3 == 1 ? FaceKind::Boundary : FaceKind::Structure),
          static_cast<int>(10 * b + f)};
    }
  }
  const BlockModel before = model;
  mergeSmallBlocks(model, 1.0);
  ASSERT_EQ(model.blocks.size(), 1u);
  ASSERT_EQ(model.blocks[0].pieces.size(), 3u);
  // The pieces in the order of their original blocks (ids 1, 2, 3).
  for (std::size_t p = 0; p < 3; ++p) {
    EXPECT_EQ(model.blocks[0].pieces[p].face_sources, before.blocks[p].pieces[0].face_sources)
        << "piece " << p;
    EXPECT_EQ(model.blocks[0].pieces[p].shape.vertices, before.blocks[p].pieces[0].shape.vertices);
  }
}

TEST(MergeSmallBlocks, NeverGluesAcrossMaterials) {
  // The small block 0.5 of material 1 touches only material-0 blocks: it stays, reported.
  BlockModel model = row({2.0, 0.5, 3.0}, {0, 1, 0});
  const MergeReport r = mergeSmallBlocks(model, 1.0);
  EXPECT_EQ(r.merged, 0);
  EXPECT_EQ(r.left_small, 1);
  EXPECT_EQ(model.blocks.size(), 3u);
}

TEST(MergeSmallBlocks, AcrossMaterialsGluesABlockWithNoNeighbourOfItsMaterial) {
  // The 0.5 m3 block of material 1 between two blocks of other materials (a slab sliver
  // between two joints): with across_materials it joins the one it shares the most area with
  // (2 m2 against 1: the later block, of material 0) and takes that block's material, not
  // its own, though it is the glued block's lowest member; the volume is kept.
  BlockModel model = row({2.0, 0.5, 3.0}, {2, 1, 0});
  model.adjacency[1].area = 2.0;
  const MergeReport r = mergeSmallBlocks(model, 1.0, true);
  EXPECT_EQ(r.merged, 1);
  EXPECT_EQ(r.merged_across, 1);
  EXPECT_NEAR(r.merged_across_volume, 0.5, 1e-12);
  EXPECT_EQ(r.left_small, 0);
  ASSERT_EQ(model.blocks.size(), 2u);
  EXPECT_EQ(model.blocks[0].material, 2);  // untouched
  EXPECT_EQ(model.blocks[1].material, 0);
  EXPECT_NEAR(model.blocks[1].mass.volume, 3.5, 1e-12);
  EXPECT_EQ(model.blocks[1].pieces.size(), 2u);
  // A tie of 1 m2 on both sides: the lower index.
  BlockModel tie = row({2.0, 0.5, 3.0}, {2, 1, 0});
  mergeSmallBlocks(tie, 1.0, true);
  ASSERT_EQ(tie.blocks.size(), 2u);
  EXPECT_EQ(tie.blocks[0].material, 2);
  EXPECT_NEAR(tie.blocks[0].mass.volume, 2.5, 1e-12);
}

TEST(MergeSmallBlocks, AcrossMaterialsChainsAndCountsEachCutBlockOnce) {
  // Two 0.3 m3 blocks of material 1 beside a 5 m3 block of material 0: the first joins the
  // second (its own material; 0.6 m3, still small), which then has no neighbour of material 1
  // and joins the material-0 block. Both cut blocks end in a block of material 0: merged 2,
  // 0.6 m3, both across.
  BlockModel model = row({0.3, 0.3, 5.0}, {1, 1, 0});
  const MergeReport r = mergeSmallBlocks(model, 1.0, true);
  EXPECT_EQ(r.merged, 2);
  EXPECT_NEAR(r.merged_volume, 0.6, 1e-12);
  EXPECT_EQ(r.merged_across, 2);
  EXPECT_NEAR(r.merged_across_volume, 0.6, 1e-12);
  ASSERT_EQ(model.blocks.size(), 1u);
  EXPECT_EQ(model.blocks[0].material, 0);
  EXPECT_NEAR(model.blocks[0].mass.volume, 5.6, 1e-12);
}

TEST(MergeSmallBlocks, AcrossMaterialsStillPrefersItsOwnMaterial) {
  // The 0.5 m3 block of material 1 shares 4 m2 with the material-0 block and 1 m2 with the
  // material-1 block: a neighbour of its own material wins over a larger face.
  BlockModel model = row({2.0, 0.5, 3.0}, {0, 1, 1});
  model.adjacency[0].area = 4.0;
  const MergeReport r = mergeSmallBlocks(model, 1.0, true);
  EXPECT_EQ(r.merged, 1);
  EXPECT_EQ(r.merged_across, 0);
  ASSERT_EQ(model.blocks.size(), 2u);
  EXPECT_NEAR(model.blocks[0].mass.volume, 2.0, 1e-12);
  EXPECT_NEAR(model.blocks[1].mass.volume, 3.5, 1e-12);
  EXPECT_EQ(model.blocks[1].material, 1);
}

TEST(MergeSmallBlocks, AcrossMaterialsNeverTouchesAStructure) {
  // A rock block between two structures (a dam and a plug) stays small; a small structure
  // block is never glued into rock.
  BlockModel model = row({2.0, 0.5, 3.0}, {0, 1, 2});
  model.blocks[0].structure = 0;
  model.blocks[2].structure = 1;
  MergeReport r = mergeSmallBlocks(model, 1.0, true);
  EXPECT_EQ(r.merged, 0);
  EXPECT_EQ(r.left_small, 1);
  EXPECT_EQ(model.blocks.size(), 3u);

  // A structure sharing 4 m2 with the small block, a rock block of another material 1 m2:
  // the rock block, though its face is smaller.
  BlockModel beside = row({2.0, 0.5, 3.0}, {0, 1, 2});
  beside.blocks[0].structure = 0;
  beside.adjacency[0].area = 4.0;
  r = mergeSmallBlocks(beside, 1.0, true);
  EXPECT_EQ(r.merged, 1);
  ASSERT_EQ(beside.blocks.size(), 2u);
  EXPECT_EQ(beside.blocks[0].structure, 0);
  EXPECT_NEAR(beside.blocks[0].mass.volume, 2.0, 1e-12);
  EXPECT_NEAR(beside.blocks[1].mass.volume, 3.5, 1e-12);

  BlockModel small_structure = row({2.0, 0.5, 3.0}, {0, 1, 0});
  small_structure.blocks[1].structure = 0;
  r = mergeSmallBlocks(small_structure, 1.0, true);
  EXPECT_EQ(r.merged, 0);
  EXPECT_EQ(r.left_small, 1);
}

TEST(MergeSmallBlocks, ChainsUntilTheGroupIsLargeEnough) {
  // Four 0.3 m3 blocks: the smallest-first rule glues them into one block of 1.2 m3.
  BlockModel model = row({0.3, 0.3, 0.3, 0.3}, {0, 0, 0, 0});
  const MergeReport r = mergeSmallBlocks(model, 1.0);
  EXPECT_EQ(r.blocks_after, 1);
  EXPECT_EQ(r.merged, 3);
  // Three cut blocks were glued into the fourth: 0.9 m3, each counted once.
  EXPECT_NEAR(r.merged_volume, 0.9, 1e-12);
  ASSERT_EQ(model.blocks.size(), 1u);
  EXPECT_NEAR(model.blocks[0].mass.volume, 1.2, 1e-12);
  EXPECT_TRUE(model.adjacency.empty());
}

TEST(MergeSmallBlocks, NeverGluesAStructureEvenOfTheRocksMaterial) {
  // A dam of the rock's material, and a small rock block beside it and beside a larger rock
  // block of the same material with a smaller face: the rock block, never the dam. A small
  // structure (a plug) of the rock's material stays as it is.
  BlockModel model = row({50.0, 0.5, 3.0}, {0, 0, 0});
  model.blocks[0].structure = 0;
  model.adjacency[0].area = 4.0;
  MergeReport r = mergeSmallBlocks(model, 1.0);
  EXPECT_EQ(r.merged, 1);
  ASSERT_EQ(model.blocks.size(), 2u);
  EXPECT_NEAR(model.blocks[0].mass.volume, 50.0, 1e-12);
  EXPECT_NEAR(model.blocks[1].mass.volume, 3.5, 1e-12);

  BlockModel plug = row({3.0, 0.5}, {0, 0});
  plug.blocks[1].structure = 0;
  r = mergeSmallBlocks(plug, 1.0, true);
  EXPECT_EQ(r.merged, 0);
  EXPECT_EQ(r.left_small, 1);
}

TEST(MergeSmallBlocks, ZeroThresholdChangesNothing) {
  BlockModel model = row({0.1, 2.0}, {0, 0});
  const MergeReport r = mergeSmallBlocks(model, 0.0);
  EXPECT_EQ(r.merged, 0);
  EXPECT_EQ(model.blocks.size(), 2u);
}

}  // namespace
}  // namespace rockmass::blocks
