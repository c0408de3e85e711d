// Running a DDA model until it is at rest: the equilibrium criterion of the overload and
// strength-reduction analyses (docs/stability.md).
#pragma once

#include "dda3d/simulation.h"

namespace rockmass::dda3d {

/// When a run counts as being at rest. A step is calm when it was accepted on every check
/// (not forced), its unbalanced ratio is at most `unbalanced_ratio` and its kinetic energy
/// ratio at most `kinetic_ratio`; equilibrium is `settle_steps` calm steps in a row.
struct EquilibriumSettings {
  int max_steps = 1000;  ///< step limit; a run that is not at rest by then is not in equilibrium
  /// Largest vertex displacement of a step d divided by 1/2 g dt^2, the distance a free body
  /// falls from rest in that step (g = |gravity|, 9.81 m/s2 when the model has none). In a
  /// static run (velocities reset every step) this is the unbalanced acceleration over g;
  /// in a dynamic one it adds 2 v / (g dt). -.
  double unbalanced_ratio = 1e-3;
  /// Kinetic energy over the work done by the loads so far (both J). -.
  double kinetic_ratio = 1e-6;
  int settle_steps = 5;  ///< calm steps in a row that make equilibrium
  /// Static runs only: a run whose unbalanced ratio is at least `failure_ratio` in
  /// `failure_steps` steps in a row is not at rest, and stops there (some block is then
  /// pushed by an unbalanced force at least this many times its weight, step after step).
  /// 0 turns the early stop off.
  double failure_ratio = 1.0;
  int failure_steps = 10;  ///< steps in a row of the early stop
};

/// How a run to equilibrium ended.
struct EquilibriumResult {
  bool reached = false;           ///< at rest within the step limit
  int steps = 0;                  ///< accepted steps taken
  double time = 0.0;              ///< simulated time at the end (s)
  double unbalanced_ratio = 0.0;  ///< of the last step (-)
  double kinetic_ratio = 0.0;     ///< at the end (-)
  double increment = 0.0;         ///< largest vertex displacement of the last step (m)
  bool failing = false;           ///< stopped early by the failure rule (not at rest)
  /// The block that moved most in the last step (-1: none), its volume (m3) and centroid
  /// (m): where the unbalanced ratio comes from.
  int fastest_block = -1;
  double fastest_volume = 0.0;
  geometry::Vec3 fastest_centroid = geometry::Vec3::Zero();
};

/// Steps `sim` until it is at rest (EquilibriumSettings) or the step limit is reached.
EquilibriumResult runToEquilibrium(Simulation& sim, const EquilibriumSettings& settings);

}  // namespace rockmass::dda3d
