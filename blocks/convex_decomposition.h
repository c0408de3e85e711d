// Convex decomposition of a closed polyhedron (a mesh domain) with CGAL's
// convex_decomposition_3 over an exact kernel (implemented in blocks/exact/nef_solids.cpp).
#pragma once

#include <vector>

#include "geometry/polyhedron.h"

namespace rockmass::blocks {

/// Convex decomposition of a closed, outward-oriented polyhedron (CGAL's
/// convex_decomposition_3 over an exact kernel). The pieces' vertices are rounded to double.
std::vector<geometry::Polyhedron> convexDecomposition(const geometry::Polyhedron& solid);

}  // namespace rockmass::blocks
