// Volume statistics and the maximum-likelihood Weibull fit.
// Analytical source: the Weibull likelihood equations of Cohen (1965), Technometrics 7(4),
// 579-588, and the asymptotic variances of the estimates, from the inverse Fisher
// information (Cohen 1965; Johnson, Kotz & Balakrishnan 1994, ch. 21):
//   Var(k^) = 6 k^2 / (pi^2 n),   Var(s^) = (1 + 6 (1 - gamma)^2 / pi^2) s^2 / (k^2 n)
//   = 1.1087 s^2 / (k^2 n), gamma = Euler's constant.
#include "blocks/volume_statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "geometry/random.h"

namespace rockmass::blocks {
namespace {

std::vector<double> weibullSample(double shape, double scale, int count, std::uint64_t seed) {
  geometry::Rng rng = geometry::makeRng(seed, /*stream=*/0);
  std::weibull_distribution<double> distribution(shape, scale);
  std::vector<double> sample(count);
  for (double& x : sample) x = distribution(rng);
  return sample;
}

// The shape equation exactly as written in the textbooks (no shifted logarithms), so that
// the test does not share the implementation's algebra.
double shapeEquationResidual(const std::vector<double>& x, double k) {
  double power_sum = 0.0;
  double power_log_sum = 0.0;
  double log_sum = 0.0;
  for (double xi : x) {
    power_sum += std::pow(xi, k);
    power_log_sum += std::pow(xi, k) * std::log(xi);
    log_sum += std::log(xi);
  }
  return power_log_sum / power_sum - 1.0 / k - log_sum / static_cast<double>(x.size());
}

double logLikelihood(const std::vector<double>& x, double k, double s) {
  double sum = 0.0;
  for (double xi : x) {
    sum += std::log(k / s) + (k - 1.0) * std::log(xi / s) - std::pow(xi / s, k);
  }
  return sum;
}

TEST(VolumeStatistics, ExactOnSmallList) {
  // Every value and partial sum is a short binary fraction, so the results are exact.
  const std::vector<double> volumes = {0.5, 2.0, 1.5, 4.0};
  const VolumeStatistics stats = volumeStatistics(volumes);
  EXPECT_EQ(stats.count, 4u);
  EXPECT_EQ(stats.total, 8.0);
  EXPECT_EQ(stats.min, 0.5);
  EXPECT_EQ(stats.max, 4.0);
  EXPECT_EQ(stats.mean, 2.0);
}

TEST(VolumeStatistics, RejectsEmptyAndNonPositiveVolumes) {
  EXPECT_THROW(volumeStatistics(std::vector<double>{}), std::invalid_argument);
  EXPECT_THROW(volumeStatistics(std::vector<double>{1.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(volumeStatistics(std::vector<double>{1.0, -2.0}), std::invalid_argument);
  EXPECT_THROW(volumeStatistics(std::vector<double>{1.0, std::nan("")}), std::invalid_argument);
}

TEST(WeibullFit, SolvesTwoPointCaseByHand) {
  // x = {1, e}: ln x = {0, 1}, and the shape equation e^k / (1 + e^k) - 1/k - 1/2 = 0 is
  // (k/2) tanh(k/2) = 1, whose root is k/2 = 1.19967864025773383 (30 digits by mpmath).
  // Then s = ((1 + e^k) / 2)^(1/k). Tolerance: the solver stops once a Newton step is below
  // 1e-13 k, and quadratic convergence leaves the root far closer than that; rounding of g
  // (~1e-16) over its slope dg/dk = 0.25 adds only ~1e-15.
  const std::vector<double> x = {1.0, std::numbers::e};
  const WeibullFit fit = fitWeibull(x);
  const double k = 2.0 * 1.19967864025773383;
  EXPECT_NEAR(fit.shape, k, 1e-13 * k);
  const double s = std::pow(0.5 * (1.0 + std::exp(k)), 1.0 / k);
  EXPECT_NEAR(fit.scale, s, 1e-13 * s);
}

TEST(WeibullFit, RecoversShapeAndScaleOfLargeSample) {
  // n = 1e4. Relative standard errors: shape sqrt(6)/pi/sqrt(n) = 0.78 %; scale
  // 1.053/(k sqrt(n)) = 0.88 % for k = 1.2 and 0.35 % for k = 3. The 3 % tolerance is at
  // least 3.4 standard errors for each, and the fixed seed makes the test deterministic.
  struct Case {
    double shape;
    double scale;  // m3
    std::uint64_t seed;
  };
  for (const Case& c : {Case{1.2, 0.5, 20240521}, Case{3.0, 10.0, 20240522}}) {
    const std::vector<double> x = weibullSample(c.shape, c.scale, 10000, /*seed=*/c.seed);
    const WeibullFit fit = fitWeibull(x);
    EXPECT_NEAR(fit.shape, c.shape, 0.03 * c.shape) << "true shape " << c.shape;
    EXPECT_NEAR(fit.scale, c.scale, 0.03 * c.scale) << "true shape " << c.shape;
    // Newton from Menon's moment estimate converges quadratically: about 4 steps.
    EXPECT_LE(fit.iterations, 10);
  }
}

TEST(WeibullFit, SatisfiesLikelihoodEquationsAndMaximisesLikelihood) {
  const std::vector<double> x = weibullSample(/*shape=*/1.5, /*scale=*/2.0, 10000, 7);
  const WeibullFit fit = fitWeibull(x);
  // The residual is a difference of O(1) terms (|ln x| < 4 here), each a sum of 1e4
  // rounded terms: rounding is at most ~n eps = 2e-12, so 1e-10 leaves a margin of 50.
  EXPECT_NEAR(shapeEquationResidual(x, fit.shape), 0.0, 1e-10);
  double power_sum = 0.0;
  for (double xi : x) power_sum += std::pow(xi, fit.shape);
  const double scale_power = std::pow(fit.scale, fit.shape);
  EXPECT_NEAR(scale_power, power_sum / static_cast<double>(x.size()), 1e-12 * scale_power);
  // A maximum, not just a stationary point: 0.1 % away in either parameter the
  // log-likelihood (about -1.5e4) drops by 1e-2 (half the Fisher information times the
  // squared step), far above the rounding of its sum (< 1e-7).
  const double best = logLikelihood(x, fit.shape, fit.scale);
  for (double factor : {0.999, 1.001}) {
    EXPECT_LT(logLikelihood(x, factor * fit.shape, fit.scale), best - 1e-4);
    EXPECT_LT(logLikelihood(x, fit.shape, factor * fit.scale), best - 1e-4);
  }
}

TEST(WeibullFit, IsEquivariantUnderScaling) {
  // Scaling the data by c scales s by c and leaves k unchanged (exactly, for the MLE). Only
  // the rounding of ln(c x) (~1e-16 relative) differs, so 1e-12 is a wide margin.
  const std::vector<double> x = weibullSample(/*shape=*/0.8, /*scale=*/3.0, 2000, 11);
  std::vector<double> scaled = x;
  for (double& v : scaled) v *= 1000.0;
  const WeibullFit fit = fitWeibull(x);
  const WeibullFit fit_scaled = fitWeibull(scaled);
  EXPECT_NEAR(fit_scaled.shape, fit.shape, 1e-12 * fit.shape);
  EXPECT_NEAR(fit_scaled.scale, 1000.0 * fit.scale, 1e-12 * fit_scaled.scale);
}

TEST(WeibullFit, RejectsDataWithoutFiniteMaximum) {
  EXPECT_THROW(fitWeibull(std::vector<double>{}), std::invalid_argument);
  EXPECT_THROW(fitWeibull(std::vector<double>{1.0}), std::invalid_argument);
  EXPECT_THROW(fitWeibull(std::vector<double>{1.0, 0.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(fitWeibull(std::vector<double>{1.0, -3.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(fitWeibull(std::vector<double>{2.5, 2.5, 2.5}), std::invalid_argument);
}

}  // namespace
}  // namespace rockmass::blocks
