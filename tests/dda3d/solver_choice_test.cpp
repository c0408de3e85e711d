// The solver a DDA run uses: SolverKind::Auto (CHOLMOD for small systems; above
// DdaSettings::solver.auto_cholmod_unknowns unknowns CHOLMOD or warm-started PCG by the cost of
// the first matrix's factorization), and a PCG run reproducing the CHOLMOD
// trajectory of a settling pile within what the PCG tolerance allows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "dda3d/simulation.h"
#include "scenarios/dda_scenes.h"

namespace rockmass::dda3d {
namespace {

using geometry::Vec3;

TEST(SolverChoice, AutoIsCholmodForSmallSystemsAndChosenByTheMatrixForLargeOnes) {
  DdaSettings settings;
  settings.kinematics = Kinematics::Rigid;
  EXPECT_EQ(settings.solver.kind, SolverKind::Auto);
  // 6 000 unknowns: 1 000 rigid blocks (6 unknowns each), 500 deformable ones (12).
  EXPECT_EQ(settings.solver.auto_cholmod_unknowns, 6000);
  const SolverOptions small = resolvedSolverOptions(settings, 1000);
  EXPECT_EQ(small.kind, SolverKind::Cholmod);
  EXPECT_EQ(small.block_size, 6);
  // Above: CHOLMOD or PCG by the first matrix's factorization cost (the AutoSolver,
  // LinearSolver.AutoTakesCholmodWhereItsFactorIsCheapAndPcgWhereItFillsIn).
  const SolverOptions large = resolvedSolverOptions(settings, 1001);
  EXPECT_EQ(large.kind, SolverKind::Auto);
  DdaSettings deformable = settings;
  deformable.kinematics = Kinematics::Deformable;
  EXPECT_EQ(resolvedSolverOptions(deformable, 500).kind, SolverKind::Cholmod);
  EXPECT_EQ(resolvedSolverOptions(deformable, 501).kind, SolverKind::Auto);
  EXPECT_EQ(resolvedSolverOptions(deformable, 501).block_size, 12);
  // The error bound 1e-2 g3 / g2 / 1e3 is 4e-6 with the defaults g2 = 0.001, g3 = 4e-4
  // (simulation_settings.h), looser than the 1e-8 cap that bench/dda_accuracy_bench.cpp calls
  // for.
  EXPECT_DOUBLE_EQ(large.tolerance, 1e-8);
  // A tighter penetration allowance makes the bound the binding one: 1e-2 * 1e-7 / 0.001 / 1e3.
  DdaSettings strict = settings;
  strict.allowed_penetration_ratio = 1e-7;
  EXPECT_DOUBLE_EQ(resolvedSolverOptions(strict, 1001).tolerance, 1e-2 * 1e-7 / 0.001 * 1e-3);
  // An explicit choice is kept.
  settings.solver.kind = SolverKind::Eigen;
  EXPECT_EQ(resolvedSolverOptions(settings, 100000).kind, SolverKind::Eigen);
}

/// 18 rigid cubes (3 x 3 x 2, staggered layers, 5 cm gaps) dropped on a fixed slab.
DdaModel smallPile() {
  DdaModel model;
  scenes::setRock(model, 30.0);
  model.blocks.push_back(scenes::boxBlock({-1, -1, -1}, {5, 5, 0}, 0, true));
  for (int k = 0; k < 18; ++k) {
    const int layer = k / 9, row = (k / 3) % 3, column = k % 3;
    const double shift = layer % 2 == 0 ? 0.0 : 0.3;
    const Vec3 low(0.1 + 1.2 * column + shift, 0.1 + 1.2 * row, 0.05 + 1.2 * layer);
    model.blocks.push_back(scenes::boxBlock(low, low + Vec3(1, 1, 1), 0, false));
  }
  model.gravity = Vec3(0, 0, -9.81);
  return model;
}

TEST(SolverChoice, WarmStartedPcgFollowsTheCholmodTrajectoryOfAPile) {
  DdaSettings settings;
  settings.kinematics = Kinematics::Rigid;
  settings.time_step = 2e-3;
  // g2 = 0.01: the landing takes 2 ms steps. At the default 0.001 the step control cuts dt at
  // every impact, and two runs whose solutions differ by the PCG tolerance part at such a
  // cut (step 73: 1.7e-16 s apart), which is a different check from this one.
  settings.max_displacement_ratio = 0.01;
  settings.solver.kind = SolverKind::Cholmod;
  Simulation direct(smallPile(), settings);
  settings.solver.kind = SolverKind::Pcg;
  settings.solver.tolerance = autoPcgTolerance(settings);
  Simulation iterative(smallPile(), settings);
  ASSERT_EQ(direct.solverName(), "cholmod");
  ASSERT_EQ(iterative.solverName(), "pcg");
  // A solve stopped at relative residual tol errs by at most kappa * tol relative to the
  // step's displacement; autoPcgTolerance() assumes kappa <= 1e3 for the block-Jacobi
  // preconditioned K. Errors of successive steps add up at worst, so the trajectories differ
  // by at most 1e3 * tol * (the path the blocks travelled: the sum over steps of the largest
  // centroid move), plus round-off. (Measured: ~0.2 tol * path, as kappa is small while
  // inertia dominates K.) Both runs must also see the same contacts and dt decisions.
  // 0.2 s: the layers fall 5 cm and land on each other. Later the pile's re-contacts are
  // chaotic: at step 115 the two runs' contact counts part (96 vs 90) under the Bossak scheme.
  constexpr int kSteps = 100;
  const double tolerance = settings.solver.tolerance;
  double path = 0.0;
  std::vector<Vec3> previous(19, Vec3::Zero());
  for (int k = 1; k <= kSteps; ++k) {
    const StepReport a = direct.step();
    const StepReport b = iterative.step();
    ASSERT_DOUBLE_EQ(a.time, b.time) << "step " << k;
    ASSERT_EQ(a.contacts.total, b.contacts.total) << "step " << k;
    double largest = 0.0, moved = 0.0;
    for (int block = 1; block <= 18; ++block) {
      const Vec3 u = direct.centroidDisplacement(block);
      moved = std::max(moved, (u - previous[static_cast<std::size_t>(block)]).norm());
      previous[static_cast<std::size_t>(block)] = u;
      largest = std::max(largest, (u - iterative.centroidDisplacement(block)).norm());
    }
    path += moved;
    ASSERT_LE(largest, 1e3 * tolerance * path + 1e-12) << "step " << k;
  }
  // The pile really landed: the bottom layer rests on the slab (fell its 5 cm gap).
  EXPECT_NEAR(direct.centroidDisplacement(1).z(), -0.05, 0.01);
  EXPECT_GT(direct.contactCounts().total, 0);
}

}  // namespace
}  // namespace rockmass::dda3d
