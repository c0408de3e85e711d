// The first-order displacement field T(x) of a 3D DDA block (Shi 1988; Jiang & Yeung 2004;
// docs dda3d-formulation.md) and the isotropic elastic matrix (Hooke's law, e.g. Timoshenko &
// Goodier, Theory of Elasticity, ch. 1).
#include "dda3d/displacement_field.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/LU>

namespace rockmass::dda3d {
namespace {

using geometry::Vec3;
using BlockVector = Eigen::Matrix<double, kBlockDofs, 1>;
using VoigtVector = Eigen::Matrix<double, kVoigtSize, 1>;

constexpr double kEps = std::numeric_limits<double>::epsilon();

// A point away from the centroid in every axis, so that every entry of T is exercised.
const Vec3 block_centroid(1.0, 2.0, -3.0);
const Vec3 test_point(3.5, -1.0, 0.25);

TEST(DisplacementMatrix, HasTheFormulationLayout) {
  // X = 2.5, Y = -3, Z = 3.25: each entry is one coordinate or half of one, so exact.
  const double x = 2.5, y = -3.0, z = 3.25;
  DisplacementMatrix expected;
  // clang-format off
  expected << 1, 0, 0,  0,  z, -y, x, 0, 0, 0,     z / 2, y / 2,
              0, 1, 0, -z,  0,  x, 0, y, 0, z / 2, 0,     x / 2,
              0, 0, 1,  y, -x,  0, 0, 0, z, y / 2, x / 2, 0;
  // clang-format on
  EXPECT_EQ(displacementMatrix(test_point, block_centroid), expected);
  DisplacementMatrix at_centroid = DisplacementMatrix::Zero();
  at_centroid.leftCols<3>().setIdentity();
  EXPECT_EQ(displacementMatrix(block_centroid, block_centroid), at_centroid);
}

TEST(DisplacementMatrix, ReproducesRigidTranslation) {
  // Only the identity block multiplies non-zero unknowns: exact.
  BlockVector d = BlockVector::Zero();
  d.head<3>() << 0.1, -0.2, 0.3;
  EXPECT_EQ(displacementMatrix(test_point, block_centroid) * d, Vec3(0.1, -0.2, 0.3));
}

TEST(DisplacementMatrix, ReproducesSmallRotation) {
  // u = r x X for a small rotation vector r. Each component is a sum of two products, so
  // rounding is below 2 ulps of |r| |X|.
  const Vec3 arm = test_point - block_centroid;
  const auto check = [&](const Vec3& r) {
    BlockVector d = BlockVector::Zero();
    d.segment<3>(3) = r;
    const Vec3 u = displacementMatrix(test_point, block_centroid) * d;
    const double tolerance = 4.0 * kEps * r.norm() * arm.norm();
    EXPECT_NEAR((u - r.cross(arm)).norm(), 0.0, tolerance) << "r = " << r.transpose();
    return u;
  };
  const double rz = 1e-3;
  const Vec3 about_z = check(Vec3(0.0, 0.0, rz));
  EXPECT_NEAR(about_z.x(), -rz * arm.y(), kEps * rz * arm.norm());
  EXPECT_NEAR(about_z.y(), rz * arm.x(), kEps * rz * arm.norm());
  EXPECT_EQ(about_z.z(), 0.0);
  check(Vec3(2e-3, -1e-3, 5e-4));
}

TEST(DisplacementMatrix, ReproducesUniformStrain) {
  // u = ex X, v = ey Y, w = ez Z for normal strains; a shear g_ij moves i by g_ij x_j / 2 and
  // j by g_ij x_i / 2 (engineering shear strain). Single products: 1 ulp.
  const Vec3 arm = test_point - block_centroid;
  const DisplacementMatrix t = displacementMatrix(test_point, block_centroid);
  const auto displacement = [&](int unknown, double value) {
    BlockVector d = BlockVector::Zero();
    d[unknown] = value;
    return Vec3(t * d);
  };
  const double tolerance = 2.0 * kEps * 1e-3 * arm.norm();
  const auto expect_near = [&](const Vec3& actual, const Vec3& expected, const char* what) {
    EXPECT_NEAR((actual - expected).norm(), 0.0, tolerance) << what;
  };
  const double g = 1e-3;
  expect_near(displacement(6, g), Vec3(g * arm.x(), 0, 0), "ex");
  expect_near(displacement(7, g), Vec3(0, g * arm.y(), 0), "ey");
  expect_near(displacement(8, g), Vec3(0, 0, g * arm.z()), "ez");
  expect_near(displacement(9, g), Vec3(0, g * arm.z() / 2, g * arm.y() / 2), "gyz");
  expect_near(displacement(10, g), Vec3(g * arm.z() / 2, 0, g * arm.x() / 2), "gzx");
  expect_near(displacement(11, g), Vec3(g * arm.y() / 2, g * arm.x() / 2, 0), "gxy");
}

TEST(DisplacementMatrix, StrainOfFieldEqualsStrainUnknowns) {
  // Differentiate u(x) = T(x) D by central differences. u is linear in x, so the
  // differences have no truncation error; with h = 0.25 (x +- h exact) rounding is about
  // eps |u| / h ~ 1e-16, and 1e-13 is a wide margin.
  BlockVector d;
  d << 0.3, -0.1, 0.2, 2e-3, -1e-3, 4e-3, 1e-3, -2e-3, 5e-4, 3e-3, -1.5e-3, 2.5e-3;
  const auto u = [&](const Vec3& x) { return Vec3(displacementMatrix(x, block_centroid) * d); };
  constexpr double kStep = 0.25;
  Eigen::Matrix3d gradient;  // gradient(i, j) = du_i / dx_j
  for (int j = 0; j < 3; ++j) {
    const Vec3 h = kStep * Vec3::Unit(j);
    gradient.col(j) = (u(test_point + h) - u(test_point - h)) / (2.0 * kStep);
  }
  VoigtVector strain;
  strain << gradient(0, 0), gradient(1, 1), gradient(2, 2), gradient(1, 2) + gradient(2, 1),
      gradient(2, 0) + gradient(0, 2), gradient(0, 1) + gradient(1, 0);
  const Vec3 rotation(0.5 * (gradient(2, 1) - gradient(1, 2)),
                      0.5 * (gradient(0, 2) - gradient(2, 0)),
                      0.5 * (gradient(1, 0) - gradient(0, 1)));
  for (int i = 0; i < kVoigtSize; ++i) {
    EXPECT_NEAR(strain[i], d[6 + i], 1e-13) << "strain component " << i;
  }
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(rotation[i], d[3 + i], 1e-13) << "rotation component " << i;
  }
}

TEST(ElasticMatrix, IsHookesLaw) {
  // Young's modulus of a hard rock; Poisson's ratios: typical, auxetic, nearly
  // incompressible. Tolerance 1e-12 relative: the inverse of E loses about
  // cond(E) ~ 1 / (1 - 2 nu) = 50 ulps at nu = 0.49, i.e. 1e-14.
  constexpr double kYoung = 30e9;  // Pa
  for (double nu : {0.25, -0.5, 0.49}) {
    SCOPED_TRACE(::testing::Message() << "nu = " << nu);
    const ElasticMatrix e = elasticMatrix(kYoung, nu);
    EXPECT_EQ(e, e.transpose());

    // Uniaxial strain (confined): sx = E (1 - nu) / ((1 + nu)(1 - 2 nu)) eps, and the
    // lateral stresses sy = sz = E nu / ((1 + nu)(1 - 2 nu)) eps.
    const double eps = 1e-4;
    const VoigtVector stress = e * (VoigtVector() << eps, 0, 0, 0, 0, 0).finished();
    const double scale = kYoung / ((1 + nu) * (1 - 2 * nu));
    const double sx = scale * (1 - nu) * eps;
    EXPECT_NEAR(stress[0], sx, 1e-12 * sx);
    EXPECT_NEAR(stress[1], scale * nu * eps, 1e-12 * sx);
    EXPECT_NEAR(stress[2], scale * nu * eps, 1e-12 * sx);
    EXPECT_EQ(stress.tail<3>(), Eigen::Vector3d::Zero());

    // Uniaxial stress: ex = s / E, ey = ez = -nu s / E, no shear.
    const ElasticMatrix compliance = e.inverse();
    const double s = 1e6;  // Pa
    const VoigtVector strain = compliance * (VoigtVector() << s, 0, 0, 0, 0, 0).finished();
    const double ex = s / kYoung;
    EXPECT_NEAR(strain[0], ex, 1e-12 * ex);
    EXPECT_NEAR(strain[1], -nu * ex, 1e-12 * ex);
    EXPECT_NEAR(strain[2], -nu * ex, 1e-12 * ex);
    EXPECT_NEAR(strain.tail<3>().norm(), 0.0, 1e-12 * ex);

    // Pure shear stress txy: engineering shear strain gxy = txy / G, G = E / (2 (1 + nu)).
    const VoigtVector shear = compliance * (VoigtVector() << 0, 0, 0, 0, 0, s).finished();
    const double gxy = 2 * (1 + nu) * s / kYoung;
    EXPECT_NEAR(shear[5], gxy, 1e-12 * gxy);
    EXPECT_NEAR(shear.head<5>().norm(), 0.0, 1e-12 * gxy);
  }
}

TEST(ElasticMatrix, RejectsNonPhysicalConstants) {
  const double nan = std::nan("");
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(elasticMatrix(0.0, 0.25), std::invalid_argument);
  EXPECT_THROW(elasticMatrix(-1e9, 0.25), std::invalid_argument);
  EXPECT_THROW(elasticMatrix(nan, 0.25), std::invalid_argument);
  EXPECT_THROW(elasticMatrix(inf, 0.25), std::invalid_argument);
  EXPECT_THROW(elasticMatrix(1e9, -1.0), std::invalid_argument);
  EXPECT_THROW(elasticMatrix(1e9, 0.5), std::invalid_argument);
  EXPECT_THROW(elasticMatrix(1e9, 0.6), std::invalid_argument);
  EXPECT_THROW(elasticMatrix(1e9, nan), std::invalid_argument);
}

}  // namespace
}  // namespace rockmass::dda3d
