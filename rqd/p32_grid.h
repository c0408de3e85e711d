#pragma once
/// Fracture intensity P32 per grid cell, counted exactly from the disc areas.
#include <vector>

#include "geometry/fracture_network.h"
#include "rqd/cell_grid.h"

namespace rockmass::rqd {

/// P32 of every cell of `grid` (m2/m3, one face counted, cell index order of CellGrid):
/// the area of all fracture surface inside the cell divided by the cell volume. Every disc
/// with area counts (also those that do not cut blocks). Areas come from Disc::areaInside:
/// exact for polygons; an ellipse is clipped as a 128-gon of exactly the ellipse's area, so
/// the areas of one ellipse over cells that cover it sum to pi a b up to rounding. A disc
/// lying exactly in a face between two cells counts once, in the upper cell (cells are
/// half-open, [min, max), except the last along each axis). Each disc is tested only against the
/// cells its bounding box overlaps whose box its plane crosses. Parallel (TBB) and
/// deterministic: sums are formed in disc order whatever the thread count.
std::vector<double> p32Grid(const geometry::FractureNetwork& network, const CellGrid& grid);

}  // namespace rockmass::rqd
