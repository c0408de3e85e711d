#pragma once
/// Summary statistics of block volumes and their maximum-likelihood Weibull fit.
///
/// Likelihood equations of the two-parameter Weibull distribution
/// f(x) = (k / s) (x / s)^(k - 1) exp(-(x / s)^k) for a complete sample x_1..x_n:
///   shape k:  sum(x^k ln x) / sum(x^k) - 1/k - mean(ln x) = 0   (the profile equation)
///   scale s:  s = (mean(x^k))^(1/k)
/// Cohen, A. C. (1965), "Maximum likelihood estimation in the Weibull distribution based on
/// complete and on censored samples", Technometrics 7(4), 579-588; also
/// Johnson, Kotz & Balakrishnan (1994), Continuous Univariate Distributions, vol. 1, ch. 21.
#include <cstddef>
#include <span>

namespace rockmass::blocks {

/// Count, sum, extremes and mean of a list of block volumes.
struct VolumeStatistics {
  std::size_t count = 0;  ///< number of blocks
  double total = 0.0;     ///< sum of the volumes (m3)
  double min = 0.0;       ///< smallest volume (m3)
  double max = 0.0;       ///< largest volume (m3)
  double mean = 0.0;      ///< total / count (m3)
};

/// Statistics of `volumes` (m3, each finite and > 0). Throws std::invalid_argument for an
/// empty list or a volume that is not finite and positive.
VolumeStatistics volumeStatistics(std::span<const double> volumes);

/// A two-parameter Weibull distribution fitted by maximum likelihood.
struct WeibullFit {
  double shape = 0.0;  ///< shape k (dimensionless)
  double scale = 0.0;  ///< scale s (unit of the data, m3 for volumes)
  int iterations = 0;  ///< safeguarded Newton steps taken on the profile equation
};

/// Maximum-likelihood Weibull fit of `volumes` (m3, each finite and > 0): the root of the
/// profile equation for k (unique: its left side increases from -inf to a positive limit),
/// found by Newton's method safeguarded by bisection, then the scale equation.
/// Throws std::invalid_argument for fewer than 2 values, a value that is not finite and
/// positive, or values that are all equal (then the likelihood grows without bound in k).
WeibullFit fitWeibull(std::span<const double> volumes);

}  // namespace rockmass::blocks
