#pragma once
/// From a scene to the settings of the DDA engine and of its stability analyses (overload,
/// strength reduction): analysis.dda, analysis.equilibrium, analysis.overload and
/// analysis.strength_reduction (docs/stability.md). dda3d knows nothing of scenes.
#include "dda3d/simulation.h"
#include "dda3d/stability.h"
#include "io/scene.h"

namespace rockmass::scene_model {

/// Engine settings of analysis.dda: mode, kinematics, time_step, max_displacement_ratio and
/// penalty (none: automatic); everything else keeps the engine's defaults.
dda3d::DdaSettings ddaSettings(const io::DdaAnalysis& dda);

/// The engine settings of the runs to equilibrium: ddaSettings(analysis.dda) with the
/// damping of analysis.equilibrium (dynamic_ratio) in dynamic mode. Throws InputError
/// naming the scene when it has no analysis.dda.
dda3d::DdaSettings equilibriumDdaSettings(const io::Scene& scene);

/// analysis.equilibrium (defaults when absent); max_steps defaults to analysis.dda.steps.
dda3d::EquilibriumSettings equilibriumSettings(const io::Scene& scene);

/// The loads analysis.overload.scales names (water with uplift when scale_uplift).
dda3d::LoadScaling loadScaling(const io::OverloadAnalysis& overload);

/// The overload search: every factor runs (the K-displacement curve), then bisection to
/// analysis.overload.tolerance. Throws InputError when the scene has no analysis.overload.
dda3d::FactorSearch overloadSearch(const io::Scene& scene);

/// The strength-reduction search: factors until the first not at rest, then bisection to
/// analysis.strength_reduction.tolerance (0.02). Throws InputError when the scene has no
/// analysis.strength_reduction.
dda3d::FactorSearch strengthReductionSearch(const io::Scene& scene);

}  // namespace rockmass::scene_model
