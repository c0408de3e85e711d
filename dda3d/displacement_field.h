#pragma once
/// First-order displacement field of a 3D DDA block and the isotropic elastic matrix.
///
/// A block has 12 unknowns about its centroid (see docs dda3d-formulation.md),
/// D = (u0, v0, w0, rx, ry, rz, ex, ey, ez, gyz, gzx, gxy): translation (m), small rotation
/// about x, y, z (rad), normal strains and engineering shear strains (dimensionless).
/// The displacement at a point is u = T(x) D (Shi 1988; Jiang & Yeung 2004).
#include <Eigen/Core>

#include "geometry/vec.h"

namespace rockmass::dda3d {

/// Number of unknowns of a deformable block.
constexpr int kBlockDofs = 12;
/// Number of strain (and stress) components in Voigt order (ex, ey, ez, gyz, gzx, gxy).
constexpr int kVoigtSize = 6;

/// T(x): displacement (m) at a point per unit of each block unknown, 3 x 12.
using DisplacementMatrix = Eigen::Matrix<double, 3, kBlockDofs>;
/// Stress (Pa) per unit strain in Voigt order, 6 x 6.
using ElasticMatrix = Eigen::Matrix<double, kVoigtSize, kVoigtSize>;

/// T(x), 3 x 12: displacement (m) at `point` (m) per unit of each unknown of a block with
/// centroid `centroid` (m); columns u0 v0 w0 rx ry rz ex ey ez gyz gzx gxy.
DisplacementMatrix displacementMatrix(const geometry::Vec3& point, const geometry::Vec3& centroid);

/// Columns rx, ry, rz of displacementMatrix(centroid + arm, centroid): the small rotation's
/// displacement r x arm as a matrix R (R r = r x arm).
inline Eigen::Matrix3d rotationColumns(const geometry::Vec3& arm) {
  Eigen::Matrix3d r;
  // clang-format off
  r << 0.0,      arm.z(),  -arm.y(),
       -arm.z(), 0.0,      arm.x(),
       arm.y(),  -arm.x(), 0.0;
  // clang-format on
  return r;
}

/// Isotropic elastic matrix (Pa), 6 x 6, mapping strains (ex, ey, ez, gyz, gzx, gxy) with
/// engineering shear strains to stresses (sx, sy, sz, tyz, tzx, txy); `young` in Pa (> 0),
/// `poisson` dimensionless in (-1, 0.5). Throws std::invalid_argument otherwise.
ElasticMatrix elasticMatrix(double young, double poisson);

}  // namespace rockmass::dda3d
