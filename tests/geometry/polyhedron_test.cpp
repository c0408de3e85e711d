#include "geometry/polyhedron.h"

#include <gtest/gtest.h>

namespace rockmass::geometry {
namespace {

/// The tetrahedron 0, a e_x, b e_y, c e_z (outward faces).
Polyhedron cornerTetrahedron(double a, double b, double c, const Vec3& shift) {
  Polyhedron p;
  p.vertices = {shift, shift + Vec3(a, 0, 0), shift + Vec3(0, b, 0), shift + Vec3(0, 0, c)};
  p.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return p;
}

TEST(Polyhedron, BoxMassPropertiesAreExact) {
  // A box [x0, x1] x ... has V = product of sides, centroid at the centre and central second
  // moments diag(V l_x^2 / 12, ...) with zero products (textbook rectangular prism). A far
  // offset checks that round-off stays relative to the box size.
  const Box box{Vec3(1000.0, -2000.0, 500.0), Vec3(1002.0, -1997.0, 504.0)};
  const MassProperties m = massProperties(boxPolyhedron(box));
  EXPECT_NEAR(m.volume, 24.0, 1e-12);
  EXPECT_NEAR((m.centroid() - box.center()).norm(), 0.0, 1e-10);
  const Eigen::Matrix3d central = m.centralSecond();
  EXPECT_NEAR(central(0, 0), 24.0 * 4.0 / 12.0, 1e-6);  // absolute 1e-6 of O(1e7) raw terms
  EXPECT_NEAR(central(1, 1), 24.0 * 9.0 / 12.0, 1e-6);
  EXPECT_NEAR(central(2, 2), 24.0 * 16.0 / 12.0, 1e-6);
  EXPECT_NEAR(central(0, 1), 0.0, 1e-6);
  EXPECT_NEAR(central(1, 2), 0.0, 1e-6);
}

TEST(Polyhedron, ThinBlockFarFromTheOriginKeepsItsCentralMomentsAboutAReference) {
  // A 1 mm sliver 300 m from the origin (a Xiangjiaba block): about the origin its raw
  // moments are ~1e5 V and its thinnest central moment V t^2 / 12 ~ 1e-7 V, below their
  // round-off, so second - V c c^T loses it (the DDA mass matrix was not positive definite).
  // About a point of the block the textbook values V l^2 / 12 come out to 1e-9 relative.
  const Box box{Vec3(300.0, 200.0, -10.0), Vec3(300.5, 200.4, -9.999)};
  const Vec3 l = box.max - box.min;
  const double v = l.x() * l.y() * l.z();
  const MassProperties m = massProperties(boxPolyhedron(box), box.min);
  EXPECT_NEAR(m.volume, v, 1e-12 * v);
  EXPECT_NEAR((box.min + m.centroid() - box.center()).norm(), 0.0, 1e-12);
  const Eigen::Matrix3d central = m.centralSecond();
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(central(k, k), v * l[k] * l[k] / 12.0, 1e-9 * v * l[k] * l[k] / 12.0) << k;
  }
}

TEST(Polyhedron, TetrahedronMatchesClosedForm) {
  // Corner tetrahedron with legs a, b, c: V = abc/6, centroid (a, b, c)/4, and about the
  // corner the integral of x^2 is V a^2 / 10 and of x y is V a b / 20 (Tonon 2004).
  const double a = 2.0, b = 3.0, c = 5.0;
  const MassProperties m = massProperties(cornerTetrahedron(a, b, c, Vec3::Zero()));
  const double v = a * b * c / 6.0;
  EXPECT_NEAR(m.volume, v, 1e-14);
  EXPECT_NEAR((m.centroid() - Vec3(a, b, c) / 4.0).norm(), 0.0, 1e-14);
  EXPECT_NEAR(m.second(0, 0), v * a * a / 10.0, 1e-13);
  EXPECT_NEAR(m.second(2, 2), v * c * c / 10.0, 1e-13);
  EXPECT_NEAR(m.second(0, 1), v * a * b / 20.0, 1e-13);
  EXPECT_NEAR(m.second(1, 2), v * b * c / 20.0, 1e-13);
}

TEST(Polyhedron, InvertedOrientationGivesNegativeVolume) {
  // Outward orientation is part of the contract: reversing every face flips the sign.
  Polyhedron p = boxPolyhedron(Box{Vec3::Zero(), Vec3::Ones()});
  for (std::vector<int>& f : p.faces) std::reverse(f.begin(), f.end());
  EXPECT_DOUBLE_EQ(massProperties(p).volume, -1.0);
}

TEST(Polyhedron, FaceNormalsPointOutward) {
  const Polyhedron p = boxPolyhedron(Box{Vec3::Zero(), Vec3(1.0, 2.0, 3.0)});
  const Vec3 expected[6] = {-Vec3::UnitX(), Vec3::UnitX(),  -Vec3::UnitY(),
                            Vec3::UnitY(),  -Vec3::UnitZ(), Vec3::UnitZ()};
  for (int f = 0; f < 6; ++f) EXPECT_EQ(faceNormal(p, f), expected[f]) << "face " << f;
  const Box b = bounds(p);
  EXPECT_EQ(b.max, Vec3(1.0, 2.0, 3.0));
}

}  // namespace
}  // namespace rockmass::geometry
