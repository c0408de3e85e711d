#include "dda3d/simulation_settings.h"

#include <algorithm>

#include "dda3d/block_terms.h"

namespace rockmass::dda3d {

double autoPcgTolerance(const DdaSettings& settings) {
  // The error bound of the step (kappa <= 1e3 for the block-Jacobi preconditioned K), capped at
  // 1e-8: bench/dda_accuracy_bench.cpp shows a train of touching blocks on a slope drifting by
  // 2 % at 4e-7 and by 0 % at 1e-8 (docs/performance.md, "DDA accuracy against time").
  return std::min(
      1e-8, 1e-2 * settings.allowed_penetration_ratio / settings.max_displacement_ratio * 1e-3);
}

SolverOptions resolvedSolverOptions(const DdaSettings& settings, int movable) {
  SolverOptions options = settings.solver;
  options.block_size = settings.kinematics == Kinematics::Rigid ? 6 : kBlockDofs;
  if (options.kind == SolverKind::Auto) {
    if (movable * options.block_size <= options.auto_cholmod_unknowns) {
      options.kind = SolverKind::Cholmod;
    } else {
      // Stays Auto: CHOLMOD or PCG by the first matrix's factorization cost (AutoSolver).
      options.tolerance = autoPcgTolerance(settings);
    }
  }
  return options;
}

}  // namespace rockmass::dda3d
