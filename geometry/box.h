#pragma once
/// Axis-aligned boxes: the rock domain and bounding boxes.
#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/vec.h"

namespace rockmass::geometry {

/// An axis-aligned box [min, max] (unit: metres).
struct Box {
  Vec3 min = Vec3::Zero();  ///< lower corner (m)
  Vec3 max = Vec3::Zero();  ///< upper corner (m)

  /// Edge lengths (m).
  Vec3 size() const { return max - min; }
  /// Volume (m3).
  double volume() const { return size().prod(); }
  /// Centre point (m).
  Vec3 center() const { return 0.5 * (min + max); }
  /// Length of the space diagonal (m).
  double diagonal() const { return size().norm(); }
  /// The box grown by `margin` metres on every side.
  Box enlarged(double margin) const { return {min.array() - margin, max.array() + margin}; }
  /// True when p lies inside or on the boundary.
  bool contains(const Vec3& p) const {
    return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
  }
  /// Euclidean distance from p to the box (0 inside).
  double distance(const Vec3& p) const {
    const Vec3 d = (min - p).cwiseMax(p - max).cwiseMax(Vec3::Zero());
    return d.norm();
  }
};

/// Axis-aligned bounding box of `points` (min +inf, max -inf when there are none).
inline Box bounds(const std::vector<Vec3>& points) {
  Box box{Vec3::Constant(std::numeric_limits<double>::infinity()),
          Vec3::Constant(-std::numeric_limits<double>::infinity())};
  for (const Vec3& p : points) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  return box;
}

/// The part [t0, t1] of [t_min, t_max] where p + t dir lies in `box` (Liang-Barsky slabs), or
/// nothing when the line misses the box there. t0 == t1 when it only touches it.
inline std::optional<std::array<double, 2>> lineInterval(const Box& box, const Vec3& p,
                                                         const Vec3& dir, double t_min,
                                                         double t_max) {
  double t0 = t_min;
  double t1 = t_max;
  for (int axis = 0; axis < 3; ++axis) {
    if (dir[axis] == 0.0) {
      if (p[axis] < box.min[axis] || p[axis] > box.max[axis]) return std::nullopt;
      continue;
    }
    double enter = (box.min[axis] - p[axis]) / dir[axis];
    double leave = (box.max[axis] - p[axis]) / dir[axis];
    if (enter > leave) std::swap(enter, leave);
    t0 = std::max(t0, enter);
    t1 = std::min(t1, leave);
    if (t0 > t1) return std::nullopt;
  }
  return std::array<double, 2>{t0, t1};
}

}  // namespace rockmass::geometry
