#pragma once
/// Point location in convex polyhedra (the pieces of blocks): which block a monitor or a
/// point load belongs to.
#include "geometry/polyhedron.h"
#include "geometry/vec.h"

namespace rockmass::geometry {

/// Signed distance (m) of `point` to the convex polyhedron's boundary as seen from its face
/// planes: max over faces of n_f . (point - v_f). Negative inside (minus the distance to the
/// nearest face plane), 0 on the boundary, positive outside (a lower bound of the distance
/// when the nearest feature is an edge or vertex). Degenerate (zero-area) faces are ignored.
double convexPlaneDistance(const Polyhedron& convex, const Vec3& point);

/// True when `point` lies inside the convex polyhedron or within `tolerance` (m) of it,
/// measured along the face normals.
bool convexContains(const Polyhedron& convex, const Vec3& point, double tolerance);

}  // namespace rockmass::geometry
