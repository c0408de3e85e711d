#include "rqd/rqd_volume.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "geometry/interrupt.h"
#include "rqd/directions.h"
#include "rqd/p32_grid.h"

namespace rockmass::rqd {
namespace {

using geometry::Vec3;

/// Progress is reported this many times at most.
constexpr std::int64_t kProgressSteps = 100;

/// "(x, y, z) - (x, y, z)" of a box (m), at the default stream precision (6 digits).
std::string boxText(const geometry::Box& box) {
  std::ostringstream text;
  text << "(" << box.min.x() << ", " << box.min.y() << ", " << box.min.z() << ") - (" << box.max.x()
       << ", " << box.max.y() << ", " << box.max.z() << ")";
  return text.str();
}

}  // namespace

void validateVolumeSpec(const VolumeSpec& spec, const geometry::Box& domain) {
  if (spec.thresholds.empty()) {
    throw std::invalid_argument("an RQD volume needs at least one threshold");
  }
  for (double t : spec.thresholds) {
    if (!(std::isfinite(t) && t >= 0.0)) {
      throw std::invalid_argument("RQD thresholds must be finite and >= 0 m, got " +
                                  std::to_string(t));
    }
  }
  if (!(std::isfinite(spec.scanline_length) && spec.scanline_length > 0.0)) {
    throw std::invalid_argument("RQD volume scanline length must be finite and > 0 m, got " +
                                std::to_string(spec.scanline_length));
  }
  if (spec.direction_count < 1) {
    throw std::invalid_argument("an RQD volume needs at least one direction, got " +
                                std::to_string(spec.direction_count));
  }
  if (!(std::isfinite(spec.merge_distance) && spec.merge_distance >= 0.0)) {
    throw std::invalid_argument("merge distance must be finite and >= 0 m, got " +
                                std::to_string(spec.merge_distance));
  }
  // Rounding slack: a region equal to the domain up to the last bits is accepted.
  const double slack = 1e-9 * domain.diagonal();
  if ((spec.region.min.array() < domain.min.array() - slack).any() ||
      (spec.region.max.array() > domain.max.array() + slack).any()) {
    throw std::invalid_argument("the RQD volume region " + boxText(spec.region) +
                                " must lie inside the rock domain " + boxText(domain));
  }
  (void)cellGridIn(spec.region, spec.cell_size);  // throws for a bad cell size or region
}

namespace {

/// Sum over `axes` of RQD(t) of the scanlines through `center`, clipped to `domain`, into
/// `sums` (one per threshold); returns how many scanlines had length. `hits`, `distances`
/// and `values` (one per threshold) are work buffers.
int sumRqd(const ScanlineScene& scene, const geometry::Box& domain, const Vec3& center,
           const std::vector<Vec3>& axes, const VolumeSpec& spec, std::vector<ScanlineHit>& hits,
           std::vector<double>& distances, std::vector<double>& values, std::vector<double>& sums) {
  std::fill(sums.begin(), sums.end(), 0.0);
  int used = 0;
  const double half = 0.5 * spec.scanline_length;
  for (const Vec3& axis : axes) {
    const Vec3 from = center - half * axis;
    const Vec3 to = center + half * axis;
    const std::optional<std::array<double, 2>> inside = clipSegmentToBox(from, to, domain);
    if (!inside || !((*inside)[1] > (*inside)[0])) continue;
    const Vec3 start = from + (*inside)[0] * (to - from);
    const Vec3 end = from + (*inside)[1] * (to - from);
    // From the parameters, not |end - start|: an unclipped scanline then has exactly the
    // length asked for, and RQD(t = length) of an unbroken scanline is exactly 100.
    const double length = ((*inside)[1] - (*inside)[0]) * spec.scanline_length;
    scene.hits(start, end, hits);
    distances.clear();
    // Hits lie in [0, |end - start|] by contract; min() guards the last rounding bit.
    for (const ScanlineHit& hit : hits) distances.push_back(std::min(hit.t, length));
    rqd(distances, length, spec.thresholds, values, spec.merge_distance);
    for (std::size_t t = 0; t < sums.size(); ++t) sums[t] += values[t];
    ++used;
  }
  return used;
}

}  // namespace

std::optional<std::array<double, 2>> clipSegmentToBox(const Vec3& start, const Vec3& end,
                                                      const geometry::Box& box) {
  return geometry::lineInterval(box, start, end - start, 0.0, 1.0);
}

RqdVolume computeRqdVolume(const ScanlineScene& scene, const geometry::FractureNetwork& network,
                           const VolumeSpec& spec, const VolumeProgress& progress) {
  validateVolumeSpec(spec, network.domain);
  RqdVolume volume;
  volume.grid = cellGridIn(spec.region, spec.cell_size);
  volume.thresholds = spec.thresholds;
  volume.scanline_length = spec.scanline_length;
  volume.direction_count = spec.direction_count;
  volume.p32 = p32Grid(network, volume.grid);

  const std::vector<Vec3> axes = scanlineAxes(spec.direction_count);
  const std::int64_t cells = volume.grid.cellCount();
  const std::size_t threshold_count = spec.thresholds.size();
  volume.mean_rqd.assign(threshold_count, std::vector<double>(static_cast<std::size_t>(cells)));

  const auto computeCells = [&](const tbb::blocked_range<std::int64_t>& range) {
    std::vector<ScanlineHit> hits;
    std::vector<double> distances;
    std::vector<double> values(threshold_count);
    std::vector<double> sums(threshold_count);
    for (std::int64_t cell = range.begin(); cell != range.end(); ++cell) {
      const auto [i, j, k] = volume.grid.coordinates(cell);
      const int used = sumRqd(scene, network.domain, volume.grid.cellCenter(i, j, k), axes, spec,
                              hits, distances, values, sums);
      // Cell centres lie at least half a cell inside the domain, so every axis has length.
      assert(used > 0);
      for (std::size_t t = 0; t < threshold_count; ++t) {
        volume.mean_rqd[t][static_cast<std::size_t>(cell)] = sums[t] / used;
      }
    }
  };
  // Batches of cells in parallel; progress is reported between batches, on this thread.
  const std::int64_t batch =
      std::max<std::int64_t>(1, (cells + kProgressSteps - 1) / kProgressSteps);
  for (std::int64_t first = 0; first < cells; first += batch) {
    const std::int64_t last = std::min(cells, first + batch);
    throwIfInterrupted("the RQD volume");
    tbb::parallel_for(tbb::blocked_range<std::int64_t>(first, last), computeCells);
    if (progress) progress(static_cast<double>(last) / static_cast<double>(cells));
  }
  return volume;
}

}  // namespace rockmass::rqd
