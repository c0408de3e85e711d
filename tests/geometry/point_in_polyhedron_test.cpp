// Point location in a convex polyhedron by its face planes (the half-space representation
// of a convex polyhedron: inside iff n_f . (p - v_f) <= 0 for every face f).
#include "geometry/point_in_polyhedron.h"

#include <gtest/gtest.h>

namespace rockmass::geometry {
namespace {

TEST(PointInPolyhedron, SignedPlaneDistanceOfABox) {
  const Polyhedron box = boxPolyhedron({{0, 0, 0}, {2, 1, 4}});
  // Inside: minus the distance to the nearest face (y = 0 or y = 1, 0.5 away). Binary
  // fractions: exact.
  EXPECT_EQ(convexPlaneDistance(box, Vec3(1, 0.5, 2)), -0.5);
  EXPECT_EQ(convexPlaneDistance(box, Vec3(1.75, 0.5, 2)), -0.25);
  EXPECT_EQ(convexPlaneDistance(box, Vec3(2, 0.5, 2)), 0.0);  // on a face
  // Outside past a corner: the largest plane distance (3), a lower bound of the true
  // distance sqrt(3^2 + 1^2).
  EXPECT_EQ(convexPlaneDistance(box, Vec3(5, 2, 2)), 3.0);
  EXPECT_TRUE(convexContains(box, Vec3(2, 1, 4), 0.0));  // a vertex
  EXPECT_FALSE(convexContains(box, Vec3(2.001, 0.5, 2), 1e-6));
  EXPECT_TRUE(convexContains(box, Vec3(2.000001, 0.5, 2), 1e-5));
}

TEST(PointInPolyhedron, TetrahedronWithASlantedFace) {
  // x + y + z <= 1 in the positive octant; the slanted face's unit normal is (1,1,1)/sqrt 3.
  Polyhedron tet;
  tet.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tet.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  ASSERT_GT(massProperties(tet).volume, 0.0);
  EXPECT_TRUE(convexContains(tet, Vec3(0.3, 0.3, 0.3), 0.0));
  // (0.4, 0.4, 0.4) is (1.2 - 1)/sqrt 3 = 0.11547 beyond the slanted face.
  EXPECT_NEAR(convexPlaneDistance(tet, Vec3(0.4, 0.4, 0.4)), 0.2 / std::sqrt(3.0), 1e-15);
  EXPECT_FALSE(convexContains(tet, Vec3(0.4, 0.4, 0.4), 0.1));
}

TEST(PointInPolyhedron, DegenerateFacesAreIgnored) {
  // A box with an extra zero-area face (three collinear points) still locates correctly.
  Polyhedron box = boxPolyhedron({{0, 0, 0}, {1, 1, 1}});
  box.vertices.push_back({0.5, 0, 0});
  box.faces.push_back({0, 8, 1});
  EXPECT_EQ(convexPlaneDistance(box, Vec3(0.5, 0.5, 0.5)), -0.5);
}

}  // namespace
}  // namespace rockmass::geometry
