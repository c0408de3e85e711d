// Convex polygons in a face's 2D frame: half-plane clipping, area, centroid (contact overlap
// areas and sub-contact point cells).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace rockmass::dda3d {

/// A point of the plane with 2D coordinates in a face's basis.
using Point2 = Eigen::Vector2d;

/// The part of the convex polygon `polygon` where the affine function value(x) <= 0
/// (Sutherland-Hodgman against one half-plane).
template <class Value>
std::vector<Point2> clipped(const std::vector<Point2>& polygon, const Value& value) {
  std::vector<Point2> out;
  out.reserve(polygon.size() + 1);
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Point2& p = polygon[k];
    const Point2& q = polygon[(k + 1) % polygon.size()];
    const double vp = value(p), vq = value(q);
    if (vp <= 0.0) out.push_back(p);
    if ((vp < 0.0 && vq > 0.0) || (vp > 0.0 && vq < 0.0))
      out.push_back(p + (vp / (vp - vq)) * (q - p));
  }
  return out;
}

inline double cross2(const Point2& a, const Point2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Area of the counter-clockwise polygon (m2).
inline double polygonArea(const std::vector<Point2>& polygon) {
  double twice = 0.0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    twice += cross2(polygon[k], polygon[(k + 1) % polygon.size()]);
  }
  return 0.5 * twice;
}

/// Centroid of a polygon of (signed) area `area`.
inline Point2 polygonCentroid(const std::vector<Point2>& polygon, double area) {
  Point2 centroid = Point2::Zero();
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Point2& p = polygon[k];
    const Point2& q = polygon[(k + 1) % polygon.size()];
    centroid += cross2(p, q) * (p + q);
  }
  return centroid / (6.0 * area);
}

}  // namespace rockmass::dda3d
