#include "blocks/region_split.h"

#include <stdexcept>

namespace rockmass::blocks {

int longestAxis(const geometry::Box& box) {
  int axis = 0;
  box.size().maxCoeff(&axis);
  return axis;
}

double freeSplitLevel(const geometry::Box& box, int axis,
                      const std::function<bool(double)>& clashes, const std::string& cutter) {
  const double size = box.max[axis] - box.min[axis];
  for (int attempt = 0; attempt < kSplitAttempts; ++attempt) {
    const double offset = (attempt % 2 == 0 ? 1.0 : -1.0) * ((attempt + 1) / 2) / 67.0;
    const double level = box.min[axis] + (0.5 + offset) * size;
    if (!clashes(level)) return level;
  }
  throw std::runtime_error(cutter + ": no free splitting plane found along " +
                           std::string(1, "xyz"[axis]) + " in " + std::to_string(kSplitAttempts) +
                           " levels of a region (every level lies in a disc or domain plane)");
}

}  // namespace rockmass::blocks
