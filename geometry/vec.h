#pragma once
/// Basic vector types shared by every module (Eigen, double precision).
#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

namespace rockmass::geometry {

/// A point or direction in 3D (unit: metres for points). Axes: x = East, y = North, z = Up.
using Vec3 = Eigen::Vector3d;
/// A point in a 2D profile (unit: metres).
using Vec2 = Eigen::Vector2d;

}  // namespace rockmass::geometry
