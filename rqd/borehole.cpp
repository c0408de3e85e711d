#include "rqd/borehole.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rqd/line_orientation.h"

namespace rockmass::rqd {

geometry::Vec3 Borehole::direction() const {
  return directionFromTrendPlunge({azimuth, plunge});
}

std::vector<DepthInterval> coreRuns(double length, double run_length) {
  if (!(std::isfinite(length) && length > 0.0 && std::isfinite(run_length) && run_length > 0.0)) {
    throw std::invalid_argument("core runs need a hole length > 0 and a run length > 0, got " +
                                std::to_string(length) + " and " + std::to_string(run_length));
  }
  if (length / run_length > 1e7) {
    throw std::invalid_argument("a hole of " + std::to_string(length) + " m in runs of " +
                                std::to_string(run_length) + " m would make over 10^7 runs");
  }
  std::vector<DepthInterval> runs;
  for (long k = 0; static_cast<double>(k) * run_length < length; ++k) {
    // Both ends from the same expression (k r), so consecutive runs share their boundary.
    const double to = static_cast<double>(k + 1) * run_length;
    runs.push_back({static_cast<double>(k) * run_length, std::min(to, length)});
  }
  return runs;
}

std::vector<double> intervalsRqd(std::span<const double> hits, double hole_length,
                                 std::span<const DepthInterval> intervals,
                                 std::span<const double> thresholds, double merge_distance) {
  for (const double t : thresholds) {
    if (!(std::isfinite(t) && t >= 0.0)) {
      throw std::invalid_argument("RQD threshold (m) must be finite and >= 0, got " +
                                  std::to_string(t));
    }
  }
  for (const DepthInterval& interval : intervals) {
    if (!(interval.from >= 0.0 && interval.to <= hole_length && interval.to > interval.from)) {
      throw std::invalid_argument(
          "depth interval [" + std::to_string(interval.from) + ", " + std::to_string(interval.to) +
          "] m is empty or outside the hole [0, " + std::to_string(hole_length) + "] m");
    }
  }
  const std::vector<double> pieces = intactPieces(hits, hole_length, merge_distance);
  std::vector<double> result;
  result.reserve(intervals.size() * thresholds.size());
  for (const DepthInterval& interval : intervals) {
    for (const double t : thresholds) {
      double credited = 0.0;
      double start = 0.0;
      for (const double piece : pieces) {
        const double end = start + piece;
        if (piece >= t) {
          credited += std::max(0.0, std::min(end, interval.to) - std::max(start, interval.from));
        }
        start = end;
      }
      result.push_back(std::min(100.0, 100.0 * credited / (interval.to - interval.from)));
    }
  }
  return result;
}

std::vector<double> boreholeHits(const ScanlineScene& scene, const Borehole& hole) {
  const std::vector<ScanlineHit> hits = scene.hits(hole.collar, hole.end());
  std::vector<double> positions(hits.size());
  std::transform(hits.begin(), hits.end(), positions.begin(),
                 [&](const ScanlineHit& h) { return std::clamp(h.t, 0.0, hole.length); });
  return positions;
}

LogError logError(std::span<const double> simulated, std::span<const LoggedInterval> measured) {
  if (simulated.size() != measured.size()) {
    throw std::invalid_argument("logError needs one simulated value per measured interval");
  }
  LogError error;
  double squares = 0.0;
  double bias = 0.0;
  for (std::size_t i = 0; i < measured.size(); ++i) {
    const double w = measured[i].interval.to - measured[i].interval.from;
    const double difference = simulated[i] - measured[i].rqd;
    bias += w * difference;
    squares += w * difference * difference;
    error.length += w;
    error.intervals += 1;
  }
  if (error.length > 0.0) {
    error.bias = bias / error.length;
    error.rms = std::sqrt(squares / error.length);
  }
  return error;
}

std::vector<LogError> logErrorPerHole(std::span<const double> simulated,
                                      std::span<const LoggedInterval> measured, int hole_count) {
  std::vector<LogError> errors;
  for (int hole = 0; hole < hole_count; ++hole) {
    std::vector<double> sim;
    std::vector<LoggedInterval> meas;
    for (std::size_t i = 0; i < measured.size(); ++i) {
      if (measured[i].hole != hole) continue;
      sim.push_back(simulated[i]);
      meas.push_back(measured[i]);
    }
    errors.push_back(logError(sim, meas));
  }
  return errors;
}

}  // namespace rockmass::rqd
