#include "dda3d/displacement_field.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rockmass::dda3d {

DisplacementMatrix displacementMatrix(const geometry::Vec3& point, const geometry::Vec3& centroid) {
  const double x = point.x() - centroid.x();
  const double y = point.y() - centroid.y();
  const double z = point.z() - centroid.z();
  DisplacementMatrix t;
  // clang-format off
  //   u0   v0   w0   rx   ry   rz   ex   ey   ez   gyz      gzx      gxy
  t << 1.0, 0.0, 0.0, 0.0, z,   -y,  x,   0.0, 0.0, 0.0,     0.5 * z, 0.5 * y,
       0.0, 1.0, 0.0, -z,  0.0, x,   0.0, y,   0.0, 0.5 * z, 0.0,     0.5 * x,
       0.0, 0.0, 1.0, y,   -x,  0.0, 0.0, 0.0, z,   0.5 * y, 0.5 * x, 0.0;
  // clang-format on
  return t;
}

ElasticMatrix elasticMatrix(double young, double poisson) {
  if (!(std::isfinite(young) && young > 0.0)) {
    throw std::invalid_argument("Young's modulus must be finite and > 0 Pa, got " +
                                std::to_string(young));
  }
  if (!(poisson > -1.0 && poisson < 0.5)) {
    throw std::invalid_argument("Poisson's ratio must lie in (-1, 0.5), got " +
                                std::to_string(poisson));
  }
  const double stiffness_scale = young / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  const double normal = stiffness_scale * (1.0 - poisson);
  const double cross = stiffness_scale * poisson;
  const double shear = young / (2.0 * (1.0 + poisson));
  ElasticMatrix e = ElasticMatrix::Zero();
  e.topLeftCorner<3, 3>().setConstant(cross);
  e.topLeftCorner<3, 3>().diagonal().setConstant(normal);
  e.bottomRightCorner<3, 3>().diagonal().setConstant(shear);
  return e;
}

}  // namespace rockmass::dda3d
