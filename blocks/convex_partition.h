// Convex parts of simple polygons (CGAL's Hertel-Mehlhorn partition): non-convex prism
// profiles of structures, and non-convex fracture polygons from FAB files.
#pragma once

#include <vector>

#include "geometry/vec.h"

namespace rockmass::blocks {

/// True when the simple polygon `polygon` (either orientation) is convex; collinear points
/// are allowed.
bool isConvex(const std::vector<geometry::Vec2>& polygon);

/// A partition of the simple polygon `polygon` into convex parts, each given by indices
/// into `polygon`, counter-clockwise. A convex polygon comes back whole (as 0..n-1 in
/// counter-clockwise order). Throws std::invalid_argument for a polygon that is not simple.
std::vector<std::vector<int>> convexPartition(const std::vector<geometry::Vec2>& polygon);

}  // namespace rockmass::blocks
