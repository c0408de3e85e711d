#include "dda3d/block_terms.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <boost/container/small_vector.hpp>

#include "geometry/disc.h"

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

double inertiaCoefficient(const NewmarkCoefficients& s, double dt) {
  return (1.0 - s.alpha_m) / (s.beta * dt * dt);
}

void inertiaTerms(const BlockMatrix& mass_matrix, const BlockVector& velocity,
                  const BlockVector& acceleration, double dt, const NewmarkCoefficients& s,
                  BlockMatrix& k, BlockVector& f) {
  const double weight = 1.0 - s.alpha_m;
  k += inertiaCoefficient(s, dt) * mass_matrix;
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

namespace {

/// A face's polygon, clipped or not: most faces of a cut rock mass have a few corners, kept
/// on the stack (the region's 10 000 wet faces are clipped every step).
using Polygon = boost::container::small_vector<Vec3, 12>;

/// Keeps the part of a convex polygon with normal . x <= offset (Sutherland-Hodgman).
Polygon clipPolygon(const Polygon& polygon, const Vec3& normal, double offset) {
  Polygon out;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Vec3& a = polygon[k];
    const Vec3& b = polygon[(k + 1) % polygon.size()];
    const double sa = normal.dot(a);
    const double sb = normal.dot(b);
    const bool a_in = sa <= offset, b_in = sb <= offset;
    if (a_in) out.push_back(a);
    if (a_in != b_in) out.push_back(a + (offset - sa) / (sb - sa) * (b - a));
  }
  return out;
}

Polygon facePolygon(const geometry::Polyhedron& piece, int face) {
  Polygon out;
  for (const int v : piece.faces[static_cast<std::size_t>(face)]) out.push_back(piece.vertices[v]);
  return out;
}

/// Integral of T(x)^T (-p(x) n) over a convex polygon, p quadratic at most in x: fanned into
/// triangles, each by the edge-midpoint rule (exact for quadratic integrands).
template <class Pressure>
BlockVector integratePressure(const BlockState& block, const Polygon& polygon, const Vec3& normal,
                              const Pressure& p) {
  BlockVector f = BlockVector::Zero();
  const auto integrand = [&](const Vec3& x) -> BlockVector {
    return displacementMatrix(x, block.centroid).transpose() * (-p(x) * normal);
  };
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
    const Vec3& a = polygon[0];
    const Vec3& b = polygon[k];
    const Vec3& c = polygon[k + 1];
    const double area = 0.5 * (b - a).cross(c - a).norm();
    f += area / 3.0 *
         (integrand(0.5 * (a + b)) + integrand(0.5 * (b + c)) + integrand(0.5 * (c + a)));
  }
  return f;
}

}  // namespace

/// The part of the face the pressure wets: below its water line (h(x) - z >= 0, i.e.
/// (e_z - grad h) . x <= level) and inside its half-spaces.
static Polygon wetPolygon(const geometry::Polyhedron& piece, int face,
                          const DdaPressure& pressure) {
  const Vec3 wet_normal = Vec3::UnitZ() - pressure.head_gradient;
  Polygon wet = clipPolygon(facePolygon(piece, face), wet_normal, pressure.level);
  for (const HalfSpace& h : pressure.within) {
    if (wet.size() < 3) break;
    wet = clipPolygon(wet, h.normal, h.offset);
  }
  return wet;
}

BlockVector pressureLoad(const BlockState& block, const geometry::Polyhedron& piece, int face,
                         const DdaPressure& pressure, double* wetted_area) {
  const Vec3 normal = geometry::faceNormal(piece, face);
  const auto p = [&](const Vec3& x) {
    return pressure.unit_weight * (pressure.level + pressure.head_gradient.dot(x) - x.z());
  };
  const Polygon wet = wetPolygon(piece, face, pressure);
  if (wetted_area != nullptr) *wetted_area = geometry::polygonArea({wet.begin(), wet.end()});
  return integratePressure(block, wet, normal, p);
}

double pressureAt(const DdaPressure& pressure, const Vec3& x) {
  return std::max(0.0,
                  pressure.unit_weight * (pressure.level + pressure.head_gradient.dot(x) - x.z()));
}

bool pressureApplies(const DdaPressure& pressure, const Vec3& x) {
  for (const HalfSpace& h : pressure.within) {
    if (h.normal.dot(x) > h.offset) return false;
  }
  return true;
}

Vec3 pressureResultant(const geometry::Polyhedron& piece, int face, const DdaPressure& pressure) {
  const Polygon wet = wetPolygon(piece, face, pressure);
  Vec3 force = Vec3::Zero();
  if (wet.size() < 3) return force;
  const Vec3 normal = geometry::faceNormal(piece, face);
  for (std::size_t k = 1; k + 1 < wet.size(); ++k) {
    const Vec3 centroid = (wet[0] + wet[k] + wet[k + 1]) / 3.0;
    const double area = 0.5 * (wet[k] - wet[0]).cross(wet[k + 1] - wet[0]).norm();
    // p is linear: its mean over a triangle is its value at the centroid.
    const double p = pressure.unit_weight *
                     (pressure.level + pressure.head_gradient.dot(centroid) - centroid.z());
    force -= area * p * normal;
  }
  return force;
}

BlockVector pressureLoad(const BlockState& block, const geometry::Polyhedron& piece, int face,
                         double level, double unit_weight) {
  DdaPressure pressure;
  pressure.level = level;
  pressure.unit_weight = unit_weight;
  return pressureLoad(block, piece, face, pressure);
}

BlockVector hydrodynamicLoad(const BlockState& block, const geometry::Polyhedron& piece, int face,
                             const DdaHydrodynamicPressure& pressure) {
  const Vec3 normal = geometry::faceNormal(piece, face);
  Polygon wet = clipPolygon(facePolygon(piece, face), Vec3::UnitZ(), pressure.level);
  if (wet.size() >= 3) {
    wet = clipPolygon(wet, -Vec3::UnitZ(), -(pressure.level - pressure.depth));
  }
  const double c = 7.0 / 8.0 * pressure.k_h * pressure.unit_weight;
  const auto p = [&](const Vec3& x) {
    return c * std::sqrt(std::max(0.0, pressure.depth * (pressure.level - x.z())));
  };
  constexpr int kSplits = 32;
  BlockVector f = BlockVector::Zero();
  for (std::size_t k = 1; k + 1 < wet.size(); ++k) {
    const Vec3 a = wet[0];
    const Vec3 u = (wet[k] - a) / kSplits;
    const Vec3 v = (wet[k + 1] - a) / kSplits;
    for (int i = 0; i < kSplits; ++i) {
      for (int j = 0; i + j < kSplits; ++j) {
        const Vec3 o = a + i * u + j * v;
        f += integratePressure(block, {o, o + u, o + v}, normal, p);
        if (i + j + 1 < kSplits)
          f += integratePressure(block, {o + u, o + u + v, o + v}, normal, p);
      }
    }
  }
  return f;
}

}  // namespace rockmass::dda3d
