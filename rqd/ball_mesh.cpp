// The only translation unit of rqd/ that includes CGAL (its templates are slow to compile).
#include "rqd/ball_mesh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>

namespace rockmass::rqd {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

/// The triangle rotated so that its smallest index comes first (orientation kept).
std::array<int, 3> canonical(std::array<int, 3> t) {
  const auto smallest = std::min_element(t.begin(), t.end());
  std::rotate(t.begin(), smallest, t.end());
  return t;
}

}  // namespace

std::vector<std::array<int, 3>> sphereTriangles(std::span<const geometry::Vec3> unit_directions) {
  if (unit_directions.size() < 4) {
    throw std::invalid_argument("a ball surface needs at least 4 directions, got " +
                                std::to_string(unit_directions.size()));
  }
  std::vector<Point> points;
  std::map<Point, int> index;
  points.reserve(unit_directions.size());
  for (std::size_t i = 0; i < unit_directions.size(); ++i) {
    const geometry::Vec3& d = unit_directions[i];
    points.emplace_back(d.x(), d.y(), d.z());
    if (!index.emplace(points.back(), static_cast<int>(i)).second) {
      throw std::invalid_argument("ball directions must be distinct; direction " +
                                  std::to_string(i) + " repeats an earlier one");
    }
  }
  Mesh hull;
  CGAL::convex_hull_3(points.begin(), points.end(), hull);
  // A closed triangulated sphere through all N points has 2N - 4 triangles (Euler); a flat
  // hull (coplanar directions) or a point left inside (not on the sphere) breaks that.
  if (hull.number_of_vertices() != points.size() ||
      hull.number_of_faces() != 2 * points.size() - 4) {
    throw std::invalid_argument(
        "ball directions must span 3D space and all lie on the unit sphere: their convex hull "
        "has " +
        std::to_string(hull.number_of_vertices()) + " of " + std::to_string(points.size()) +
        " points as vertices and " + std::to_string(hull.number_of_faces()) + " faces");
  }
  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(hull.number_of_faces());
  for (const Mesh::Face_index face : hull.faces()) {
    std::array<int, 3> t{};
    int corner = 0;
    for (const Mesh::Vertex_index v : hull.vertices_around_face(hull.halfedge(face))) {
      if (corner == 3) throw std::logic_error("convex_hull_3 returned a non-triangular face");
      t[corner++] = index.at(hull.point(v));
    }
    triangles.push_back(canonical(t));
  }
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

}  // namespace rockmass::rqd
