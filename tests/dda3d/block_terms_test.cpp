// Sub-matrices of one block against closed forms: the mass matrix of a cube (integral of
// X^2 over a cube of side s is s^5 / 12), the hydrostatic load on a half-submerged face and
// a pressure under a head rising in plan (integrals of linear and quadratic pressures over a
// rectangle), and Westergaard's added pressure on a vertical face.
#include "dda3d/block_terms.h"
#include "tests/support/verification.h"

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

TEST(BlockTerms, PressureWithAHeadGradientAndAHalfSpaceIsIntegratedExactly) {
  // The bottom face (z = 0, outward -z, index 4) of a 2 m cube under a head rising along x,
  // h = 2 + 0.5 x (an uplift diagram's linear part): p = gw (2 + 0.5 x), pushing up.
  // Whole face: gw * integral over [0,2]^2 of (2 + 0.5 x) = gw (8 + 2) = 10 gw.
  // Only x <= 1 (a drain line): gw * 2 * (2 + 0.25) = 4.5 gw.
  BlockState b;
  b.pieces.push_back(geometry::boxPolyhedron({Vec3::Zero(), Vec3::Constant(2.0)}));
  b.updateMassProperties();
  const double gw = 9810.0;
  DdaPressure p = hydrostaticPressure(0, 0, 4, 2.0, gw, /*uplift=*/true);
  p.head_gradient = Vec3(0.5, 0.0, 0.0);
  const BlockVector whole = pressureLoad(b, b.pieces[0], 4, p);
  EXPECT_NEAR(whole[2], 10.0 * gw, 1e-12 * gw);  // the edge-midpoint rule is exact (quadratic)
  EXPECT_NEAR(pressureResultant(b.pieces[0], 4, p).z(), 10.0 * gw, 1e-12 * gw);
  // The moment about the centroid's y axis: gw * integral_0^2 2 (2 + 0.5 x)(x - 1) dx =
  // 2/3 gw (the side of higher head carries more), as -r_y for an upward force east of the
  // centroid.
  EXPECT_NEAR(whole[4], -2.0 / 3.0 * gw, 1e-12 * gw);
  p.within = {{Vec3::UnitX(), 1.0}};
  EXPECT_NEAR(pressureLoad(b, b.pieces[0], 4, p)[2], 4.5 * gw, 1e-12 * gw);
  // A head below the face wets nothing.
  p.level = -1.0;
  p.head_gradient = Vec3::Zero();
  EXPECT_EQ(pressureLoad(b, b.pieces[0], 4, p), BlockVector::Zero());
}

TEST(BlockTerms, WestergaardResultantOnAVerticalFace) {
  // Westergaard (1933), as USBR Design of Small Dams (ch. 8) uses it: on a vertical face in a
  // reservoir of depth h, p = 7/8 k_h gw sqrt(h y) at depth y; the resultant per unit width is
  // 7/12 k_h gw h^2, acting 0.4 h above the base. Face x = 0 (outward -x) of a 1 x 1 x 10 m
  // block, water to its top: 7/12 * 0.1 * 9810 * 100 = 57 225 N along +x.
  BlockState b;
  b.pieces.push_back(geometry::boxPolyhedron({Vec3::Zero(), Vec3(1.0, 1.0, 10.0)}));
  b.updateMassProperties();
  const DdaHydrodynamicPressure w{.block = 0,
                                  .piece = 0,
                                  .face = 0,
                                  .level = 10.0,
                                  .depth = 10.0,
                                  .k_h = 0.1,
                                  .unit_weight = 9810.0};
  const BlockVector f = hydrodynamicLoad(b, b.pieces[0], 0, w);
  const double resultant = 7.0 / 12.0 * 0.1 * 9810.0 * 100.0;
  EXPECT_NEAR(f[0], resultant, 0.01 * resultant);  // the 1 %
  test::recordVerification({.group = "Earthquakes",
                            .name = "Westergaard added pressure on a vertical face 10 m deep, "
                                    "k_h = 0.1: resultant per unit width",
                            .source = "7/12 k_h gamma_w h^2 (Westergaard 1933; USBR, Design of "
                                      "Small Dams, ch. 8)",
                            .expected = resultant,
                            .measured = f[0],
                            .tolerance = 0.01,
                            .relative = true,
                            .unit = "N"});
  // Its line of action 0.4 h above the base: the moment about the centroid (z = 5) is
  // F (4 - 5) about y for a force along +x (r_y = z-lever: T_u = Z r_y).
  EXPECT_NEAR(f[4] / f[0], 4.0 - 5.0, 0.01 * 10.0);
  // Above the reservoir nothing; with k_h = 0 nothing.
  DdaHydrodynamicPressure dry = w;
  dry.k_h = 0.0;
  EXPECT_EQ(hydrodynamicLoad(b, b.pieces[0], 0, dry), BlockVector::Zero());
}

}  // namespace
}  // namespace rockmass::dda3d
