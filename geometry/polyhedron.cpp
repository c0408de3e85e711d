#include "geometry/polyhedron.h"

#include <limits>

namespace rockmass::geometry {

MassProperties massProperties(const Polyhedron& polyhedron) {
  return massProperties(polyhedron, Vec3::Zero());
}

MassProperties massProperties(const Polyhedron& polyhedron, const Vec3& reference) {
  MassProperties local;  // about r = first vertex
  if (polyhedron.vertices.empty()) return local;
  const Vec3 r = polyhedron.vertices.front() - reference;
  for (const std::vector<int>& face : polyhedron.faces) {
    if (face.size() < 3) continue;
    const Vec3 a = polyhedron.vertices[face[0]] - polyhedron.vertices.front();
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      const Vec3 b = polyhedron.vertices[face[k]] - polyhedron.vertices.front();
      const Vec3 c = polyhedron.vertices[face[k + 1]] - polyhedron.vertices.front();
      const double v = a.dot(b.cross(c)) / 6.0;  // signed; the fourth vertex is r (0 here)
      const Vec3 sum = a + b + c;
      local.volume += v;
      local.first += v * sum / 4.0;
      local.second +=
          v / 20.0 *
          (a * a.transpose() + b * b.transpose() + c * c.transpose() + sum * sum.transpose());
    }
  }
  // Shift from the first vertex to the reference: x - reference = y + r.
  MassProperties global;
  global.volume = local.volume;
  global.first = local.first + local.volume * r;
  global.second = local.second + r * local.first.transpose() + local.first * r.transpose() +
                  local.volume * r * r.transpose();
  return global;
}

Box bounds(const Polyhedron& polyhedron) {
  return bounds(polyhedron.vertices);
}

Polyhedron boxPolyhedron(const Box& box) {
  Polyhedron p;
  for (int i = 0; i < 8; ++i) {
    p.vertices.emplace_back((i & 1) ? box.max.x() : box.min.x(),
                            (i & 2) ? box.max.y() : box.min.y(),
                            (i & 4) ? box.max.z() : box.min.z());
  }
  p.faces = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  return p;
}

Vec3 faceNormal(const Polyhedron& polyhedron, int face) {
  const std::vector<int>& f = polyhedron.faces[static_cast<std::size_t>(face)];
  Vec3 n = Vec3::Zero();
  for (std::size_t k = 0; k < f.size(); ++k) {
    const Vec3& p = polyhedron.vertices[f[k]];
    const Vec3& q = polyhedron.vertices[f[(k + 1) % f.size()]];
    n += p.cross(q);  // Newell: twice the vector area
  }
  const double length = n.norm();
  return length > 0.0 ? Vec3(n / length) : Vec3(Vec3::Zero());
}

}  // namespace rockmass::geometry
