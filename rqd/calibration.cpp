#include "rqd/calibration.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rockmass::rqd {

double thinningUniform(std::uint64_t seed, std::int64_t disc_id) {
  // SplitMix64 finaliser of a Weyl-sequence state built from the seed and the id.
  std::uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (static_cast<std::uint64_t>(disc_id) + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  // 53 bits, shifted by half an ulp: never 0 or 1.
  return (static_cast<double>(z >> 11) + 0.5) * 0x1.0p-53;
}

geometry::DfnSpec scaleIntensity(geometry::DfnSpec spec, std::span<const int> sets, double factor) {
  if (!(std::isfinite(factor) && factor > 0.0)) {
    throw std::invalid_argument("an intensity multiplier must be > 0, got " +
                                std::to_string(factor));
  }
  for (const int index : sets) {
    if (index < 0 || index >= static_cast<int>(spec.joint_sets.size())) {
      throw std::invalid_argument("no joint set with index " + std::to_string(index));
    }
    geometry::JointSetSpec& set = spec.joint_sets[static_cast<std::size_t>(index)];
    if (set.p32) *set.p32 *= factor;
    if (set.spacing) {
      // The spacing X becomes X / factor: every parameter of its distribution scales.
      geometry::DistributionSpec& s = *set.spacing;
      s.mean /= factor;
      s.std /= factor;
      if (s.min) *s.min /= factor;
      if (s.max) *s.max /= factor;
    }
  }
  return spec;
}

std::vector<ThinnedHole> thinnedHoles(const ScanlineScene& scene,
                                      const geometry::FractureNetwork& network,
                                      std::span<const Borehole> holes, std::span<const int> sets,
                                      std::uint64_t seed, double max_multiplier) {
  std::vector<ThinnedHole> result;
  for (const Borehole& hole : holes) {
    ThinnedHole thinned;
    thinned.length = hole.length;
    for (const ScanlineHit& hit : scene.hits(hole.collar, hole.end())) {
      // Disc ids are 1..N in network order.
      const geometry::Disc& disc = network.discs.at(static_cast<std::size_t>(hit.disc_id - 1));
      const bool in_group = std::find(sets.begin(), sets.end(), disc.set) != sets.end();
      thinned.hits.push_back(std::clamp(hit.t, 0.0, hole.length));
      thinned.birth.push_back(in_group ? thinningUniform(seed, disc.id) * max_multiplier : -1.0);
    }
    result.push_back(std::move(thinned));
  }
  return result;
}

std::vector<double> hitsAt(const ThinnedHole& hole, double multiplier) {
  std::vector<double> hits;
  for (std::size_t i = 0; i < hole.hits.size(); ++i) {
    if (hole.birth[i] < multiplier) hits.push_back(hole.hits[i]);
  }
  return hits;
}

std::vector<double> simulateIntervals(std::span<const ThinnedHole> holes,
                                      std::span<const LoggedInterval> measured, double multiplier,
                                      double threshold, double merge_distance) {
  std::vector<double> simulated(measured.size());
  const double thresholds[] = {threshold};
  for (std::size_t h = 0; h < holes.size(); ++h) {
    std::vector<DepthInterval> intervals;
    std::vector<std::size_t> where;
    for (std::size_t i = 0; i < measured.size(); ++i) {
      if (measured[i].hole != static_cast<int>(h)) continue;
      intervals.push_back(measured[i].interval);
      where.push_back(i);
    }
    if (intervals.empty()) continue;
    const std::vector<double> values = intervalsRqd(hitsAt(holes[h], multiplier), holes[h].length,
                                                    intervals, thresholds, merge_distance);
    for (std::size_t j = 0; j < where.size(); ++j) simulated[where[j]] = values[j];
  }
  return simulated;
}

CalibrationResult calibrateMultiplier(std::span<const ThinnedHole> holes,
                                      std::span<const LoggedInterval> measured,
                                      const CalibrationSettings& settings) {
  if (measured.empty()) throw std::invalid_argument("calibration needs a measured log");
  if (!(settings.min_multiplier > 0.0 && settings.max_multiplier > settings.min_multiplier &&
        settings.max_evaluations >= 2 && settings.tolerance >= 0.0)) {
    throw std::invalid_argument(
        "calibration needs 0 < min multiplier < max multiplier, at least 2 evaluations and a "
        "tolerance >= 0");
  }
  CalibrationResult result;
  const auto bias = [&](double m) {
    const std::vector<double> simulated =
        simulateIntervals(holes, measured, m, settings.threshold, settings.merge_distance);
    result.steps.push_back({m, logError(simulated, measured)});
    return result.steps.back().error.bias;
  };
  // The bias never increases with m (see the header): f(lo) >= 0 >= f(hi) brackets the root.
  double lo = settings.min_multiplier;
  double hi = settings.max_multiplier;
  double f_lo = bias(lo);
  double f_hi = bias(hi);
  result.bracketed = f_lo >= 0.0 && f_hi <= 0.0;
  const double width_tolerance = 1e-6 * settings.max_multiplier;
  const auto done = [&] {
    return std::abs(f_lo) <= settings.tolerance || std::abs(f_hi) <= settings.tolerance ||
           hi - lo <= width_tolerance;
  };
  // Values the secant uses at each end: the bias, or a fraction of it (Illinois).
  double w_lo = f_lo;
  double w_hi = f_hi;
  int last_side = 0;  // which end moved last: -1 lo, +1 hi
  while (result.bracketed && !done() &&
         static_cast<int>(result.steps.size()) < settings.max_evaluations) {
    // Secant (false position) through the two ends; bisection if it falls outside.
    double c = (lo * w_hi - hi * w_lo) / (w_hi - w_lo);
    if (!(c > lo && c < hi)) c = 0.5 * (lo + hi);
    const double f_c = bias(c);
    if (f_c > 0.0) {
      lo = c;
      f_lo = w_lo = f_c;
      // Illinois: when the same end moves twice, halve the value kept at the other end,
      // so that the secant reaches across it.
      if (last_side == -1) w_hi *= 0.5;
      last_side = -1;
    } else {
      hi = c;
      f_hi = w_hi = f_c;
      if (last_side == +1) w_lo *= 0.5;
      last_side = +1;
    }
  }
  result.converged = result.bracketed && done();
  const auto best = std::min_element(result.steps.begin(), result.steps.end(),
                                     [](const CalibrationStep& p, const CalibrationStep& q) {
                                       return std::abs(p.error.bias) < std::abs(q.error.bias);
                                     });
  result.multiplier = best->multiplier;
  result.error = best->error;
  result.evaluations = static_cast<int>(result.steps.size());
  return result;
}

}  // namespace rockmass::rqd
