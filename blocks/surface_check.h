// Checks that a polygon surface bounds a solid: closed, manifold, consistently and outward
// oriented, not self-intersecting (CGAL Polygon_mesh_processing). Used for mesh domains.
#pragma once

#include <optional>
#include <string>

#include "geometry/polyhedron.h"

namespace rockmass::blocks {

/// What is wrong with `surface` as the boundary of a solid, or nullopt when it is a valid
/// one. Messages (checked in this order): "has no faces", "is not closed: N border edges",
/// "is not manifold: N edges shared by more than two faces", "is not consistently oriented:
/// N edges run the same way in both faces", "intersects itself: N pairs of faces" (CGAL
/// does_self_intersect / self_intersections), "is oriented inward" (CGAL is_outward_oriented;
/// reverse the faces). Vertices are matched by index: weld duplicates before. When the
/// surface is valid and `triangles` is given, it receives the surface with every face
/// triangulated by CGAL (PMP::triangulate_faces, correct for concave planar faces), same
/// vertices.
std::optional<std::string> surfaceProblem(const geometry::Polyhedron& surface,
                                          geometry::Polyhedron* triangles = nullptr);

/// Whether a polygon soup is a closed, consistently oriented surface once its duplicate
/// points are merged (PMP::merge_duplicate_points_in_polygon_soup; for meshes read back
/// from files, where a triangle may have its own copies of its points): every edge is used
/// by exactly two polygons running opposite ways, and CGAL::is_closed holds on the
/// Surface_mesh built from the soup. A point where the solid touches itself (two cones of
/// faces meeting at one vertex, which a block glued from convex pieces can have) is split
/// into one copy per cone first (PMP::orient_polygon_soup), as a Surface_mesh needs.
bool isClosedSurface(const geometry::Polyhedron& soup);

}  // namespace rockmass::blocks
