// Plane sections of convex polyhedra and fracture traces against results known in closed
// form (elementary geometry: rectangles, similar triangles, the regular hexagon of a cube's
// mid-plane, chords of circles and ellipses), and the degenerate cases: a plane that only
// touches a polyhedron, a fracture parallel to the plane, a non-convex polygon.
#include "geometry/plane_section.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace rockmass::geometry {
namespace {

/// A tetrahedron with outward faces: the corner at the origin and the unit points.
Polyhedron unitTetrahedron() {
  Polyhedron t;
  t.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  t.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return t;
}

/// The plane through `point` with unit normal `normal` and some orthonormal frame.
SectionPlane planeThrough(const Vec3& point, const Vec3& normal) {
  SectionPlane p;
  p.origin = point;
  p.normal = normal.normalized();
  p.u_axis = p.normal.unitOrthogonal();
  p.v_axis = p.normal.cross(p.u_axis);
  return p;
}

TEST(PlaneSection, BoxCutByAnAxisPlaneIsItsSideRectangle) {
  const Polyhedron box = boxPolyhedron({{0, 0, 0}, {2, 3, 4}});
  const auto s = sectionPolyhedron(box, axisPlane(1, 1.0));
  ASSERT_TRUE(s);
  ASSERT_EQ(s->points.size(), 4u);
  EXPECT_NEAR(signedArea(s->points), 8.0, 1e-12);  // 2 x 4, counter-clockwise (> 0)
  // u = x and v = z for a y plane: the corners are the box's x-z corners.
  for (const Vec2& p : s->points) {
    EXPECT_TRUE(p.x() == 0.0 || p.x() == 2.0);
    EXPECT_TRUE(p.y() == 0.0 || p.y() == 4.0);
  }
  // Each edge lies in one of the four side faces (not in the y faces).
  ASSERT_EQ(s->edge_faces.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    const Vec3 n = faceNormal(box, s->edge_faces[static_cast<std::size_t>(k)]);
    EXPECT_NEAR(std::abs(n.y()), 0.0, 1e-12);
  }
}

TEST(PlaneSection, ObliquePlaneThroughABox) {
  // x + y = 2.5 crosses [0,2] x [0,3] along a segment of length 2 sqrt(2), times the height 4.
  const Polyhedron box = boxPolyhedron({{0, 0, 0}, {2, 3, 4}});
  const auto s = sectionPolyhedron(box, planeThrough({1.25, 1.25, 0}, {1, 1, 0}));
  ASSERT_TRUE(s);
  EXPECT_NEAR(std::abs(signedArea(s->points)), 8.0 * std::sqrt(2.0), 1e-9);
}

TEST(PlaneSection, CubeMidPlaneIsARegularHexagon) {
  // x + y + z = 1.5 cuts the unit cube in a regular hexagon of side sqrt(2)/2: area
  // (3 sqrt(3) / 2) s^2 = 3 sqrt(3) / 4.
  const Polyhedron cube = boxPolyhedron({{0, 0, 0}, {1, 1, 1}});
  const auto s = sectionPolyhedron(cube, planeThrough({0.5, 0.5, 0.5}, {1, 1, 1}));
  ASSERT_TRUE(s);
  ASSERT_EQ(s->points.size(), 6u);
  EXPECT_NEAR(signedArea(s->points), 3.0 * std::sqrt(3.0) / 4.0, 1e-12);
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_NEAR((s->points[(k + 1) % 6] - s->points[k]).norm(), std::sqrt(0.5), 1e-12);
  }
}

TEST(PlaneSection, TetrahedronAtHalfHeightIsAQuarterOfItsBase) {
  // z = 0.5 cuts a triangle similar to the base (area 1/2) with ratio 1/2: area 1/8.
  const auto s = sectionPolyhedron(unitTetrahedron(), axisPlane(2, 0.5));
  ASSERT_TRUE(s);
  ASSERT_EQ(s->points.size(), 3u);
  EXPECT_NEAR(signedArea(s->points), 0.125, 1e-15);
}

TEST(PlaneSection, TouchingOrMissingPlanesGiveNothing) {
  const Polyhedron box = boxPolyhedron({{0, 0, 0}, {1, 1, 1}});
  EXPECT_FALSE(sectionPolyhedron(box, axisPlane(1, 0.0)));  // on a face
  EXPECT_FALSE(sectionPolyhedron(box, axisPlane(1, 1.0)));  // on the opposite face
  EXPECT_FALSE(sectionPolyhedron(box, axisPlane(2, 2.0)));  // misses
  // Through one vertex only (x + y + z = 3 touches (1, 1, 1)).
  EXPECT_FALSE(sectionPolyhedron(box, planeThrough({1, 1, 1}, {1, 1, 1})));
  // Along an edge only (x + y = 2 touches the edge x = y = 1).
  EXPECT_FALSE(sectionPolyhedron(box, planeThrough({1, 1, 0}, {1, 1, 0})));
  // A plane through a vertex that also crosses the interior does cut (a triangle).
  const auto s = sectionPolyhedron(unitTetrahedron(), planeThrough({0, 0, 0}, {1, -1, 0}));
  ASSERT_TRUE(s);
  // x = y through the tetrahedron: triangle (0,0,0), (1/2,1/2,0), (0,0,1); area sqrt(2)/4.
  EXPECT_NEAR(std::abs(signedArea(s->points)), std::sqrt(2.0) / 4.0, 1e-12);
}

TEST(PlaneSection, FaceInPlaneAboveGivesTheFaceOfThePolyhedronAbove) {
  // The box [0,2]x[0,1]x[0,3] on the plane y = 0 (normal +y, the box above it): its y_min
  // face, 2 x 3 = 6 m2, whose four edges lie in the x_min, x_max, z_min and z_max faces
  // (boxPolyhedron order 0, 1, 4, 5), never in the y_min face (2) itself.
  const Polyhedron box = boxPolyhedron({{0, 0, 0}, {2, 1, 3}});
  const auto s = sectionPolyhedron(box, axisPlane(1, 0.0), 1e-9, FaceInPlane::Above);
  ASSERT_TRUE(s);
  EXPECT_NEAR(signedArea(s->points), 6.0, 1e-15);
  std::vector<int> faces = s->edge_faces;
  std::sort(faces.begin(), faces.end());
  EXPECT_EQ(faces, (std::vector<int>{0, 1, 4, 5}));
  // On y = 1 the box lies below the plane: nothing, as with Skip on either face.
  EXPECT_FALSE(sectionPolyhedron(box, axisPlane(1, 1.0), 1e-9, FaceInPlane::Above));
  EXPECT_FALSE(sectionPolyhedron(box, axisPlane(1, 0.0), 1e-9, FaceInPlane::Skip));
  // Touching along an edge or at a vertex from above still gives nothing.
  EXPECT_FALSE(
      sectionPolyhedron(box, planeThrough({2, 1, 0}, {1, 1, 0}), 1e-9, FaceInPlane::Above));
  EXPECT_FALSE(sectionPolyhedron(unitTetrahedron(), planeThrough({1, 0, 0}, {1, 0, 0}), 1e-9,
                                 FaceInPlane::Above));
  // A plane within the tolerance of the face (1e-12 below it) is the same case.
  const auto near = sectionPolyhedron(box, axisPlane(1, -1e-12), 1e-9, FaceInPlane::Above);
  ASSERT_TRUE(near);
  EXPECT_NEAR(signedArea(near->points), 6.0, 1e-12);
}

TEST(PlaneSection, CircleAndEllipseChords) {
  const Box big{Vec3::Constant(-100), Vec3::Constant(100)};
  // A circle of radius 2 in the plane x = 0, centre on the y axis at 0.5 from the plane
  // y = 0: chord 2 sqrt(4 - 0.25).
  Disc circle;
  circle.center = {0, 0.5, 0};
  circle.normal = Vec3::UnitX();
  circle.major = Vec3::UnitZ();
  circle.a = circle.b = 2.0;
  auto t = sectionTrace(circle, axisPlane(1, 0.0), big);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_NEAR((t[0].second - t[0].first).norm(), 2.0 * std::sqrt(3.75), 1e-12);
  // An ellipse a = 3 along z, b = 1 along y, cut at 0.5 along its minor axis:
  // x^2 / 9 + 0.25 = 1, chord 6 sqrt(0.75).
  Disc ellipse = circle;
  ellipse.center = Vec3::Zero();
  ellipse.a = 3.0;
  ellipse.b = 1.0;
  t = sectionTrace(ellipse, axisPlane(1, 0.5), big);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_NEAR((t[0].second - t[0].first).norm(), 6.0 * std::sqrt(0.75), 1e-12);
  // Beyond the minor semi-axis: no trace. Parallel to the plane: no trace.
  EXPECT_TRUE(sectionTrace(ellipse, axisPlane(1, 1.5), big).empty());
  EXPECT_TRUE(sectionTrace(ellipse, axisPlane(0, 0.0), big).empty());
  // Clipped by the box: only z in [0, 1] of the chord along z remains.
  t = sectionTrace(ellipse, axisPlane(1, 0.5), {{-1, -1, 0}, {1, 1, 1}});
  ASSERT_EQ(t.size(), 1u);
  EXPECT_NEAR((t[0].second - t[0].first).norm(), 1.0, 1e-12);
}

TEST(PlaneSection, NonConvexPolygonGivesTwoSegments) {
  // A U-shaped polygon in the plane x = 0 (y, z): two prongs above z = 1, cut at z = 1.5:
  // segments y in [0, 1] and [2, 3].
  const Disc u = discFromPolygon(
      {{0, 0, 0}, {0, 3, 0}, {0, 3, 2}, {0, 2, 2}, {0, 2, 1}, {0, 1, 1}, {0, 1, 2}, {0, 0, 2}});
  const auto t = sectionTrace(u, axisPlane(2, 1.5), {Vec3::Constant(-10), Vec3::Constant(10)});
  ASSERT_EQ(t.size(), 2u);
  std::vector<double> lengths = {(t[0].second - t[0].first).norm(),
                                 (t[1].second - t[1].first).norm()};
  EXPECT_NEAR(lengths[0], 1.0, 1e-12);
  EXPECT_NEAR(lengths[1], 1.0, 1e-12);
  // A polygon ellipse (the cutters' 4-gon of a circle of radius 1, a square rotated so that
  // its corners sit on the axes) cut through its centre: the diagonal, length 2.
  Disc circle;
  circle.normal = Vec3::UnitX();
  circle.major = Vec3::UnitY();
  circle.a = circle.b = 1.0;
  const auto d =
      sectionTrace(circle, axisPlane(2, 0.0), {Vec3::Constant(-10), Vec3::Constant(10)}, 4);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_NEAR((d[0].second - d[0].first).norm(), 2.0, 1e-12);
}

}  // namespace
}  // namespace rockmass::geometry
