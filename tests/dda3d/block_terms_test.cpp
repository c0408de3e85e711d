// Sub-matrices of one block against closed forms: the mass matrix of a cube (integral of
// X^2 over a cube of side s is s^5 / 12) and the hydrostatic load on a half-submerged face
// (integrals of linear and quadratic pressures over a rectangle).
#include "dda3d/block_terms.h"

#include <gtest/gtest.h>

namespace rockmass::dda3d {
namespace {

using geometry::Vec3;

BlockState cube(double side, double density) {
  BlockState b;
  b.pieces.push_back(geometry::boxPolyhedron({Vec3::Zero(), Vec3::Constant(side)}));
  b.updateMassProperties();
  b.mass = density * b.volume;
  return b;
}

TEST(BlockTerms, CubeMassMatrix) {
  const double s = 2.0, rho = 2600.0;
  const BlockMatrix m = massMatrix(cube(s, rho));
  const double second = std::pow(s, 5) / 12.0;  // integral of X^2
  // Translation: rho V; rotation about x: rho (Y^2 + Z^2); strain ex: rho X^2; shear gyz:
  // rho (Z^2 + Y^2) / 4. Sums of exact products: 1e-12 relative.
  EXPECT_NEAR(m(0, 0), rho * s * s * s, 1e-12 * rho * s * s * s);
  EXPECT_NEAR(m(3, 3), rho * 2.0 * second, 1e-12 * rho * second);
  EXPECT_NEAR(m(6, 6), rho * second, 1e-12 * rho * second);
  EXPECT_NEAR(m(9, 9), rho * 2.0 * second / 4.0, 1e-12 * rho * second);
  // A cube's second moments are isotropic: rotation and strain do not couple.
  EXPECT_NEAR((m.block<3, 6>(3, 6)).norm(), 0.0, 1e-12 * rho * second);
  EXPECT_EQ(m, m.transpose());
}

TEST(BlockTerms, HalfSubmergedFacePressure) {
  // Unit cube, water level z = 0.5, face x = 0 (outward normal -x, index 0 of
  // boxPolyhedron). p = gw (0.5 - z) on 0 <= z <= 0.5: force +x of gw / 8; moment about
  // the centroid's y axis (unknown ry, T_u = Z): integral of (z - 1/2) p = -gw / 24.
  const BlockState b = cube(1.0, 2600.0);
  const double gw = 9810.0;
  const BlockVector f = pressureLoad(b, b.pieces[0], 0, 0.5, gw);
  EXPECT_NEAR(f[0], gw / 8.0, 1e-12 * gw);  // the midpoint rule is exact for quadratics
  EXPECT_NEAR(f[1], 0.0, 1e-12 * gw);
  EXPECT_NEAR(f[2], 0.0, 1e-12 * gw);
  EXPECT_NEAR(f[4], -gw / 24.0, 1e-12 * gw);
  // A dry face (level below it) carries nothing.
  EXPECT_EQ(pressureLoad(b, b.pieces[0], 0, -0.1, gw), BlockVector::Zero());
}

}  // namespace
}  // namespace rockmass::dda3d
