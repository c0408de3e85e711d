#include "dda3d/block_terms.h"

#include <stdexcept>
#include <vector>

namespace rockmass::dda3d {

using geometry::Vec3;

BlockMatrix elasticStiffness(const BlockState& block, const ElasticMatrix& elastic) {
  BlockMatrix k = BlockMatrix::Zero();
  k.bottomRightCorner<kVoigtSize, kVoigtSize>() = block.volume * elastic;
  return k;
}

BlockVector initialStressLoad(const BlockState& block) {
  BlockVector f = BlockVector::Zero();
  f.tail<kVoigtSize>() = -block.volume * block.stress;
  return f;
}

NewmarkCoefficients shiCoefficients() {
  return {.alpha_m = 0.0, .beta = 0.5, .gamma = 1.0};
}

NewmarkCoefficients bossakCoefficients(double spectral_radius) {
  if (!(spectral_radius >= 0.0 && spectral_radius <= 1.0)) {
    throw std::invalid_argument("the spectral radius of the time integration must be in [0, 1]");
  }
  const double alpha_m = (spectral_radius - 1.0) / (spectral_radius + 1.0);
  return {
      .alpha_m = alpha_m, .beta = 0.25 * (1.0 - alpha_m) * (1.0 - alpha_m), .gamma = 0.5 - alpha_m};
}

void inertiaTerms(const BlockMatrix& mass_matrix, const BlockVector& velocity,
                  const BlockVector& acceleration, double dt, const NewmarkCoefficients& s,
                  BlockMatrix& k, BlockVector& f) {
  const double weight = 1.0 - s.alpha_m;
  k += (weight / (s.beta * dt * dt)) * mass_matrix;
  f += mass_matrix * ((weight / (s.beta * dt)) * velocity +
                      (weight * (0.5 - s.beta) / s.beta - s.alpha_m) * acceleration);
}

BlockVector endAcceleration(const BlockVector& d, const BlockVector& velocity,
                            const BlockVector& acceleration, double dt,
                            const NewmarkCoefficients& s) {
  return (d - dt * velocity - (0.5 - s.beta) * dt * dt * acceleration) / (s.beta * dt * dt);
}

BlockVector endVelocity(const BlockVector& velocity, const BlockVector& acceleration,
                        const BlockVector& end_acceleration, double dt,
                        const NewmarkCoefficients& s) {
  return velocity + dt * ((1.0 - s.gamma) * acceleration + s.gamma * end_acceleration);
}

BlockVector bodyForceLoad(const BlockState& block, const Vec3& gravity) {
  BlockVector f = BlockVector::Zero();
  f.head<3>() = block.mass * gravity;
  return f;
}

BlockVector pointLoad(const BlockState& block, const Vec3& point, const Vec3& force) {
  return displacementMatrix(point, block.centroid).transpose() * force;
}

BlockVector pressureLoad(const BlockState& block, const geometry::Polyhedron& piece, int face,
                         double level, double unit_weight) {
  const Vec3 normal = geometry::faceNormal(piece, face);
  // Clip the polygon to z <= level (one Sutherland-Hodgman pass).
  std::vector<Vec3> wet;
  const std::vector<int>& ids = piece.faces[static_cast<std::size_t>(face)];
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const Vec3& a = piece.vertices[ids[k]];
    const Vec3& b = piece.vertices[ids[(k + 1) % ids.size()]];
    const bool a_in = a.z() <= level, b_in = b.z() <= level;
    if (a_in) wet.push_back(a);
    if (a_in != b_in) wet.push_back(a + (level - a.z()) / (b.z() - a.z()) * (b - a));
  }
  BlockVector f = BlockVector::Zero();
  const auto integrand = [&](const Vec3& x) -> BlockVector {
    const double p = unit_weight * (level - x.z());
    return displacementMatrix(x, block.centroid).transpose() * (-p * normal);
  };
  for (std::size_t k = 1; k + 1 < wet.size(); ++k) {
    const Vec3& a = wet[0];
    const Vec3& b = wet[k];
    const Vec3& c = wet[k + 1];
    const double area = 0.5 * (b - a).cross(c - a).norm();
    f += area / 3.0 *
         (integrand(0.5 * (a + b)) + integrand(0.5 * (b + c)) + integrand(0.5 * (c + a)));
  }
  return f;
}

}  // namespace rockmass::dda3d
