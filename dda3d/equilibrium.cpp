#include "dda3d/equilibrium.h"

#include <algorithm>
#include <cmath>

namespace rockmass::dda3d {

namespace {

/// The acceleration (m/s2) the unbalanced ratio is measured against: |g|, or standard
/// gravity when the model has none.
double referenceAcceleration(const DdaModel& model) {
  const double g = model.gravity.norm();
  return g > 0.0 ? g : 9.81;
}

}  // namespace

EquilibriumResult runToEquilibrium(Simulation& sim, const EquilibriumSettings& settings) {
  EquilibriumResult result;
  const double g = referenceAcceleration(sim.model());
  int calm = 0;
  int pushed = 0;
  const bool can_fail = sim.settings().mode == AnalysisMode::Static &&
                        settings.failure_ratio > 0.0 && settings.failure_steps > 0;
  while (result.steps < settings.max_steps) {
    const StepReport report = sim.step();
    ++result.steps;
    result.increment =
        report.displacement_ratio * sim.settings().max_displacement_ratio * sim.halfDomainSize();
    result.unbalanced_ratio = result.increment / (0.5 * g * report.time_step * report.time_step);
    result.fastest_block = report.fastest_block;
    if (report.fastest_block >= 0) {
      const BlockState& fastest = sim.blocks()[static_cast<std::size_t>(report.fastest_block)];
      result.fastest_volume = fastest.volume;
      result.fastest_centroid = fastest.centroid;
    }
    const EnergyAccount energy = sim.energy();
    const double work = std::abs(energy.work_of_loads);
    result.kinetic_ratio = energy.kinetic > 0.0 ? energy.kinetic / std::max(work, 1e-300) : 0.0;
    const bool still = !report.forced && result.unbalanced_ratio <= settings.unbalanced_ratio &&
                       result.kinetic_ratio <= settings.kinetic_ratio;
    calm = still ? calm + 1 : 0;
    if (calm >= settings.settle_steps) {
      result.reached = true;
      break;
    }
    pushed = can_fail && result.unbalanced_ratio >= settings.failure_ratio ? pushed + 1 : 0;
    if (pushed >= settings.failure_steps) {
      result.failing = true;
      break;
    }
  }
  result.time = sim.time();
  return result;
}

}  // namespace rockmass::dda3d
