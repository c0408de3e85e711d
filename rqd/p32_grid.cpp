#include "rqd/p32_grid.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace rockmass::rqd {
namespace {

using geometry::Box;
using geometry::Disc;
using geometry::Vec3;

/// Area of one disc inside one cell.
struct CellArea {
  std::int64_t cell = 0;  ///< cell index
  double area = 0.0;      ///< m2
};

/// Index range [low, high] of the cells along `axis` that the interval [from, to] (m)
/// overlaps, clamped to the grid; low > high when it misses the grid.
std::array<int, 2> cellRange(const CellGrid& grid, int axis, double from, double to) {
  const double h = grid.cell_size;
  const double o = grid.origin[axis];
  const int last = grid.dims[static_cast<std::size_t>(axis)] - 1;
  if (to < o || from > o + h * (last + 1)) return {1, 0};
  const double low = std::floor((from - o) / h);
  const double high = std::floor((to - o) / h);
  return {static_cast<int>(std::clamp(low, 0.0, static_cast<double>(last))),
          static_cast<int>(std::clamp(high, 0.0, static_cast<double>(last)))};
}

/// Axis-aligned bounds of a polygon (m).
Box polygonBounds(const std::vector<Vec3>& polygon) {
  Box box{polygon.front(), polygon.front()};
  for (const Vec3& p : polygon) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  return box;
}

/// Largest distance (m) of a polygon-form disc's vertices from its plane (0 for ellipses):
/// FAB polygons need not be exactly planar.
double offPlane(const Disc& disc) {
  double deviation = 0.0;
  for (const Vec3& p : disc.polygon) {
    deviation = std::max(deviation, std::abs(disc.normal.dot(p - disc.center)));
  }
  return deviation;
}

/// True when `piece` (clipped to `cell`) lies flat in the cell's upper face along some axis
/// and a neighbour cell shares that face: cells are half-open [min, max) except the last
/// along each axis, so a fracture lying exactly in a face between two cells counts once.
bool onSharedUpperFace(const std::vector<Vec3>& piece, const Box& cell, const CellGrid& grid,
                       const std::array<int, 3>& ijk) {
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (ijk[axis] + 1 == grid.dims[axis]) continue;
    const auto a = static_cast<int>(axis);
    if (!piece.empty() && std::all_of(piece.begin(), piece.end(),
                                      [&](const Vec3& p) { return p[a] == cell.max[a]; })) {
      return true;
    }
  }
  return false;
}

/// The non-zero areas of `disc` inside the cells of `grid`, in cell index order.
std::vector<CellArea> discCellAreas(const Disc& disc, const CellGrid& grid) {
  const double total = disc.area();
  if (!(std::isfinite(total) && total > 0.0)) return {};
  // The bounds of the polygon that is clipped (the area-preserving 128-gon reaches slightly
  // beyond the ellipse).
  const std::vector<Vec3> outline = disc.areaOutline();
  const Box bounds = polygonBounds(outline);
  std::array<std::array<int, 2>, 3> range{};
  for (int axis = 0; axis < 3; ++axis) {
    range[static_cast<std::size_t>(axis)] =
        cellRange(grid, axis, bounds.min[axis], bounds.max[axis]);
    if (range[static_cast<std::size_t>(axis)][0] > range[static_cast<std::size_t>(axis)][1]) {
      return {};
    }
  }
  // A cell can hold part of the disc only if the disc's plane crosses it: the distance of
  // the cell centre from the plane is at most the cell's half-extent along the normal. The
  // pad keeps cells whose crossing rounding might hide, and non-planar polygons' cells.
  const double half_extent = 0.5 * grid.cell_size * disc.normal.cwiseAbs().sum();
  const double reach = half_extent + offPlane(disc) + 1e-9 * grid.cell_size;
  std::vector<CellArea> areas;
  for (int k = range[2][0]; k <= range[2][1]; ++k) {
    for (int j = range[1][0]; j <= range[1][1]; ++j) {
      for (int i = range[0][0]; i <= range[0][1]; ++i) {
        if (std::abs(disc.normal.dot(grid.cellCenter(i, j, k) - disc.center)) > reach) continue;
        const Box cell = grid.cellBox(i, j, k);
        const std::vector<Vec3> inside = geometry::clipPolygonToBox(outline, cell);
        if (onSharedUpperFace(inside, cell, grid, {i, j, k})) continue;
        const double area = geometry::polygonArea(inside);
        if (area > 0.0) areas.push_back({grid.index(i, j, k), area});
      }
    }
  }
  return areas;
}

}  // namespace

std::vector<double> p32Grid(const geometry::FractureNetwork& network, const CellGrid& grid) {
  const std::vector<Disc>& discs = network.discs;
  std::vector<std::vector<CellArea>> per_disc(discs.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, discs.size()),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t d = range.begin(); d != range.end(); ++d) {
                        per_disc[d] = discCellAreas(discs[d], grid);
                      }
                    });
  // Summed serially in disc order, so the result does not depend on the thread count.
  std::vector<double> p32(static_cast<std::size_t>(grid.cellCount()), 0.0);
  for (const std::vector<CellArea>& areas : per_disc) {
    for (const CellArea& piece : areas) p32[static_cast<std::size_t>(piece.cell)] += piece.area;
  }
  const double cell_volume = std::pow(grid.cell_size, 3);
  for (double& value : p32) value /= cell_volume;
  return p32;
}

}  // namespace rockmass::rqd
