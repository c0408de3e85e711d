// Disc geometry: outlines, line intersection, clipped areas, polygon discs.
#include "geometry/disc.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/orientation.h"

namespace rockmass::geometry {
namespace {

Disc ellipse(const Vec3& center, const Vec3& normal, const Vec3& major, double a, double b) {
  Disc d;
  d.center = center;
  d.normal = normal.normalized();
  d.major = major.normalized();
  d.a = a;
  d.b = b;
  return d;
}

TEST(Disc, OutlineLiesOnTheEllipseCounterClockwise) {
  const Vec3 n = normalFromOrientation({60.0, 35.0});
  const Disc d = ellipse({1, 2, 3}, n, strikeVector({60.0, 35.0}), 4.0, 1.5);
  const std::vector<Vec3> outline = d.outline(24);
  ASSERT_EQ(outline.size(), 24u);
  for (const Vec3& p : outline) {
    const Vec3 q = p - d.center;
    EXPECT_NEAR(q.dot(n), 0.0, 1e-14);
    EXPECT_NEAR(std::pow(q.dot(d.major) / 4.0, 2) + std::pow(q.dot(d.minor()) / 1.5, 2), 1.0,
                1e-14);
  }
  // Counter-clockwise about the normal; the inscribed 24-gon has (n/2) sin(2 pi/n) a b.
  EXPECT_NEAR(polygonNormal(outline).dot(n), 1.0, 1e-14);
  EXPECT_NEAR(polygonArea(outline), 12.0 * std::sin(2 * kPi / 24) * 6.0, 1e-12);
  EXPECT_NEAR(d.area(), kPi * 6.0, 1e-14);
}

TEST(Disc, LineIntersection) {
  const Disc d = ellipse({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 2.0, 1.0);
  // Straight down through the centre from z = 5: hit at t = 5.
  EXPECT_DOUBLE_EQ(*d.intersectLine({0, 0, 5}, {0, 0, -1}), 5.0);
  // Inside along the major axis, outside along the minor axis at the same distance.
  EXPECT_TRUE(d.intersectLine({1.9, 0, 1}, {0, 0, -2}).has_value());
  EXPECT_FALSE(d.intersectLine({0, 1.1, 1}, {0, 0, -2}).has_value());
  // Parallel to the plane: no crossing.
  EXPECT_FALSE(d.intersectLine({0, 0, 1}, {1, 0, 0}).has_value());
  // Polygon form: a unit square with a notch-free interior.
  const Disc square = discFromPolygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});
  EXPECT_TRUE(square.intersectLine({0.9, 0.9, -1}, {0, 0, 1}).has_value());
  EXPECT_FALSE(square.intersectLine({1.1, 0.5, -1}, {0, 0, 1}).has_value());
}

TEST(Disc, AreaInsideABox) {
  const Box box{{0, 0, 0}, {10, 10, 10}};
  // Fully inside: exactly pi a b.
  const Disc inside = ellipse({5, 5, 5}, {0, 0, 1}, {1, 0, 0}, 2.0, 1.0);
  EXPECT_DOUBLE_EQ(inside.areaInside(box), 2.0 * kPi);
  // Centred on the face x = 10 with its normal along z: half the area (the clipped
  // 128-gon keeps the ellipse's area to 1e-3 relative, as documented).
  const Disc half = ellipse({10, 5, 5}, {0, 0, 1}, {1, 0, 0}, 2.0, 1.0);
  EXPECT_NEAR(half.areaInside(box), kPi, 1e-3 * kPi);
  // Centred on the edge x = 10, y = 10: a quarter.
  const Disc quarter = ellipse({10, 10, 5}, {0, 0, 1}, {1, 0, 0}, 2.0, 1.0);
  EXPECT_NEAR(quarter.areaInside(box), 0.5 * kPi, 1e-3 * kPi);
  // Far away: nothing. A disc larger than the box, through its middle: the full section.
  EXPECT_EQ(ellipse({20, 5, 5}, {0, 0, 1}, {1, 0, 0}, 2.0, 1.0).areaInside(box), 0.0);
  const Disc big = ellipse({5, 5, 5}, {1, 0, 0}, {0, 1, 0}, 100.0, 100.0);
  EXPECT_NEAR(big.areaInside(box), 100.0, 1e-9);
}

TEST(Disc, PolygonDiscDescribesItsPolygon) {
  const Disc d = discFromPolygon({{-1, -1, 5}, {1, -1, 5}, {1, 1, 5}, {-1, 1, 5}});
  EXPECT_NEAR((d.center - Vec3(0, 0, 5)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(std::abs(d.normal.z()), 1.0, 1e-15);
  EXPECT_DOUBLE_EQ(d.area(), 4.0);
  EXPECT_DOUBLE_EQ(d.a, std::sqrt(2.0));
  EXPECT_NEAR(d.b, 4.0 / (kPi * std::sqrt(2.0)), 1e-15);
  EXPECT_NEAR(d.major.dot(d.normal), 0.0, 1e-15);
  EXPECT_EQ(d.outline(24).size(), 4u);  // polygons are used as given
  // Clipping keeps exact areas for polygons: the square cut by x <= 0.5.
  EXPECT_NEAR(d.areaInside(Box{{-5, -5, 0}, {0.5, 5, 10}}), 3.0, 1e-15);
  EXPECT_THROW(discFromPolygon({{0, 0, 0}, {1, 0, 0}}), std::invalid_argument);
  EXPECT_THROW(discFromPolygon({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}), std::invalid_argument);
}

}  // namespace
}  // namespace rockmass::geometry
