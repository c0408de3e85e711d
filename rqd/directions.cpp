#include "rqd/directions.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "geometry/orientation.h"

namespace rockmass::rqd {

std::vector<geometry::Vec3> fibonacciSphere(int count) {
  if (count < 1) {
    throw std::invalid_argument("fibonacciSphere: the direction count must be >= 1, got " +
                                std::to_string(count));
  }
  const double golden_angle = geometry::kPi * (3.0 - std::sqrt(5.0));
  std::vector<geometry::Vec3> directions;
  directions.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / count;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double longitude = golden_angle * i;
    directions.emplace_back(r * std::cos(longitude), r * std::sin(longitude), z);
  }
  return directions;
}

}  // namespace rockmass::rqd

namespace rockmass::rqd {

std::vector<geometry::Vec3> scanlineAxes(int count) {
  if (count < 1 || count > std::numeric_limits<int>::max() / 2) {
    throw std::invalid_argument("scanlineAxes: the axis count must be in [1, 2^30), got " +
                                std::to_string(count));
  }
  std::vector<geometry::Vec3> axes = fibonacciSphere(2 * count);
  axes.resize(static_cast<std::size_t>(count));
  return axes;
}

}  // namespace rockmass::rqd
