#include "blocks/volume_statistics.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace rockmass::blocks {
namespace {

/// Newton steps below this fraction of k end the shape iteration. Newton converges
/// quadratically, so the root is then known to far better than this; a tighter value would
/// chase the rounding noise of the sums.
constexpr double kShapeRelativeTolerance = 1e-13;
/// Bound on the safeguarded Newton steps. Bisection alone would halve the initial bracket
/// (at most a factor 2 wide) below kShapeRelativeTolerance in about 45 steps.
constexpr int kMaxShapeIterations = 100;

void requireFinitePositive(std::span<const double> volumes) {
  for (std::size_t i = 0; i < volumes.size(); ++i) {
    if (!(std::isfinite(volumes[i]) && volumes[i] > 0.0)) {
      throw std::invalid_argument("block volume #" + std::to_string(i) + " is " +
                                  std::to_string(volumes[i]) +
                                  " m3; every volume must be finite and positive");
    }
  }
}

/// Left side g(k) of the profile equation and its derivative dg/dk.
struct ProfileValue {
  double residual = 0.0;  ///< g(k), unit of ln x
  double slope = 0.0;     ///< dg/dk = weighted variance of ln x + 1/k^2 (> 0)
};

/// g(k) = sum(w u) / sum(w) - 1/k - mean(u) with weights w = exp(k u). `log_offsets` are
/// u = ln x - max(ln x) <= 0: the equation is unchanged by this shift, and the weights stay
/// in (0, 1] so that no power x^k can overflow.
ProfileValue profileEquation(std::span<const double> log_offsets, double mean_offset,
                             double shape) {
  double weight_sum = 0.0;
  double weighted_sum = 0.0;
  for (double u : log_offsets) {
    const double w = std::exp(shape * u);
    weight_sum += w;
    weighted_sum += w * u;
  }
  const double weighted_mean = weighted_sum / weight_sum;
  double weighted_square_sum = 0.0;
  for (double u : log_offsets) {
    const double d = u - weighted_mean;
    weighted_square_sum += std::exp(shape * u) * d * d;
  }
  return {.residual = weighted_mean - 1.0 / shape - mean_offset,
          .slope = weighted_square_sum / weight_sum + 1.0 / (shape * shape)};
}

}  // namespace

VolumeStatistics volumeStatistics(std::span<const double> volumes) {
  if (volumes.empty()) {
    throw std::invalid_argument("volume statistics need at least one block volume, got none");
  }
  requireFinitePositive(volumes);
  VolumeStatistics stats;
  stats.count = volumes.size();
  stats.min = volumes.front();
  stats.max = volumes.front();
  for (double v : volumes) {
    stats.total += v;
    stats.min = std::min(stats.min, v);
    stats.max = std::max(stats.max, v);
  }
  stats.mean = stats.total / static_cast<double>(stats.count);
  return stats;
}

WeibullFit fitWeibull(std::span<const double> volumes) {
  if (volumes.size() < 2) {
    throw std::invalid_argument("a Weibull fit needs at least 2 volumes, got " +
                                std::to_string(volumes.size()));
  }
  requireFinitePositive(volumes);

  const double n = static_cast<double>(volumes.size());
  std::vector<double> log_offsets(volumes.size());
  std::transform(volumes.begin(), volumes.end(), log_offsets.begin(),
                 [](double v) { return std::log(v); });
  const double max_log = *std::max_element(log_offsets.begin(), log_offsets.end());
  double offset_sum = 0.0;
  for (double& u : log_offsets) {
    u -= max_log;
    offset_sum += u;
  }
  if (*std::min_element(log_offsets.begin(), log_offsets.end()) == 0.0) {
    throw std::invalid_argument(
        "all " + std::to_string(volumes.size()) +
        " volumes are equal (to the precision of their logarithms): the Weibull likelihood "
        "grows without bound in the shape, so there is no fit; supply varied volumes");
  }
  const double mean_offset = offset_sum / n;
  const auto profile = [&](double shape) {
    return profileEquation(log_offsets, mean_offset, shape);
  };

  // Start from Menon's (1963) moment estimate: ln x of a Weibull variable has standard
  // deviation pi / (sqrt(6) k).
  double square_sum = 0.0;
  for (double u : log_offsets) square_sum += (u - mean_offset) * (u - mean_offset);
  const double start = std::numbers::pi / (std::sqrt(6.0 * square_sum / n));

  // Bracket the root: g increases from -inf (k -> 0) to max(u) - mean(u) > 0 (k -> inf).
  const ProfileValue at_start = profile(start);
  double lower = start;
  double upper = start;
  if (at_start.residual < 0.0) {
    for (upper = 2.0 * start; profile(upper).residual < 0.0; upper *= 2.0) lower = upper;
  } else {
    for (lower = 0.5 * start; profile(lower).residual > 0.0; lower *= 0.5) upper = lower;
  }

  // Newton's method from the start, falling back to bisection whenever a step would leave
  // the bracket; each evaluation narrows the bracket from its side.
  double shape = start;
  ProfileValue value = at_start;
  int iterations = 0;
  while (value.residual != 0.0) {
    if (++iterations > kMaxShapeIterations) {
      throw std::runtime_error("Weibull fit: the shape did not converge in " +
                               std::to_string(kMaxShapeIterations) + " safeguarded Newton steps");
    }
    (value.residual < 0.0 ? lower : upper) = shape;
    const double newton = shape - value.residual / value.slope;
    const double next = (newton > lower && newton < upper) ? newton : 0.5 * (lower + upper);
    const double step = next - shape;
    shape = next;
    if (std::abs(step) <= kShapeRelativeTolerance * shape) break;
    value = profile(shape);
  }

  double weight_sum = 0.0;
  for (double u : log_offsets) weight_sum += std::exp(shape * u);
  const double scale = std::exp(max_log) * std::pow(weight_sum / n, 1.0 / shape);
  return {.shape = shape, .scale = scale, .iterations = iterations};
}

}  // namespace rockmass::blocks
