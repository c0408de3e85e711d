// The exact cutter (see exact_cutter.h). The only translation unit of the blocks module that
// instantiates CGAL Nef polyhedra.
#include "blocks/exact_cutter.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_decomposition_3.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include "blocks/block_assembly.h"
#include "blocks/piece_soundness.h"
#include "blocks/region_split.h"
#include "blocks/slab_material.h"
#include "blocks/union_find.h"
#include "geometry/interrupt.h"

namespace rockmass::blocks {
namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using FT = K::FT;
using Point3 = K::Point_3;
using Point2 = K::Point_2;
using Vector3 = K::Vector_3;
using Plane3 = K::Plane_3;
using Nef = CGAL::Nef_polyhedron_3<K>;
using Mesh = CGAL::Surface_mesh<Point3>;
using ExactFT = K::Exact_kernel::FT;  // a rational number type (GMP)
using geometry::Box;
using geometry::Polyhedron;
using geometry::Vec3;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

Point3 toPoint(const Vec3& v) {
  return Point3(v.x(), v.y(), v.z());
}

Vec3 toVec(const Point3& p) {
  return Vec3(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
}

/// A plane known exactly, with a unit normal and offset in double for quick candidate search.
struct KnownPlane {
  Plane3 exact;
  Vec3 normal = Vec3::UnitZ();  ///< unit, approximate
  double offset = 0.0;          ///< normal . x = offset, approximate (m)
};

KnownPlane knownPlane(const Plane3& plane) {
  const Vec3 n(CGAL::to_double(plane.a()), CGAL::to_double(plane.b()), CGAL::to_double(plane.c()));
  const double length = n.norm();
  return {plane, n / length, -CGAL::to_double(plane.d()) / length};
}

/// True when every point lies exactly on `plane`; a quick double test rejects most planes.
bool allOnPlane(const KnownPlane& plane, const Vec3& approx_normal, double approx_offset,
                const std::vector<Point3>& points, double tolerance) {
  const double cosine = plane.normal.dot(approx_normal);
  if (std::abs(cosine) < 1.0 - 1e-9) return false;
  if (std::abs(approx_offset - (cosine > 0 ? plane.offset : -plane.offset)) > tolerance) {
    return false;
  }
  return std::all_of(points.begin(), points.end(),
                     [&](const Point3& p) { return plane.exact.has_on(p); });
}

/// Plane of a planar polygon through its first non-collinear vertex triple.
std::optional<Plane3> polygonPlane(const std::vector<Point3>& polygon) {
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    if (!CGAL::collinear(polygon[0], polygon[i], polygon[i + 1])) {
      return Plane3(polygon[0], polygon[i], polygon[i + 1]);
    }
  }
  return std::nullopt;
}

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

/// A cutting disc as an exactly planar polygon.
struct ExactDisc {
  std::int64_t id = 0;
  KnownPlane plane;
  std::vector<Point3> polygon;    ///< exactly on plane.exact
  std::vector<Point2> polygon2d;  ///< polygon with coordinate `drop_axis` left out
  int drop_axis = 2;
  Box bounds;                          ///< of the rounded polygon
  std::vector<Vec3> rounded;           ///< the polygon in double (m)
  std::vector<Eigen::Vector2d> ccw2d;  ///< polygon2d in double, counter-clockwise
};

/// Drops coordinate `axis` of p.
Point2 project(const Point3& p, int axis) {
  switch (axis) {
    case 0:
      return Point2(p.y(), p.z());
    case 1:
      return Point2(p.z(), p.x());
    default:
      return Point2(p.x(), p.y());
  }
}

/// The disc's outline as an exactly planar polygon. An interlayer segment (a rectangle swept
/// along x or y: its vertices are exactly coplanar in double) is kept as given, on the plane
/// through its vertices: the segments of an interlayer surface share their knee edges exactly,
/// and lifting each onto its own plane would open round-off windows (1e-13 m2) between them
/// through which the slab would glue to the rock. Any other outline is lifted exactly onto
/// the plane through the centre: each vertex keeps two coordinates and gets the third (along
/// the normal's largest component) solved from the plane equation in rational arithmetic.
ExactDisc makeExactDisc(const geometry::Disc& disc, int segments) {
  ExactDisc out;
  out.id = disc.id;
  out.bounds.min = Vec3::Constant(std::numeric_limits<double>::infinity());
  out.bounds.max = -out.bounds.min;
  const std::vector<Vec3> outline = disc.outline(segments);
  const auto add = [&](const Point3& p, const Vec3& v) {
    if (!out.polygon.empty() && (out.polygon.back() == p || out.polygon.front() == p)) return;
    out.polygon.push_back(p);
    out.rounded.push_back(v);
    out.bounds.min = out.bounds.min.cwiseMin(v);
    out.bounds.max = out.bounds.max.cwiseMax(v);
  };
  std::optional<Plane3> given;
  if (!disc.polygon.empty() && disc.origin == geometry::DiscOrigin::Interlayer) {
    std::vector<Point3> points;
    for (const Vec3& v : outline) points.push_back(toPoint(v));
    given = polygonPlane(points);
    if (given && !std::all_of(points.begin(), points.end(),
                              [&](const Point3& p) { return given->has_on(p); })) {
      given.reset();
    }
  }
  if (given) {
    out.plane = knownPlane(*given);
    if (out.plane.normal.dot(disc.normal) < 0.0) out.plane = knownPlane(given->opposite());
    out.plane.normal.cwiseAbs().maxCoeff(&out.drop_axis);
    for (const Vec3& v : outline) add(toPoint(v), v);
  } else {
    const Vec3 n = disc.normal;
    const double w = -n.dot(disc.center);
    const Plane3 plane(n.x(), n.y(), n.z(), w);
    int k = 0;
    n.cwiseAbs().maxCoeff(&k);
    out.drop_axis = k;
    out.plane = knownPlane(plane);
    for (const Vec3& v : outline) {
      std::array<FT, 3> c{FT(v.x()), FT(v.y()), FT(v.z())};
      FT rest = FT(w);
      for (int j = 0; j < 3; ++j) {
        if (j != k) rest += FT(n[j]) * c[j];
      }
      c[k] = -rest / FT(n[k]);
      add(Point3(c[0], c[1], c[2]), v);
    }
  }
  for (const Point3& p : out.polygon) out.polygon2d.push_back(project(p, out.drop_axis));
  for (const Point2& p : out.polygon2d) {
    out.ccw2d.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()));
  }
  double twice = 0.0;
  for (std::size_t i = 0; i < out.ccw2d.size(); ++i) {
    const Eigen::Vector2d& a = out.ccw2d[i];
    const Eigen::Vector2d& b = out.ccw2d[(i + 1) % out.ccw2d.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  if (twice < 0.0) std::reverse(out.ccw2d.begin(), out.ccw2d.end());
  return out;
}

/// Conservative double test: may the disc's polygon meet the box?
bool mayMeet(const ExactDisc& disc, const Box& box) {
  const double margin = 1e-9 * (1.0 + box.diagonal());
  for (int a = 0; a < 3; ++a) {
    if (disc.bounds.max[a] < box.min[a] - margin || disc.bounds.min[a] > box.max[a] + margin) {
      return false;
    }
  }
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner((i & 1) ? box.max.x() : box.min.x(), (i & 2) ? box.max.y() : box.min.y(),
                      (i & 4) ? box.max.z() : box.min.z());
    const double s = disc.plane.normal.dot(corner) - disc.plane.offset;
    low = std::min(low, s);
    high = std::max(high, s);
  }
  return low <= margin && high >= -margin;
}

/// What a plane of a region's cell complex is.
struct PlaneTag {
  enum Kind { RegionFace, DomainFace, DiscPlane } kind = RegionFace;
  int index = -1;      ///< boundary id, or disc group
  int axis = 0;        ///< RegionFace / box DomainFace: the axis
  double level = 0.0;  ///< RegionFace / box DomainFace: the coordinate
};

/// A surface that splits cells without being a disc: a face of the domain surface.
struct Splitter {
  std::vector<Vec3> polygon;  ///< m
  KnownPlane plane;
  PlaneTag tag;
};

/// Conservative double test: may the polygon meet the box?
bool mayMeetBox(const std::vector<Vec3>& polygon, const Box& box) {
  const double margin = 1e-9 * (1.0 + box.diagonal());
  for (int a = 0; a < 3; ++a) {
    double low = std::numeric_limits<double>::infinity();
    double high = -low;
    for (const Vec3& p : polygon) {
      low = std::min(low, p[a]);
      high = std::max(high, p[a]);
    }
    if (high < box.min[a] - margin || low > box.max[a] + margin) return false;
  }
  return true;
}

/// Everything the regions share, read-only.
struct Context {
  const CutInput* input = nullptr;
  std::vector<ExactDisc> discs;
  std::vector<Polyhedron> domain_solids;    ///< the surface, or the pieces
  std::vector<KnownPlane> boundary_planes;  ///< one per face of domain_solids (id = index)
  /// Mesh domains, per boundary plane: the first boundary plane it coincides with (the key
  /// of the plane's interior faces), and the disc group lying in it (-1: none).
  std::vector<int> boundary_canonical;
  std::vector<int> boundary_group;
  std::vector<Splitter> surface_splitters;  ///< domain surface faces (mesh domains)
  std::vector<std::vector<int>> groups;     ///< discs in one plane (indices into discs)
  std::vector<int> group_of_disc;           ///< per disc
  double tolerance = 0.0;                   ///< double prefilter tolerance for plane offsets (m)
  bool box_domain = true;                   ///< the domain is its bounding box
};

/// Planes of every face of `solid` (a plane that matches nothing for a degenerate face).
std::vector<KnownPlane> facePlanes(const Polyhedron& solid) {
  std::vector<KnownPlane> planes;
  for (const std::vector<int>& face : solid.faces) {
    std::vector<Point3> points;
    for (const int v : face) points.push_back(toPoint(solid.vertices[v]));
    const auto plane = polygonPlane(points);
    planes.push_back(knownPlane(plane ? *plane : Plane3(0, 0, 1, -1e300)));
  }
  return planes;
}

/// The vertices of one face (m).
std::vector<Vec3> facePolygon(const Polyhedron& solid, std::size_t face) {
  std::vector<Vec3> polygon;
  for (const int v : solid.faces[face]) polygon.push_back(solid.vertices[v]);
  return polygon;
}

/// True when an axis-aligned plane coordinate[axis] == level coincides with the plane.
bool isAxisPlane(const Plane3& plane, int axis, double level) {
  const std::array<FT, 3> n{plane.a(), plane.b(), plane.c()};
  for (int j = 0; j < 3; ++j) {
    if (j != axis && n[j] != 0) return false;
  }
  return n[axis] * FT(level) + plane.d() == 0;
}

/// A region of the kd split and the discs that may meet it.
struct Region {
  Box box;
  std::vector<int> discs;
};

/// Splitting level along `axis` of `box` that coincides with no disc or domain plane, nor
/// comes within the prefilter tolerance of one nearly normal to the axis (so that region faces
/// are never covered by a disc or lie on the domain surface).
double splitLevel(const Context& context, const std::vector<int>& discs, const Box& box, int axis) {
  // A plane within 1e-12 rad of the axis plane and within the prefilter tolerance of the
  // level clashes too: a fault with dip 90 has a normal (1, 6e-17, 6e-17) from cos(90 deg),
  // and a region face 1e-16 m from it glued blocks across a crossing fault (issue 3's
  // two-faults-and-a-joint scene: 21 blocks against 23 with one region and with the fast
  // cutter, whose kd split has the same rule).
  const auto clashes = [&](double level) {
    const auto near = [&](const KnownPlane& p) {
      return isAxisPlane(p.exact, axis, level) ||
             (std::abs(p.normal[axis]) >= 1.0 - 1e-12 &&
              std::abs(p.offset / p.normal[axis] - level) <= context.tolerance);
    };
    bool clash = false;
    for (const int d : discs) clash = clash || near(context.discs[d].plane);
    for (const KnownPlane& p : context.boundary_planes) clash = clash || near(p);
    return clash;
  };
  return freeSplitLevel(box, axis, clashes, "exact cutter");
}

/// kd split of the domain until each region meets at most `max_discs` discs.
void splitRegions(const Context& context, const Region& region, double min_size, int max_discs,
                  std::vector<Region>& out) {
  const int axis = longestAxis(region.box);
  if (static_cast<int>(region.discs.size()) <= max_discs ||
      region.box.size()[axis] < 2.0 * min_size) {
    out.push_back(region);
    return;
  }
  const double level = splitLevel(context, region.discs, region.box, axis);
  for (int side = 0; side < 2; ++side) {
    Region child;
    child.box = region.box;
    (side == 0 ? child.box.max : child.box.min)[axis] = level;
    for (const int d : region.discs) {
      if (mayMeet(context.discs[d], child.box)) child.discs.push_back(d);
    }
    splitRegions(context, child, min_size, max_discs, out);
  }
}

/// A convex cell with exact vertices. Every vertex is the intersection of three face planes,
/// so coordinates never grow through repeated splits.
struct Cell {
  struct Face {
    std::vector<int> ring;  ///< outward, counter-clockwise seen from outside
    int plane = 0;          ///< index into the region's plane table
  };
  std::vector<Point3> vertices;
  std::vector<Face> faces;
};

/// The planes of one region.
struct PlaneTable {
  std::vector<Plane3> planes;
  std::vector<PlaneTag> tags;
  int add(const Plane3& plane, const PlaneTag& tag) {
    planes.push_back(plane);
    tags.push_back(tag);
    return static_cast<int>(planes.size()) - 1;
  }
};

/// Splits a cell by plane `split` of the table: {negative part, positive part}; a part is
/// empty when the cell lies on one side (touching counts as one side).
std::array<std::optional<Cell>, 2> splitCell(const Cell& cell, int split, const PlaneTable& table) {
  const Plane3& plane = table.planes[static_cast<std::size_t>(split)];
  std::vector<CGAL::Oriented_side> side(cell.vertices.size());
  bool negative = false;
  bool positive = false;
  for (std::size_t i = 0; i < cell.vertices.size(); ++i) {
    side[i] = plane.oriented_side(cell.vertices[i]);
    negative = negative || side[i] == CGAL::ON_NEGATIVE_SIDE;
    positive = positive || side[i] == CGAL::ON_POSITIVE_SIDE;
  }
  if (!negative || !positive) {
    std::array<std::optional<Cell>, 2> out;
    out[positive ? 1 : 0] = cell;
    return out;
  }
  // The face on the other side of each directed edge.
  std::map<std::pair<int, int>, int> face_of_edge;
  for (std::size_t f = 0; f < cell.faces.size(); ++f) {
    const std::vector<int>& ring = cell.faces[f].ring;
    for (std::size_t k = 0; k < ring.size(); ++k) {
      face_of_edge[{ring[k], ring[(k + 1) % ring.size()]}] = static_cast<int>(f);
    }
  }
  std::vector<Point3> points = cell.vertices;
  std::map<std::pair<int, int>, int> crossing;  // edge (low, high) -> new vertex
  const auto crossingVertex = [&](int a, int b, int face) {
    const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
    if (const auto it = crossing.find(key); it != crossing.end()) return it->second;
    const int other = face_of_edge.at({b, a});
    const auto hit = CGAL::intersection(table.planes[cell.faces[face].plane],
                                        table.planes[cell.faces[other].plane], plane);
    const Point3* p = hit ? boost::get<Point3>(&*hit) : nullptr;
    if (p == nullptr) throw std::logic_error("exact cutter: degenerate edge split");
    points.push_back(*p);
    const int index = static_cast<int>(points.size()) - 1;
    crossing.emplace(key, index);
    return index;
  };
  std::array<std::optional<Cell>, 2> out;
  for (int part = 0; part < 2; ++part) {
    const CGAL::Oriented_side keep = part == 0 ? CGAL::ON_NEGATIVE_SIDE : CGAL::ON_POSITIVE_SIDE;
    const auto onPlane = [&](int v) {
      return v >= static_cast<int>(side.size()) || side[v] == CGAL::ON_ORIENTED_BOUNDARY;
    };
    std::vector<Cell::Face> faces;
    std::map<int, int> cap_next;  // cap edge v -> u (reversed face edges on the plane)
    for (std::size_t f = 0; f < cell.faces.size(); ++f) {
      const std::vector<int>& ring = cell.faces[f].ring;
      std::vector<int> kept;
      bool strictly = false;
      for (std::size_t k = 0; k < ring.size(); ++k) {
        const int a = ring[k];
        const int b = ring[(k + 1) % ring.size()];
        if (side[a] == keep || side[a] == CGAL::ON_ORIENTED_BOUNDARY) kept.push_back(a);
        strictly = strictly || side[a] == keep;
        if (side[a] != CGAL::ON_ORIENTED_BOUNDARY && side[b] != CGAL::ON_ORIENTED_BOUNDARY &&
            side[a] != side[b]) {
          kept.push_back(crossingVertex(a, b, static_cast<int>(f)));
        }
      }
      if (!strictly || kept.size() < 3) continue;
      for (std::size_t k = 0; k < kept.size(); ++k) {
        const int u = kept[k];
        const int v = kept[(k + 1) % kept.size()];
        if (onPlane(u) && onPlane(v)) cap_next[v] = u;
      }
      faces.push_back({std::move(kept), cell.faces[f].plane});
    }
    Cell::Face cap;
    cap.plane = split;
    if (!cap_next.empty()) {
      const int first = cap_next.begin()->first;
      int v = first;
      do {
        cap.ring.push_back(v);
        v = cap_next.at(v);
      } while (v != first && cap.ring.size() <= cap_next.size());
    }
    if (cap.ring.size() >= 3) faces.push_back(std::move(cap));
    // Compact the vertices.
    Cell result;
    std::map<int, int> renumber;
    for (Cell::Face& face : faces) {
      for (int& v : face.ring) {
        const auto [it, added] = renumber.try_emplace(v, static_cast<int>(result.vertices.size()));
        if (added) result.vertices.push_back(points[static_cast<std::size_t>(v)]);
        v = it->second;
      }
    }
    result.faces = std::move(faces);
    out[part] = std::move(result);
  }
  return out;
}

/// Average of the vertices: an interior point of a convex cell.
Point3 interiorPoint(const std::vector<Point3>& vertices) {
  FT sx = 0, sy = 0, sz = 0;
  for (const Point3& p : vertices) {
    sx += p.x();
    sy += p.y();
    sz += p.z();
  }
  const FT n(static_cast<int>(vertices.size()));
  return Point3(sx / n, sy / n, sz / n);
}

/// Conservative double test: may `polygon` meet the interior of the cell (rounded)?
bool polygonMayMeetCell(const std::vector<Vec3>& polygon, const Polyhedron& cell, double margin) {
  std::vector<Vec3> clipped = polygon;
  for (std::size_t f = 0; f < cell.faces.size() && !clipped.empty(); ++f) {
    const Vec3 n = geometry::faceNormal(cell, static_cast<int>(f));
    const double offset = n.dot(cell.vertices[cell.faces[f][0]]) + margin;
    std::vector<Vec3> out;
    for (std::size_t i = 0; i < clipped.size(); ++i) {
      const Vec3& p = clipped[i];
      const Vec3& q = clipped[(i + 1) % clipped.size()];
      const double sp = n.dot(p) - offset;
      const double sq = n.dot(q) - offset;
      if (sp <= 0.0) out.push_back(p);
      if ((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0)) {
        out.push_back(p + (sp / (sp - sq)) * (q - p));
      }
    }
    clipped = std::move(out);
  }
  return !clipped.empty();
}

/// A face kept for matching with the faces of other pieces in the same plane.
struct FaceRecord {
  int piece = 0;  ///< piece index (region-local, later global)
  /// (0, axis, level) region face; (1, group, 0) disc plane; (2, boundary plane, 0) the
  /// plane of a mesh domain face, inside the domain.
  std::tuple<int, int, double> plane_key;
  bool above = false;              ///< the piece lies on the positive side of the plane
  int drop_axis = 0;               ///< coordinate left out by the 2D projection
  std::vector<Point2> polygon;     ///< projected, counter-clockwise
  std::array<double, 4> bounds{};  ///< u_min, u_max, v_min, v_max of the projection
  FaceSource source;
};

/// What one region produced.
struct RegionResult {
  std::vector<Piece> pieces;
  std::vector<FaceRecord> records;
  std::vector<std::pair<int, int>> nef_links;  ///< pieces in the same Nef volume (referee)
  ExactFT exact_volume = 0;
  double nef_seconds = 0.0;
  double decompose_seconds = 0.0;
  double extract_seconds = 0.0;
};
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

/// The double polyhedron of a raw piece.
Polyhedron roundPiece(const RawPiece& raw) {
  Polyhedron shape;
  shape.vertices.reserve(raw.vertices.size());
  for (const Point3& p : raw.vertices) shape.vertices.push_back(toVec(p));
  for (const RawFace& face : raw.faces) shape.faces.push_back(face.ring);
  return shape;
}

/// Clips a planar polygon to the box (Sutherland-Hodgman against its six planes, exact).
std::vector<Point3> clipToBox(std::vector<Point3> polygon, const Box& box) {
  for (int axis = 0; axis < 3 && !polygon.empty(); ++axis) {
    for (int side = 0; side < 2 && !polygon.empty(); ++side) {
      const FT bound(side == 0 ? box.min[axis] : box.max[axis]);
      const auto inside = [&](const Point3& p) {
        return side == 0 ? p.cartesian(axis) >= bound : p.cartesian(axis) <= bound;
      };
      std::vector<Point3> out;
      for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Point3& p = polygon[i];
        const Point3& q = polygon[(i + 1) % polygon.size()];
        const bool p_in = inside(p);
        if (p_in) out.push_back(p);
        if (p_in != inside(q)) {
          const FT t = (bound - p.cartesian(axis)) / (q.cartesian(axis) - p.cartesian(axis));
          out.push_back(p + t * (q - p));
        }
      }
      polygon = std::move(out);
    }
  }
  return polygon;
}

/// The rock of a region as a Nef polyhedron: the domain within the region (structures lie
/// outside the rock: checkStructuresOutsideRock).
Nef regionRock(const Context& context, const Box& region) {
  const Box& domain = context.input->domain_box;
  Box clipped{region.min.cwiseMax(domain.min), region.max.cwiseMin(domain.max)};
  Nef rock = nefFromPolyhedron(geometry::boxPolyhedron(clipped));
  if (!context.box_domain) {
    Nef solid;
    for (const Polyhedron& p : context.domain_solids) solid += nefFromPolyhedron(p);
    rock *= solid;
  }
  return rock;
}

/// Keeps the part of a convex polygon on the left of s->t (or on the right when `left` is
/// false), exact.
std::vector<Point2> clipHalfPlane(const std::vector<Point2>& polygon, const Point2& s,
                                  const Point2& t, bool left) {
  const K::Line_2 line(s, t);
  const CGAL::Oriented_side keep = left ? CGAL::ON_POSITIVE_SIDE : CGAL::ON_NEGATIVE_SIDE;
  std::vector<Point2> out;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Point2& p = polygon[i];
    const Point2& q = polygon[(i + 1) % polygon.size()];
    const CGAL::Oriented_side sp = line.oriented_side(p);
    const CGAL::Oriented_side sq = line.oriented_side(q);
    if (sp == keep || sp == CGAL::ON_ORIENTED_BOUNDARY) out.push_back(p);
    if (sp != CGAL::ON_ORIENTED_BOUNDARY && sq != CGAL::ON_ORIENTED_BOUNDARY && sp != sq) {
      const auto hit = CGAL::intersection(K::Segment_2(p, q), line);
      if (const Point2* x = hit ? boost::get<Point2>(&*hit) : nullptr) out.push_back(*x);
    }
  }
  return out;
}

/// True when the polygon has no area.
bool flat(const std::vector<Point2>& polygon) {
  if (polygon.size() < 3) return true;
  FT twice = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Point2& p = polygon[i];
    const Point2& q = polygon[(i + 1) % polygon.size()];
    twice += p.x() * q.y() - q.x() * p.y();
  }
  return twice == 0;
}

/// Counter-clockwise copy of a polygon.
std::vector<Point2> counterClockwise(std::vector<Point2> polygon) {
  FT twice = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Point2& p = polygon[i];
    const Point2& q = polygon[(i + 1) % polygon.size()];
    twice += p.x() * q.y() - q.x() * p.y();
  }
  if (twice < 0) std::reverse(polygon.begin(), polygon.end());
  return polygon;
}

/// Double version of a projected polygon.
std::vector<Eigen::Vector2d> toDouble(const std::vector<Point2>& polygon) {
  std::vector<Eigen::Vector2d> out;
  for (const Point2& p : polygon) out.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()));
  return out;
}

/// Smallest signed distance of q to the edges of a counter-clockwise convex polygon:
/// positive inside, negative outside (double).
double insideDistance(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& q) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d e = polygon[(i + 1) % polygon.size()] - polygon[i];
    const Eigen::Vector2d d = q - polygon[i];
    best = std::min(best, (e.x() * d.y() - e.y() * d.x()) / e.norm());
  }
  return best;
}

/// Quick double answer to coveredByGroup for a one-disc group: covered when every vertex is
/// clearly inside the disc, not covered when one is clearly outside, else unknown.
std::optional<bool> quickCovered(const Context& context, int group,
                                 const std::vector<Eigen::Vector2d>& polygon, int drop_axis) {
  const std::vector<int>& members = context.groups[static_cast<std::size_t>(group)];
  if (members.size() != 1) return std::nullopt;
  const ExactDisc& disc = context.discs[static_cast<std::size_t>(members.front())];
  if (disc.drop_axis != drop_axis) return std::nullopt;
  const double eps = 1e-9 * (1.0 + disc.bounds.diagonal());
  bool all_inside = true;
  for (const Eigen::Vector2d& q : polygon) {
    const double d = insideDistance(disc.ccw2d, q);
    if (d < -eps) return false;
    all_inside = all_inside && d > eps;
  }
  if (all_inside) return true;
  return std::nullopt;
}

/// Whether the convex polygon (projected by dropping `drop_axis`) lies wholly inside the
/// union of the discs of `group`: the polygon minus each (convex) disc polygon in turn,
/// exactly, leaves nothing with area.
bool coveredByGroup(const Context& context, int group, const std::vector<Point2>& polygon,
                    int drop_axis) {
  if (const auto quick = quickCovered(context, group, toDouble(polygon), drop_axis)) return *quick;
  std::vector<std::vector<Point2>> rest{polygon};
  for (const int d : context.groups[static_cast<std::size_t>(group)]) {
    std::vector<Point2> disc;
    for (const Point3& p : context.discs[static_cast<std::size_t>(d)].polygon) {
      disc.push_back(project(p, drop_axis));
    }
    disc = counterClockwise(std::move(disc));
    std::vector<std::vector<Point2>> next;
    for (std::vector<Point2> piece : rest) {
      for (std::size_t i = 0; i < disc.size() && !flat(piece); ++i) {
        const Point2& s = disc[i];
        const Point2& t = disc[(i + 1) % disc.size()];
        std::vector<Point2> outside = clipHalfPlane(piece, s, t, /*left=*/false);
        if (!flat(outside)) next.push_back(std::move(outside));
        piece = clipHalfPlane(piece, s, t, /*left=*/true);
      }
    }
    rest = std::move(next);
    if (rest.empty()) return true;
  }
  return rest.empty();
}

/// The disc of `group` whose polygon holds point q (projected), else the group's first.
int discHolding(const Context& context, int group, const Point3& q) {
  const std::vector<int>& members = context.groups[static_cast<std::size_t>(group)];
  for (const int d : members) {
    const ExactDisc& disc = context.discs[static_cast<std::size_t>(d)];
    if (CGAL::bounded_side_2(disc.polygon2d.begin(), disc.polygon2d.end(),
                             project(q, disc.drop_axis), K()) != CGAL::ON_UNBOUNDED_SIDE) {
      return d;
    }
  }
  return members.front();
}

/// Projection of a face ring, counter-clockwise, with its bounds.
void projectFace(const std::vector<Point3>& vertices, const std::vector<int>& ring, int drop_axis,
                 FaceRecord& record) {
  record.drop_axis = drop_axis;
  record.bounds = {
      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const int v : ring) {
    const Point2 q = project(vertices[static_cast<std::size_t>(v)], drop_axis);
    record.polygon.push_back(q);
    const double u = CGAL::to_double(q.x());
    const double w = CGAL::to_double(q.y());
    record.bounds = {std::min(record.bounds[0], u), std::max(record.bounds[1], u),
                     std::min(record.bounds[2], w), std::max(record.bounds[3], w)};
  }
  record.polygon = counterClockwise(std::move(record.polygon));
}

/// Whether a cell face (its ring in `vertices`) lies inside the domain, not on its surface:
/// its interior point is in a marked volume of the domain's Nef polyhedron.
bool insideDomain(const Nef& domain, const std::vector<Point3>& vertices,
                  const std::vector<int>& ring) {
  std::vector<Point3> points;
  for (const int v : ring) points.push_back(vertices[static_cast<std::size_t>(v)]);
  Nef::Volume_const_handle volume;
  return CGAL::assign(volume, domain.locate(interiorPoint(points))) && volume->mark();
}

/// Whether the point is inside the rock: inside the domain (always, for a box domain).
bool insideRock(const Point3& p, const Nef* domain_nef) {
  if (domain_nef == nullptr) return true;
  Nef::Volume_const_handle volume;
  return CGAL::assign(volume, domain_nef->locate(p)) && volume->mark();
}

/// The region's starting cell: the region box with its six axis planes.
Cell startCell(const Context& context, const Box& box, PlaneTable& table) {
  const Polyhedron shape = geometry::boxPolyhedron(box);
  Cell cell;
  for (const Vec3& v : shape.vertices) cell.vertices.push_back(toPoint(v));
  const Box& domain = context.input->domain_box;
  for (int f = 0; f < 6; ++f) {
    const int axis = f / 2;
    const double level = f % 2 == 0 ? box.min[axis] : box.max[axis];
    std::array<double, 3> n{0.0, 0.0, 0.0};
    n[axis] = 1.0;
    const Plane3 plane(n[0], n[1], n[2], -level);
    PlaneTag tag{PlaneTag::RegionFace, -1, axis, level};
    if (level == domain.min[axis] || level == domain.max[axis]) {
      tag.kind = PlaneTag::DomainFace;
      for (std::size_t b = 0; b < context.boundary_planes.size(); ++b) {
        if (isAxisPlane(context.boundary_planes[b].exact, axis, level)) {
          tag.index = static_cast<int>(b);
          break;
        }
      }
    }
    cell.faces.push_back({shape.faces[static_cast<std::size_t>(f)], table.add(plane, tag)});
  }
  return cell;
}

/// Cuts one region: splits its box into convex cells by every splitting surface (domain
/// surface, discs) that meets a cell, drops cells outside the rock, and
/// records the provenance of every face. With `nef_referee`, the region's rock minus its
/// discs is also built as a Nef polyhedron and each cell is located in it.
RegionResult cutRegion(const Context& context, const Region& region, bool exact_volume,
                       bool nef_referee) {
  RegionResult result;
  auto start = Clock::now();
  PlaneTable table;
  std::vector<Cell> cells{startCell(context, region.box, table)};
  const double margin = 1e-9 * (1.0 + context.input->domain_box.diagonal());
  const auto splitAll = [&](const std::vector<Vec3>& polygon, int plane) {
    std::vector<Cell> next;
    for (Cell& cell : cells) {
      Polyhedron rounded;
      for (const Point3& p : cell.vertices) rounded.vertices.push_back(toVec(p));
      for (const Cell::Face& f : cell.faces) rounded.faces.push_back(f.ring);
      if (!polygonMayMeetCell(polygon, rounded, margin)) {
        next.push_back(std::move(cell));
        continue;
      }
      for (std::optional<Cell>& part : splitCell(cell, plane, table)) {
        if (part) next.push_back(std::move(*part));
      }
    }
    cells = std::move(next);
  };
  for (const Splitter& s : context.surface_splitters) {
    if (!mayMeetBox(s.polygon, region.box)) continue;
    splitAll(s.polygon, table.add(s.plane.exact, s.tag));
  }
  for (const int d : region.discs) {
    const ExactDisc& disc = context.discs[static_cast<std::size_t>(d)];
    splitAll(disc.rounded,
             table.add(disc.plane.exact, {PlaneTag::DiscPlane, context.group_of_disc[d], 0, 0.0}));
  }
  result.decompose_seconds = secondsSince(start);

  std::optional<Nef> domain_nef;
  if (!context.box_domain) {
    domain_nef.emplace();
    for (const Polyhedron& solid : context.domain_solids) *domain_nef += nefFromPolyhedron(solid);
  }
  std::optional<Nef> rock;
  if (nef_referee) {
    start = Clock::now();
    rock = regionRock(context, region.box);
    for (const int d : region.discs) {
      const std::vector<Point3> clipped =
          clipToBox(context.discs[static_cast<std::size_t>(d)].polygon, region.box);
      if (clipped.size() < 3 || !polygonPlane(clipped)) continue;
      *rock -= Nef(clipped.begin(), clipped.end());
    }
    result.nef_seconds = secondsSince(start);
  }

  start = Clock::now();
  std::unordered_map<const void*, int> piece_of_volume;
  for (const Cell& cell : cells) {
    const Point3 inside = interiorPoint(cell.vertices);
    if (!insideRock(inside, domain_nef ? &*domain_nef : nullptr)) continue;
    const int index = static_cast<int>(result.pieces.size());
    if (rock) {
      Nef::Volume_const_handle volume;
      if (CGAL::assign(volume, rock->locate(inside))) {
        const auto [it, added] = piece_of_volume.try_emplace(&*volume, index);
        if (!added) result.nef_links.emplace_back(it->second, index);
      }
    }
    Piece piece;
    for (const Point3& p : cell.vertices) piece.shape.vertices.push_back(toVec(p));
    // A face in the plane of disc group `group`: a Disc face where the group's discs cover it
    // wholly, else fictitious; recorded for the matching in that plane.
    const auto discFace = [&](int group, const std::vector<int>& ring, FaceRecord& record) {
      const int first = context.groups[static_cast<std::size_t>(group)].front();
      const int drop = context.discs[static_cast<std::size_t>(first)].drop_axis;
      FaceSource source{FaceKind::Fictitious, -1};
      record.plane_key = {1, group, 0.0};
      projectFace(cell.vertices, ring, drop, record);
      if (coveredByGroup(context, group, record.polygon, drop)) {
        std::vector<Point3> points;
        for (const int v : ring) points.push_back(cell.vertices[static_cast<std::size_t>(v)]);
        const int d = discHolding(context, group, interiorPoint(points));
        source = {FaceKind::Disc, static_cast<int>(context.discs[static_cast<std::size_t>(d)].id)};
      }
      record.source = source;
      result.records.push_back(std::move(record));
      return source;
    };
    std::vector<std::vector<int>> rings;
    for (const Cell::Face& face : cell.faces) {
      piece.shape.faces.push_back(face.ring);
      rings.push_back(face.ring);
      const PlaneTag& tag = table.tags[static_cast<std::size_t>(face.plane)];
      FaceSource source{FaceKind::Fictitious, -1};
      FaceRecord record;
      record.piece = index;
      record.above = table.planes[static_cast<std::size_t>(face.plane)].oriented_side(inside) ==
                     CGAL::ON_POSITIVE_SIDE;
      switch (tag.kind) {
        case PlaneTag::RegionFace:
          record.plane_key = {0, tag.axis, tag.level};
          projectFace(cell.vertices, face.ring, tag.axis, record);
          result.records.push_back(std::move(record));
          break;
        case PlaneTag::DomainFace: {
          // A mesh face's full plane also cuts the rock inside the domain: only the faces
          // on the surface are Boundary; the others are matched in their plane.
          // (A face on the domain's bounding box is never inside it, so tag.index >= 0 below.)
          if (!domain_nef || !insideDomain(*domain_nef, cell.vertices, face.ring)) {
            source = {FaceKind::Boundary, tag.index};
          } else if (const int group = context.boundary_group[tag.index]; group >= 0) {
            source = discFace(group, face.ring, record);
          } else {
            const int canonical = context.boundary_canonical[tag.index];
            const KnownPlane& plane = context.boundary_planes[canonical];
            int drop = 0;
            plane.normal.cwiseAbs().maxCoeff(&drop);
            record.plane_key = {2, canonical, 0.0};
            record.above = plane.exact.oriented_side(inside) == CGAL::ON_POSITIVE_SIDE;
            projectFace(cell.vertices, face.ring, drop, record);
            result.records.push_back(std::move(record));
          }
          break;
        }
        case PlaneTag::DiscPlane:
          source = discFace(tag.index, face.ring, record);
          break;
      }
      piece.face_sources.push_back(source);
    }
    if (exact_volume) result.exact_volume += exactVolume(cell.vertices, rings);
    result.pieces.push_back(std::move(piece));
  }
  result.extract_seconds = secondsSince(start);
  return result;
}

/// What the double separating-axis filter says about two convex polygons.
enum class Overlap { No, Yes, Unsure };

/// Double separating-axis test of two counter-clockwise convex polygons: No or Yes when
/// every margin is clear of round-off, else Unsure (touching faces: shared edges).
Overlap overlapFilter(const std::vector<Eigen::Vector2d>& pd,
                      const std::vector<Eigen::Vector2d>& qd) {
  bool certain = true;
  const auto clearlySeparates = [&](const std::vector<Eigen::Vector2d>& a,
                                    const std::vector<Eigen::Vector2d>& b) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      const Eigen::Vector2d e = a[(i + 1) % a.size()] - a[i];
      const double eps = 1e-9 * (1.0 + e.norm() + a[i].norm());
      double best = -std::numeric_limits<double>::infinity();
      for (const Eigen::Vector2d& x : b) {
        const Eigen::Vector2d d = x - a[i];
        best = std::max(best, (e.x() * d.y() - e.y() * d.x()) / e.norm());
      }
      if (best < -eps) return true;
      if (best <= eps) certain = false;
    }
    return false;
  };
  if (clearlySeparates(pd, qd) || clearlySeparates(qd, pd)) return Overlap::No;
  return certain ? Overlap::Yes : Overlap::Unsure;
}

/// Whether two counter-clockwise convex polygons share an area > 0 (separating axis test on
/// the edges of both, exact).
bool overlapExact(const std::vector<Point2>& p, const std::vector<Point2>& q) {
  const auto separates = [](const std::vector<Point2>& a, const std::vector<Point2>& b) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      const Point2& s = a[i];
      const Point2& t = a[(i + 1) % a.size()];
      const bool all_outside = std::all_of(b.begin(), b.end(), [&](const Point2& x) {
        return CGAL::orientation(s, t, x) != CGAL::LEFT_TURN;
      });
      if (all_outside) return true;
    }
    return false;
  };
  return !separates(p, q) && !separates(q, p);
}

/// Area of the intersection of two convex counter-clockwise polygons (double; m2 in the
/// projection, scaled back to the plane by `scale`).
double overlapArea(const std::vector<Point2>& p, const std::vector<Point2>& q, double scale) {
  std::vector<Eigen::Vector2d> clipped = toDouble(p);
  const std::vector<Eigen::Vector2d> qd = toDouble(q);
  for (std::size_t i = 0; i < qd.size() && clipped.size() >= 3; ++i) {
    const Eigen::Vector2d s = qd[i];
    const Eigen::Vector2d e = qd[(i + 1) % qd.size()] - s;
    std::vector<Eigen::Vector2d> out;
    for (std::size_t k = 0; k < clipped.size(); ++k) {
      const Eigen::Vector2d& x = clipped[k];
      const Eigen::Vector2d& y = clipped[(k + 1) % clipped.size()];
      const double sx = e.x() * (x - s).y() - e.y() * (x - s).x();
      const double sy = e.x() * (y - s).y() - e.y() * (y - s).x();
      if (sx >= 0.0) out.push_back(x);
      if ((sx > 0.0 && sy < 0.0) || (sx < 0.0 && sy > 0.0))
        out.push_back(x + sx / (sx - sy) * (y - x));
    }
    clipped = std::move(out);
  }
  double twice = 0.0;
  for (std::size_t i = 0; clipped.size() >= 3 && i < clipped.size(); ++i) {
    const Eigen::Vector2d& a = clipped[i];
    const Eigen::Vector2d& b = clipped[(i + 1) % clipped.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * std::abs(twice) * scale;
}

/// A crack face between two pieces.
struct CrackContact {
  int piece_a = 0;
  int piece_b = 0;
  FaceSource source;
  double area = 0.0;
};

/// Matches faces in the same plane on opposite sides: pieces glue where the shared part is
/// not wholly covered by discs (region faces are never covered); covered shared parts
/// between pieces are crack contacts.
///
/// Candidate pairs come from a sweep over the faces' u-ranges in each plane. A pair whose
/// pieces are already glued is skipped: gluing them again changes nothing, and a crack
/// between two pieces of one block is no adjacency. So pairs the double filter decides run
/// first, and the pairs it cannot decide (faces that share an edge, where the exact test is
/// expensive) only afterwards, when most of them already lie in one block.
std::vector<CrackContact> matchFaces(const Context& context, const std::vector<FaceRecord>& records,
                                     UnionFind& sets, bool discs) {
  std::map<std::tuple<int, int, double>, std::vector<const FaceRecord*>> by_plane;
  for (const FaceRecord& r : records) {
    // The referee glues its Nef volumes across region faces only.
    if (!discs && std::get<0>(r.plane_key) != 0) continue;
    by_plane[r.plane_key].push_back(&r);
  }
  std::vector<CrackContact> cracks;
  // Decides one pair that overlaps with area: glue, or record the crack.
  const auto settle = [&](const FaceRecord* a, const FaceRecord* b) {
    if (std::get<0>(a->plane_key) != 1) {  // region faces, mesh planes inside the domain
      sets.unite(a->piece, b->piece);
      return;
    }
    const int group = std::get<1>(a->plane_key);
    const bool covered =
        a->source.kind == FaceKind::Disc || b->source.kind == FaceKind::Disc || [&] {
          std::vector<Point2> shared = a->polygon;
          for (std::size_t i = 0; i < b->polygon.size() && shared.size() >= 3; ++i) {
            shared = clipHalfPlane(shared, b->polygon[i], b->polygon[(i + 1) % b->polygon.size()],
                                   /*left=*/true);
          }
          return coveredByGroup(context, group, shared, a->drop_axis);
        }();
    if (!covered) {
      sets.unite(a->piece, b->piece);
    } else {
      const ExactDisc& disc =
          context.discs[static_cast<std::size_t>(context.groups[group].front())];
      const double scale = 1.0 / std::abs(disc.plane.normal[disc.drop_axis]);
      const FaceSource source = a->source.kind == FaceKind::Disc ? a->source : b->source;
      cracks.push_back({a->piece, b->piece, source, overlapArea(a->polygon, b->polygon, scale)});
    }
  };
  std::vector<std::pair<const FaceRecord*, const FaceRecord*>> unsure;
  for (auto& [key, faces] : by_plane) {
    std::vector<const FaceRecord*> below;
    std::vector<const FaceRecord*> above;
    for (const FaceRecord* r : faces) (r->above ? above : below).push_back(r);
    const auto by_u_min = [](const FaceRecord* x, const FaceRecord* y) {
      return x->bounds[0] < y->bounds[0];
    };
    std::sort(above.begin(), above.end(), by_u_min);
    std::vector<std::vector<Eigen::Vector2d>> above_double;
    for (const FaceRecord* b : above) above_double.push_back(toDouble(b->polygon));
    for (const FaceRecord* a : below) {
      const std::vector<Eigen::Vector2d> a_double = toDouble(a->polygon);
      for (std::size_t j = 0; j < above.size() && above[j]->bounds[0] <= a->bounds[1]; ++j) {
        const FaceRecord* b = above[j];
        if (b->bounds[1] < a->bounds[0] || a->bounds[3] < b->bounds[2] ||
            b->bounds[3] < a->bounds[2]) {
          continue;
        }
        if (sets.find(a->piece) == sets.find(b->piece)) continue;
        const Overlap overlap = overlapFilter(a_double, above_double[j]);
        if (overlap == Overlap::Yes) settle(a, b);
        if (overlap == Overlap::Unsure) unsure.emplace_back(a, b);
      }
    }
  }
  for (const auto& [a, b] : unsure) {
    if (sets.find(a->piece) == sets.find(b->piece)) continue;
    if (overlapExact(a->polygon, b->polygon)) settle(a, b);
  }
  return cracks;
}
/// Exact volume of the domain solids.
ExactFT exactDomainVolume(const Context& context) {
  ExactFT total = 0;
  for (const Polyhedron& solid : context.domain_solids) {
    std::vector<Point3> vertices;
    for (const Vec3& v : solid.vertices) vertices.push_back(toPoint(v));
    total += exactVolume(vertices, solid.faces);
  }
  return total;
}

/// Fills context.boundary_canonical and boundary_group (mesh domains): the full plane of a
/// surface face also splits the rock inside the domain, and the cell faces it makes there are
/// matched by plane (a mesh's coplanar faces are one plane) like region faces, or like disc
/// faces when a disc group lies in that plane.
void linkBoundaryPlanes(Context& context) {
  std::vector<std::vector<Point3>> points;
  for (const Polyhedron& solid : context.domain_solids) {
    for (std::size_t f = 0; f < solid.faces.size(); ++f) {
      std::vector<Point3> face;
      for (const int v : solid.faces[f]) face.push_back(toPoint(solid.vertices[v]));
      points.push_back(std::move(face));
    }
  }
  const std::size_t count = context.boundary_planes.size();
  context.boundary_canonical.assign(count, -1);
  context.boundary_group.assign(count, -1);
  for (std::size_t b = 0; b < count; ++b) {
    const KnownPlane& plane = context.boundary_planes[b];
    for (std::size_t c = 0; c < b && context.boundary_canonical[b] < 0; ++c) {
      if (context.boundary_canonical[c] == static_cast<int>(c) &&
          allOnPlane(context.boundary_planes[c], plane.normal, plane.offset, points[b],
                     context.tolerance)) {
        context.boundary_canonical[b] = static_cast<int>(c);
      }
    }
    if (context.boundary_canonical[b] >= 0) {
      context.boundary_group[b] =
          context.boundary_group[static_cast<std::size_t>(context.boundary_canonical[b])];
      continue;
    }
    context.boundary_canonical[b] = static_cast<int>(b);
    for (std::size_t g = 0; g < context.groups.size(); ++g) {
      const ExactDisc& first = context.discs[static_cast<std::size_t>(context.groups[g].front())];
      if (allOnPlane(first.plane, plane.normal, plane.offset, points[b], context.tolerance)) {
        context.boundary_group[b] = static_cast<int>(g);
        break;
      }
    }
  }
}

std::string toString(const ExactFT& value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

Context makeContext(const CutInput& input) {
  Context context;
  context.input = &input;
  context.tolerance = 1e-7 * (1.0 + input.domain_box.diagonal());
  if (!input.domain_surface.faces.empty()) {
    context.domain_solids.push_back(input.domain_surface);
  } else {
    context.domain_solids = input.domain_pieces;
  }
  if (context.domain_solids.empty()) {
    throw std::invalid_argument("exact cutter: the input has no domain");
  }
  if (input.disc_segments < 3) {
    throw std::invalid_argument("exact cutter: disc_segments must be at least 3, got " +
                                std::to_string(input.disc_segments));
  }
  const Box first = geometry::bounds(context.domain_solids.front());
  context.box_domain = input.domain_surface.faces.empty() && context.domain_solids.size() == 1 &&
                       context.domain_solids.front().faces.size() == 6 &&
                       first.min == input.domain_box.min && first.max == input.domain_box.max;
  for (const Polyhedron& solid : context.domain_solids) {
    const std::vector<KnownPlane> planes = facePlanes(solid);
    for (std::size_t f = 0; f < planes.size(); ++f) {
      if (!context.box_domain) {
        const int id = static_cast<int>(context.boundary_planes.size());
        context.surface_splitters.push_back(
            {facePolygon(solid, f), planes[f], {PlaneTag::DomainFace, id, 0, 0.0}});
      }
      context.boundary_planes.push_back(planes[f]);
    }
  }
  if (input.network != nullptr) {
    for (const geometry::Disc& disc : input.network->discs) {
      if (!disc.cuts) continue;
      ExactDisc exact = makeExactDisc(disc, input.disc_segments);
      if (exact.polygon.size() >= 3 && mayMeet(exact, input.domain_box)) {
        context.discs.push_back(std::move(exact));
      }
    }
  }
  // Discs in one plane form a group: their union is what covers a face.
  for (std::size_t d = 0; d < context.discs.size(); ++d) {
    const ExactDisc& disc = context.discs[d];
    int group = -1;
    for (std::size_t g = 0; g < context.groups.size() && group < 0; ++g) {
      const ExactDisc& first = context.discs[static_cast<std::size_t>(context.groups[g].front())];
      if (allOnPlane(first.plane, disc.plane.normal, disc.plane.offset, disc.polygon,
                     context.tolerance)) {
        group = static_cast<int>(g);
      }
    }
    if (group < 0) {
      group = static_cast<int>(context.groups.size());
      context.groups.emplace_back();
    }
    context.groups[static_cast<std::size_t>(group)].push_back(static_cast<int>(d));
    context.group_of_disc.push_back(group);
  }
  if (!context.box_domain) linkBoundaryPlanes(context);
  return context;
}

/// A block from a set of pieces: mass properties and bounds.
Block makeBlock(std::vector<Piece> pieces, int material) {
  Block block;
  block.material = material;
  block.bounds.min = Vec3::Constant(std::numeric_limits<double>::infinity());
  block.bounds.max = -block.bounds.min;
  for (const Piece& piece : pieces) {
    block.mass += geometry::massProperties(piece.shape);
    const Box b = geometry::bounds(piece.shape);
    block.bounds.min = block.bounds.min.cwiseMin(b.min);
    block.bounds.max = block.bounds.max.cwiseMax(b.max);
  }
  block.pieces = std::move(pieces);
  return block;
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

std::vector<Polyhedron> convexDecomposition(const Polyhedron& solid) {
  Nef nef = nefFromPolyhedron(solid);
  CGAL::convex_decomposition_3(nef);
  return convexVolumes(nef);
}

namespace {

/// With the Nef referee: the Nef volumes, glued across region faces, must give the same
/// partition as the exact faces (`sets`); the report gets the Nef block count and whether
/// they agree.
void refereeWithNef(const Context& context, const std::vector<FaceRecord>& records,
                    const std::vector<std::pair<int, int>>& nef_links, UnionFind& sets,
                    ExactCutReport& local) {
  const int count = static_cast<int>(sets.size());
  UnionFind nef_sets(static_cast<std::size_t>(count));
  for (const auto& [a, b] : nef_links) nef_sets.unite(a, b);
  matchFaces(context, records, nef_sets, /*discs=*/false);
  std::map<int, int> forward;
  std::map<int, int> backward;
  bool agrees = true;
  for (int i = 0; i < count; ++i) {
    const int a = sets.find(i);
    const int b = nef_sets.find(i);
    agrees = agrees && forward.try_emplace(a, b).first->second == b &&
             backward.try_emplace(b, a).first->second == a;
  }
  local.nef_blocks = static_cast<int>(backward.size());
  local.nef_agrees = agrees;
}

/// Sound pieces (piece_soundness.h): slivers are folded away and near vertices merged after
/// the gluing, which the exact faces decided, so the blocks are those of the exact partition;
/// a block of slivers only disappears. Returns which pieces were folded.
std::vector<bool> soundPieces(std::vector<Piece>& pieces, const SoundnessTolerances& soundness,
                              SoundnessReport& report) {
  std::vector<bool> folded(pieces.size(), false);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    SoundPieceReport piece_report;
    std::optional<SoundPiece> sound = soundPiece(pieces[i], soundness, &piece_report);
    addToReport(pieces[i], sound, piece_report, report);
    if (sound) {
      pieces[i] = std::move(sound->piece);
    } else {
      folded[i] = true;
    }
  }
  return folded;
}

/// The rock blocks: components of the piece graph (`sets`), in order of their first kept
/// piece, each of the material holding most of its volume. `block_of_piece` gets each
/// piece's block; a folded piece belongs to its component's block (it keeps its mass there),
/// or to none (-1).
std::vector<Block> rockBlocks(const CutInput& input, const CutTolerances& tolerances,
                              const std::vector<Piece>& pieces, const std::vector<bool>& folded,
                              UnionFind& sets, std::vector<int>& block_of_piece) {
  std::vector<std::vector<int>> members;
  std::unordered_map<int, int> component;
  block_of_piece.assign(pieces.size(), -1);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (folded[i]) continue;
    const int root_piece = sets.find(static_cast<int>(i));
    const auto [it, added] = component.try_emplace(root_piece, static_cast<int>(members.size()));
    if (added) members.emplace_back();
    members[it->second].push_back(static_cast<int>(i));
    block_of_piece[i] = it->second;
  }
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (!folded[i]) continue;
    const auto it = component.find(sets.find(static_cast<int>(i)));
    if (it != component.end()) block_of_piece[i] = it->second;
  }
  const SlabMaterials slabs(input.network, input.disc_segments, input.rock_material,
                            tolerances.distance);
  std::vector<Block> blocks;
  for (const std::vector<int>& group : members) {
    std::vector<Piece> block_pieces;
    for (const int i : group) block_pieces.push_back(pieces[i]);
    const int material = slabs.ofBlock(block_pieces);
    blocks.push_back(makeBlock(std::move(block_pieces), material));
  }
  for (std::size_t i = 0; i < pieces.size(); ++i) {  // folded slivers keep their mass
    if (!folded[i] || block_of_piece[i] < 0) continue;
    const geometry::MassProperties m = geometry::massProperties(pieces[i].shape);
    blocks[static_cast<std::size_t>(block_of_piece[i])].mass += m;
    blocks[static_cast<std::size_t>(block_of_piece[i])].folded_volume += m.volume;
  }
  return blocks;
}

/// Rock pieces near the structures, then the structures' pieces, with the block of each, and
/// the contacts between them.
struct StructureContacts {
  std::vector<Piece> near;
  std::vector<int> block_of_near;
  std::vector<PieceContact> contacts;
};

/// One block per structure appended to `blocks`, and its contacts with the rock pieces near
/// it and with the other structures.
StructureContacts structureBlocks(const CutInput& input, const CutTolerances& tolerances,
                                  const std::vector<Piece>& pieces, const std::vector<bool>& folded,
                                  const std::vector<int>& block_of_piece,
                                  std::vector<Block>& blocks) {
  StructureContacts out;
  std::vector<Piece>& near = out.near;
  std::vector<int>& block_of_near = out.block_of_near;
  if (!input.structures.empty()) {
    std::vector<Box> structure_boxes;
    for (const StructureSolid& structure : input.structures) {
      for (const Polyhedron& shape : structure.pieces) {
        structure_boxes.push_back(geometry::bounds(shape).enlarged(tolerances.distance));
      }
    }
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      if (folded[i]) continue;
      const Box b = geometry::bounds(pieces[i].shape);
      const bool close =
          std::any_of(structure_boxes.begin(), structure_boxes.end(), [&](const Box& s) {
            return (b.min.array() <= s.max.array()).all() && (s.min.array() <= b.max.array()).all();
          });
      if (close) {
        near.push_back(pieces[i]);
        block_of_near.push_back(block_of_piece[i]);
      }
    }
  }
  const std::size_t near_rock = near.size();
  for (std::size_t s = 0; s < input.structures.size(); ++s) {
    std::vector<Piece> structure_pieces = labelStructurePieces(input, s, tolerances);
    for (const Piece& piece : structure_pieces) {
      near.push_back(piece);
      block_of_near.push_back(static_cast<int>(blocks.size()));
    }
    blocks.push_back(makeBlock(std::move(structure_pieces), input.structures[s].material));
    blocks.back().structure = static_cast<int>(s);
  }
  appendStructureContacts(near, near_rock, tolerances, out.contacts);

  return out;
}

}  // namespace

BlockModel cutExact(const CutInput& input, const ExactCutOptions& options, ExactCutReport* report) {
  const Context context = makeContext(input);
  checkStructuresOutsideRock(input, cutTolerances(input.domain_box));
  Region root;
  root.box = input.domain_box;
  for (std::size_t d = 0; d < context.discs.size(); ++d) root.discs.push_back(static_cast<int>(d));
  std::vector<Region> regions;
  splitRegions(context, root, input.domain_box.size().maxCoeff() / 64.0,
               std::max(1, options.max_discs_per_region), regions);

  std::vector<RegionResult> results(regions.size());
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, regions.size(), [&](std::size_t r) {
      throwIfInterrupted("the block cut (exact cutter)");
      results[r] = cutRegion(context, regions[r], options.check_exact_volume, options.nef_referee);
    });
  });

  const auto glue_start = Clock::now();
  std::vector<Piece> pieces;
  std::vector<FaceRecord> records;
  std::vector<std::pair<int, int>> nef_links;
  ExactCutReport local;
  ExactFT rock_volume = 0;
  for (RegionResult& result : results) {
    const int offset = static_cast<int>(pieces.size());
    for (auto [a, b] : result.nef_links) nef_links.emplace_back(a + offset, b + offset);
    for (FaceRecord& r : result.records) {
      r.piece += offset;
      records.push_back(std::move(r));
    }
    for (Piece& p : result.pieces) pieces.push_back(std::move(p));
    rock_volume += result.exact_volume;
    local.nef_seconds += result.nef_seconds;
    local.split_seconds += result.decompose_seconds;
    local.extract_seconds += result.extract_seconds;
  }
  for (const Region& region : regions) {
    local.disc_region_pairs += static_cast<int>(region.discs.size());
  }
  UnionFind sets(pieces.size());
  const std::vector<CrackContact> cracks = matchFaces(context, records, sets, /*discs=*/true);
  if (options.nef_referee) refereeWithNef(context, records, nef_links, sets, local);

  // Sound pieces (piece_soundness.h): slivers are folded away and near vertices merged
  // after the gluing, which the exact faces decided, so the blocks are those of the exact
  // partition; a block of slivers only disappears.
  const std::vector<bool> folded =
      soundPieces(pieces, soundnessTolerances(input.domain_box), local.soundness);

  // Rock blocks: components of the piece graph, in order of their first kept piece.
  const CutTolerances tolerances = cutTolerances(input.domain_box);
  std::vector<int> block_of_piece;
  std::vector<Block> blocks = rockBlocks(input, tolerances, pieces, folded, sets, block_of_piece);
  // Structures: one block each, as the fast cutter makes them (block_assembly.h), and their
  // contacts with the rock pieces near them and with each other.
  const StructureContacts structures =
      structureBlocks(input, tolerances, pieces, folded, block_of_piece, blocks);
  // Deterministic ids: the order both cutters share.
  const std::vector<int> order = blockOrder(blocks, input.domain_box);
  std::vector<int> id_of(blocks.size());
  for (std::size_t rank = 0; rank < order.size(); ++rank) {
    id_of[order[rank]] = static_cast<int>(rank) + 1;
  }

  // Adjacency: cracks between pieces of different blocks, and contacts with structures.
  std::map<std::tuple<int, int, int, int>, double> shared;
  const auto add = [&](int block_a, int block_b, const FaceSource& source, double area) {
    if (block_a < 0 || block_b < 0) return;  // a block of slivers only, folded away
    int a = id_of[block_a];
    int b = id_of[block_b];
    if (a == b) return;
    if (a > b) std::swap(a, b);
    shared[{a, b, static_cast<int>(source.kind), source.id}] += area;
  };
  for (const CrackContact& c : cracks) {
    add(block_of_piece[c.piece_a], block_of_piece[c.piece_b], c.source, c.area);
  }
  for (const PieceContact& c : structures.contacts) {
    // The rule of assembleBlocks: no fictitious side; the structure's face names the contact
    // (piece_a's when both sides are structures).
    const FaceSource& a =
        structures.near[static_cast<std::size_t>(c.piece_a)].face_sources[c.face_a];
    const FaceSource& b =
        structures.near[static_cast<std::size_t>(c.piece_b)].face_sources[c.face_b];
    if (a.kind == FaceKind::Fictitious || b.kind == FaceKind::Fictitious) continue;
    add(structures.block_of_near[c.piece_a], structures.block_of_near[c.piece_b],
        a.kind == FaceKind::Structure ? a : b, c.area);
  }

  BlockModel model;
  model.domain = input.domain_box;
  for (const Polyhedron& solid : context.domain_solids) {
    model.domain_volume += geometry::massProperties(solid).volume;
  }
  model.blocks.resize(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    blocks[i].id = id_of[i];
    model.blocks[static_cast<std::size_t>(id_of[i] - 1)] = std::move(blocks[i]);
  }
  for (const auto& [key, area] : shared) {
    const auto [a, b, kind, id] = key;
    model.adjacency.push_back({a, b, area, {static_cast<FaceKind>(kind), id}});
  }
  local.glue_seconds = secondsSince(glue_start);
  local.regions = static_cast<int>(regions.size());
  local.pieces = static_cast<int>(pieces.size()) - local.soundness.folded_pieces;
  if (options.check_exact_volume) {
    local.rock_volume_exact = toString(rock_volume);
    const ExactFT domain = exactDomainVolume(context);
    local.domain_volume_exact = toString(domain);
    local.volume_conserved = domain == rock_volume;
  }
  if (report != nullptr) *report = local;
  return model;
}

}  // namespace rockmass::blocks
