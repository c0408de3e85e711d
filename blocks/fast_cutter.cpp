#include "blocks/fast_cutter.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include "blocks/convex_partition.h"
#include "blocks/convex_split.h"
#include "blocks/piece_contacts.h"
#include "blocks/region_split.h"
#include "blocks/union_find.h"
#include "geometry/disc.h"
#include "geometry/interrupt.h"

namespace rockmass::blocks {
namespace {

using geometry::Box;
using geometry::Vec2;

/// A convex cutting polygon: (part of) one disc.
struct CutPolygon {
  int disc_id = 0;
  Plane plane;               ///< the disc's plane
  std::vector<Vec3> points;  ///< counter-clockwise about plane.normal
  std::vector<Plane> edges;  ///< per edge: perpendicular to the disc, normal pointing inside
  Box box;                   ///< bounding box of the points
  int plane_id = 0;          ///< id of `plane` (a UnionFind id: coincident planes share a root)
  int first_edge_id = 0;     ///< id of edges[0]; edges[k] has first_edge_id + k
  int group = -1;            ///< FullPlanes: its DiscGroup
};

/// A piece being cut, with the id of the plane each face lies in. Faces made by one cutting
/// plane share its id; coincident planes are merged when a polygon meets a face in its
/// plane. Contacts are then searched among faces of one plane only.
struct WorkPiece {
  Piece piece;
  std::vector<int> planes;  ///< per face
};

/// The convex cutting polygons of one disc.
void addCutPolygons(const geometry::Disc& disc, int segments, double tolerance, UnionFind& ids,
                    std::vector<CutPolygon>& out) {
  std::vector<Vec3> outline = disc.outline(segments);
  const Vec3 n = disc.normal.normalized();
  const Plane plane = Plane::through(disc.center, n);
  // FAB polygons are used as given, up to their tiny departures from planarity.
  for (Vec3& p : outline) p -= plane.distance(p) * n;
  if (geometry::polygonNormal(outline).dot(n) < 0.0) std::reverse(outline.begin(), outline.end());
  const Vec3 u = n.unitOrthogonal();
  const Vec3 w = n.cross(u);
  std::vector<Vec2> flat;
  for (const Vec3& p : outline)
    flat.emplace_back((p - disc.center).dot(u), (p - disc.center).dot(w));
  for (const std::vector<int>& part : convexPartition(flat)) {
    CutPolygon polygon;
    polygon.disc_id = static_cast<int>(disc.id);
    polygon.plane = plane;
    polygon.plane_id =
        out.empty() || out.back().disc_id != polygon.disc_id ? ids.add() : out.back().plane_id;
    for (int i : part) polygon.points.push_back(outline[i]);
    const std::size_t m = polygon.points.size();
    polygon.box = {Vec3::Constant(std::numeric_limits<double>::infinity()),
                   Vec3::Constant(-std::numeric_limits<double>::infinity())};
    for (std::size_t k = 0; k < m; ++k) {
      const Vec3& p = polygon.points[k];
      const Vec3& q = polygon.points[(k + 1) % m];
      polygon.box.min = polygon.box.min.cwiseMin(p);
      polygon.box.max = polygon.box.max.cwiseMax(p);
      const Vec3 inward = n.cross(q - p);
      if (inward.norm() <= tolerance) continue;  // a degenerate edge cuts nothing
      polygon.edges.push_back(Plane::through(p, inward.normalized()));
    }
    polygon.first_edge_id = ids.add();
    for (std::size_t k = 1; k < polygon.edges.size(); ++k) ids.add();
    out.push_back(std::move(polygon));
  }
}

/// The live pieces and a uniform grid over their bounding boxes, for the query "which pieces
/// may meet this polygon". Dead pieces are dropped from the cells lazily.
class PieceStore {
 public:
  PieceStore(const Box& domain, std::size_t polygons) : domain_(domain) {
    const Vec3 size = domain.size().cwiseMax(1e-300);
    const double target = std::clamp(2.0 * static_cast<double>(polygons), 1.0, 262144.0);
    const double cell = std::cbrt(size.prod() / target);
    for (int a = 0; a < 3; ++a) {
      dims_[a] = std::clamp(static_cast<int>(std::ceil(size[a] / cell)), 1, 256);
      cell_size_[a] = size[a] / dims_[a];
    }
    cells_.resize(static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2]);
  }

  int add(WorkPiece piece) {
    const int id = static_cast<int>(pieces_.size());
    boxes_.push_back(geometry::bounds(piece.piece.shape));
    pieces_.push_back(std::move(piece));
    alive_.push_back(1);
    seen_.push_back(-1);
    forCells(boxes_.back(), [&](std::vector<int>& cell) { cell.push_back(id); });
    return id;
  }
  void kill(int id) {
    alive_[id] = 0;
    pieces_[id] = WorkPiece{};
  }
  const WorkPiece& piece(int id) const { return pieces_[id]; }
  const Box& box(int id) const { return boxes_[id]; }

  /// Live pieces whose boxes meet `box`, ascending.
  std::vector<int> query(const Box& box) {
    ++stamp_;
    std::vector<int> found;
    forCells(box, [&](std::vector<int>& cell) {
      std::erase_if(cell, [&](int id) { return !alive_[id]; });
      for (int id : cell) {
        if (seen_[id] == stamp_) continue;
        seen_[id] = stamp_;
        const Box& b = boxes_[id];
        if ((b.min.array() <= box.max.array()).all() && (box.min.array() <= b.max.array()).all()) {
          found.push_back(id);
        }
      }
    });
    std::sort(found.begin(), found.end());
    return found;
  }

  /// The live pieces in creation order.
  std::vector<WorkPiece> takeAlive() {
    std::vector<WorkPiece> out;
    for (std::size_t i = 0; i < pieces_.size(); ++i) {
      if (alive_[i]) out.push_back(std::move(pieces_[i]));
    }
    return out;
  }

 private:
  template <class F>
  void forCells(const Box& box, F&& f) {
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] =
          std::clamp(static_cast<int>(std::floor((box.min[a] - domain_.min[a]) / cell_size_[a])), 0,
                     dims_[a] - 1);
      hi[a] =
          std::clamp(static_cast<int>(std::floor((box.max[a] - domain_.min[a]) / cell_size_[a])), 0,
                     dims_[a] - 1);
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x)
          f(cells_[(static_cast<std::size_t>(z) * dims_[1] + y) * dims_[0] + x]);
  }

  Box domain_;
  int dims_[3] = {1, 1, 1};
  double cell_size_[3] = {1, 1, 1};
  std::vector<std::vector<int>> cells_;
  std::vector<WorkPiece> pieces_;
  std::vector<Box> boxes_;
  std::vector<char> alive_;
  std::vector<int> seen_;
  int stamp_ = 0;
};

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// True when the box lies more than `tolerance` on one side of the plane.
bool boxMissesPlane(const Box& box, const Plane& plane, double tolerance) {
  const Vec3 c = box.center();
  const Vec3 h = 0.5 * box.size();
  const double reach = h.dot(plane.normal.cwiseAbs());
  return std::abs(plane.distance(c)) > reach + tolerance;
}

/// The two halves of a split work piece, with the face of the input each face comes from
/// (-1: the new face).
struct WorkSplit {
  WorkPiece below, above;
  std::vector<int> below_origin, above_origin;
};

/// Splits a work piece by a plane with id `plane_id`; faces keep their plane ids.
std::optional<WorkSplit> splitWork(const WorkPiece& work, const Plane& plane, int plane_id,
                                   double tolerance, FaceSource cap) {
  std::optional<SplitPieces> split = splitPiece(work.piece, plane, tolerance, cap);
  if (!split) return std::nullopt;
  const auto planes = [&](const std::vector<int>& origin) {
    std::vector<int> out;
    out.reserve(origin.size());
    for (int f : origin) out.push_back(f < 0 ? plane_id : work.planes[f]);
    return out;
  };
  std::vector<int> below_planes = planes(split->below_origin);
  std::vector<int> above_planes = planes(split->above_origin);
  return WorkSplit{{std::move(split->below), std::move(below_planes)},
                   {std::move(split->above), std::move(above_planes)},
                   std::move(split->below_origin),
                   std::move(split->above_origin)};
}

/// What cutting one piece by one polygon gives.
struct CutResult {
  std::optional<std::vector<WorkPiece>> pieces;  ///< replacements, or nothing: unchanged
  std::vector<std::pair<int, int>> coincident;   ///< plane ids found to be one plane
  long long splits = 0;                          ///< plane splits made
};

/// Cuts one piece by one polygon.
CutResult cutPiece(const WorkPiece& work, const CutPolygon& polygon, const CutTolerances& tol) {
  CutResult result;
  const Piece& piece = work.piece;
  const Section section = planeSection(piece, polygon.plane, tol.distance);
  if (section.kind == SectionKind::None) return result;
  if (section.kind == SectionKind::OnFace) {
    result.coincident.emplace_back(work.planes[section.face], polygon.plane_id);
    // A disc on a face that is already real (boundary, structure, another crack) adds nothing.
    if (piece.face_sources[section.face].kind != FaceKind::Fictitious) return result;
  }
  // Does the polygon cover any of the section?
  std::vector<Vec3> covered = section.polygon;
  for (const Plane& edge : polygon.edges) {
    covered = clipPolygon(covered, edge);
    if (covered.size() < 3) return result;
  }
  // A covered part thinner than the distance tolerance is a graze along a polygon edge:
  // nothing to cut. A small but compact one is a real crossing (a piece corner poking
  // 0.1 mm through a crack): it is cut, as the exact cutter cuts it.
  if (thinnerThan(covered, tol.distance)) return result;

  std::vector<WorkPiece> out;
  WorkPiece core = work;
  std::vector<Vec3> core_section = section.polygon;
  for (std::size_t k = 0; k < polygon.edges.size(); ++k) {
    const Plane& edge = polygon.edges[k];
    double lowest = 0.0;
    for (const Vec3& p : core_section) lowest = std::min(lowest, edge.distance(p));
    if (lowest >= -tol.distance) continue;  // the section is inside this edge's half-plane
    if (auto split = splitWork(core, edge, polygon.first_edge_id + static_cast<int>(k),
                               tol.distance, {FaceKind::Fictitious, -1})) {
      ++result.splits;
      out.push_back(std::move(split->below));  // outside the polygon: not cut by the disc
      core = std::move(split->above);
    }
    core_section = clipPolygon(core_section, edge);
  }
  const FaceSource disc{FaceKind::Disc, polygon.disc_id};
  if (section.kind == SectionKind::Crossing) {
    if (auto split = splitWork(core, polygon.plane, polygon.plane_id, tol.distance, disc)) {
      ++result.splits;
      out.push_back(std::move(split->below));
      out.push_back(std::move(split->above));
    } else {
      out.push_back(std::move(core));
    }
  } else {
    // The disc lies on a fictitious face: its part inside the polygon becomes a crack.
    bool relabelled = false;
    Piece& c = core.piece;
    for (std::size_t f = 0; f < c.shape.faces.size(); ++f) {
      if (c.face_sources[f].kind != FaceKind::Fictitious) continue;
      const std::vector<int>& face = c.shape.faces[f];
      const bool on = std::all_of(face.begin(), face.end(), [&](int v) {
        return std::abs(polygon.plane.distance(c.shape.vertices[v])) <= tol.distance;
      });
      if (on) {
        c.face_sources[f] = disc;
        relabelled = true;
      }
    }
    if (out.empty() && !relabelled) return result;
    out.push_back(std::move(core));
  }
  result.pieces = std::move(out);
  return result;
}

/// What both strategies start from: the labelled domain pieces, one plane id per domain face
/// (faces shared by two domain pieces united), then the cutting polygons with their plane and
/// edge ids, in disc order.
struct CutStart {
  UnionFind plane_ids;  ///< coincident planes end up with one root
  std::vector<Piece> domain;
  std::vector<std::vector<int>> domain_planes;  ///< per domain piece, per face
  std::vector<CutPolygon> polygons;
};

CutStart startCut(const CutInput& input, const CutTolerances& tol) {
  CutStart s;
  s.domain = labelDomainPieces(input, tol);
  s.domain_planes.resize(s.domain.size());
  for (std::size_t i = 0; i < s.domain.size(); ++i) {
    for (std::size_t f = 0; f < s.domain[i].shape.faces.size(); ++f) {
      s.domain_planes[i].push_back(s.plane_ids.add());
    }
  }
  if (s.domain.size() > 1) {
    for (const PieceContact& c : findPieceContacts(s.domain, tol.distance, tol.area)) {
      s.plane_ids.unite(s.domain_planes[c.piece_a][c.face_a], s.domain_planes[c.piece_b][c.face_b]);
    }
  }
  for (const geometry::Disc& disc : input.network->discs) {
    if (disc.cuts) {
      addCutPolygons(disc, input.disc_segments, tol.distance, s.plane_ids, s.polygons);
    }
  }
  return s;
}

BlockModel cutEdgePlanes(const CutInput& input, const CutTolerances& tol, FastCutReport* report) {
  FastCutReport counters;
  counters.regions = 1;
  const auto start = std::chrono::steady_clock::now();

  CutStart setup = startCut(input, tol);
  UnionFind& plane_ids = setup.plane_ids;
  std::vector<Piece>& domain = setup.domain;
  std::vector<std::vector<int>>& domain_planes = setup.domain_planes;
  const std::vector<CutPolygon>& polygons = setup.polygons;
  counters.cutting_polygons = static_cast<int>(polygons.size());

  PieceStore store(input.domain_box, polygons.size());
  for (std::size_t i = 0; i < domain.size(); ++i) {
    store.add({std::move(domain[i]), std::move(domain_planes[i])});
  }
  std::vector<int> ids;
  std::vector<CutResult> results;
  for (const CutPolygon& polygon : polygons) {
    ids = store.query(polygon.box.enlarged(tol.distance));
    std::erase_if(
        ids, [&](int id) { return boxMissesPlane(store.box(id), polygon.plane, tol.distance); });
    counters.piece_tests += static_cast<long long>(ids.size());
    // The pieces a polygon meets are cut independently (in parallel), then replaced in
    // ascending order, so the result does not depend on the thread count.
    results.assign(ids.size(), CutResult{});
    const auto cut_one = [&](std::size_t k) {
      results[k] = cutPiece(store.piece(ids[k]), polygon, tol);
    };
    if (ids.size() >= 32) {
      tbb::parallel_for(std::size_t{0}, ids.size(), cut_one);
    } else {
      for (std::size_t k = 0; k < ids.size(); ++k) cut_one(k);
    }
    for (std::size_t k = 0; k < ids.size(); ++k) {
      counters.splits += results[k].splits;
      for (const auto& [a, b] : results[k].coincident) plane_ids.unite(a, b);
      if (!results[k].pieces) continue;
      store.kill(ids[k]);
      for (WorkPiece& p : *results[k].pieces) store.add(std::move(p));
    }
  }
  std::vector<WorkPiece> work = store.takeAlive();
  counters.pieces = static_cast<int>(work.size());
  counters.cut_seconds = secondsSince(start);

  const auto assemble_start = std::chrono::steady_clock::now();
  std::vector<Piece> pieces;
  std::vector<std::vector<int>> planes;
  pieces.reserve(work.size());
  planes.reserve(work.size());
  for (WorkPiece& w : work) {
    for (int& id : w.planes) id = plane_ids.find(id);
    pieces.push_back(std::move(w.piece));
    planes.push_back(std::move(w.planes));
  }
  const std::vector<PieceContact> contacts =
      findContactsByPlane(pieces, planes, tol.distance, tol.area);
  AssemblyReport assembly;
  BlockModel model = assembleBlocks(std::move(pieces), contacts, input, tol, &assembly);
  counters.inconsistent_contacts = assembly.inconsistent_contacts;
  counters.soundness = assembly.soundness;
  counters.pieces -= assembly.soundness.folded_pieces;
  counters.assemble_seconds = secondsSince(assemble_start);
  if (report) *report = counters;
  return model;
}

// ---------------------------------------------------------------------------------------
// FastStrategy::FullPlanes: the exact cutter's strategy in floating point.

/// Discs in one plane (within the tolerance): their union is what covers a face.
struct DiscGroup {
  Plane plane;                ///< the plane of the group's first disc
  int plane_id = 0;           ///< plane id shared by all its polygons
  std::vector<int> polygons;  ///< indices of its cutting polygons
};

/// Puts every cutting polygon into the group of its plane; a polygon that joins a group is
/// moved onto the group's plane (its points projected, its edges rebuilt) and takes its id.
std::vector<DiscGroup> groupPolygons(std::vector<CutPolygon>& polygons, double tolerance) {
  std::vector<DiscGroup> groups;
  std::vector<int> group_of_plane_id;  // by the polygon's own plane id, for the parts of a disc
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    CutPolygon& polygon = polygons[i];
    int found = -1;
    if (i > 0 && polygons[i - 1].disc_id == polygon.disc_id) {
      found = polygons[i - 1].group;  // the next convex part of the same disc
    }
    for (std::size_t g = 0; g < groups.size() && found < 0; ++g) {
      const Plane& plane = groups[g].plane;
      if (std::abs(plane.normal.dot(polygon.plane.normal)) < 1.0 - 1e-12) continue;
      const bool on = std::all_of(polygon.points.begin(), polygon.points.end(), [&](const Vec3& p) {
        return std::abs(plane.distance(p)) <= tolerance;
      });
      if (on) found = static_cast<int>(g);
    }
    if (found < 0) {
      found = static_cast<int>(groups.size());
      groups.push_back({polygon.plane, polygon.plane_id, {}});
    } else if (groups[found].plane_id != polygon.plane_id) {
      // Rebase onto the group's plane, counter-clockwise about its normal.
      const Plane& plane = groups[found].plane;
      for (Vec3& p : polygon.points) p -= plane.distance(p) * plane.normal;
      if (plane.normal.dot(polygon.plane.normal) < 0.0) {
        std::reverse(polygon.points.begin(), polygon.points.end());
      }
      polygon.plane = plane;
      polygon.plane_id = groups[found].plane_id;
      polygon.edges.clear();
      const std::size_t m = polygon.points.size();
      for (std::size_t k = 0; k < m; ++k) {
        const Vec3 inward = plane.normal.cross(polygon.points[(k + 1) % m] - polygon.points[k]);
        if (inward.norm() <= tolerance) continue;
        polygon.edges.push_back(Plane::through(polygon.points[k], inward.normalized()));
      }
    }
    polygon.group = found;
    groups[found].polygons.push_back(static_cast<int>(i));
  }
  return groups;
}

/// How the discs of a plane cover a convex face in that plane.
enum class Cover : std::uint8_t {
  None,     ///< not at all (the covered part has no area above the tolerance)
  Partial,  ///< partly
  Whole,    ///< wholly (what is left uncovered has no area above the tolerance)
};

/// True when every point lies inside the convex polygon, within `tolerance` (m).
bool insidePolygon(const std::vector<Vec3>& points, const CutPolygon& polygon, double tolerance) {
  for (const Plane& edge : polygon.edges) {
    for (const Vec3& p : points) {
      if (edge.distance(p) < -tolerance) return false;
    }
  }
  return true;
}

/// Polygons with more edges than this are clipped against a face rather than the face
/// against them (overlapInto). The ellipses of `disc_segments` (at most 1024 by the scene
/// reader, 24 by default) and FAB polygons of up to 64 vertices keep the face-by-edges path.
constexpr std::size_t kManyEdges = 64;

/// `out` = the part of the convex `face` (points in the polygon's plane) inside the convex
/// polygon. The face is clipped by the polygon's edges one by one; the part left can grow by
/// a vertex per edge, so a polygon of n edges over a face costs O(n^2) (a FAB circle of
/// 200 000 vertices: 97 s). A polygon of more than kManyEdges edges, and more than the face
/// has, is clipped by the face's edges instead: the same convex set, O(n m).
void overlapInto(const std::vector<Vec3>& face, const CutPolygon& polygon, std::vector<Vec3>& out,
                 std::vector<Vec3>& scratch) {
  if (polygon.edges.size() <= kManyEdges || polygon.edges.size() <= face.size()) {
    out.assign(face.begin(), face.end());
    for (const Plane& edge : polygon.edges) {
      clipPolygon(out, edge, scratch);
      std::swap(out, scratch);
      if (out.size() < 3) return;
    }
    return;
  }
  const Vec3& n = polygon.plane.normal;
  const double turn = geometry::polygonNormal(face).dot(n) < 0.0 ? -1.0 : 1.0;
  out.assign(polygon.points.begin(), polygon.points.end());
  const std::size_t m = face.size();
  for (std::size_t k = 0; k < m; ++k) {
    const Vec3 inward = turn * n.cross(face[(k + 1) % m] - face[k]);
    const double length = inward.norm();
    if (!(length > 0.0)) continue;
    clipPolygon(out, Plane::through(face[k], inward / length), scratch);
    std::swap(out, scratch);
    if (out.size() < 3) return;
  }
}

/// Area (m2) of the part of `face` inside the convex polygon.
double coveredArea(const std::vector<Vec3>& face, const CutPolygon& polygon) {
  // A face wholly outside one edge line (every point strictly outside) has nothing covered:
  // the clipping below would end empty, or, through round-off in its constructed points, in
  // a sliver of no area. Decided by signs before any clipping (most faces in a disc plane
  // lie outside the disc).
  for (const Plane& edge : polygon.edges) {
    if (std::all_of(face.begin(), face.end(),
                    [&](const Vec3& p) { return edge.distance(p) < 0.0; })) {
      return 0.0;
    }
  }
  thread_local std::vector<Vec3> a, b;
  overlapInto(face, polygon, a, b);
  return a.size() < 3 ? 0.0 : geometry::polygonArea(a);
}

/// How the group's polygons cover the convex face (points in the group's plane); `disc` gets
/// the disc holding the face's centre when Whole. Double precision with the cutter's
/// tolerances: a vertex within tolerance.distance of an edge is on it, an uncovered or
/// covered part of area at most tolerance.area is none.
Cover coverage(const std::vector<Vec3>& face, const DiscGroup& group,
               const std::vector<CutPolygon>& polygons, const CutTolerances& tol, int* disc) {
  const geometry::Box box = [&] {
    geometry::Box b{face[0], face[0]};
    for (const Vec3& p : face) {
      b.min = b.min.cwiseMin(p);
      b.max = b.max.cwiseMax(p);
    }
    return b.enlarged(tol.distance);
  }();
  const auto boxesMeet = [&](const Box& other) {
    return (box.min.array() <= other.max.array()).all() &&
           (other.min.array() <= box.max.array()).all();
  };
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : face) centre += p;
  centre /= static_cast<double>(face.size());
  const auto holder = [&] {
    for (int i : group.polygons) {
      if (insidePolygon({centre}, polygons[i], tol.distance)) return polygons[i].disc_id;
    }
    return polygons[group.polygons.front()].disc_id;
  };
  // Fast path: the face lies inside one polygon.
  bool any = false;
  for (int i : group.polygons) {
    if (!boxesMeet(polygons[i].box)) continue;
    if (insidePolygon(face, polygons[i], tol.distance)) {
      *disc = polygons[i].disc_id;
      return Cover::Whole;
    }
    any = any || coveredArea(face, polygons[i]) > tol.area;
  }
  if (!any) return Cover::None;
  if (group.polygons.size() == 1) return Cover::Partial;
  // Several polygons: peel the parts of the face outside each polygon in turn; what is left
  // at the end is uncovered.
  std::vector<std::vector<Vec3>> rest{face};
  std::vector<Vec3> outside;
  for (int i : group.polygons) {
    const CutPolygon& polygon = polygons[i];
    if (!boxesMeet(polygon.box)) continue;
    std::vector<std::vector<Vec3>> next;
    for (std::vector<Vec3> piece : rest) {
      for (const Plane& edge : polygon.edges) {
        if (piece.size() < 3) break;
        clipPolygon(piece, Plane{-edge.normal, -edge.offset}, outside);
        if (outside.size() >= 3 && geometry::polygonArea(outside) > tol.area) {
          next.push_back(outside);
        }
        piece = clipPolygon(piece, edge);
      }
    }
    rest = std::move(next);
    if (rest.empty()) break;
  }
  if (!rest.empty()) return Cover::Partial;
  *disc = holder();
  return Cover::Whole;
}

/// Face `face` of a cell may touch face `other_face` of cell `other` of the same region.
struct Link {
  int face = 0;
  int other = 0;  ///< index in the region's cell store
  int other_face = 0;
  int back = 0;  ///< position of the reverse link in the other cell's list (lists of live
                 ///< cells only change in place or grow at the end, so positions hold)
};

/// A cell of a region: a work piece, its bounding box and, when contacts are tracked, the
/// faces of other cells of the region that may touch its faces.
struct Cell {
  WorkPiece work;
  Box box;
  std::vector<Link> links;
};

/// A kd region: its box, the plane id of each of its six faces (boxPolyhedron order; -1 on
/// the domain's bounding box) and the polygons that may meet it, ascending.
struct Region {
  Box box;
  std::array<int, 6> face_plane{-1, -1, -1, -1, -1, -1};
  std::vector<int> polygons;
};

/// Conservative: may the polygon meet the box?
bool polygonMayMeetBox(const CutPolygon& polygon, const Box& box, double tolerance) {
  const Box b = box.enlarged(tolerance);
  if ((polygon.box.max.array() < b.min.array()).any() ||
      (polygon.box.min.array() > b.max.array()).any()) {
    return false;
  }
  return !boxMissesPlane(box, polygon.plane, tolerance);
}

/// kd split of `region` (longest axis) until it meets at most `max_polygons` polygons or
/// its longest edge is below `min_size`. Split levels avoid every axis-aligned polygon
/// plane and domain-piece face plane (`avoid[axis]`: their levels), so a region face never
/// lies in a disc: region faces are fictitious.
void splitRegions(const std::vector<CutPolygon>& polygons,
                  const std::array<std::vector<double>, 3>& avoid, double min_size,
                  int max_polygons, double tolerance, UnionFind& plane_ids, Region region,
                  std::vector<Region>& out) {
  const int axis = longestAxis(region.box);
  if (static_cast<int>(region.polygons.size()) <= max_polygons ||
      region.box.size()[axis] < 2.0 * min_size) {
    out.push_back(std::move(region));
    return;
  }
  const double level = freeSplitLevel(
      region.box, axis,
      [&](double level) {
        return std::any_of(avoid[axis].begin(), avoid[axis].end(),
                           [&](double x) { return std::abs(x - level) <= 1e3 * tolerance; });
      },
      "fast cutter");
  const int plane = plane_ids.add();
  for (int side = 0; side < 2; ++side) {
    Region child;
    child.box = region.box;
    child.face_plane = region.face_plane;
    // boxPolyhedron faces: 2 axis = min side, 2 axis + 1 = max side.
    if (side == 0) {
      child.box.max[axis] = level;
      child.face_plane[2 * axis + 1] = plane;
    } else {
      child.box.min[axis] = level;
      child.face_plane[2 * axis] = plane;
    }
    for (int p : region.polygons) {
      if (polygonMayMeetBox(polygons[p], child.box, tolerance)) child.polygons.push_back(p);
    }
    splitRegions(polygons, avoid, min_size, max_polygons, tolerance, plane_ids, std::move(child),
                 out);
  }
}

/// What one region gives.
struct RegionCut {
  std::vector<Piece> pieces;
  std::vector<int> planes;  ///< plane id of every face of `pieces`, in piece and face order
  /// Tracked: the faces that may touch another (piece indices into `pieces`), for the
  /// contact tests, and the pairs of them (indices into faces.faces).
  ContactFaces faces;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  std::vector<std::pair<int, int>> coincident;  ///< plane ids found to be one plane
  /// Tracked: faces that are the two sides of one cut (the same loop, bitwise): (piece,
  /// face, other piece, other face), piece indices into `pieces`. Their coverage is one.
  std::vector<std::array<int, 4>> twins;
  /// Tracked: the contacts of the twins that touch (mirroredContactArea), not in `pairs`.
  std::vector<PieceContact> mirrored;
  /// Tracked: the faces of `pieces` in the region's kd faces (planes between regions), for
  /// the search across regions, with their plane ids (kd_planes, per entry of kd.faces).
  ContactFaces kd;
  std::vector<int> kd_planes;
  /// Per piece: what the assembly needs of it (computed here, while the piece is in cache).
  std::vector<PieceFacts> facts;
  long long piece_tests = 0;
  long long splits = 0;
};

/// The region's starting cells: the domain pieces clipped to the region box.
std::vector<Cell> regionCells(const Region& region, const std::vector<Piece>& domain,
                              const std::vector<std::vector<int>>& domain_planes, bool box_domain,
                              const CutTolerances& tol) {
  std::vector<Cell> cells;
  if (box_domain) {
    // The box itself: exact coordinates, faces on the domain keep its labels.
    WorkPiece work;
    work.piece.shape = geometry::boxPolyhedron(region.box);
    for (int f = 0; f < 6; ++f) {
      if (region.face_plane[f] < 0) {
        work.piece.face_sources.push_back(domain[0].face_sources[f]);
        work.planes.push_back(domain_planes[0][f]);
      } else {
        work.piece.face_sources.push_back({FaceKind::Fictitious, -1});
        work.planes.push_back(region.face_plane[f]);
      }
    }
    cells.push_back({std::move(work), region.box, {}});
    return cells;
  }
  const geometry::Polyhedron box_shape = geometry::boxPolyhedron(region.box);
  for (std::size_t i = 0; i < domain.size(); ++i) {
    const Box b = geometry::bounds(domain[i].shape);
    if ((b.max.array() < region.box.min.array()).any() ||
        (b.min.array() > region.box.max.array()).any()) {
      continue;
    }
    WorkPiece work{domain[i], domain_planes[i]};
    bool empty = false;
    for (int f = 0; f < 6 && !empty; ++f) {
      if (region.face_plane[f] < 0) continue;
      const Plane plane = Plane::through(box_shape.vertices[box_shape.faces[f][0]],
                                         geometry::faceNormal(box_shape, f));
      if (auto split = splitWork(work, plane, region.face_plane[f], tol.distance,
                                 {FaceKind::Fictitious, -1})) {
        work = std::move(split->below);
      } else {
        const Vec3 c = geometry::massProperties(work.piece.shape).centroid();
        empty = plane.distance(c) > 0.0;
      }
    }
    if (empty) continue;
    const Box box = geometry::bounds(work.piece.shape);
    cells.push_back({std::move(work), box, {}});
  }
  return cells;
}

/// The lowest and highest signed distance (m) of the points of face f of `piece` from
/// `plane`.
std::pair<double, double> faceReach(const Piece& piece, int f, const Plane& plane) {
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (int v : piece.shape.faces[f]) {
    const double d = plane.distance(piece.shape.vertices[v]);
    low = std::min(low, d);
    high = std::max(high, d);
  }
  return {low, high};
}

/// The starting cells' mutual neighbours (several domain pieces in the region): faces of
/// two cells with opposite normals, one lying in the plane of the other within twice the
/// tolerance, whose boxes meet. Conservative: the contact test decides later.
void initialTouching(std::vector<Cell>& cells, double tolerance) {
  const double margin = 2.0 * tolerance;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    for (std::size_t j = i + 1; j < cells.size(); ++j) {
      const Box near = cells[i].box.enlarged(margin);
      if ((near.max.array() < cells[j].box.min.array()).any() ||
          (cells[j].box.max.array() < near.min.array()).any()) {
        continue;
      }
      const Piece& a = cells[i].work.piece;
      const Piece& b = cells[j].work.piece;
      for (int fa = 0; fa < static_cast<int>(a.shape.faces.size()); ++fa) {
        const Vec3 na = geometry::faceNormal(a.shape, fa);
        const Plane pa = Plane::through(a.shape.vertices[a.shape.faces[fa][0]], na);
        for (int fb = 0; fb < static_cast<int>(b.shape.faces.size()); ++fb) {
          const Vec3 nb = geometry::faceNormal(b.shape, fb);
          if (na.dot(nb) > -0.999) continue;
          const Plane pb = Plane::through(b.shape.vertices[b.shape.faces[fb][0]], nb);
          const auto [low_b, high_b] = faceReach(b, fb, pa);
          const auto [low_a, high_a] = faceReach(a, fa, pb);
          const bool b_on_a = low_b >= -margin && high_b <= margin;
          const bool a_on_b = low_a >= -margin && high_a <= margin;
          if (!b_on_a && !a_on_b) continue;
          const int at_i = static_cast<int>(cells[i].links.size());
          const int at_j = static_cast<int>(cells[j].links.size());
          cells[i].links.push_back({fa, static_cast<int>(j), fb, at_j});
          cells[j].links.push_back({fb, static_cast<int>(i), fa, at_i});
        }
      }
    }
  }
}

/// The cells of one region in flat arrays, so that a split allocates nothing once the arrays
/// have grown: cell c's vertices are vertices[v_begin[c] ..], its faces are the global faces
/// f_begin[c] .. f_begin[c] + f_count[c] - 1, face g's loop is loops[face_begin[g] ..
/// + face_size[g]) (indices into the cell's vertices). A split appends its two halves; the
/// entries of a dead cell stay unused until the region is done.
class CellStore {
 public:
  /// Appends a cell; returns its index.
  int add(const WorkPiece& work, const Box& box, std::vector<Link> links) {
    const int id = beginCell(box, std::move(links));
    const geometry::Polyhedron& shape = work.piece.shape;
    vertices_.insert(vertices_.end(), shape.vertices.begin(), shape.vertices.end());
    v_count_.back() = static_cast<int>(shape.vertices.size());
    for (std::size_t f = 0; f < shape.faces.size(); ++f) {
      face_begin_.push_back(static_cast<int>(loops_.size()));
      face_size_.push_back(static_cast<int>(shape.faces[f].size()));
      loops_.insert(loops_.end(), shape.faces[f].begin(), shape.faces[f].end());
      source_.push_back(work.piece.face_sources[f]);
      plane_.push_back(work.planes[f]);
    }
    f_count_.back() = static_cast<int>(shape.faces.size());
    return id;
  }
  /// Appends one half of a split of cell `from` (FlatSplit below or above): new faces (origin
  /// -1) get `plane_id` and a Fictitious source, the others those of their origin face.
  int addHalf(int from, const std::vector<Vec3>& vertices, const std::vector<int>& loops,
              const std::vector<int>& sizes, const std::vector<int>& origin, int plane_id) {
    Box box;
    box.min = Vec3::Constant(std::numeric_limits<double>::infinity());
    box.max = -box.min;
    for (const Vec3& v : vertices) {
      box.min = box.min.cwiseMin(v);
      box.max = box.max.cwiseMax(v);
    }
    const int id = beginCell(box, {});
    vertices_.insert(vertices_.end(), vertices.begin(), vertices.end());
    v_count_.back() = static_cast<int>(vertices.size());
    int at = static_cast<int>(loops_.size());
    loops_.insert(loops_.end(), loops.begin(), loops.end());
    const int first = f_begin_[from];
    for (std::size_t f = 0; f < sizes.size(); ++f) {
      face_begin_.push_back(at);
      face_size_.push_back(sizes[f]);
      at += sizes[f];
      const FaceSource source =
          origin[f] < 0 ? FaceSource{FaceKind::Fictitious, -1} : source_[first + origin[f]];
      const int plane = origin[f] < 0 ? plane_id : plane_[first + origin[f]];
      source_.push_back(source);
      plane_.push_back(plane);
    }
    f_count_.back() = static_cast<int>(sizes.size());
    return id;
  }
  /// Cell c as a flat piece (valid until the next add).
  FlatPieceView view(int c) const {
    return {std::span<const Vec3>(vertices_).subspan(v_begin_[c], v_count_[c]), loops_,
            std::span<const int>(face_begin_).subspan(f_begin_[c], f_count_[c]),
            std::span<const int>(face_size_).subspan(f_begin_[c], f_count_[c])};
  }
  int faceCount(int c) const { return f_count_[c]; }
  /// Index of face f of cell c among all faces of the store (0 .. faceTotal() - 1).
  std::size_t faceIndex(int c, int f) const { return static_cast<std::size_t>(f_begin_[c] + f); }
  std::size_t faceTotal() const { return face_begin_.size(); }
  int planeOf(int c, int f) const { return plane_[f_begin_[c] + f]; }
  const Box& box(int c) const { return boxes_[c]; }
  std::size_t size() const { return v_begin_.size(); }
  std::vector<Link>& links(int c) { return links_[c]; }
  /// Drops a dead cell's links.
  void kill(int c) {
    links_[c].clear();
    spare_links_.push_back(std::move(links_[c]));
  }
  /// Empties the store, keeping its storage (the store of a thread is reused by its
  /// regions: no allocation, no page faults once grown).
  void clear() {
    vertices_.clear();
    loops_.clear();
    face_begin_.clear();
    face_size_.clear();
    plane_.clear();
    source_.clear();
    v_begin_.clear();
    v_count_.clear();
    f_begin_.clear();
    f_count_.clear();
    boxes_.clear();
    for (std::vector<Link>& list : links_) {
      list.clear();
      spare_links_.push_back(std::move(list));
    }
    links_.clear();
  }
  /// The corners of face f of cell c, in loop order, into `out`.
  void faceCorners(int c, int f, std::vector<Vec3>& out) const {
    const int g = f_begin_[c] + f;
    out.clear();
    for (int k = face_begin_[g]; k < face_begin_[g] + face_size_[g]; ++k) {
      out.push_back(vertices_[v_begin_[c] + loops_[k]]);
    }
  }
  /// Newell unit normal of face f of cell c (zero for a degenerate face).
  Vec3 faceNormal(int c, int f) const {
    const int g = f_begin_[c] + f;
    const int n = face_size_[g];
    Vec3 sum = Vec3::Zero();
    for (int k = 0; k < n; ++k) {
      const Vec3& p = vertices_[v_begin_[c] + loops_[face_begin_[g] + k]];
      const Vec3& q = vertices_[v_begin_[c] + loops_[face_begin_[g] + (k + 1 == n ? 0 : k + 1)]];
      sum += p.cross(q);
    }
    const double length = sum.norm();
    return length > 0.0 ? Vec3(sum / length) : Vec3(Vec3::Zero());
  }
  /// The lowest and highest signed distance (m) of the points of face f of cell c from
  /// `plane`.
  std::pair<double, double> faceReach(int c, int f, const Plane& plane) const {
    double low = std::numeric_limits<double>::infinity(), high = -low;
    const int g = f_begin_[c] + f;
    for (int k = face_begin_[g]; k < face_begin_[g] + face_size_[g]; ++k) {
      const double d = plane.distance(vertices_[v_begin_[c] + loops_[k]]);
      low = std::min(low, d);
      high = std::max(high, d);
    }
    return {low, high};
  }
  /// True when face g of cell d is face f of cell c run backwards (the two sides of one cut,
  /// bitwise equal points), as sameLoop in piece_contacts.cpp decides it.
  bool mirrored(int c, int f, int d, int g) const {
    const int fc = f_begin_[c] + f, gd = f_begin_[d] + g;
    const int n = face_size_[fc];
    if (face_size_[gd] != n) return false;
    const auto a = [&](int k) -> const Vec3& {
      return vertices_[v_begin_[c] + loops_[face_begin_[fc] + k]];
    };
    const auto b = [&](int k) -> const Vec3& {
      return vertices_[v_begin_[d] + loops_[face_begin_[gd] + k]];
    };
    int start = n;
    for (int k = 0; k < n; ++k) {
      if (b(k) == a(0)) {
        start = k;
        break;
      }
    }
    if (start == n) return false;
    for (int k = 0; k < n; ++k) {
      if (a(k) != b((start + n - k) % n)) return false;
    }
    return true;
  }
  /// Cell c as a piece; the plane ids of its faces are appended to `planes`.
  Piece piece(int c, std::vector<int>& planes) const {
    Piece piece;
    const auto first = vertices_.begin() + v_begin_[c];
    piece.shape.vertices.assign(first, first + v_count_[c]);
    piece.shape.faces.resize(static_cast<std::size_t>(f_count_[c]));
    piece.face_sources.resize(static_cast<std::size_t>(f_count_[c]));
    for (int f = 0; f < f_count_[c]; ++f) {
      const int g = f_begin_[c] + f;
      const auto loop = loops_.begin() + face_begin_[g];
      piece.shape.faces[f].assign(loop, loop + face_size_[g]);
      piece.face_sources[f] = source_[g];
      planes.push_back(plane_[g]);
    }
    return piece;
  }

 private:
  int beginCell(const Box& box, std::vector<Link> links) {
    const int id = static_cast<int>(v_begin_.size());
    v_begin_.push_back(static_cast<int>(vertices_.size()));
    v_count_.push_back(0);
    f_begin_.push_back(static_cast<int>(face_begin_.size()));
    f_count_.push_back(0);
    boxes_.push_back(box);
    if (links.empty() && !spare_links_.empty()) {
      links = std::move(spare_links_.back());  // cleared, with its capacity
      spare_links_.pop_back();
    }
    links_.push_back(std::move(links));
    return id;
  }
  std::vector<Vec3> vertices_;
  std::vector<int> loops_;
  std::vector<int> face_begin_, face_size_, plane_;
  std::vector<FaceSource> source_;
  std::vector<int> v_begin_, v_count_, f_begin_, f_count_;
  std::vector<Box> boxes_;
  std::vector<std::vector<Link>> links_;
  std::vector<std::vector<Link>> spare_links_;  ///< emptied lists of dead cells, for reuse
};

/// Hands the links of cell c to its two halves `below` and `above` (the split `split`), and
/// updates the linked cells' own links. A face that goes to one half keeps its links; for a
/// face split between the halves, a linked face stays with a half unless the two can share
/// no more than a strip narrower than half the tolerance: the half's part of the face lies
/// on its side of the plane up to the new face's points (cap_low, cap_high: their lowest and
/// highest distance), the linked face on the other side from its lowest (highest) point on,
/// and a band of the plane's distances of height h is a strip of width h / sin(angle between
/// the face's plane and the splitting plane) in the face. Such a strip is never a real
/// contact (area at most half the tolerance times its extent, see realContact), nor is any
/// part of it after further splits, so the link is dropped; the contact tests would only
/// reject it (most such pairs are a face and the part of its former neighbour that the same
/// plane split off: they share the line where the plane crosses them). The two new faces are
/// linked.
void relink(CellStore& store, int c, int below_id, int above_id, const FlatSplit& split,
            const Plane& plane, double tolerance) {
  thread_local std::vector<int> to_below, to_above;
  const std::size_t faces = static_cast<std::size_t>(store.faceCount(c));
  to_below.assign(faces, -1);
  to_above.assign(faces, -1);
  int new_below = -1, new_above = -1;
  for (std::size_t f = 0; f < split.below_origin.size(); ++f) {
    (split.below_origin[f] < 0 ? new_below : to_below[split.below_origin[f]]) = static_cast<int>(f);
  }
  for (std::size_t f = 0; f < split.above_origin.size(); ++f) {
    (split.above_origin[f] < 0 ? new_above : to_above[split.above_origin[f]]) = static_cast<int>(f);
  }
  std::vector<Link>& below = store.links(below_id);
  std::vector<Link>& above = store.links(above_id);
  below.clear();
  above.clear();
  below.push_back({new_below, above_id, new_above, 0});
  above.push_back({new_above, below_id, new_below, 0});
  // The new face's points: the ON vertices and crossing points, the part of the plane both
  // halves reach.
  double cap_low = std::numeric_limits<double>::infinity(), cap_high = -cap_low;
  {
    const std::size_t n = static_cast<std::size_t>(split.below_size.back());
    const std::size_t first = split.below_loops.size() - n;
    for (std::size_t k = first; k < split.below_loops.size(); ++k) {
      const double d = plane.distance(split.below_vertices[split.below_loops[k]]);
      cap_low = std::min(cap_low, d);
      cap_high = std::max(cap_high, d);
    }
  }
  const double margin = 2.0 * tolerance;  // beyond it on the other side: no contact
  // Per split face: half the tolerance times the sine of its angle with the plane (0: not
  // computed yet).
  thread_local std::vector<double> strip;
  strip.assign(faces, 0.0);
  for (const Link& link : store.links(c)) {
    if (link.other_face < 0) continue;  // a link whose face vanished in an earlier split
    const int fb = to_below[link.face], fa = to_above[link.face];
    bool keep_below = fb >= 0, keep_above = fa >= 0;
    if (keep_below && keep_above) {
      double& width = strip[static_cast<std::size_t>(link.face)];
      if (width == 0.0) {
        const Vec3 n = store.faceNormal(c, link.face);
        width = 0.5 * tolerance * n.cross(plane.normal).norm();
        // Parallel (degenerate): only the reach decides.
        if (width == 0.0) width = -std::numeric_limits<double>::infinity();
      }
      const auto [low, high] = store.faceReach(link.other, link.other_face, plane);
      keep_below = low <= margin && !(cap_high - low <= width);
      keep_above = high >= -margin && !(high - cap_low <= width);
    }
    // The linked cell's link back to (c, face) goes to the half kept, or one per half.
    std::vector<Link>& other = store.links(link.other);
    Link& back = other[static_cast<std::size_t>(link.back)];
    if (keep_below) {
      below.push_back({fb, link.other, link.other_face, link.back});
      back.other = below_id;
      back.other_face = fb;
      back.back = static_cast<int>(below.size()) - 1;
      if (keep_above) {
        above.push_back({fa, link.other, link.other_face, static_cast<int>(other.size())});
        other.push_back({link.other_face, above_id, fa, static_cast<int>(above.size()) - 1});
      }
    } else if (keep_above) {
      above.push_back({fa, link.other, link.other_face, link.back});
      back.other = above_id;
      back.other_face = fa;
      back.back = static_cast<int>(above.size()) - 1;
    } else {
      // The face lies in the splitting plane within the tolerance on both halves (a face
      // too small to keep): nothing of it is left to touch.
      back.other_face = -1;
    }
  }
}

/// Splits the region's cells by the full plane of every polygon that meets them. With
/// `track`, follows which faces may touch through the splits (RegionCut::touching).
RegionCut cutRegion(const Region& region, const std::vector<CutPolygon>& polygons,
                    const std::vector<Piece>& domain,
                    const std::vector<std::vector<int>>& domain_planes, bool box_domain,
                    const CutTolerances& tol, const SoundnessTolerances& soundness, bool track) {
  RegionCut out;
  // Cells stay at their index in `store` (dead ones are dropped from `live`); `live` lists
  // the live ones in order, a split cell's halves taking its place.
  thread_local CellStore store;
  store.clear();
  {
    std::vector<Cell> start = regionCells(region, domain, domain_planes, box_domain, tol);
    if (track) initialTouching(start, tol.distance);
    for (Cell& cell : start) store.add(cell.work, cell.box, std::move(cell.links));
  }
  std::vector<int> live(store.size()), next;
  std::iota(live.begin(), live.end(), 0);
  std::vector<Vec3> section, covered, scratch;
  SectionScratch crossed;  // the section's work, reused by the split that follows it
  FlatSplit split;
  for (int p : region.polygons) {
    const CutPolygon& polygon = polygons[p];
    const Box reach = polygon.box.enlarged(tol.distance);
    next.clear();
    for (const int id : live) {
      const Box& box = store.box(id);
      const bool near = (box.min.array() <= reach.max.array()).all() &&
                        (reach.min.array() <= box.max.array()).all() &&
                        !boxMissesPlane(box, polygon.plane, tol.distance);
      if (!near) {
        next.push_back(id);
        continue;
      }
      ++out.piece_tests;
      int on_face = -1;
      const SectionKind kind =
          planeSectionFlat(store.view(id), polygon.plane, tol.distance, section, &on_face, crossed);
      if (kind == SectionKind::OnFace) {
        out.coincident.emplace_back(store.planeOf(id, on_face), polygon.plane_id);
      }
      if (kind != SectionKind::Crossing) {
        next.push_back(id);
        continue;
      }
      // Does the polygon meet the section with area? A section whose box misses the
      // polygon's (grown by the tolerance) does not: no cut, as the tests below would find
      // (their clip would come out empty). Then vertex signs: an edge with the whole section
      // outside (within the tolerance) leaves at most a strip of that width; a section
      // inside every edge is covered whole; only the rest is clipped.
      if (!section.empty()) {
        Vec3 low = section.front(), high = section.front();
        for (const Vec3& x : section) {
          low = low.cwiseMin(x);
          high = high.cwiseMax(x);
        }
        if ((high.array() < reach.min.array()).any() || (low.array() > reach.max.array()).any()) {
          next.push_back(id);
          continue;
        }
      }
      bool apart = false, inside = true;
      for (const Plane& edge : polygon.edges) {
        double low = std::numeric_limits<double>::infinity(), high = -low;
        for (const Vec3& x : section) {
          const double d = edge.distance(x);
          low = std::min(low, d);
          high = std::max(high, d);
        }
        if (high <= tol.distance) {
          apart = true;
          break;
        }
        inside = inside && low >= 0.0;
      }
      // A covered part thinner than the distance tolerance is a graze: no cut. A small but
      // compact one (a corner poking 0.1 mm through a crack) is cut, as the exact cutter
      // cuts it (blocks-exact2's rule for EdgePlanes, thinnerThan).
      bool cut = false;
      if (!apart && inside) {
        cut = !thinnerThan(section, tol.distance);
      } else if (!apart) {
        overlapInto(section, polygon, covered, scratch);
        cut = covered.size() >= 3 && !thinnerThan(covered, tol.distance);
      }
      if (!cut || !splitFlat(store.view(id), crossed, split)) {
        next.push_back(id);
        continue;
      }
      ++out.splits;
      const int below_id = store.addHalf(id, split.below_vertices, split.below_loops,
                                         split.below_size, split.below_origin, polygon.plane_id);
      const int above_id = store.addHalf(id, split.above_vertices, split.above_loops,
                                         split.above_size, split.above_origin, polygon.plane_id);
      if (track) relink(store, id, below_id, above_id, split, polygon.plane, tol.distance);
      store.kill(id);
      next.push_back(below_id);
      next.push_back(above_id);
    }
    std::swap(live, next);
  }
  std::vector<int> local(store.size(), -1);
  out.pieces.reserve(live.size());
  out.facts.reserve(live.size());
  for (std::size_t k = 0; k < live.size(); ++k) {
    local[live[k]] = static_cast<int>(k);
    out.pieces.push_back(store.piece(live[k], out.planes));
    const Piece& piece = out.pieces.back();
    out.facts.push_back({geometry::massProperties(piece.shape), geometry::bounds(piece.shape),
                         hasCloseVertices(piece, soundness)});
  }
  if (track) {
    // The contact table straight from the flat store (sequential, still in cache), faces in
    // first-use order of the pairs: slots and sizes first, then the table sized once and
    // filled.
    constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> slot(store.faceTotal(), kNone);
    struct Use {
      int cell, piece, face;
      std::uint32_t begin;
    };
    std::vector<Use> uses;
    std::uint32_t corners = 0;
    std::vector<Vec3> corners_a, corners_b;
    const auto slotOf = [&](int cell, int k, int face) {
      std::uint32_t& at = slot[store.faceIndex(cell, face)];
      if (at == kNone) {
        at = static_cast<std::uint32_t>(uses.size());
        uses.push_back({cell, k, face, corners});
        corners += static_cast<std::uint32_t>(store.view(cell).face_size[face]);
      }
      return at;
    };
    for (std::size_t k = 0; k < live.size(); ++k) {
      for (const Link& link : store.links(live[k])) {
        if (link.other_face < 0) continue;
        const int other = local[link.other];
        if (other <= static_cast<int>(k)) continue;
        if (store.planeOf(live[k], link.face) == store.planeOf(link.other, link.other_face) &&
            store.mirrored(live[k], link.face, link.other, link.other_face)) {
          // The two sides of one cut: their contact is decided without a table entry.
          out.twins.push_back({static_cast<int>(k), link.face, other, link.other_face});
          store.faceCorners(live[k], link.face, corners_a);
          store.faceCorners(link.other, link.other_face, corners_b);
          if (const std::optional<double> area =
                  mirroredContactArea(corners_a, corners_b, tol.distance, tol.area)) {
            out.mirrored.push_back({static_cast<int>(k), link.face, other, link.other_face, *area});
          }
          continue;
        }
        const std::uint32_t a = slotOf(live[k], static_cast<int>(k), link.face);
        const std::uint32_t b = slotOf(link.other, other, link.other_face);
        out.pairs.emplace_back(a, b);
      }
    }
    // The faces in the region's kd faces, in piece and face order (counted, then the table
    // sized once and filled).
    std::vector<std::pair<int, int>> kd_faces;  // (k, face)
    std::uint32_t kd_corners = 0;
    for (std::size_t k = 0; k < live.size(); ++k) {
      for (int f = 0; f < store.faceCount(live[k]); ++f) {
        const int plane = store.planeOf(live[k], f);
        if (std::find(region.face_plane.begin(), region.face_plane.end(), plane) ==
            region.face_plane.end()) {
          continue;
        }
        kd_faces.emplace_back(static_cast<int>(k), f);
        kd_corners += static_cast<std::uint32_t>(store.view(live[k]).face_size[f]);
        out.kd_planes.push_back(plane);
      }
    }
    out.kd.faces.resize(kd_faces.size());
    out.kd.points.resize(kd_corners);
    out.kd.inward.resize(kd_corners);
    kd_corners = 0;
    for (std::size_t u = 0; u < kd_faces.size(); ++u) {
      const auto [k, f] = kd_faces[u];
      const FlatPieceView view = store.view(live[static_cast<std::size_t>(k)]);
      const auto loop = view.loops.subspan(static_cast<std::size_t>(view.face_begin[f]),
                                           static_cast<std::size_t>(view.face_size[f]));
      out.kd.set(static_cast<std::uint32_t>(u), k, f, kd_corners, view.vertices, loop);
      kd_corners += static_cast<std::uint32_t>(loop.size());
    }
    out.faces.faces.resize(uses.size());
    out.faces.points.resize(corners);
    out.faces.inward.resize(corners);
    for (std::size_t u = 0; u < uses.size(); ++u) {
      const FlatPieceView view = store.view(uses[u].cell);
      const auto f = static_cast<std::size_t>(uses[u].face);
      out.faces.set(static_cast<std::uint32_t>(u), uses[u].piece, uses[u].face, uses[u].begin,
                    view.vertices,
                    view.loops.subspan(static_cast<std::size_t>(view.face_begin[f]),
                                       static_cast<std::size_t>(view.face_size[f])));
    }
  }
  return out;
}

/// The vertices of face f of a piece.
void faceLoop(const Piece& piece, int f, std::vector<Vec3>& out) {
  out.clear();
  for (int v : piece.shape.faces[f]) out.push_back(piece.shape.vertices[v]);
}

/// Levels of the axis-aligned polygon planes and domain face planes along each axis: the
/// kd split avoids them (splitRegions).
std::array<std::vector<double>, 3> axisPlaneLevels(const std::vector<CutPolygon>& polygons,
                                                   const std::vector<Piece>& domain) {
  std::array<std::vector<double>, 3> avoid;
  for (const CutPolygon& polygon : polygons) {
    for (int a = 0; a < 3; ++a) {
      if (std::abs(polygon.plane.normal[a]) >= 1.0 - 1e-12) {
        avoid[a].push_back(polygon.plane.offset * (polygon.plane.normal[a] > 0 ? 1.0 : -1.0));
      }
    }
  }
  for (const Piece& piece : domain) {
    for (std::size_t f = 0; f < piece.shape.faces.size(); ++f) {
      const Vec3 n = geometry::faceNormal(piece.shape, static_cast<int>(f));
      for (int a = 0; a < 3; ++a) {
        if (std::abs(n[a]) >= 1.0 - 1e-12) {
          avoid[a].push_back(piece.shape.vertices[piece.shape.faces[f][0]][a]);
        }
      }
    }
  }
  return avoid;
}

/// The regions' kd faces in one table, in plane order (ties in piece and face order): the
/// table findContactsByPlane would build from the pieces.
ContactFaces kdFaceTable(const std::vector<RegionCut>& cuts, const std::vector<int>& piece_first,
                         UnionFind& plane_ids) {
  ContactFaces kd;
  std::vector<int> kd_root;
  for (std::size_t r = 0; r < cuts.size(); ++r) {
    kd.append(cuts[r].kd, piece_first[r]);
    for (int id : cuts[r].kd_planes) kd_root.push_back(plane_ids.find(id));
  }
  {
    std::vector<std::uint32_t> order(kd.faces.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return kd_root[a] < kd_root[b]; });
    std::vector<ContactFaces::Face> sorted;
    sorted.reserve(order.size());
    for (std::uint32_t k : order) sorted.push_back(kd.faces[k]);
    kd.faces = std::move(sorted);
    for (std::size_t b = 0; b < order.size();) {
      std::size_t e = b + 1;
      while (e < order.size() && kd_root[order[e]] == kd_root[order[b]]) ++e;
      if (e - b >= 2) kd.groups.emplace_back(b, e);
      b = e;
    }
  }
  return kd;
}

/// Contacts inside regions and across them, with their sources, in one list in
/// (piece_a, piece_b, face_a, face_b) order.
void mergeContacts(const std::vector<PieceContact>& inside,
                   const std::vector<FaceSource>& inside_sources,
                   const std::vector<PieceContact>& across,
                   const std::vector<FaceSource>& across_sources,
                   std::vector<PieceContact>& contacts, std::vector<FaceSource>& sources) {
  // One list in (piece_a, piece_b, face_a, face_b) order, as findContactsByPlane sorts:
  // both lists are in that order already (and share no face pair: a contact inside a region
  // joins pieces of one region, one across regions pieces of two), so they are merged.
  const auto before = [](const PieceContact& x, const PieceContact& y) {
    return std::tie(x.piece_a, x.piece_b, x.face_a, x.face_b) <
           std::tie(y.piece_a, y.piece_b, y.face_a, y.face_b);
  };
  contacts.reserve(inside.size() + across.size());
  sources.reserve(inside.size() + across.size());
  std::size_t i = 0, j = 0;
  while (i < inside.size() || j < across.size()) {
    if (j == across.size() || (i < inside.size() && !before(across[j], inside[i]))) {
      contacts.push_back(inside[i]);
      sources.push_back(inside_sources[i++]);
    } else {
      contacts.push_back(across[j]);
      sources.push_back(across_sources[j++]);
    }
  }
}

/// The contacts of tracked regions: inside a region the pairs each region tracked; across
/// regions the faces in the kd planes only (two pieces of different regions can share area
/// only in the plane between them). `planes` is overwritten (kd plane ids, else -1).
std::vector<PieceContact> trackedContacts(
    const std::vector<ContactTablePart>& tracked, const std::vector<Region>& regions,
    const std::vector<RegionCut>& cuts, const std::vector<int>& piece_first,
    std::size_t piece_count, UnionFind& plane_ids, std::vector<int>& planes,
    const CutTolerances& tol, const ContactDecision& decide, std::vector<FaceSource>& sources) {
  std::vector<PieceContact> contacts;
  // Inside a region: the tracked pairs. Across regions: faces in the kd planes only (two
  // pieces of different regions can share area only in the plane between them).
  std::vector<FaceSource> inside_sources, across_sources;
  const std::vector<PieceContact> inside =
      decideTableContacts(tracked, piece_count, tol.distance, tol.area, decide, &inside_sources);
  std::vector<char> kd_plane(plane_ids.size(), 0);
  for (const Region& region : regions) {
    for (int id : region.face_plane) {
      if (id >= 0) kd_plane[plane_ids.find(id)] = 1;
    }
  }
  // In place (no copy): the contacts inside regions are decided already, and the faces
  // searched now keep their (kd plane) ids, which is all `decide` reads of them.
  for (int& id : planes) id = kd_plane[id] ? id : -1;
  const ContactFaces kd = kdFaceTable(cuts, piece_first, plane_ids);
  const std::vector<PieceContact> across =
      decidePlaneContacts(kd, piece_count, tol.distance, tol.area, decide, &across_sources);
  mergeContacts(inside, inside_sources, across, across_sources, contacts, sources);
  return contacts;
}

BlockModel cutFullPlanes(const CutInput& input, const FastCutOptions& options,
                         const CutTolerances& tol, FastCutReport* report) {
  FastCutReport counters;
  const auto start = std::chrono::steady_clock::now();
  CutStart setup = startCut(input, tol);
  UnionFind& plane_ids = setup.plane_ids;
  const std::vector<Piece>& domain = setup.domain;
  const std::vector<std::vector<int>>& domain_planes = setup.domain_planes;
  std::vector<CutPolygon>& polygons = setup.polygons;
  const bool box_domain = domain.size() == 1 && domain[0].shape.faces.size() == 6 &&
                          geometry::bounds(domain[0].shape).min == input.domain_box.min &&
                          geometry::bounds(domain[0].shape).max == input.domain_box.max &&
                          domain[0].shape.vertices.size() == 8;
  const std::vector<DiscGroup> groups = groupPolygons(polygons, tol.distance);
  counters.cutting_polygons = static_cast<int>(polygons.size());

  // Regions.
  const std::array<std::vector<double>, 3> avoid = axisPlaneLevels(polygons, domain);
  Region root;
  root.box = input.domain_box;
  for (std::size_t p = 0; p < polygons.size(); ++p) {
    if (polygonMayMeetBox(polygons[p], root.box, tol.distance)) {
      root.polygons.push_back(static_cast<int>(p));
    }
  }
  std::vector<Region> regions;
  splitRegions(polygons, avoid, input.domain_box.size().maxCoeff() / 64.0,
               std::max(1, options.max_discs_per_region), tol.distance, plane_ids, std::move(root),
               regions);
  counters.regions = static_cast<int>(regions.size());

  const SoundnessTolerances soundness = soundnessTolerances(input.domain_box);
  std::vector<RegionCut> cuts(regions.size());
  tbb::parallel_for(std::size_t{0}, regions.size(), [&](std::size_t r) {
    throwIfInterrupted("the block cut (fast cutter)");
    cuts[r] = cutRegion(regions[r], polygons, domain, domain_planes, box_domain, tol, soundness,
                        options.track_contacts);
  });
  std::vector<Piece> pieces;
  std::vector<int> planes;  // plane id of every face, in piece and face order (first_face)
  // Tracked: per region, the faces that may touch and the pairs of them (each region's
  // table stays where the region built it; the contact decisions read them in place).
  std::vector<ContactTablePart> tracked;
  std::vector<std::array<int, 4>> twins;  // (piece, face, piece, face), global piece indices
  {
    std::size_t piece_total = 0, face_total = 0;
    for (const RegionCut& cut : cuts) {
      piece_total += cut.pieces.size();
      face_total += cut.planes.size();
    }
    pieces.reserve(piece_total);
    planes.reserve(face_total);
  }
  std::vector<int> piece_first;   // per region: the global index of its first piece
  std::vector<PieceFacts> facts;  // per piece, for the assembly
  for (RegionCut& cut : cuts) {
    piece_first.push_back(static_cast<int>(pieces.size()));
    counters.piece_tests += cut.piece_tests;
    counters.splits += cut.splits;
    for (const auto& [a, b] : cut.coincident) plane_ids.unite(a, b);
    if (!cut.pairs.empty() || !cut.mirrored.empty()) {
      tracked.push_back({&cut.faces, static_cast<int>(pieces.size()), cut.pairs, cut.mirrored});
    }
    const int first = static_cast<int>(pieces.size());
    for (const auto& [i, f, j, g] : cut.twins) twins.push_back({first + i, f, first + j, g});
    for (Piece& piece : cut.pieces) pieces.push_back(std::move(piece));
    planes.insert(planes.end(), cut.planes.begin(), cut.planes.end());
    facts.insert(facts.end(), cut.facts.begin(), cut.facts.end());
  }
  counters.pieces = static_cast<int>(pieces.size());
  for (int& id : planes) id = plane_ids.find(id);
  // Face f of piece i is face first_face[i] + f of the flat per-face tables.
  std::vector<std::size_t> first_face(pieces.size() + 1, 0);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    first_face[i + 1] = first_face[i] + pieces[i].shape.faces.size();
  }
  const auto planeOf = [&](int piece, int face) {
    return planes[first_face[piece] + static_cast<std::size_t>(face)];
  };
  counters.cut_seconds = secondsSince(start);

  // Coverage of every face in a disc plane (a plane whose root is a group's).
  const auto assemble_start = std::chrono::steady_clock::now();
  std::vector<int> group_of_root(plane_ids.size(), -1);  // by plane root id
  for (std::size_t g = 0; g < groups.size(); ++g) {
    int& slot = group_of_root[plane_ids.find(groups[g].plane_id)];
    if (slot < 0) slot = static_cast<int>(g);  // the first group of a root, as emplace kept
  }
  const auto groupOf = [&](int root) { return root < 0 ? -1 : group_of_root[root]; };
  // cover_table / face_source [first_face[i] + f]: the coverage and source of face f of
  // piece i (flat copies for the contact decisions: no cache miss per piece there).
  std::vector<Cover> cover_table(first_face.back(), Cover::None);
  std::vector<FaceSource> face_source(first_face.back());
  const auto coverOf = [&](int piece, int face) -> Cover& {
    return cover_table[first_face[piece] + static_cast<std::size_t>(face)];
  };
  // The second face of a pair of twins (the two sides of one cut) is not covered itself: it
  // takes the coverage of the first, the same loop run backwards (a pair whose first face is
  // itself a second, possible only for overlapping cells, is covered on both sides).
  std::vector<char> second_twin(first_face.back(), 0);
  std::erase_if(twins, [&](const std::array<int, 4>& t) {
    if (second_twin[first_face[t[0]] + static_cast<std::size_t>(t[1])]) return true;
    second_twin[first_face[t[2]] + static_cast<std::size_t>(t[3])] = 1;
    return false;
  });
  tbb::parallel_for(std::size_t{0}, pieces.size(), [&](std::size_t i) {
    Piece& piece = pieces[i];
    Cover* cover = &cover_table[first_face[i]];
    const char* second = &second_twin[first_face[i]];
    thread_local std::vector<Vec3> loop;
    for (std::size_t f = 0; f < piece.shape.faces.size(); ++f) {
      if (piece.face_sources[f].kind != FaceKind::Fictitious || second[f]) continue;
      const int g = groupOf(planeOf(static_cast<int>(i), static_cast<int>(f)));
      if (g < 0) continue;
      faceLoop(piece, static_cast<int>(f), loop);
      int disc = -1;
      cover[f] = coverage(loop, groups[g], polygons, tol, &disc);
      if (cover[f] == Cover::Whole) piece.face_sources[f] = {FaceKind::Disc, disc};
    }
    std::copy(piece.face_sources.begin(), piece.face_sources.end(),
              face_source.begin() + static_cast<std::ptrdiff_t>(first_face[i]));
  });
  for (const auto& [i, f, j, g] : twins) {
    const std::size_t from = first_face[i] + static_cast<std::size_t>(f);
    const std::size_t to = first_face[j] + static_cast<std::size_t>(g);
    if (pieces[j].face_sources[g].kind != FaceKind::Fictitious) continue;
    cover_table[to] = cover_table[from];
    if (cover_table[to] == Cover::Whole) {
      pieces[j].face_sources[g] = face_source[to] = face_source[from];
    }
  }

  counters.coverage_seconds = secondsSince(assemble_start);
  const auto contact_start = std::chrono::steady_clock::now();
  // Contacts; each one glues its pieces unless the discs wholly cover the shared part.
  // Pairs of pieces glued already are skipped (findContactsByPlane with a decision).
  const ContactDecision decide = [&](const PieceContact& c, bool same_loop) -> FaceSource {
    const FaceSource& a = face_source[first_face[c.piece_a] + c.face_a];
    const FaceSource& b = face_source[first_face[c.piece_b] + c.face_b];
    const Cover ca = coverOf(c.piece_a, c.face_a);
    const Cover cb = coverOf(c.piece_b, c.face_b);
    const int g = groupOf(planeOf(c.piece_a, c.face_a));
    if (g < 0 || a.kind == FaceKind::Boundary || a.kind == FaceKind::Structure ||
        b.kind == FaceKind::Boundary || b.kind == FaceKind::Structure) {
      // Not a disc plane: the face labels decide.
      return a.kind == FaceKind::Fictitious ? b : a;
    }
    if (ca == Cover::Whole || cb == Cover::Whole) return ca == Cover::Whole ? a : b;
    if (ca == Cover::None || cb == Cover::None) return {FaceKind::Fictitious, -1};
    // Both partly covered, and the two sides of one cut: the shared part is the face itself,
    // partly covered, so the pieces glue.
    if (same_loop) return {FaceKind::Fictitious, -1};
    // Both partly covered: the coverage of their overlap decides.
    thread_local std::vector<Vec3> la, lb, shared;
    faceLoop(pieces[c.piece_a], c.face_a, la);
    faceLoop(pieces[c.piece_b], c.face_b, lb);
    const Vec3 normal = geometry::faceNormal(pieces[c.piece_a].shape, c.face_a);
    faceOverlap(la, lb, normal, shared);
    int disc = -1;
    const bool whole =
        shared.size() >= 3 && coverage(shared, groups[g], polygons, tol, &disc) == Cover::Whole;
    return whole ? FaceSource{FaceKind::Disc, disc} : FaceSource{FaceKind::Fictitious, -1};
  };
  std::vector<FaceSource> sources;
  std::vector<PieceContact> contacts;
  if (!options.track_contacts) {
    contacts = findContactsByPlane(pieces, planes, tol.distance, tol.area, decide, &sources);
  } else {
    contacts = trackedContacts(tracked, regions, cuts, piece_first, pieces.size(), plane_ids,
                               planes, tol, decide, sources);
  }
  counters.contact_seconds = secondsSince(contact_start);
  tracked.clear();
  cuts.clear();
  AssemblyReport assembly;
  BlockModel model =
      assembleBlocks(std::move(pieces), contacts, input, tol, &assembly, &sources, &facts);
  counters.inconsistent_contacts = assembly.inconsistent_contacts;
  counters.soundness = assembly.soundness;
  counters.pieces -= assembly.soundness.folded_pieces;
  counters.assemble_seconds = secondsSince(assemble_start);
  if (report) *report = counters;
  return model;
}

}  // namespace

BlockModel cutFast(const CutInput& input, const FastCutOptions& options, FastCutReport* report) {
  if (input.domain_pieces.empty()) throw std::invalid_argument("cutFast: no domain piece");
  if (input.network == nullptr) throw std::invalid_argument("cutFast: no fracture network");
  if (input.disc_segments < 3) throw std::invalid_argument("cutFast: disc_segments < 3");
  const CutTolerances tol = cutTolerances(input.domain_box);
  checkStructuresOutsideRock(input, tol);
  if (options.strategy == FastStrategy::EdgePlanes) return cutEdgePlanes(input, tol, report);
  return cutFullPlanes(input, options, tol, report);
}

BlockModel cutFast(const CutInput& input, FastCutReport* report) {
  return cutFast(input, FastCutOptions{}, report);
}

}  // namespace rockmass::blocks
