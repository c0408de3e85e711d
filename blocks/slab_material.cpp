#include "blocks/slab_material.h"

#include <cstdint>
#include <limits>
#include <vector>

namespace rockmass::blocks {
namespace {

/// Nearest crossing of the line point + t dir with the discs `ids`, on the side where
/// t >= 0 (ahead) or t <= 0 (behind); +infinity when there is none.
double nearestCrossing(const geometry::FractureNetwork& network,
                       const std::vector<std::int64_t>& ids, const geometry::Vec3& point,
                       const geometry::Vec3& dir, bool ahead) {
  double best = std::numeric_limits<double>::infinity();
  for (const std::int64_t id : ids) {
    if (id < 1 || id > static_cast<std::int64_t>(network.discs.size())) continue;
    const auto t = network.discs[static_cast<std::size_t>(id - 1)].intersectLine(point, dir);
    if (!t) continue;
    const double distance = ahead ? *t : -*t;
    if (distance >= 0.0 && distance < best) best = distance;
  }
  return best;
}

}  // namespace

int materialAt(const geometry::FractureNetwork& network, const geometry::Vec3& point,
               int rock_material) {
  for (const geometry::Slab& slab : network.slabs) {
    if (slab.lower.empty() || slab.upper.empty()) continue;
    const geometry::Vec3 dir = network.sets[static_cast<std::size_t>(slab.set)].mean_normal;
    const double lower_ahead = nearestCrossing(network, slab.lower, point, dir, true);
    const double lower_behind = nearestCrossing(network, slab.lower, point, dir, false);
    const double upper_ahead = nearestCrossing(network, slab.upper, point, dir, true);
    const double upper_behind = nearestCrossing(network, slab.upper, point, dir, false);
    const bool lower_first_ahead = lower_ahead < upper_ahead;
    const bool lower_first_behind = lower_behind < upper_behind;
    const bool ahead_found =
        std::min(lower_ahead, upper_ahead) < std::numeric_limits<double>::infinity();
    const bool behind_found =
        std::min(lower_behind, upper_behind) < std::numeric_limits<double>::infinity();
    if (ahead_found && behind_found && lower_first_ahead != lower_first_behind) {
      return slab.material;
    }
  }
  return rock_material;
}

}  // namespace rockmass::blocks
