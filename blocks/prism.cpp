#include "blocks/prism.h"

#include <algorithm>
#include <stdexcept>

#include "blocks/convex_partition.h"

namespace rockmass::blocks {

using geometry::Vec3;

std::vector<geometry::Polyhedron> prismPieces(const std::vector<geometry::Vec2>& profile,
                                              char sweep, double from, double to) {
  if (profile.size() < 3) throw std::invalid_argument("a prism profile needs 3 points or more");
  if (!(from < to)) throw std::invalid_argument("a prism needs from < to");
  const int sweep_axis = sweep == 'x' ? 0 : 1;
  const int profile_axis = 1 - sweep_axis;
  const auto point = [&](const geometry::Vec2& p, double s) {
    Vec3 q;
    q[profile_axis] = p.x();
    q[sweep_axis] = s;
    q[2] = p.y();
    return q;
  };
  std::vector<geometry::Polyhedron> pieces;
  for (const std::vector<int>& part : convexPartition(profile)) {
    geometry::Polyhedron p;
    const int n = static_cast<int>(part.size());
    for (int i : part) p.vertices.push_back(point(profile[i], from));
    for (int i : part) p.vertices.push_back(point(profile[i], to));
    std::vector<int> near, far;
    for (int k = 0; k < n; ++k) {
      near.push_back(n - 1 - k);
      far.push_back(n + k);
      const int next = (k + 1) % n;
      p.faces.push_back({k, next, n + next, n + k});
    }
    p.faces.push_back(near);
    p.faces.push_back(far);
    // The profile's orientation and the sweep axis decide the handedness: make it outward.
    if (geometry::massProperties(p).volume < 0.0) {
      for (std::vector<int>& f : p.faces) std::reverse(f.begin(), f.end());
    }
    if (!(geometry::massProperties(p).volume > 0.0)) {
      throw std::invalid_argument("the prism profile has no area");
    }
    pieces.push_back(std::move(p));
  }
  return pieces;
}

}  // namespace rockmass::blocks
