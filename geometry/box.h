#pragma once
/// Axis-aligned boxes: the rock domain and bounding boxes.
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

}  // namespace rockmass::geometry
