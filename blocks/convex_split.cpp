#include "blocks/convex_split.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <span>

namespace rockmass::blocks {
namespace {

/// -1, 0 or +1: the side of the plane a vertex is on, ON within the tolerance (into
/// `sides`), and the signed distances.
void classify(std::span<const Vec3> points, const Plane& plane, double tolerance,
              std::vector<std::int8_t>& sides, std::vector<double>& distances) {
  sides.resize(points.size());
  distances.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double s = plane.distance(points[i]);
    distances[i] = s;
    sides[i] = s > tolerance ? 1 : (s < -tolerance ? -1 : 0);
  }
}

/// A number that grows with atan2(y, x) over [-pi, pi] (the same order, signed zeros
/// included, without an arc tangent): y / (|x| + |y|) for x >= 0, 2 - that for x < 0 and y
/// positive, -2 - that for x < 0 and y negative.
double pseudoAngle(double y, double x) {
  const double sum = std::abs(x) + std::abs(y);
  if (sum == 0.0) return 0.0;
  const double r = y / sum;
  if (x >= 0.0) return r;
  return std::signbit(y) ? -2.0 - r : 2.0 - r;
}

/// Order of `points` (a convex polygon's vertices in any order, all in a plane with unit
/// normal `normal`) counter-clockwise about `normal`: by angle about their mean, which lies
/// inside the polygon, so points on a common edge still sort along it (starting from the
/// direction -u, as atan2 does). Into `order` (a scratch buffer reused by the caller's thread).
void counterClockwise(const std::vector<Vec3>& points, const Vec3& normal,
                      std::vector<int>& order) {
  Vec3 center = Vec3::Zero();
  for (const Vec3& p : points) center += p;
  center /= static_cast<double>(points.size());
  const Vec3 u = normal.unitOrthogonal();
  const Vec3 w = normal.cross(u);
  thread_local std::vector<double> angle;
  angle.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3 d = points[i] - center;
    angle[i] = pseudoAngle(d.dot(w), d.dot(u));
  }
  // A stable insertion sort: sections have a handful of points, and std::stable_sort would
  // allocate a buffer on every call (the same order: a stable sort's result is unique).
  order.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int k = static_cast<int>(i);
    std::size_t j = i;
    while (j > 0 && angle[k] < angle[order[j - 1]]) {
      order[j] = order[j - 1];
      --j;
    }
    order[j] = k;
  }
}

/// The point where edge (a, b) crosses the plane, from the signed distances of its ends
/// (of opposite signs). Computed from the lexicographically smaller end, so that the two
/// pieces sharing the edge get the very same point.
Vec3 crossingPoint(const Vec3& a, const Vec3& b, double sa, double sb) {
  const bool swap = std::lexicographical_compare(b.data(), b.data() + 3, a.data(), a.data() + 3);
  const Vec3& p = swap ? b : a;
  const Vec3& q = swap ? a : b;
  const double sp = swap ? sb : sa;
  const double sq = swap ? sa : sb;
  return p + (sp / (sp - sq)) * (q - p);
}

/// Face access of a Polyhedron, for the shared cores below.
struct PolyhedronFaces {
  const geometry::Polyhedron& shape;
  std::size_t count() const { return shape.faces.size(); }
  std::span<const int> face(std::size_t f) const { return shape.faces[f]; }
};

/// Face access of a flat piece.
struct FlatFaces {
  const FlatPieceView& piece;
  std::size_t count() const { return piece.face_begin.size(); }
  std::span<const int> face(std::size_t f) const {
    return piece.loops.subspan(static_cast<std::size_t>(piece.face_begin[f]),
                               static_cast<std::size_t>(piece.face_size[f]));
  }
};

/// The plane's crossing of a convex piece (into `scratch`): every vertex classified, then, when
/// vertices lie on both sides, the section's points (ON vertices in index order, then one
/// crossing point per cut edge in the order the faces first meet the edges) and their
/// counter-clockwise order. True when the plane crosses (vertices on both sides).
template <class Faces>
bool crossCore(std::span<const Vec3> vertices, const Faces& faces, const Plane& plane,
               double tolerance, SectionScratch& scratch) {
  classify(vertices, plane, tolerance, scratch.side, scratch.distance);
  const std::vector<std::int8_t>& side = scratch.side;
  const std::vector<double>& s = scratch.distance;
  const bool has_below = std::find(side.begin(), side.end(), -1) != side.end();
  const bool has_above = std::find(side.begin(), side.end(), 1) != side.end();
  scratch.points.clear();
  scratch.edges.clear();
  if (!has_below || !has_above) return false;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (side[i] == 0) scratch.points.push_back(vertices[i]);
  }
  scratch.on_count = static_cast<int>(scratch.points.size());
  for (std::size_t f = 0; f < faces.count(); ++f) {
    const std::span<const int> face = faces.face(f);
    for (std::size_t k = 0; k < face.size(); ++k) {
      const int a = face[k];
      const int b = face[(k + 1) % face.size()];
      if (side[a] * side[b] >= 0) continue;
      const std::pair<int, int> edge{std::min(a, b), std::max(a, b)};
      // Each cut edge is met twice (once per face): its point is made at the first meeting.
      if (std::find(scratch.edges.begin(), scratch.edges.end(), edge) != scratch.edges.end()) {
        continue;
      }
      scratch.edges.push_back(edge);
      scratch.points.push_back(crossingPoint(vertices[edge.first], vertices[edge.second],
                                             s[edge.first], s[edge.second]));
    }
  }
  counterClockwise(scratch.points, plane.normal, scratch.order);
  return true;
}

/// The split shared by splitPiece and splitFlat, from crossCore's `scratch` of the same piece
/// and plane: both halves into `out` (vertices, loops in face order with the new face last,
/// origins). False when the section has fewer than 3 points.
template <class Faces>
bool splitCore(std::span<const Vec3> vertices, const Faces& faces, const SectionScratch& scratch,
               FlatSplit& out) {
  const std::vector<std::int8_t>& side = scratch.side;
  std::vector<Vec3>& below = out.below_vertices;
  std::vector<Vec3>& above = out.above_vertices;
  below.clear();
  above.clear();
  out.below_loops.clear();
  out.above_loops.clear();
  out.below_size.clear();
  out.above_size.clear();
  out.below_origin.clear();
  out.above_origin.clear();
  thread_local std::vector<int> below_index, above_index;
  below_index.assign(vertices.size(), -1);
  above_index.assign(vertices.size(), -1);
  // (below, above) index of each section point: ON vertices, then crossing points, which
  // follow the kept vertices in both halves in the order crossCore made them.
  thread_local std::vector<std::pair<int, int>> cap_index;
  cap_index.clear();
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (side[i] <= 0) {
      below_index[i] = static_cast<int>(below.size());
      below.push_back(vertices[i]);
    }
    if (side[i] >= 0) {
      above_index[i] = static_cast<int>(above.size());
      above.push_back(vertices[i]);
    }
    if (side[i] == 0) cap_index.emplace_back(below_index[i], above_index[i]);
  }
  const int below_kept = static_cast<int>(below.size());
  const int above_kept = static_cast<int>(above.size());
  const std::size_t crossings = scratch.edges.size();
  for (std::size_t c = 0; c < crossings; ++c) {
    const Vec3& p = scratch.points[static_cast<std::size_t>(scratch.on_count) + c];
    below.push_back(p);
    above.push_back(p);
    cap_index.emplace_back(below_kept + static_cast<int>(c), above_kept + static_cast<int>(c));
  }
  const auto crossing = [&](int a, int b) {
    const std::pair<int, int> edge{std::min(a, b), std::max(a, b)};
    return static_cast<int>(std::find(scratch.edges.begin(), scratch.edges.end(), edge) -
                            scratch.edges.begin());
  };

  for (std::size_t f = 0; f < faces.count(); ++f) {
    const std::span<const int> face = faces.face(f);
    const std::size_t below_start = out.below_loops.size();
    const std::size_t above_start = out.above_loops.size();
    bool below_off_plane = false, above_off_plane = false;
    for (std::size_t k = 0; k < face.size(); ++k) {
      const int a = face[k];
      const int b = face[(k + 1) % face.size()];
      if (side[a] <= 0) out.below_loops.push_back(below_index[a]);
      if (side[a] >= 0) out.above_loops.push_back(above_index[a]);
      below_off_plane |= side[a] < 0;
      above_off_plane |= side[a] > 0;
      if (side[a] * side[b] < 0) {
        const int c = crossing(a, b);
        out.below_loops.push_back(below_kept + c);
        out.above_loops.push_back(above_kept + c);
      }
    }
    // A loop with no vertex off the plane lies in the new face: the cap replaces it.
    const std::size_t below_count = out.below_loops.size() - below_start;
    const std::size_t above_count = out.above_loops.size() - above_start;
    if (below_count >= 3 && below_off_plane) {
      out.below_size.push_back(static_cast<int>(below_count));
      out.below_origin.push_back(static_cast<int>(f));
    } else {
      out.below_loops.resize(below_start);
    }
    if (above_count >= 3 && above_off_plane) {
      out.above_size.push_back(static_cast<int>(above_count));
      out.above_origin.push_back(static_cast<int>(f));
    } else {
      out.above_loops.resize(above_start);
    }
  }
  if (scratch.points.size() < 3) return false;
  // The cap: counter-clockwise about +n seen from outside `below`; `above` gets the reverse
  // loop starting at the same vertex, so both fan it into the same triangles.
  const std::vector<int>& order = scratch.order;
  for (int k : order) out.below_loops.push_back(cap_index[k].first);
  out.above_loops.push_back(cap_index[order[0]].second);
  for (std::size_t k = order.size() - 1; k >= 1; --k) {
    out.above_loops.push_back(cap_index[order[k]].second);
  }
  out.below_size.push_back(static_cast<int>(order.size()));
  out.above_size.push_back(static_cast<int>(order.size()));
  out.below_origin.push_back(-1);
  out.above_origin.push_back(-1);
  return true;
}

/// One half of a flat split as a Piece.
void halfPiece(const std::vector<Vec3>& vertices, const std::vector<int>& loops,
               const std::vector<int>& sizes, const std::vector<int>& origin, const Piece& input,
               FaceSource cap, Piece& out) {
  out.shape.vertices.assign(vertices.begin(), vertices.end());
  out.shape.faces.resize(sizes.size());
  out.face_sources.resize(sizes.size());
  std::size_t at = 0;
  for (std::size_t f = 0; f < sizes.size(); ++f) {
    const auto first = loops.begin() + static_cast<std::ptrdiff_t>(at);
    out.shape.faces[f].assign(first, first + sizes[f]);
    at += static_cast<std::size_t>(sizes[f]);
    out.face_sources[f] = origin[f] < 0 ? cap : input.face_sources[origin[f]];
  }
}

/// The section shared by planeSection and planeSectionFlat (crossCore into `scratch`).
template <class Faces>
SectionKind sectionCore(std::span<const Vec3> vertices, const Faces& faces, const Plane& plane,
                        double tolerance, std::vector<Vec3>& polygon, int* face_out,
                        SectionScratch& scratch) {
  polygon.clear();
  if (crossCore(vertices, faces, plane, tolerance, scratch)) {
    polygon.reserve(scratch.order.size());
    for (int k : scratch.order) polygon.push_back(scratch.points[k]);
    return SectionKind::Crossing;
  }
  const std::vector<std::int8_t>& side = scratch.side;
  for (std::size_t f = 0; f < faces.count(); ++f) {
    const std::span<const int> face = faces.face(f);
    const bool on = std::all_of(face.begin(), face.end(), [&](int v) { return side[v] == 0; });
    if (!on) continue;
    *face_out = static_cast<int>(f);
    for (int v : face) polygon.push_back(vertices[v]);
    // The face is counter-clockwise about its outward normal, which may be -n (Newell).
    Vec3 n = Vec3::Zero();
    for (std::size_t k = 0; k < face.size(); ++k) {
      n += vertices[face[k]].cross(vertices[face[(k + 1) % face.size()]]);
    }
    const double length = n.norm();
    const Vec3 normal = length > 0.0 ? Vec3(n / length) : Vec3(Vec3::Zero());
    if (normal.dot(plane.normal) < 0.0) std::reverse(polygon.begin(), polygon.end());
    return SectionKind::OnFace;
  }
  return SectionKind::None;
}

}  // namespace

std::optional<SplitPieces> splitPiece(const Piece& piece, const Plane& plane, double tolerance,
                                      FaceSource cap) {
  thread_local SectionScratch scratch;
  thread_local FlatSplit flat;
  const PolyhedronFaces faces{piece.shape};
  if (!crossCore(piece.shape.vertices, faces, plane, tolerance, scratch) ||
      !splitCore(piece.shape.vertices, faces, scratch, flat)) {
    return std::nullopt;
  }
  SplitPieces out;
  halfPiece(flat.below_vertices, flat.below_loops, flat.below_size, flat.below_origin, piece, cap,
            out.below);
  halfPiece(flat.above_vertices, flat.above_loops, flat.above_size, flat.above_origin, piece, cap,
            out.above);
  out.below_origin = flat.below_origin;
  out.above_origin = flat.above_origin;
  return out;
}

bool splitFlat(const FlatPieceView& piece, const Plane& plane, double tolerance, FlatSplit& out) {
  thread_local SectionScratch scratch;
  return crossCore(piece.vertices, FlatFaces{piece}, plane, tolerance, scratch) &&
         splitCore(piece.vertices, FlatFaces{piece}, scratch, out);
}

bool splitFlat(const FlatPieceView& piece, const SectionScratch& scratch, FlatSplit& out) {
  return splitCore(piece.vertices, FlatFaces{piece}, scratch, out);
}

Section planeSection(const Piece& piece, const Plane& plane, double tolerance) {
  thread_local SectionScratch scratch;
  Section section;
  section.kind = sectionCore(piece.shape.vertices, PolyhedronFaces{piece.shape}, plane, tolerance,
                             section.polygon, &section.face, scratch);
  return section;
}

SectionKind planeSectionFlat(const FlatPieceView& piece, const Plane& plane, double tolerance,
                             std::vector<Vec3>& polygon, int* face) {
  thread_local SectionScratch scratch;
  return planeSectionFlat(piece, plane, tolerance, polygon, face, scratch);
}

SectionKind planeSectionFlat(const FlatPieceView& piece, const Plane& plane, double tolerance,
                             std::vector<Vec3>& polygon, int* face, SectionScratch& scratch) {
  return sectionCore(piece.vertices, FlatFaces{piece}, plane, tolerance, polygon, face, scratch);
}

std::vector<Vec3> clipPolygon(const std::vector<Vec3>& polygon, const Plane& plane) {
  std::vector<Vec3> out;
  clipPolygon(polygon, plane, out);
  return out;
}

void clipPolygon(const std::vector<Vec3>& polygon, const Plane& plane, std::vector<Vec3>& out) {
  out.clear();
  const std::size_t n = polygon.size();
  if (n == 0) return;
  // Each point's distance once (the next edge's start is this edge's end).
  const double first = plane.distance(polygon[0]);
  double sp = first;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = polygon[i];
    const Vec3& q = polygon[i + 1 == n ? 0 : i + 1];
    const double sq = i + 1 == n ? first : plane.distance(q);
    if (sp >= 0.0) out.push_back(p);
    if ((sp > 0.0 && sq < 0.0) || (sp < 0.0 && sq > 0.0))
      out.push_back(p + (sp / (sp - sq)) * (q - p));
    sp = sq;
  }
}

}  // namespace rockmass::blocks
