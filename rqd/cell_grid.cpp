#include "rqd/cell_grid.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rockmass::rqd {

double cellsAlong(double length, double cell_size) {
  return std::floor(length / cell_size * (1.0 + 1e-9));
}

CellGrid cellGridIn(const geometry::Box& region, double cell_size) {
  if (!(std::isfinite(cell_size) && cell_size > 0.0)) {
    throw std::invalid_argument("grid cell size must be finite and > 0 m, got " +
                                std::to_string(cell_size));
  }
  const geometry::Vec3 size = region.size();
  if (!size.allFinite() || !region.min.allFinite() || (size.array() <= 0.0).any()) {
    throw std::invalid_argument("grid region must be a finite box with positive edges");
  }
  CellGrid grid;
  grid.cell_size = cell_size;
  double total = 1.0;
  for (int axis = 0; axis < 3; ++axis) {
    const double cells = cellsAlong(size[axis], cell_size);
    if (cells < 1.0) {
      throw std::invalid_argument("grid region is " + std::to_string(size[axis]) +
                                  " m along axis " + std::string(1, "xyz"[axis]) +
                                  ", thinner than one cell of " + std::to_string(cell_size) +
                                  " m: use a smaller spacing");
    }
    if (cells > std::numeric_limits<int>::max()) {
      throw std::invalid_argument("grid has too many cells along axis " +
                                  std::string(1, "xyz"[axis]) + ": use a larger spacing");
    }
    grid.dims[static_cast<std::size_t>(axis)] = static_cast<int>(cells);
    total *= cells;
    if (total > kMaxGridCells) {
      throw std::invalid_argument("grid of spacing " + std::to_string(cell_size) +
                                  " m would have more than 1e7 cells: use a larger spacing");
    }
    // Centre the cells in the region; never start below its lower bound.
    grid.origin[axis] = region.min[axis] + std::max(0.0, 0.5 * (size[axis] - cells * cell_size));
  }
  return grid;
}

}  // namespace rockmass::rqd
