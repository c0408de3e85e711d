#include "dda3d/block_terms.h"

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

void inertiaTerms(const BlockMatrix& mass_matrix, const BlockVector& velocity, double dt,
                  BlockMatrix& k, BlockVector& f) {
  k += (2.0 / (dt * dt)) * mass_matrix;
  f += (2.0 / dt) * (mass_matrix * velocity);
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
