#pragma once
/// A regular grid of cubic cells: the support of RQD and P32 volumes.
#include <array>
#include <cstdint>

#include "geometry/box.h"
#include "geometry/vec.h"

namespace rockmass::rqd {

/// dims[0] x dims[1] x dims[2] cubic cells of edge `cell_size`, the first one with its lower
/// corner at `origin`. Cells are numbered with x fastest: index = i + nx (j + ny k).
struct CellGrid {
  geometry::Vec3 origin = geometry::Vec3::Zero();  ///< lower corner of cell (0, 0, 0) (m)
  double cell_size = 1.0;                          ///< edge length of every cell (m)
  std::array<int, 3> dims{0, 0, 0};                ///< number of cells along x, y, z

  /// Number of cells.
  std::int64_t cellCount() const { return static_cast<std::int64_t>(dims[0]) * dims[1] * dims[2]; }
  /// Linear index of cell (i, j, k), x fastest.
  std::int64_t index(int i, int j, int k) const {
    return i + static_cast<std::int64_t>(dims[0]) * (j + static_cast<std::int64_t>(dims[1]) * k);
  }
  /// Integer coordinates (i, j, k) of the cell with linear index `cell`.
  std::array<int, 3> coordinates(std::int64_t cell) const {
    const std::int64_t plane = static_cast<std::int64_t>(dims[0]) * dims[1];
    const auto k = static_cast<int>(cell / plane);
    const std::int64_t rest = cell - k * plane;
    return {static_cast<int>(rest % dims[0]), static_cast<int>(rest / dims[0]), k};
  }
  /// Centre of cell (i, j, k) (m).
  geometry::Vec3 cellCenter(int i, int j, int k) const {
    return origin + cell_size * geometry::Vec3(i + 0.5, j + 0.5, k + 0.5);
  }
  /// The closed box of cell (i, j, k) (m).
  geometry::Box cellBox(int i, int j, int k) const {
    const geometry::Vec3 low = origin + cell_size * geometry::Vec3(i, j, k);
    return {low, low + geometry::Vec3::Constant(cell_size)};
  }
  /// The box covered by all cells (m).
  geometry::Box bounds() const {
    return {origin, origin + cell_size * geometry::Vec3(dims[0], dims[1], dims[2])};
  }
};

/// The grid of whole cells of edge `cell_size` (m, > 0) that fits in `region`, centred in it:
/// floor(size / cell_size) cells per axis (a relative slack of 1e-9 absorbs rounding, so a
/// 100 m region with 5 m cells has 20 cells), the leftover split equally on both sides.
/// Every cell lies inside `region`. Throws std::invalid_argument for a non-positive or
/// non-finite cell size, an empty or non-finite region, a region thinner than one cell along
/// some axis, more than 2^31 - 1 cells along an axis, or more than kMaxGridCells in all.
CellGrid cellGridIn(const geometry::Box& region, double cell_size);

/// The most cells a grid may have: each casts its scanlines, and at 1e7 cells a grid already
/// takes minutes (a spacing of 1e-6 m asked for 4e21 cells and never finished). cellGridIn
/// refuses more; the scene reader refuses them at the spacing's line.
inline constexpr double kMaxGridCells = 1e7;

/// Whole cells of edge `cell_size` along `length` (m): the 1e-9 slack keeps the last cell of
/// an exact multiple that round-off would drop.
double cellsAlong(double length, double cell_size);

}  // namespace rockmass::rqd
