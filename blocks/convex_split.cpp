#include "blocks/convex_split.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

namespace rockmass::blocks {
namespace {

/// -1, 0 or +1: the side of the plane a vertex is on, ON within the tolerance (into
/// `sides`), and the signed distances.
void classify(const std::vector<Vec3>& points, const Plane& plane, double tolerance,
              std::vector<std::int8_t>& sides, std::vector<double>& distances) {
  sides.resize(points.size());
  distances.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double s = plane.distance(points[i]);
    distances[i] = s;
    sides[i] = s > tolerance ? 1 : (s < -tolerance ? -1 : 0);
  }
}

/// Order of `points` (a convex polygon's vertices in any order, all in a plane with unit
/// normal `normal`) counter-clockwise about `normal`: by angle about their mean, which lies
/// inside the polygon, so points on a common edge still sort along it. Into `order` (a
/// scratch buffer reused by the caller's thread).
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
    angle[i] = std::atan2(d.dot(w), d.dot(u));
  }
  order.resize(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return angle[a] < angle[b]; });
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

}  // namespace

std::optional<SplitPieces> splitPiece(const Piece& piece, const Plane& plane, double tolerance,
                                      FaceSource cap) {
  const std::vector<Vec3>& vertices = piece.shape.vertices;
  // Scratch buffers reused by this thread's splits (no allocation once grown).
  thread_local std::vector<double> s;
  thread_local std::vector<std::int8_t> side;
  classify(vertices, plane, tolerance, side, s);
  const bool has_below = std::find(side.begin(), side.end(), -1) != side.end();
  const bool has_above = std::find(side.begin(), side.end(), 1) != side.end();
  if (!has_below || !has_above) return std::nullopt;

  SplitPieces out;
  geometry::Polyhedron& below = out.below.shape;
  geometry::Polyhedron& above = out.above.shape;
  below.vertices.reserve(vertices.size() + 4);
  above.vertices.reserve(vertices.size() + 4);
  below.faces.reserve(piece.shape.faces.size() + 1);
  above.faces.reserve(piece.shape.faces.size() + 1);
  thread_local std::vector<int> below_index, above_index, order;
  below_index.assign(vertices.size(), -1);
  above_index.assign(vertices.size(), -1);
  thread_local std::vector<Vec3> cap_points;  // the new face: ON vertices, then crossing points
  thread_local std::vector<std::pair<int, int>> cap_index;  // (below, above) of each cap point
  cap_points.clear();
  cap_index.clear();
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    if (side[i] <= 0) {
      below_index[i] = static_cast<int>(below.vertices.size());
      below.vertices.push_back(vertices[i]);
    }
    if (side[i] >= 0) {
      above_index[i] = static_cast<int>(above.vertices.size());
      above.vertices.push_back(vertices[i]);
    }
    if (side[i] == 0) {
      cap_points.push_back(vertices[i]);
      cap_index.emplace_back(below_index[i], above_index[i]);
    }
  }
  // Crossing points, one per cut edge (an edge appears in two faces).
  struct Cut {
    int a, b, below, above;
  };
  thread_local std::vector<Cut> cuts;
  cuts.clear();
  const auto crossing = [&](int a, int b) -> const Cut& {
    const int lo = std::min(a, b), hi = std::max(a, b);
    for (const Cut& c : cuts) {
      if (c.a == lo && c.b == hi) return c;
    }
    const Vec3 p = crossingPoint(vertices[lo], vertices[hi], s[lo], s[hi]);
    Cut c{lo, hi, static_cast<int>(below.vertices.size()), static_cast<int>(above.vertices.size())};
    below.vertices.push_back(p);
    above.vertices.push_back(p);
    cap_points.push_back(p);
    cap_index.emplace_back(c.below, c.above);
    cuts.push_back(c);
    return cuts.back();
  };

  for (std::size_t f = 0; f < piece.shape.faces.size(); ++f) {
    const std::vector<int>& face = piece.shape.faces[f];
    std::vector<int> below_loop, above_loop;
    bool below_off_plane = false, above_off_plane = false;
    for (std::size_t k = 0; k < face.size(); ++k) {
      const int a = face[k];
      const int b = face[(k + 1) % face.size()];
      if (side[a] <= 0) below_loop.push_back(below_index[a]);
      if (side[a] >= 0) above_loop.push_back(above_index[a]);
      below_off_plane |= side[a] < 0;
      above_off_plane |= side[a] > 0;
      if (side[a] * side[b] < 0) {
        const Cut& c = crossing(a, b);
        below_loop.push_back(c.below);
        above_loop.push_back(c.above);
      }
    }
    // A loop with no vertex off the plane lies in the new face: the cap replaces it.
    if (below_loop.size() >= 3 && below_off_plane) {
      below.faces.push_back(std::move(below_loop));
      out.below.face_sources.push_back(piece.face_sources[f]);
      out.below_origin.push_back(static_cast<int>(f));
    }
    if (above_loop.size() >= 3 && above_off_plane) {
      above.faces.push_back(std::move(above_loop));
      out.above.face_sources.push_back(piece.face_sources[f]);
      out.above_origin.push_back(static_cast<int>(f));
    }
  }
  if (cap_points.size() < 3) return std::nullopt;
  // The cap: counter-clockwise about +n seen from outside `below`; `above` gets the reverse
  // loop starting at the same vertex, so both fan it into the same triangles.
  counterClockwise(cap_points, plane.normal, order);
  std::vector<int> below_cap, above_cap;
  below_cap.reserve(order.size());
  above_cap.reserve(order.size());
  for (int k : order) below_cap.push_back(cap_index[k].first);
  above_cap.push_back(cap_index[order[0]].second);
  for (std::size_t k = order.size() - 1; k >= 1; --k)
    above_cap.push_back(cap_index[order[k]].second);
  below.faces.push_back(std::move(below_cap));
  above.faces.push_back(std::move(above_cap));
  out.below.face_sources.push_back(cap);
  out.above.face_sources.push_back(cap);
  out.below_origin.push_back(-1);
  out.above_origin.push_back(-1);
  return out;
}

Section planeSection(const Piece& piece, const Plane& plane, double tolerance) {
  const std::vector<Vec3>& vertices = piece.shape.vertices;
  thread_local std::vector<double> s;
  thread_local std::vector<std::int8_t> side;
  classify(vertices, plane, tolerance, side, s);
  const bool has_below = std::find(side.begin(), side.end(), -1) != side.end();
  const bool has_above = std::find(side.begin(), side.end(), 1) != side.end();
  Section section;
  if (has_below && has_above) {
    section.kind = SectionKind::Crossing;
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      if (side[i] == 0) section.polygon.push_back(vertices[i]);
    }
    for (const std::vector<int>& face : piece.shape.faces) {
      for (std::size_t k = 0; k < face.size(); ++k) {
        const int a = face[k];
        const int b = face[(k + 1) % face.size()];
        // Each cut edge is met twice (once per face); keep it from the face where a < b.
        if (side[a] * side[b] < 0 && a < b) {
          section.polygon.push_back(crossingPoint(vertices[a], vertices[b], s[a], s[b]));
        }
      }
    }
    thread_local std::vector<int> order;
    thread_local std::vector<Vec3> unsorted;
    counterClockwise(section.polygon, plane.normal, order);
    unsorted.assign(section.polygon.begin(), section.polygon.end());
    for (std::size_t k = 0; k < order.size(); ++k) section.polygon[k] = unsorted[order[k]];
    return section;
  }
  for (std::size_t f = 0; f < piece.shape.faces.size(); ++f) {
    const std::vector<int>& face = piece.shape.faces[f];
    const bool on = std::all_of(face.begin(), face.end(), [&](int v) { return side[v] == 0; });
    if (!on) continue;
    section.kind = SectionKind::OnFace;
    section.face = static_cast<int>(f);
    for (int v : face) section.polygon.push_back(vertices[v]);
    // The face is counter-clockwise about its outward normal, which may be -n.
    if (geometry::faceNormal(piece.shape, section.face).dot(plane.normal) < 0.0) {
      std::reverse(section.polygon.begin(), section.polygon.end());
    }
    return section;
  }
  return section;
}

std::vector<Vec3> clipPolygon(const std::vector<Vec3>& polygon, const Plane& plane) {
  std::vector<Vec3> out;
  clipPolygon(polygon, plane, out);
  return out;
}

void clipPolygon(const std::vector<Vec3>& polygon, const Plane& plane, std::vector<Vec3>& out) {
  out.clear();
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = polygon[i];
    const Vec3& q = polygon[(i + 1) % n];
    const double sp = plane.distance(p);
    const double sq = plane.distance(q);
    if (sp >= 0.0) out.push_back(p);
    if ((sp > 0.0 && sq < 0.0) || (sp < 0.0 && sq > 0.0))
      out.push_back(p + (sp / (sp - sq)) * (q - p));
  }
}

}  // namespace rockmass::blocks
