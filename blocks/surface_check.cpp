#include "blocks/surface_check.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>

#include <iterator>
#include <map>
#include <utility>
#include <vector>

namespace rockmass::blocks {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

}  // namespace

std::optional<std::string> surfaceProblem(const geometry::Polyhedron& surface,
                                          geometry::Polyhedron* triangles) {
  if (surface.faces.empty()) return "has no faces";
  // Edge uses from the polygon soup: once = border, > 2 = non-manifold, twice the same way =
  // inconsistent orientation.
  std::map<std::pair<int, int>, std::pair<int, int>> uses;  // (min, max) -> (forward, backward)
  for (const std::vector<int>& face : surface.faces) {
    for (std::size_t k = 0; k < face.size(); ++k) {
      const int a = face[k], b = face[(k + 1) % face.size()];
      auto& u = uses[{std::min(a, b), std::max(a, b)}];
      (a < b ? u.first : u.second) += 1;
    }
  }
  int border = 0, non_manifold = 0, inconsistent = 0;
  for (const auto& [edge, u] : uses) {
    const int n = u.first + u.second;
    if (n == 1) ++border;
    if (n > 2) ++non_manifold;
    if (n == 2 && u.first != 1) ++inconsistent;
  }
  if (border > 0) return "is not closed: " + std::to_string(border) + " border edges";
  if (non_manifold > 0) {
    return "is not manifold: " + std::to_string(non_manifold) +
           " edges shared by more than two faces";
  }
  if (inconsistent > 0) {
    return "is not consistently oriented: " + std::to_string(inconsistent) +
           " edges run the same way in both faces";
  }

  std::vector<Kernel::Point_3> points;
  for (const geometry::Vec3& p : surface.vertices) points.emplace_back(p.x(), p.y(), p.z());
  std::vector<std::vector<std::size_t>> polygons;
  for (const std::vector<int>& face : surface.faces) {
    polygons.emplace_back(face.begin(), face.end());
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) {
    return "is not a manifold surface (a vertex joins separate sheets)";
  }
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  if (!CGAL::is_closed(mesh)) return "is not closed";
  PMP::triangulate_faces(mesh);
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
  PMP::self_intersections(mesh, std::back_inserter(pairs));
  if (!pairs.empty()) {
    return "intersects itself: " + std::to_string(pairs.size()) + " pairs of faces";
  }
  if (!PMP::is_outward_oriented(mesh)) return "is oriented inward (reverse its faces)";
  if (triangles != nullptr) {
    // polygon_soup_to_polygon_mesh keeps the points in order, so vertex indices carry over.
    triangles->vertices = surface.vertices;
    triangles->faces.clear();
    for (const Mesh::Face_index f : mesh.faces()) {
      std::vector<int> loop;
      for (const Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
        loop.push_back(static_cast<int>(v.idx()));
      }
      triangles->faces.push_back(std::move(loop));
    }
  }
  return std::nullopt;
}

bool isClosedSurface(const geometry::Polyhedron& soup) {
  std::vector<Kernel::Point_3> points;
  for (const geometry::Vec3& p : soup.vertices) points.emplace_back(p.x(), p.y(), p.z());
  std::vector<std::vector<std::size_t>> polygons;
  for (const std::vector<int>& face : soup.faces) polygons.emplace_back(face.begin(), face.end());
  PMP::merge_duplicate_points_in_polygon_soup(points, polygons);
  if (polygons.empty()) return false;
  // Every edge in exactly two polygons, once each way.
  std::map<std::pair<std::size_t, std::size_t>, int> directed;
  for (const std::vector<std::size_t>& polygon : polygons) {
    for (std::size_t k = 0; k < polygon.size(); ++k) {
      ++directed[{polygon[k], polygon[(k + 1) % polygon.size()]}];
    }
  }
  for (const auto& [edge, count] : directed) {
    const auto back = directed.find({edge.second, edge.first});
    if (count != 1 || back == directed.end() || back->second != 1) return false;
  }
  // A point where the solid touches itself (two cones of faces around one point) is split
  // into one copy per cone, as CGAL's orient_polygon_soup does; orientations are already
  // consistent, so that is all it changes.
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) PMP::orient_polygon_soup(points, polygons);
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) return false;
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  return CGAL::is_closed(mesh);
}

}  // namespace rockmass::blocks
