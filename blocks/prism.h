// Structures given as prisms: a 2D profile swept along an axis, as convex pieces.
#pragma once

#include <vector>

#include "geometry/polyhedron.h"
#include "geometry/vec.h"

namespace rockmass::blocks {

/// The prism of `profile` ((x, z) points for sweep 'y', (y, z) points for sweep 'x'; a
/// simple polygon in either orientation) between sweep coordinates `from` < `to` (m), as
/// closed convex outward polyhedra, one per part of the profile's convex partition.
/// Throws std::invalid_argument for a profile that is not a simple polygon with area, or
/// from >= to.
std::vector<geometry::Polyhedron> prismPieces(const std::vector<geometry::Vec2>& profile,
                                              char sweep, double from, double to);

}  // namespace rockmass::blocks
