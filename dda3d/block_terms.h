// The sub-matrices of one block (formulation doc, "Energy terms"): each returns the block's
// contribution to K_ii (12 x 12) or F_i (12), for a block with the current geometry.
#pragma once

#include "dda3d/block_state.h"
#include "geometry/polyhedron.h"

namespace rockmass::dda3d {

/// Elastic stiffness: K_ii[6:12, 6:12] += V E (N m).
BlockMatrix elasticStiffness(const BlockState& block, const ElasticMatrix& elastic);

/// Initial (current) stress: F_i[6:12] -= V sigma (N m).
BlockVector initialStressLoad(const BlockState& block);

/// Inertia with Newmark beta = 1/2, gamma = 1: K_ii += (2 / dt^2) M, F_i += (2 / dt) M V.
/// `mass_matrix` from massMatrix(); `dt` in s.
void inertiaTerms(const BlockMatrix& mass_matrix, const BlockVector& velocity, double dt,
                  BlockMatrix& k, BlockVector& f);

/// Body force: F_i[0:3] += m g (first moments about the centroid vanish). `gravity` m/s2.
BlockVector bodyForceLoad(const BlockState& block, const geometry::Vec3& gravity);

/// Point load: F_i += T(x)^T P, `point` (m), `force` (N).
BlockVector pointLoad(const BlockState& block, const geometry::Vec3& point,
                      const geometry::Vec3& force);

/// Hydrostatic pressure p = unit_weight * max(0, level - z) on face `face` of `piece`:
/// F_i += integral over the face of T(x)^T (-p(x) n) dA. The face is clipped at the water
/// line, fanned into triangles, and each triangle integrated with the edge-midpoint rule,
/// exact for the quadratic integrand. `level` m, `unit_weight` N/m3.
BlockVector pressureLoad(const BlockState& block, const geometry::Polyhedron& piece, int face,
                         double level, double unit_weight);

}  // namespace rockmass::dda3d
