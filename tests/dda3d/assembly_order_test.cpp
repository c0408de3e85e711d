// The assembly sums a pair of rigid blocks' contact terms in the frame of the pair's lower
// block (Simulation::assembleSystem, BlockSystem::RigidSpringSums): an entry whose point is on
// the upper block adds its spring with its ends swapped, T_i - T_j and its offsets changing
// sign together. Listing the same blocks in the opposite order swaps which block is lower for
// every pair, so each entry takes the other branch; the steps must not change beyond the
// round-off of the sums' order. The spring's energy, 1/2 k (d0 + e^T (T_i D_i - T_j D_j))^2,
// is the same with i and j swapped and d0, e negated (Shi 1988, ch. 4).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dda3d/simulation.h"
#include "scenarios/dda_scenes.h"

namespace rockmass::dda3d {
namespace {

using geometry::Vec3;

/// Two unit cubes stacked on a fixed slab, the top one pushed sideways, under gravity tilted
/// 35 degrees off the vertical (friction 30 degrees: the cubes slide on their joints); the
/// blocks listed slab first or slab last. `top`, `middle`: the cubes' indices.
DdaModel stack(bool slab_first, int& top, int& middle) {
  DdaModel model;
  scenes::setRock(model, 30.0);
  const DdaBlock slab = scenes::boxBlock(Vec3(-3, -3, -1), Vec3(3, 3, 0), 0, true);
  const DdaBlock lower = scenes::boxBlock(Vec3(0, 0, 0), Vec3(1, 1, 1), 0, false);
  const DdaBlock upper = scenes::boxBlock(Vec3(0.2, 0.1, 1), Vec3(1.1, 0.9, 2), 0, false);
  if (slab_first) {
    model.blocks = {slab, lower, upper};
    middle = 1;
    top = 2;
  } else {
    model.blocks = {upper, lower, slab};
    middle = 1;
    top = 0;
  }
  const double a = scenes::radians(35.0);
  model.gravity = Vec3(9.81 * std::sin(a), 0.0, -9.81 * std::cos(a));
  model.point_loads.push_back({top, Vec3(0.6, 0.5, 1.8), Vec3(0.0, 2.0e3, 0.0)});
  return model;
}

TEST(AssemblyOrder, ListingTheBlocksTheOtherWayGivesTheSameSteps) {
  DdaSettings settings;
  settings.kinematics = Kinematics::Rigid;
  settings.time_step = 2e-3;
  std::vector<Vec3> moved[2];
  int sliding[2] = {0, 0};
  for (const bool slab_first : {true, false}) {
    int top = -1, middle = -1;
    Simulation sim(stack(slab_first, top, middle), settings);
    const std::vector<BlockState> start = sim.blocks();
    for (int k = 0; k < 40; ++k) sim.step();
    for (const Contact& c : sim.contacts()) sliding[slab_first] += c.state == ContactState::Sliding;
    const std::vector<BlockState>& blocks = sim.blocks();
    for (const int b : {middle, top}) {
      moved[slab_first].push_back(blocks[static_cast<std::size_t>(b)].centroid -
                                  start[static_cast<std::size_t>(b)].centroid);
    }
  }
  // The runs exercise both kinds of terms: the cubes slide down the tilted slab, springs and
  // friction forces alike.
  EXPECT_GT(sliding[0], 0);
  EXPECT_GT(sliding[1], 0);
  for (std::size_t b = 0; b < 2; ++b) {
    // The cubes move 3 and 6 mm in the 0.08 s; the two orders sum the same terms in another
    // order, and the contacts' detection is the same: 1e-9 of the motion (measured 1e-15 m),
    // against the whole motion for a sign lost in the swap (measured: the offsets' sign of a
    // swapped locked or sliding entry, or its pair's stored block read untransposed, fail).
    const double scale = moved[1][b].norm();
    EXPECT_GT(scale, 1e-3) << "cube " << b << " did not move";
    EXPECT_LE((moved[1][b] - moved[0][b]).norm(), 1e-9 * scale)
        << "cube " << b << ": " << moved[1][b].transpose() << " against "
        << moved[0][b].transpose();
  }
}

}  // namespace
}  // namespace rockmass::dda3d
