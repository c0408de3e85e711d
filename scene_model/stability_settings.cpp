#include "scene_model/stability_settings.h"

#include <algorithm>

#include "io/input_error.h"

namespace rockmass::scene_model {

using namespace io;  // NOLINT: the scene's types

namespace {

/// Throws "file: analysis.<key>: required by <what>".
[[noreturn]] void missing(const Scene& scene, const std::string& key, const std::string& what) {
  throw InputError(scene.file.string() + ": analysis." + key + ": required by " + what +
                   "; add it to the scene's analysis section");
}

}  // namespace

dda3d::DdaSettings ddaSettings(const DdaAnalysis& dda) {
  dda3d::DdaSettings settings = dda.engine;
  settings.solver.block_size =
      settings.kinematics == dda3d::Kinematics::Deformable ? dda3d::kBlockDofs : 6;
  return settings;
}

dda3d::DdaSettings equilibriumDdaSettings(const Scene& scene) {
  if (!scene.analysis.dda) {
    missing(scene, "dda", "the overload and strength-reduction runs (mode, time_step, ...)");
  }
  dda3d::DdaSettings settings = ddaSettings(*scene.analysis.dda);
  settings.dynamic_ratio = scene.analysis.equilibrium.value_or(EquilibriumAnalysis{}).dynamic_ratio;
  return settings;
}

dda3d::EquilibriumSettings equilibriumSettings(const Scene& scene) {
  const EquilibriumAnalysis e = scene.analysis.equilibrium.value_or(EquilibriumAnalysis{});
  dda3d::EquilibriumSettings settings;
  settings.max_steps =
      e.max_steps.value_or(scene.analysis.dda ? scene.analysis.dda->steps : settings.max_steps);
  settings.unbalanced_ratio = e.unbalanced_ratio;
  settings.kinetic_ratio = e.kinetic_ratio;
  settings.settle_steps = e.settle_steps;
  settings.failure_ratio = e.failure_ratio;
  settings.failure_steps = e.failure_steps;
  settings.steady_steps = e.steady_steps;
  settings.steady_spread = e.steady_spread;
  settings.drift_steps = e.drift_steps;
  settings.watch =
      e.watch_monitors ? dda3d::EquilibriumWatch::Monitors : dda3d::EquilibriumWatch::All;
  return settings;
}

dda3d::LoadScaling loadScaling(const OverloadAnalysis& overload) {
  const auto named = [&](const char* load) {
    return std::find(overload.scales.begin(), overload.scales.end(), load) != overload.scales.end();
  };
  return {.gravity = named("gravity"),
          .water = named("water"),
          .uplift = named("water") && overload.scale_uplift,
          .point_loads = named("point_loads"),
          .seismic = named("seismic")};
}

namespace {

/// The search over `factors` to `tolerance`; every factor runs (sweep_all) or the search
/// stops at the first not at rest.
dda3d::FactorSearch factorSearch(const Scene& scene, const std::vector<double>& factors,
                                 double tolerance, bool sweep_all) {
  dda3d::FactorSearch search;
  search.factors = factors;
  search.tolerance = tolerance;
  search.sweep_all = sweep_all;
  search.equilibrium = equilibriumSettings(scene);
  return search;
}

}  // namespace

dda3d::FactorSearch overloadSearch(const Scene& scene) {
  if (!scene.analysis.overload) missing(scene, "overload", "the overload method");
  return factorSearch(scene, scene.analysis.overload->factors, scene.analysis.overload->tolerance,
                      /*sweep_all=*/true);
}

dda3d::FactorSearch strengthReductionSearch(const Scene& scene) {
  if (!scene.analysis.strength_reduction) {
    missing(scene, "strength_reduction", "the strength reduction");
  }
  dda3d::FactorSearch search =
      factorSearch(scene, scene.analysis.strength_reduction->factors,
                   scene.analysis.strength_reduction->tolerance, /*sweep_all=*/false);
  // Only the strength reduction offers the incremental path (docs/stability.md, "Path of the
  // runs"): its loads, and so the base's tension zone, are the same at every factor.
  search.incremental = scene.analysis.strength_reduction->incremental;
  return search;
}

}  // namespace rockmass::scene_model
