// The energy account of a DDA run (docs/dda3d.md, "Energy account").
#pragma once

namespace rockmass::dda3d {

/// Energies (J), for checking that nothing grows beyond the work of the loads.
/// Balance: stored() + dissipated() = work_of_loads, up to the energy of contact state
/// changes between steps (a contact that closes, a shear spring that starts at the friction
/// force), the geometric non-linearity of a step (exact rotation, moving contact frames) and
/// the solver's residual (docs/dda3d.md, "Energy account").
struct EnergyAccount {
  double kinetic = 0.0;        ///< 1/2 V^T M V
  double strain = 0.0;         ///< 1/2 V eps^T E eps of the accumulated strain
  double springs = 0.0;        ///< contact, fixed-point and bolt springs
  double work_of_loads = 0.0;  ///< cumulative work of body forces, point loads, pressure
  /// Cumulative work done against the friction forces of sliding contacts, f N s . slip
  /// (>= 0 step by step: s is the direction of the slip).
  double friction = 0.0;
  /// Cumulative energy the time integration removed: per step 1/2 d^T K d (forces taken at
  /// the end of the step) + d^T M ((1 - alpha_m) a1 + alpha_m a0) - (T1 - T0), plus the
  /// kinetic energy removed by a dynamic ratio below 1 or by static mode.
  double numerical = 0.0;
  /// Cumulative energy the springs gained between steps (signed): contacts detected, closed
  /// or opened, shear springs restarted, penalty raised. A contact that closes on a moving
  /// block adds here what the end-of-step spring force then removes in `numerical`.
  double contact_changes = 0.0;
  double stored() const { return kinetic + strain + springs; }
  double dissipated() const { return friction + numerical; }
};

}  // namespace rockmass::dda3d
