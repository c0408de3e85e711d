// Nef polyhedra of double solids, their convex volumes read back, exact volumes, and the
// convex decomposition of mesh domains (blocks/convex_decomposition.h).
#include "blocks/exact/cut_parts.h"

#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_decomposition_3.h>

#include <algorithm>
#include <unordered_map>

#include "blocks/convex_decomposition.h"

namespace rockmass::blocks::exactcut {

namespace {

using Mesh = CGAL::Surface_mesh<Point3>;

/// Whether a face of `solid` is a convex polygon (then a fan from its first vertex is a
/// valid triangulation). Double test on the Newell normal; a near-flat corner counts as
/// convex only when its turn is positive beyond round-off.
bool convexFace(const Polyhedron& solid, const std::vector<int>& face) {
  if (face.size() <= 3) return true;
  Vec3 normal = Vec3::Zero();
  for (std::size_t k = 0; k < face.size(); ++k) {
    normal += solid.vertices[face[k]].cross(solid.vertices[face[(k + 1) % face.size()]]);
  }
  for (std::size_t k = 0; k < face.size(); ++k) {
    const Vec3& a = solid.vertices[face[k]];
    const Vec3& b = solid.vertices[face[(k + 1) % face.size()]];
    const Vec3& c = solid.vertices[face[(k + 2) % face.size()]];
    const Vec3 turn = (b - a).cross(c - b);
    if (turn.dot(normal) <= 1e-12 * turn.norm() * normal.norm()) return false;
  }
  return true;
}

/// Collects the halffacets of a shell.
struct FacetCollector {
  std::vector<Nef::Halffacet_const_handle>* facets;
  void visit(Nef::Halffacet_const_handle h) { facets->push_back(h); }
  void visit(Nef::Vertex_const_handle) {}
  void visit(Nef::Halfedge_const_handle) {}
  void visit(Nef::SHalfedge_const_handle) {}
  void visit(Nef::SHalfloop_const_handle) {}
  void visit(Nef::SFace_const_handle) {}
};

/// A face of a convex volume as read from the Nef polyhedron.
struct RawFace {
  Nef::Halffacet_const_handle facet;  ///< the halffacet on the volume's side
  std::vector<int> ring;              ///< outward, counter-clockwise (vertex indices)
};

/// A convex volume with exact vertices and outward faces.
struct RawPiece {
  std::vector<Point3> vertices;
  std::vector<RawFace> faces;
  int faces_with_holes = 0;
};

/// Vertex indices of one facet cycle.
std::vector<Nef::Vertex_const_handle> cycleVertices(Nef::Halffacet_cycle_const_iterator cycle) {
  std::vector<Nef::Vertex_const_handle> out;
  if (!cycle.is_shalfedge()) return out;
  Nef::SHalfedge_const_handle start(cycle);
  Nef::SHalfedge_around_facet_const_circulator c(start), end(c);
  CGAL_For_all(c, end) {
    out.push_back(c->source()->center_vertex());
  }
  return out;
}

/// Reads a marked convex volume: exact vertices and faces oriented outward. A face with
/// holes keeps its outer ring and is counted (convex pieces of cut rock do not have them).
RawPiece readVolume(const Nef& nef, Nef::Volume_const_handle volume) {
  std::vector<Nef::Halffacet_const_handle> facets;
  FacetCollector collector{&facets};
  for (auto shell = volume->shells_begin(); shell != volume->shells_end(); ++shell) {
    nef.visit_shell_objects(Nef::SFace_const_handle(shell), collector);
  }
  RawPiece piece;
  std::unordered_map<const void*, int> index;
  std::vector<std::vector<int>> rings;
  for (Nef::Halffacet_const_handle h : facets) {
    if (h->incident_volume() != volume) h = h->twin();
    auto cycle = h->facet_cycles_begin();
    std::vector<int> ring;
    for (const Nef::Vertex_const_handle v : cycleVertices(cycle)) {
      const auto [it, added] = index.try_emplace(&*v, static_cast<int>(piece.vertices.size()));
      if (added) piece.vertices.push_back(v->point());
      ring.push_back(it->second);
    }
    if (std::next(cycle) != h->facet_cycles_end()) ++piece.faces_with_holes;
    if (ring.size() >= 3) piece.faces.push_back({h, std::move(ring)});
  }
  // Orient each ring so that its Newell normal points away from an interior point.
  FT sx = 0, sy = 0, sz = 0;
  for (const Point3& p : piece.vertices) {
    sx += p.x();
    sy += p.y();
    sz += p.z();
  }
  const FT count(static_cast<int>(piece.vertices.size()));
  const Point3 inside(sx / count, sy / count, sz / count);
  for (RawFace& face : piece.faces) {
    Vector3 normal(0, 0, 0);
    for (std::size_t i = 0; i < face.ring.size(); ++i) {
      const Point3& p = piece.vertices[face.ring[i]];
      const Point3& q = piece.vertices[face.ring[(i + 1) % face.ring.size()]];
      normal = normal + CGAL::cross_product(p - CGAL::ORIGIN, q - CGAL::ORIGIN);
    }
    if (normal * (piece.vertices[face.ring[0]] - inside) < 0) {
      std::reverse(face.ring.begin(), face.ring.end());
    }
  }
  return piece;
}

/// The double polyhedron of a raw piece.
Polyhedron roundPiece(const RawPiece& raw) {
  Polyhedron shape;
  shape.vertices.reserve(raw.vertices.size());
  for (const Point3& p : raw.vertices) shape.vertices.push_back(toVec(p));
  for (const RawFace& face : raw.faces) shape.faces.push_back(face.ring);
  return shape;
}

/// Reads convex volumes of a decomposed Nef polyhedron as double polyhedra.
std::vector<Polyhedron> convexVolumes(const Nef& nef) {
  std::vector<Polyhedron> out;
  for (auto vi = nef.volumes_begin(); vi != nef.volumes_end(); ++vi) {
    if (vi->mark()) out.push_back(roundPiece(readVolume(nef, vi)));
  }
  return out;
}

}  // namespace

/// Nef polyhedron of a closed polyhedron whose coordinates are taken as exact. Convex faces
/// are fanned into triangles; any other face (a concave polygon, or one with a flat corner)
/// is triangulated by CGAL (PMP::triangulate_faces: a constrained Delaunay triangulation of
/// the polygon). A fan of a concave polygon covers area outside it and overlaps itself: the
/// Nef polyhedron built from such a surface is not the solid, and convex_decomposition_3 did
/// not return on it (the L-shaped prism). Coplanar triangles merge again inside the Nef.
Nef nefFromPolyhedron(const Polyhedron& solid) {
  Mesh mesh;
  std::vector<Mesh::Vertex_index> vertices;
  vertices.reserve(solid.vertices.size());
  for (const Vec3& v : solid.vertices) vertices.push_back(mesh.add_vertex(toPoint(v)));
  bool polygons = false;
  for (const std::vector<int>& face : solid.faces) {
    if (convexFace(solid, face)) {
      for (std::size_t k = 1; k + 1 < face.size(); ++k) {
        mesh.add_face(vertices[face[0]], vertices[face[k]], vertices[face[k + 1]]);
      }
    } else {
      std::vector<Mesh::Vertex_index> loop;
      for (const int v : face) loop.push_back(vertices[v]);
      mesh.add_face(loop);
      polygons = true;
    }
  }
  if (polygons) CGAL::Polygon_mesh_processing::triangulate_faces(mesh);
  return Nef(mesh);
}

/// Exact volume of a closed outward polyhedron with exact vertices (divergence theorem).
ExactFT exactVolume(const std::vector<Point3>& vertices,
                    const std::vector<std::vector<int>>& faces) {
  std::vector<K::Exact_kernel::Point_3> p;
  p.reserve(vertices.size());
  for (const Point3& v : vertices) p.push_back(CGAL::exact(v));
  ExactFT six_volume = 0;
  const auto origin = p.empty() ? K::Exact_kernel::Point_3(0, 0, 0) : p.front();
  for (const std::vector<int>& face : faces) {
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      six_volume +=
          CGAL::determinant(p[face[0]] - origin, p[face[k]] - origin, p[face[k + 1]] - origin);
    }
  }
  return six_volume / 6;
}

}  // namespace rockmass::blocks::exactcut

namespace rockmass::blocks {

std::vector<geometry::Polyhedron> convexDecomposition(const geometry::Polyhedron& solid) {
  exactcut::Nef nef = exactcut::nefFromPolyhedron(solid);
  CGAL::convex_decomposition_3(nef);
  return exactcut::convexVolumes(nef);
}

}  // namespace rockmass::blocks
