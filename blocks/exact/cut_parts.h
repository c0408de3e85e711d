// The parts of the exact cutter (blocks/exact_cutter.h) its files share: the exact kernel's
// types, exactly planar discs and the cut's context (exact/context.cpp), the convex cell
// complex of a region (exact/cells.cpp), coverage of a face by the discs of its plane
// (exact/coverage.cpp), the matching of faces across pieces (exact/face_matching.cpp) and
// Nef polyhedra of double solids (exact/nef_solids.cpp). Internal to the blocks module: the
// files under blocks/exact/ are the only ones of the module that instantiate CGAL's exact
// kernel and Nef polyhedra.
#pragma once

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Nef_polyhedron_3.h>

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "blocks/block_model.h"
#include "blocks/cutter.h"
#include "blocks/union_find.h"
#include "geometry/disc.h"
#include "geometry/polyhedron.h"

namespace rockmass::blocks::exactcut {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using FT = K::FT;
using Point3 = K::Point_3;
using Point2 = K::Point_2;
using Vector3 = K::Vector_3;
using Plane3 = K::Plane_3;
using Nef = CGAL::Nef_polyhedron_3<K>;
using ExactFT = K::Exact_kernel::FT;  // a rational number type (GMP)
using geometry::Box;
using geometry::Polyhedron;
using geometry::Vec3;
using Clock = std::chrono::steady_clock;

/// Wall seconds since `start` (the report's timings).
inline double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

inline Point3 toPoint(const Vec3& v) {
  return Point3(v.x(), v.y(), v.z());
}

inline Vec3 toVec(const Point3& p) {
  return Vec3(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
}

/// A plane known exactly, with a unit normal and offset in double for quick candidate search.
struct KnownPlane {
  Plane3 exact;
  Vec3 normal = Vec3::UnitZ();  ///< unit, approximate
  double offset = 0.0;          ///< normal . x = offset, approximate (m)
};

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

/// A region of the kd split and the discs that may meet it.
struct Region {
  Box box;
  std::vector<int> discs;
};

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

/// A crack face between two pieces.
struct CrackContact {
  int piece_a = 0;
  int piece_b = 0;
  FaceSource source;
  double area = 0.0;
};

// exact/context.cpp

/// The plane with its approximate unit normal and offset.
KnownPlane knownPlane(const Plane3& plane);

/// Plane of a planar polygon through its first non-collinear vertex triple.
std::optional<Plane3> polygonPlane(const std::vector<Point3>& polygon);

/// Drops coordinate `axis` of p.
Point2 project(const Point3& p, int axis);

/// Conservative double test: may the disc's polygon meet the box?
bool mayMeet(const ExactDisc& disc, const Box& box);

/// True when an axis-aligned plane coordinate[axis] == level coincides with the plane.
bool isAxisPlane(const Plane3& plane, int axis, double level);

/// The cut's context: the domain's solids and planes, the exact discs that may meet the
/// domain and their groups by plane. Throws std::invalid_argument when the input has no
/// domain or fewer than 3 disc segments.
Context makeContext(const CutInput& input);

// exact/cells.cpp

/// Average of the vertices: an interior point of a convex cell.
Point3 interiorPoint(const std::vector<Point3>& vertices);

/// Cuts one region: splits its box into convex cells by every splitting surface (domain
/// surface, discs) that meets a cell, drops cells outside the rock, and records the
/// provenance of every face. With `nef_referee`, the region's rock minus its discs is also
/// built as a Nef polyhedron and each cell is located in it.
RegionResult cutRegion(const Context& context, const Region& region, bool exact_volume,
                       bool nef_referee);

// exact/coverage.cpp

/// Keeps the part of a convex polygon on the left of s->t (or on the right when `left` is
/// false), exact.
std::vector<Point2> clipHalfPlane(const std::vector<Point2>& polygon, const Point2& s,
                                  const Point2& t, bool left);

/// Counter-clockwise copy of a polygon.
std::vector<Point2> counterClockwise(std::vector<Point2> polygon);

/// Double version of a projected polygon.
std::vector<Eigen::Vector2d> toDouble(const std::vector<Point2>& polygon);

/// Whether the convex polygon (projected by dropping `drop_axis`) lies wholly inside the
/// union of the discs of `group`.
bool coveredByGroup(const Context& context, int group, const std::vector<Point2>& polygon,
                    int drop_axis);

/// The disc of `group` whose polygon holds point q (projected), else the group's first.
int discHolding(const Context& context, int group, const Point3& q);

// exact/face_matching.cpp

/// Matches faces in the same plane on opposite sides: pieces glue (`sets`) where the shared
/// part is not wholly covered by discs; covered shared parts are crack contacts. With
/// `discs` false only region faces are matched (the Nef referee's gluing).
std::vector<CrackContact> matchFaces(const Context& context, const std::vector<FaceRecord>& records,
                                     UnionFind& sets, bool discs);

// exact/nef_solids.cpp

/// Nef polyhedron of a closed polyhedron whose coordinates are taken as exact.
Nef nefFromPolyhedron(const Polyhedron& solid);

/// Exact volume of a closed outward polyhedron with exact vertices (divergence theorem).
ExactFT exactVolume(const std::vector<Point3>& vertices,
                    const std::vector<std::vector<int>>& faces);

}  // namespace rockmass::blocks::exactcut
