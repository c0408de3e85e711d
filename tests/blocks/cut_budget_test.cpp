// The block budget's estimate (blocks/cut_budget.h) against cuts whose blocks are known.
#include <gtest/gtest.h>

#include "blocks/cut_budget.h"
#include "blocks/fast_cutter.h"
#include "scenarios/disc_scenes.h"
#include "tests/blocks/block_test_support.h"

namespace rockmass::blocks {
namespace {

using geometry::Vec3;

/// k planes across the 10 m cube normal to each axis, evenly spaced.
geometry::FractureNetwork planeGrid(int k) {
  std::vector<geometry::Disc> discs;
  for (int axis = 0; axis < 3; ++axis) {
    for (int i = 1; i <= k; ++i) {
      Vec3 center = Vec3::Constant(5.0);
      center[axis] = 10.0 * i / (k + 1.0);
      discs.push_back(test::circle(center, Vec3::Unit(axis)));
    }
  }
  return test::cubeNetwork(discs);
}

TEST(BlockEstimate, PlaneGridCountsItsLinesPointsAndCellsExactly) {
  // Three families of k planes through a cube: 3k planes, 3k^2 lines, k^3 points, and
  // (k + 1)^3 cells (Zaslavsky: 1 + planes + lines + points for an arrangement in general
  // position inside a convex region). The fast cutter makes the same blocks.
  const geometry::FractureNetwork network = planeGrid(3);
  const CutInput input = boxCutInput(network);
  const BlockEstimate estimate = estimateBlocks(input, 1e6);
  EXPECT_FALSE(estimate.stopped);
  EXPECT_EQ(estimate.discs, 9);
  EXPECT_EQ(estimate.intersections, 27);
  EXPECT_EQ(estimate.vertices, 27);
  EXPECT_EQ(estimate.blocks, 64.0);
  EXPECT_EQ(cutFast(input).blocks.size(), 64u);
}

TEST(BlockEstimate, StopsOnceTheEstimatePassesTheLimit) {
  // 10 planes per axis: 1331 cells. Under a limit of 500 the count stops early, with a
  // lower bound above the limit, and says which set made the crossings.
  const geometry::FractureNetwork network = planeGrid(10);
  const BlockEstimate estimate = estimateBlocks(boxCutInput(network), 500.0);
  EXPECT_TRUE(estimate.stopped);
  EXPECT_GT(estimate.blocks, 500.0);
  EXPECT_LE(estimate.blocks, 1331.0);
  ASSERT_EQ(estimate.set_intersections.size(), 1u);
  EXPECT_EQ(estimate.set_intersections[0], 2 * estimate.intersections);
  const BlockEstimate full = estimateBlocks(boxCutInput(network), 1e6);
  EXPECT_EQ(full.blocks, 1331.0);
}

TEST(BlockEstimate, FiniteDiscsMakeFewerBlocksThanTheEstimate) {
  // Random elliptical discs (the cutter benchmark's series): finite discs cut fewer blocks
  // than planes with the same crossings, so the estimate is an upper one; it stays within
  // a factor 10 so that the default limit does not refuse ordinary networks.
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const geometry::FractureNetwork network = randomDiscNetwork(sizeSeriesScene(100, seed));
    const CutInput input = boxCutInput(network);
    const BlockEstimate estimate = estimateBlocks(input, 1e9);
    const double blocks = static_cast<double>(cutFast(input).blocks.size());
    EXPECT_GE(estimate.blocks, blocks) << "seed " << seed;
    EXPECT_LE(estimate.blocks, 10.0 * blocks) << "seed " << seed;
  }
}

TEST(BlockEstimate, DiscsThatDoNotMeetAddNoCrossings) {
  // Two 1 m discs 5 m apart, and one outside the domain: two discs, no crossing.
  const geometry::FractureNetwork network = test::cubeNetwork(
      {test::circle({2, 2, 2}, Vec3::UnitZ(), 1.0), test::circle({7, 7, 7}, Vec3::UnitX(), 1.0),
       test::circle({20, 20, 20}, Vec3::UnitY(), 1.0)});
  const BlockEstimate estimate = estimateBlocks(boxCutInput(network), 1e6);
  EXPECT_EQ(estimate.discs, 2);
  EXPECT_EQ(estimate.intersections, 0);
  EXPECT_EQ(estimate.blocks, 3.0);
}

}  // namespace
}  // namespace rockmass::blocks
