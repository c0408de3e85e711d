// Cutting polygons, work-piece splits, the cut's start, disc groups and their coverage of a
// face: the parts of the fast cutter both strategies share (blocks/fast_cut_parts.h).
#include "blocks/fast_cut_parts.h"

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
#include "blocks/union_find.h"
#include "geometry/disc.h"
#include "geometry/interrupt.h"

namespace rockmass::blocks::fastcut {

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

/// True when every point lies inside the convex polygon, within `tolerance` (m).
bool insidePolygon(const std::vector<Vec3>& points, const CutPolygon& polygon, double tolerance) {
  for (const Plane& edge : polygon.edges) {
    for (const Vec3& p : points) {
      if (edge.distance(p) < -tolerance) return false;
    }
  }
  return true;
}

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

BlockModel assembleCut(std::vector<Piece> pieces, const std::vector<PieceContact>& contacts,
                       const CutInput& input, const CutTolerances& tol, FastCutReport& counters,
                       std::chrono::steady_clock::time_point assemble_start, FastCutReport* report,
                       const std::vector<FaceSource>* sources,
                       const std::vector<PieceFacts>* facts) {
  AssemblyReport assembly;
  BlockModel model =
      assembleBlocks(std::move(pieces), contacts, input, tol, &assembly, sources, facts);
  counters.inconsistent_contacts = assembly.inconsistent_contacts;
  counters.soundness = assembly.soundness;
  counters.pieces -= assembly.soundness.folded_pieces;
  counters.assemble_seconds = secondsSince(assemble_start);
  if (report) *report = counters;
  return model;
}

}  // namespace rockmass::blocks::fastcut
