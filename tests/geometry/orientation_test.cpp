// Orientation conventions (ISRM dip direction / dip; x = East, y = North, z = Up).
#include "geometry/orientation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace rockmass::geometry {
namespace {

// Exact-arithmetic cases are compared to 1e-15: only sin/cos rounding remains.
constexpr double kTight = 1e-15;

void expectNear(const Vec3& actual, const Vec3& expected, double tolerance) {
  EXPECT_NEAR(actual.x(), expected.x(), tolerance);
  EXPECT_NEAR(actual.y(), expected.y(), tolerance);
  EXPECT_NEAR(actual.z(), expected.z(), tolerance);
}

TEST(Orientation, KnownNormals) {
  // A vertical plane dipping North has its normal along +-y.
  expectNear(normalFromOrientation({0.0, 90.0}), Vec3(0, 1, 0), kTight);
  // A vertical plane dipping East: normal along +x.
  expectNear(normalFromOrientation({90.0, 90.0}), Vec3(1, 0, 0), kTight);
  // A horizontal plane: normal up, whatever the dip direction.
  expectNear(normalFromOrientation({123.0, 0.0}), Vec3(0, 0, 1), kTight);
  // 45 degrees towards the South-West (225): normal (-1/2, -1/2, sqrt(2)/2).
  expectNear(normalFromOrientation({225.0, 45.0}), Vec3(-0.5, -0.5, std::sqrt(0.5)), kTight);
}

TEST(Orientation, StrikeFollowsTheRightHandRule) {
  // Dip direction East -> strike North; dip direction North -> strike West.
  expectNear(strikeVector({90.0, 30.0}), Vec3(0, 1, 0), kTight);
  expectNear(strikeVector({0.0, 30.0}), Vec3(-1, 0, 0), kTight);
  // Dip vector of a plane dipping 30 degrees East: (cos 30, 0, -sin 30).
  expectNear(dipVector({90.0, 30.0}), Vec3(std::cos(radians(30)), 0, -0.5), kTight);
  // Looking along strike the plane dips to the right: dip x strike is the upward normal.
  for (double dd = 0.0; dd < 360.0; dd += 17.0) {
    const PlaneOrientation o{dd, 63.0};
    expectNear(dipVector(o).cross(strikeVector(o)), normalFromOrientation(o), 1e-15);
  }
}

TEST(Orientation, RoundTripOverTheHemisphere) {
  // Round trips lose only rounding: 1e-9 degrees is far above it and far below any use.
  for (double dd = 0.0; dd < 360.0; dd += 7.3) {
    for (double dip = 0.5; dip <= 90.0; dip += 4.45) {
      const Vec3 n = normalFromOrientation({dd, dip});
      EXPECT_NEAR(n.norm(), 1.0, 1e-15);
      for (const Vec3& candidate : {n, Vec3(-n), Vec3(3.7 * n)}) {
        const PlaneOrientation back = orientationFromNormal(candidate);
        EXPECT_NEAR(back.dip, dip, 1e-9);
        if (dip < 90.0) {
          EXPECT_NEAR(back.dip_direction, dd, 1e-9) << "dip " << dip;
        } else {
          // A vertical plane: the two dip directions 180 degrees apart are one plane.
          EXPECT_NEAR(std::abs(std::remainder(back.dip_direction - dd, 180.0)), 0.0, 1e-9);
        }
      }
    }
  }
}

TEST(Orientation, HorizontalPlaneAndBadInput) {
  const PlaneOrientation flat = orientationFromNormal(Vec3(0, 0, -2));
  EXPECT_EQ(flat.dip, 0.0);
  EXPECT_EQ(flat.dip_direction, 0.0);
  EXPECT_THROW(orientationFromNormal(Vec3::Zero()), std::invalid_argument);
  EXPECT_EQ(wrapDegrees(-90.0), 270.0);
  EXPECT_EQ(wrapDegrees(720.0), 0.0);
  EXPECT_EQ(wrapDegrees(-1e-20), 0.0);
}

}  // namespace
}  // namespace rockmass::geometry
