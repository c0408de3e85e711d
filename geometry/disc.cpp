#include "geometry/disc.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "geometry/fisher.h"
#include "geometry/orientation.h"

namespace rockmass::geometry {
namespace {

/// Newell's vector: twice the area times the unit normal of a planar polygon.
Vec3 newellVector(const std::vector<Vec3>& polygon) {
  Vec3 sum = Vec3::Zero();
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) sum += polygon[i].cross(polygon[(i + 1) % n]);
  return sum;
}

/// Keeps the part of `polygon` where coordinate `axis` is >= bound (keep_above) or <= bound.
std::vector<Vec3> clipAgainstPlane(const std::vector<Vec3>& polygon, int axis, double bound,
                                   bool keep_above) {
  std::vector<Vec3> out;
  const std::size_t n = polygon.size();
  out.reserve(n + 2);
  const auto inside = [&](const Vec3& p) {
    return keep_above ? p[axis] >= bound : p[axis] <= bound;
  };
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& p = polygon[i];
    const Vec3& q = polygon[(i + 1) % n];
    const bool p_in = inside(p);
    const bool q_in = inside(q);
    if (p_in) out.push_back(p);
    if (p_in != q_in) {
      const double t = (bound - p[axis]) / (q[axis] - p[axis]);
      Vec3 crossing = p + t * (q - p);
      crossing[axis] = bound;
      out.push_back(crossing);
    }
  }
  return out;
}

/// Ellipse polygon with `segments` vertices whose area equals pi a b exactly: the inscribed
/// polygon is scaled about the centre by sqrt(pi / ((n / 2) sin(2 pi / n))).
std::vector<Vec3> areaPreservingOutline(const Disc& disc, int segments) {
  const double inscribed = 0.5 * segments * std::sin(2.0 * kPi / segments);
  const double scale = std::sqrt(kPi / inscribed);
  std::vector<Vec3> outline = disc.outline(segments);
  for (Vec3& p : outline) p = disc.center + scale * (p - disc.center);
  return outline;
}

/// Crossing-number test of a point against a polygon, both given in the polygon's plane
/// by 2D coordinates along (u, v).
bool insidePolygon2d(const std::vector<Vec3>& polygon, const Vec3& origin, const Vec3& u,
                     const Vec3& v, const Vec3& point) {
  const double px = (point - origin).dot(u);
  const double py = (point - origin).dot(v);
  bool inside = false;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const double xi = (polygon[i] - origin).dot(u), yi = (polygon[i] - origin).dot(v);
    const double xj = (polygon[j] - origin).dot(u), yj = (polygon[j] - origin).dot(v);
    if ((yi > py) != (yj > py) && px < (xj - xi) * (py - yi) / (yj - yi) + xi) inside = !inside;
  }
  return inside;
}

}  // namespace

double polygonArea(const std::vector<Vec3>& polygon) {
  return polygon.size() < 3 ? 0.0 : 0.5 * newellVector(polygon).norm();
}

Vec3 polygonNormal(const std::vector<Vec3>& polygon) {
  if (polygon.size() < 3) return Vec3::Zero();
  const Vec3 sum = newellVector(polygon);
  const double length = sum.norm();
  return length > 0.0 ? Vec3(sum / length) : Vec3::Zero();
}

Vec3 polygonCentroid(const std::vector<Vec3>& polygon) {
  const Vec3 normal = polygonNormal(polygon);
  Vec3 weighted = Vec3::Zero();
  double total = 0.0;
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    const double area =
        0.5 * (polygon[i] - polygon[0]).cross(polygon[i + 1] - polygon[0]).dot(normal);
    weighted += area * (polygon[0] + polygon[i] + polygon[i + 1]) / 3.0;
    total += area;
  }
  if (total == 0.0) {
    Vec3 mean = Vec3::Zero();
    for (const Vec3& p : polygon) mean += p;
    return polygon.empty() ? mean : Vec3(mean / static_cast<double>(polygon.size()));
  }
  return weighted / total;
}

std::vector<Vec3> clipPolygonToBox(const std::vector<Vec3>& polygon, const Box& box) {
  std::vector<Vec3> clipped = polygon;
  for (int axis = 0; axis < 3 && !clipped.empty(); ++axis) {
    clipped = clipAgainstPlane(clipped, axis, box.min[axis], /*keep_above=*/true);
    if (!clipped.empty()) {
      clipped = clipAgainstPlane(clipped, axis, box.max[axis], /*keep_above=*/false);
    }
  }
  return clipped;
}

Disc discFromPolygon(std::vector<Vec3> polygon) {
  if (polygon.size() < 3) {
    throw std::invalid_argument("a fracture polygon needs at least 3 vertices, got " +
                                std::to_string(polygon.size()));
  }
  const double area = polygonArea(polygon);
  if (!(area > 0.0)) throw std::invalid_argument("a fracture polygon has no area");
  Disc disc;
  disc.center = polygonCentroid(polygon);
  disc.normal = polygonNormal(polygon);
  const auto farthest = std::max_element(polygon.begin(), polygon.end(), [&](auto& p, auto& q) {
    return (p - disc.center).squaredNorm() < (q - disc.center).squaredNorm();
  });
  const Vec3 offset = *farthest - disc.center;
  Vec3 major = offset - offset.dot(disc.normal) * disc.normal;
  if (major.norm() > 0.0) {
    major.normalize();
  } else {
    Vec3 unused;
    orthonormalBasis(disc.normal, major, unused);
  }
  disc.major = major;
  disc.a = offset.norm();
  disc.b = area / (kPi * disc.a);
  disc.polygon = std::move(polygon);
  return disc;
}

double Disc::area() const {
  return polygon.empty() ? kPi * a * b : polygonArea(polygon);
}

std::vector<Vec3> Disc::outline(int segments) const {
  if (!polygon.empty()) return polygon;
  const Vec3 minor_axis = minor();
  std::vector<Vec3> points;
  points.reserve(static_cast<std::size_t>(segments));
  for (int k = 0; k < segments; ++k) {
    const double theta = 2.0 * kPi * k / segments;
    points.push_back(center + a * std::cos(theta) * major + b * std::sin(theta) * minor_axis);
  }
  return points;
}

std::optional<double> Disc::intersectLine(const Vec3& origin, const Vec3& dir) const {
  const double denominator = normal.dot(dir);
  if (std::abs(denominator) <= 1e-300) return std::nullopt;
  const double t = normal.dot(center - origin) / denominator;
  const Vec3 point = origin + t * dir;
  if (!polygon.empty()) {
    if (!insidePolygon2d(polygon, center, major, minor(), point)) return std::nullopt;
    return t;
  }
  const Vec3 local = point - center;
  const double x = local.dot(major) / a;
  const double y = local.dot(minor()) / b;
  if (x * x + y * y > 1.0) return std::nullopt;
  return t;
}

double Disc::areaInside(const Box& box) const {
  if (box.distance(center) > a) return 0.0;
  if (polygon.empty() && box.contains(center.array() - a) && box.contains(center.array() + a)) {
    return area();
  }
  return polygonArea(clipPolygonToBox(areaOutline(), box));
}

std::vector<Vec3> Disc::areaOutline() const {
  constexpr int kClipSegments = 128;
  return polygon.empty() ? areaPreservingOutline(*this, kClipSegments) : polygon;
}

Box Disc::bounds() const {
  if (!polygon.empty()) return geometry::bounds(polygon);
  // Half-extent along axis k of centre + a cos(s) major + b sin(s) minor.
  const Vec3 half = ((a * major).cwiseAbs2() + (b * minor()).cwiseAbs2()).cwiseSqrt();
  return {center - half, center + half};
}

}  // namespace rockmass::geometry
