#pragma once
/// RQD and P32 volumes: on a regular grid of cubic cells, the mean RQD(t) of scanlines through
/// each cell centre over a set of directions, and the fracture intensity P32 of each cell.
#include <array>
#include <functional>
#include <optional>
#include <vector>

#include "geometry/box.h"
#include "geometry/fracture_network.h"
#include "rqd/cell_grid.h"
#include "rqd/embree_scene.h"
#include "rqd/scanline_rqd.h"

namespace rockmass::rqd {

/// What to compute (scene keys analysis.rqd.grid.*, see docs/rqd-volume.md).
struct VolumeSpec {
  geometry::Box region;            ///< box the grid fills (m); must lie inside the domain
  double cell_size = 0.0;          ///< cell edge length (m, > 0)
  double scanline_length = 0.0;    ///< length of each scanline, centred on a cell centre (m)
  int direction_count = 200;       ///< scanline axes per cell (>= 1), see scanlineAxes()
  std::vector<double> thresholds;  ///< RQD thresholds t (m, >= 0), at least one
  double merge_distance = kDefaultMergeDistance;  ///< hits closer than this are one (m)
};

/// The volumes, on `grid`; every per-cell array is in CellGrid index order (x fastest).
struct RqdVolume {
  CellGrid grid;                              ///< the cells
  std::vector<double> thresholds;             ///< RQD thresholds (m), as in the spec
  std::vector<std::vector<double>> mean_rqd;  ///< [threshold][cell]: mean RQD(t) (percent)
  std::vector<double> p32;                    ///< [cell]: fracture area per volume (m2/m3)
  double scanline_length = 0.0;               ///< scanline length (m)
  int direction_count = 0;                    ///< scanline axes per cell
};

/// Called on the calling thread with the fraction of cells done, in (0, 1], increasing.
using VolumeProgress = std::function<void(double fraction)>;

/// Computes the RQD and P32 volumes of `network` on the grid cellGridIn(spec.region,
/// spec.cell_size). `scene` must have been built from `network` (its form, exact or
/// triangulated, is the caller's choice).
///
/// RQD: for each cell and each axis d of scanlineAxes(spec.direction_count), the segment of
/// length spec.scanline_length centred on the cell centre along d is clipped to the rock
/// domain (network.domain), and RQD(t) of the clipped segment (rqd(), with
/// spec.merge_distance) is averaged over the axes with equal weights. Away from the domain
/// boundary no clipping happens; near it a scanline measures only rock.
/// P32: p32Grid(network, grid).
///
/// Parallel (TBB) and deterministic: each cell is computed alone, in a fixed order, so the
/// result does not depend on the thread count. Throws std::invalid_argument for a bad spec
/// (no thresholds, a negative or non-finite threshold, a non-positive scanline length or
/// cell size, fewer than one direction, a region outside the domain, or those of
/// cellGridIn()).
RqdVolume computeRqdVolume(const ScanlineScene& scene, const geometry::FractureNetwork& network,
                           const VolumeSpec& spec, const VolumeProgress& progress = {});

/// Checks `spec` against the rock `domain` without computing anything (cheap: callers check a
/// spec read from a file before long work). Throws std::invalid_argument, with a message that
/// says what is wrong, for exactly the specs computeRqdVolume() rejects.
void validateVolumeSpec(const VolumeSpec& spec, const geometry::Box& domain);

/// The part of the segment [start, end] (m) inside the closed `box`, as parameters
/// [t0, t1] of start + t (end - start), t in [0, 1]; nothing when the segment misses the box
/// (touching counts: t0 == t1). Slab method (Kay & Kajiya 1986).
std::optional<std::array<double, 2>> clipSegmentToBox(const geometry::Vec3& start,
                                                      const geometry::Vec3& end,
                                                      const geometry::Box& box);

}  // namespace rockmass::rqd
