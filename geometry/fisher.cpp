#include "geometry/fisher.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "geometry/orientation.h"

namespace rockmass::geometry {

void orthonormalBasis(const Vec3& n, Vec3& u, Vec3& v) {
  // Cross with the coordinate axis least aligned with n: well conditioned for every n.
  Vec3 axis = Vec3::UnitX();
  if (std::abs(n.y()) < std::abs(n.x()) && std::abs(n.y()) <= std::abs(n.z())) {
    axis = Vec3::UnitY();
  } else if (std::abs(n.z()) < std::abs(n.x()) && std::abs(n.z()) < std::abs(n.y())) {
    axis = Vec3::UnitZ();
  }
  u = n.cross(axis).normalized();
  v = n.cross(u);
}

Vec3 sampleFisher(const Vec3& mean, double kappa, Rng& rng) {
  if (!(kappa > 0.0) || !std::isfinite(kappa)) {
    throw std::invalid_argument("Fisher kappa must be a finite number > 0");
  }
  // Wood (1994), Simulation of the von Mises Fisher distribution, Commun. Stat. Simul.
  // Comput. 23(1): on the 2-sphere the cosine w of the angle to the mean has the density
  // proportional to exp(kappa w) on [-1, 1], inverted in closed form:
  //   w = 1 + ln(xi + (1 - xi) exp(-2 kappa)) / kappa,   xi ~ U(0, 1).
  // exp(-2 kappa) underflows harmlessly to 0 for large kappa; xi is never 0, so the log is
  // finite. 1 - w is computed directly to keep the small angles of large kappa accurate.
  const double xi = uniformOpen01(rng);
  const double one_minus_w =
      std::min(2.0, -std::log(xi + (1.0 - xi) * std::exp(-2.0 * kappa)) / kappa);
  const double w = 1.0 - one_minus_w;
  const double sine = std::sqrt(std::max(0.0, one_minus_w * (2.0 - one_minus_w)));
  const double phi = 2.0 * kPi * uniformOpen01(rng);
  Vec3 u, v;
  const Vec3 m = mean.normalized();
  orthonormalBasis(m, u, v);
  return (w * m + sine * (std::cos(phi) * u + std::sin(phi) * v)).normalized();
}

FisherEstimate estimateFisher(std::span<const Vec3> axes) {
  FisherEstimate estimate;
  if (axes.empty()) return estimate;
  // Axial data: the principal eigenvector of the orientation tensor sum(n n^T) picks the
  // hemisphere; each axis is flipped onto it before the resultant is formed.
  Eigen::Matrix3d tensor = Eigen::Matrix3d::Zero();
  for (const Vec3& a : axes) {
    const Vec3 n = a.normalized();
    tensor += n * n.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(tensor);
  const Vec3 principal = solver.eigenvectors().col(2);
  Vec3 resultant = Vec3::Zero();
  for (const Vec3& a : axes) {
    const Vec3 n = a.normalized();
    resultant += n.dot(principal) >= 0.0 ? n : Vec3(-n);
  }
  const double count = static_cast<double>(axes.size());
  const double length = resultant.norm();
  estimate.mean = length > 0.0 ? Vec3(resultant / length) : principal;
  estimate.resultant = length / count;
  // Fisher (1953): kappa ~ (N - 1) / (N - R), unbiased for large kappa.
  estimate.kappa = count - length > 0.0 ? (count - 1.0) / (count - length)
                                        : std::numeric_limits<double>::infinity();
  return estimate;
}

}  // namespace rockmass::geometry
