// How far a block may move in a step: the bound on its vertices' displacement and the reach
// that contact detection looks ahead by (docs/dda3d.md, "Step control").
#include <algorithm>
#include <cmath>

#include "dda3d/block_terms.h"
#include "dda3d/contact_detection.h"

namespace rockmass::dda3d {

using geometry::Polyhedron;
using geometry::Vec3;

LinearDisplacement::LinearDisplacement(const BlockState& block, const BlockVector& d)
    : centroid_(block.centroid) {
  // T(x) d is affine in x: u(x) = u(c) + J (x - c), J column k = (T(c + e_k) - T(c)) d.
  at_centroid_ = displacementMatrix(block.centroid, block.centroid) * d;
  for (int k = 0; k < 3; ++k) {
    jacobian_.col(k) =
        displacementMatrix(block.centroid + Vec3::Unit(k), block.centroid) * d - at_centroid_;
  }
}

double largestVertexDisplacement(const BlockState& block, const BlockVector& d) {
  if (d.isZero(0.0)) return 0.0;  // every vertex's displacement is exactly zero
  const LinearDisplacement field(block, d);
  double largest = 0.0;
  for (const Polyhedron& piece : block.pieces) {
    for (const Vec3& v : piece.vertices) largest = std::max(largest, field.squaredAt(v));
  }
  return std::sqrt(largest);
}

double stepReach(const BlockState& block, double dt, double last_dt, const ReachLimits& limits) {
  if (block.fixed) return 0.0;
  return stepReach(block, dt, last_dt, limits,
                   largestVertexDisplacement(block, block.last_displacement));
}

double stepReach(const BlockState& block, double dt, double last_dt, const ReachLimits& limits,
                 double last_largest) {
  if (block.fixed) return 0.0;
  const double by_velocity =
      largestVertexDisplacement(block, block.velocity) * dt + 0.5 * limits.acceleration * dt * dt;
  const double by_last_step = last_largest * (last_dt > 0.0 ? dt / last_dt : 1.0);
  return std::min(limits.cap, std::max(limits.floor, 2.0 * std::max(by_velocity, by_last_step)));
}

}  // namespace rockmass::dda3d
