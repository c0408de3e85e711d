#pragma once
/// The surface of an RQD ball: a triangle mesh over the ball's directions.
#include <array>
#include <span>
#include <vector>

#include "geometry/vec.h"

namespace rockmass::rqd {

/// Triangles (indices into `unit_directions`) of the convex hull of the directions, each
/// oriented counter-clockwise seen from outside (outward normals). Since every direction
/// lies on the unit sphere, every one is a hull vertex and the hull is the spherical
/// Delaunay triangulation of the directions; moving each vertex radially to its RQD radius
/// keeps the connectivity of a closed, star-shaped surface. Computed with CGAL's
/// convex_hull_3; the list is put in a canonical order (each triangle starting at its
/// smallest index, triangles sorted), so it depends only on the directions. Throws
/// std::invalid_argument for fewer than 4 directions or directions that are all coplanar.
std::vector<std::array<int, 3>> sphereTriangles(std::span<const geometry::Vec3> unit_directions);

}  // namespace rockmass::rqd
