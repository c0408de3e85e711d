#include "geometry/plane_section.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rockmass::geometry {

namespace {

/// z component of (b - a) x (c - a).
double cross(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

/// Convex hull (Andrew's monotone chain), counter-clockwise, without collinear or repeated
/// points: turns smaller than `eps` (an area, m2) count as straight.
std::vector<Vec2> convexHull(std::vector<Vec2> points, double eps) {
  std::sort(points.begin(), points.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (points.size() < 3) return points;
  std::vector<Vec2> hull(2 * points.size());
  std::size_t k = 0;
  for (const Vec2& p : points) {  // lower chain
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p) <= eps) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= eps) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);  // the last point repeats the first
  return hull;
}

/// Clips the segment a-b to `box` (Liang-Barsky); false when nothing is left.
bool clipToBox(Vec3& a, Vec3& b, const Box& box) {
  const Vec3 d = b - a;
  const auto inside = lineInterval(box, a, d, 0.0, 1.0);
  if (!inside) return false;
  const Vec3 start = a + (*inside)[0] * d;
  b = a + (*inside)[1] * d;
  a = start;
  return true;
}

/// The trace of an exact ellipse in the plane, unclipped: its chord along the line where
/// the two planes meet.
std::optional<std::pair<Vec3, Vec3>> ellipseChord(const Disc& disc, const SectionPlane& plane) {
  Vec3 dir = disc.normal.cross(plane.normal);
  if (dir.norm() < 1e-12) return std::nullopt;  // parallel planes
  dir.normalize();
  // The point of the line nearest the centre: c + alpha n_d + beta n_p on both planes.
  const double k = disc.normal.dot(plane.normal);
  const double h = plane.distance(disc.center);
  const double beta = -h / (1.0 - k * k);
  const double alpha = -beta * k;
  const Vec3 p0 = disc.center + alpha * disc.normal + beta * plane.normal;
  const Vec3 minor = disc.minor();
  const double x0 = (p0 - disc.center).dot(disc.major), y0 = (p0 - disc.center).dot(minor);
  const double dx = dir.dot(disc.major), dy = dir.dot(minor);
  const double a2 = disc.a * disc.a, b2 = disc.b * disc.b;
  const double qa = dx * dx / a2 + dy * dy / b2;
  const double qb = 2.0 * (x0 * dx / a2 + y0 * dy / b2);
  const double qc = x0 * x0 / a2 + y0 * y0 / b2 - 1.0;
  const double discriminant = qb * qb - 4.0 * qa * qc;
  if (!(discriminant > 0.0)) return std::nullopt;  // misses or only touches the ellipse
  const double root = std::sqrt(discriminant);
  return std::make_pair(p0 + (-qb - root) / (2.0 * qa) * dir, p0 + (-qb + root) / (2.0 * qa) * dir);
}

/// The traces of a planar polygon in the plane, unclipped: crossings of its edges sorted
/// along the line of the two planes and paired (even-odd), so non-convex polygons give
/// several chords. A vertex on the plane counts as on the positive side (a consistent
/// tie-break that keeps the crossing count even).
std::vector<std::pair<Vec3, Vec3>> polygonChords(const std::vector<Vec3>& polygon,
                                                 const SectionPlane& plane) {
  std::vector<std::pair<Vec3, Vec3>> chords;
  const Vec3 dir = polygonNormal(polygon).cross(plane.normal);
  if (dir.norm() < 1e-12) return chords;
  std::vector<std::pair<double, Vec3>> crossings;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& a = polygon[i];
    const Vec3& b = polygon[(i + 1) % n];
    const double da = plane.distance(a), db = plane.distance(b);
    if ((da < 0.0) == (db < 0.0)) continue;
    const Vec3 p = a + (da / (da - db)) * (b - a);
    crossings.emplace_back(p.dot(dir), p);
  }
  std::sort(crossings.begin(), crossings.end(),
            [](const auto& x, const auto& y) { return x.first < y.first; });
  for (std::size_t i = 0; i + 1 < crossings.size(); i += 2) {
    chords.emplace_back(crossings[i].second, crossings[i + 1].second);
  }
  return chords;
}

}  // namespace

SectionPlane axisPlane(int axis, double offset) {
  if (axis < 0 || axis > 2) throw std::invalid_argument("axisPlane: axis must be 0, 1 or 2");
  SectionPlane plane;
  plane.normal = Vec3::Unit(axis);
  plane.origin = offset * plane.normal;
  plane.u_axis = Vec3::Unit(axis == 0 ? 1 : 0);
  plane.v_axis = Vec3::Unit(axis == 2 ? 1 : 2);
  return plane;
}

double signedArea(const std::vector<Vec2>& polygon) {
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[(i + 1) % polygon.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * twice;
}

std::optional<PolygonSection> sectionPolyhedron(const Polyhedron& polyhedron,
                                                const SectionPlane& plane, double tolerance,
                                                FaceInPlane face_in_plane) {
  std::vector<double> d;
  d.reserve(polyhedron.vertices.size());
  double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  for (const Vec3& v : polyhedron.vertices) {
    d.push_back(plane.distance(v));
    lowest = std::min(lowest, d.back());
    highest = std::max(highest, d.back());
  }
  // On the positive side with a face in the plane: that face is the section (Above).
  const bool face_above =
      face_in_plane == FaceInPlane::Above && lowest >= -tolerance && highest > tolerance;
  if (!face_above && !(lowest < -tolerance && highest > tolerance)) {
    return std::nullopt;  // touches at most
  }

  std::vector<Vec2> points;
  double scale = 0.0;
  for (std::size_t i = 0; i < polyhedron.vertices.size(); ++i) {
    if (std::abs(d[i]) <= tolerance) points.push_back(plane.project(polyhedron.vertices[i]));
  }
  for (const std::vector<int>& face : polyhedron.faces) {
    for (std::size_t k = 0; k < face.size(); ++k) {
      const int a = face[k], b = face[(k + 1) % face.size()];
      const double da = d[static_cast<std::size_t>(a)], db = d[static_cast<std::size_t>(b)];
      if (!((da > tolerance && db < -tolerance) || (da < -tolerance && db > tolerance))) continue;
      const Vec3& va = polyhedron.vertices[static_cast<std::size_t>(a)];
      const Vec3& vb = polyhedron.vertices[static_cast<std::size_t>(b)];
      points.push_back(plane.project(va + (da / (da - db)) * (vb - va)));
    }
  }
  for (const Vec2& p : points) scale = std::max(scale, p.cwiseAbs().maxCoeff());
  const double eps = 1e-14 * std::max(1.0, scale * scale);
  PolygonSection section;
  section.points = convexHull(std::move(points), eps);
  if (section.points.size() < 3) return std::nullopt;

  // Each edge lies in the face whose plane passes nearest its midpoint, other than a face
  // that lies in the plane (face_above: the section itself).
  std::vector<bool> in_plane(polyhedron.faces.size(), false);
  for (std::size_t f = 0; f < polyhedron.faces.size() && face_above; ++f) {
    in_plane[f] = std::all_of(polyhedron.faces[f].begin(), polyhedron.faces[f].end(), [&](int v) {
      return std::abs(d[static_cast<std::size_t>(v)]) <= tolerance;
    });
  }
  for (std::size_t k = 0; k < section.points.size(); ++k) {
    const Vec3 mid =
        plane.lift(0.5 * (section.points[k] + section.points[(k + 1) % section.points.size()]));
    int best = -1;
    double best_distance = std::numeric_limits<double>::infinity();
    for (std::size_t f = 0; f < polyhedron.faces.size(); ++f) {
      if (in_plane[f]) continue;
      const Vec3 n = faceNormal(polyhedron, static_cast<int>(f));
      const Vec3& v0 = polyhedron.vertices[static_cast<std::size_t>(polyhedron.faces[f][0])];
      const double distance = std::abs(n.dot(mid - v0));
      if (distance < best_distance) {
        best_distance = distance;
        best = static_cast<int>(f);
      }
    }
    section.edge_faces.push_back(best);
  }
  return section;
}

std::vector<std::pair<Vec2, Vec2>> sectionTrace(const Disc& disc, const SectionPlane& plane,
                                                const Box& box, int segments) {
  std::vector<std::pair<Vec3, Vec3>> chords;
  if (disc.polygon.empty() && segments == 0) {
    if (auto chord = ellipseChord(disc, plane)) chords.push_back(*chord);
  } else {
    chords = polygonChords(disc.outline(segments), plane);
  }
  std::vector<std::pair<Vec2, Vec2>> traces;
  for (auto& [a, b] : chords) {
    if (!clipToBox(a, b, box) || (b - a).norm() == 0.0) continue;
    traces.emplace_back(plane.project(a), plane.project(b));
  }
  return traces;
}

}  // namespace rockmass::geometry
