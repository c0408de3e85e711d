// RQD ball surfaces: the convex hull of the Fibonacci directions is a closed, outward
// oriented triangulated sphere through every direction, in a canonical order.
#include "rqd/ball_mesh.h"

#include <gtest/gtest.h>

#include <map>
#include <utility>
#include <vector>

#include "rqd/directions.h"

namespace rockmass::rqd {
namespace {

using geometry::Vec3;

TEST(SphereTriangles, ClosedOutwardTriangulationThroughEveryDirection) {
  for (const int n : {4, 7, 100, 2000}) {
    const std::vector<Vec3> directions = fibonacciSphere(n);
    const std::vector<std::array<int, 3>> triangles = sphereTriangles(directions);
    // Euler: a triangulated sphere with n vertices has 2n - 4 triangles.
    ASSERT_EQ(triangles.size(), static_cast<std::size_t>(2 * n - 4)) << n;
    std::map<std::pair<int, int>, int> edges;  // directed edge -> count
    std::vector<int> used(n, 0);
    double area = 0.0;
    for (const auto& t : triangles) {
      const Vec3 normal =
          (directions[t[1]] - directions[t[0]]).cross(directions[t[2]] - directions[t[0]]);
      // Outward: the normal points away from the origin, inside the sphere.
      EXPECT_GT(normal.dot(directions[t[0]] + directions[t[1]] + directions[t[2]]), 0.0);
      area += 0.5 * normal.norm();
      for (int c = 0; c < 3; ++c) {
        ++edges[{t[c], t[(c + 1) % 3]}];
        used[t[c]] = 1;
      }
      EXPECT_TRUE(t[0] < t[1] && t[0] < t[2]);  // canonical rotation
    }
    EXPECT_TRUE(std::is_sorted(triangles.begin(), triangles.end()));
    // Closed and consistently oriented: each directed edge once, its reverse once.
    for (const auto& [edge, count] : edges) {
      EXPECT_EQ(count, 1);
      EXPECT_EQ(edges.count({edge.second, edge.first}), 1u);
    }
    for (int v = 0; v < n; ++v) EXPECT_EQ(used[v], 1) << v;
    // 2000 points: the polyhedron's area approaches the sphere's 4 pi from below
    // (within 0.5%: chord error of triangles ~0.08 rad wide).
    if (n == 2000) {
      EXPECT_NEAR(area, 4.0 * 3.14159265358979, 0.02 * 3.14159265358979);
    }
  }
}

TEST(SphereTriangles, RejectsTooFewOrFlatDirections) {
  EXPECT_THROW(sphereTriangles(fibonacciSphere(3)), std::invalid_argument);
  const std::vector<Vec3> flat{Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitX(), -Vec3::UnitY()};
  EXPECT_THROW(sphereTriangles(flat), std::invalid_argument);
  const std::vector<Vec3> repeated{Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), Vec3::UnitX()};
  EXPECT_THROW(sphereTriangles(repeated), std::invalid_argument);
}

}  // namespace
}  // namespace rockmass::rqd
