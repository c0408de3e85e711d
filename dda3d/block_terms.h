// The sub-matrices of one block (formulation doc, "Energy terms"): each returns the block's
// contribution to K_ii (12 x 12) or F_i (12), for a block with the current geometry.
#pragma once

#include "dda3d/block_state.h"
#include "dda3d/model.h"
#include "geometry/polyhedron.h"

namespace rockmass::dda3d {

/// Elastic stiffness: K_ii[6:12, 6:12] += V E (N m).
BlockMatrix elasticStiffness(const BlockState& block, const ElasticMatrix& elastic);

/// Initial (current) stress: F_i[6:12] -= V sigma (N m).
BlockVector initialStressLoad(const BlockState& block);

/// Coefficients of a one-step Newmark-type scheme with a Bossak (Wood-Bossak-Zienkiewicz)
/// weighting of the inertia: over a step of length dt with displacement d,
///   d       = dt v0 + dt^2 ((1/2 - beta) a0 + beta a1),
///   v1      = v0 + dt ((1 - gamma) a0 + gamma a1),
///   M ((1 - alpha_m) a1 + alpha_m a0) + (internal forces at the end) = F (at the end).
/// Derivation and properties: docs/dda3d.md, "Time integration".
struct NewmarkCoefficients {
  double alpha_m = 0.0;  ///< Bossak inertia weight (0: plain Newmark)
  double beta = 0.5;     ///< -
  double gamma = 1.0;    ///< -
};

/// Shi's DDA scheme (the formulation doc): beta = 1/2, gamma = 1, alpha_m = 0. First-order
/// accurate; its spectral radius tends to 1 for stiff modes (no high-frequency damping).
NewmarkCoefficients shiCoefficients();

/// The Bossak alpha scheme with high-frequency spectral radius `spectral_radius` (rho_inf in
/// [0, 1]): alpha_m = (rho_inf - 1) / (rho_inf + 1), gamma = 1/2 - alpha_m,
/// beta = (1 - alpha_m)^2 / 4. Second-order accurate and unconditionally stable for linear
/// systems; rho_inf = 0 annihilates the stiffest modes in one or two steps, rho_inf = 1 is
/// the undamped trapezoidal rule. Throws std::invalid_argument outside [0, 1].
NewmarkCoefficients bossakCoefficients(double spectral_radius);

/// The factor c0 = (1 - alpha_m) / (beta dt^2) of the mass matrix in a step's stiffness.
double inertiaCoefficient(const NewmarkCoefficients& scheme, double dt);

/// Inertia of one step: K_ii += (1 - alpha_m) / (beta dt^2) M and
/// F_i += M ((1 - alpha_m) / (beta dt) v0 + ((1 - alpha_m) (1/2 - beta) / beta - alpha_m) a0).
/// With Shi's coefficients: (2 / dt^2) M and (2 / dt) M v0 (the formulation doc).
/// `mass_matrix` from massMatrix(); `velocity` (v0) and `acceleration` (a0) at the start of
/// the step; `dt` in s.
void inertiaTerms(const BlockMatrix& mass_matrix, const BlockVector& velocity,
                  const BlockVector& acceleration, double dt, const NewmarkCoefficients& scheme,
                  BlockMatrix& k, BlockVector& f);

/// Acceleration a1 at the end of a step of displacement `d` (from the displacement update).
BlockVector endAcceleration(const BlockVector& d, const BlockVector& velocity,
                            const BlockVector& acceleration, double dt,
                            const NewmarkCoefficients& scheme);

/// Velocity v1 at the end of a step: v0 + dt ((1 - gamma) a0 + gamma a1).
BlockVector endVelocity(const BlockVector& velocity, const BlockVector& acceleration,
                        const BlockVector& end_acceleration, double dt,
                        const NewmarkCoefficients& scheme);

/// Body force: F_i[0:3] += m g (first moments about the centroid vanish). `gravity` m/s2.
BlockVector bodyForceLoad(const BlockState& block, const geometry::Vec3& gravity);

/// Point load: F_i += T(x)^T P, `point` (m), `force` (N).
BlockVector pointLoad(const BlockState& block, const geometry::Vec3& point,
                      const geometry::Vec3& force);

/// Water pressure (DdaPressure: p = unit_weight * max(0, h(x) - z), h linear) on face `face`
/// of `piece`: F_i += integral over the face of T(x)^T (-p(x) n) dA. The face is clipped at
/// the water line (h(x) = z) and by the pressure's half-spaces, fanned into triangles, and
/// each triangle integrated with the edge-midpoint rule, exact for the quadratic integrand.
/// With `wetted_area`, it gets the area of that clipped part (m2).
BlockVector pressureLoad(const BlockState& block, const geometry::Polyhedron& piece, int face,
                         const DdaPressure& pressure, double* wetted_area = nullptr);

/// The hydrostatic case of the above (no head gradient, the whole face): `level` m,
/// `unit_weight` N/m3.
BlockVector pressureLoad(const BlockState& block, const geometry::Polyhedron& piece, int face,
                         double level, double unit_weight);

/// The pressure's field at x (Pa): unit_weight * (h(x) - z), 0 above the water line; its
/// half-spaces are not applied (the field continued through the block).
double pressureAt(const DdaPressure& pressure, const geometry::Vec3& x);

/// True when x lies inside every half-space of the pressure (where its field applies).
bool pressureApplies(const DdaPressure& pressure, const geometry::Vec3& x);

/// The force of the pressure on the face as the piece stands (N): integral of -p n dA.
geometry::Vec3 pressureResultant(const geometry::Polyhedron& piece, int face,
                                 const DdaPressure& pressure);

/// Westergaard's added pressure (DdaHydrodynamicPressure) on face `face` of `piece`, as a
/// load like pressureLoad's. The square root is integrated numerically: the wet part's
/// triangles are each split into 32 x 32 and summed with the edge-midpoint rule (within
/// 0.1 % of the exact resultant on a vertical face, tested).
BlockVector hydrodynamicLoad(const BlockState& block, const geometry::Polyhedron& piece, int face,
                             const DdaHydrodynamicPressure& pressure);

}  // namespace rockmass::dda3d
