#include "geometry/point_in_polyhedron.h"

#include <algorithm>
#include <limits>

namespace rockmass::geometry {

double convexPlaneDistance(const Polyhedron& convex, const Vec3& point) {
  double distance = -std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < convex.faces.size(); ++f) {
    const Vec3 n = faceNormal(convex, static_cast<int>(f));
    if (n.isZero()) continue;
    const Vec3& on_face = convex.vertices[static_cast<std::size_t>(convex.faces[f].front())];
    distance = std::max(distance, n.dot(point - on_face));
  }
  return distance;
}

bool convexContains(const Polyhedron& convex, const Vec3& point, double tolerance) {
  return convexPlaneDistance(convex, point) <= tolerance;
}

}  // namespace rockmass::geometry
