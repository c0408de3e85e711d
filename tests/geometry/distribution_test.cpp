// Sampled distributions against their exact CDFs (Kolmogorov-Smirnov) and moments.
#include "geometry/distribution.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace rockmass::geometry {
namespace {

constexpr int kSamples = 10'000;
// Kolmogorov-Smirnov critical value at significance 0.001 for n = 10^4: 1.949 / sqrt(n).
// The seed is fixed, so the test is deterministic; a sampler with a wrong parameterisation
// (e.g. lognormal mean/std taken in log space) gives D of 0.1 or more.
const double kKsCritical = 1.949 / std::sqrt(static_cast<double>(kSamples));

DistributionSpec spec(DistributionKind kind, double mean, double std,
                      std::optional<double> min = std::nullopt,
                      std::optional<double> max = std::nullopt) {
  return {kind, mean, std, min, max};
}

std::vector<double> draw(const Distribution& d, int n, std::uint64_t seed) {
  Rng rng = makeRng(seed, 0);
  std::vector<double> x(n);
  for (double& v : x) v = d.sample(rng);
  return x;
}

/// Kolmogorov-Smirnov statistic of the sample against the distribution's own CDF.
double ksStatistic(std::vector<double> x, const Distribution& d) {
  std::sort(x.begin(), x.end());
  double worst = 0.0;
  const double n = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double f = d.cdf(x[i]);
    worst = std::max({worst, std::abs(f - i / n), std::abs((i + 1) / n - f)});
  }
  return worst;
}

/// Mean and std of the truncated distribution by Simpson's rule on its density (finite
/// window); 20000 panels make the quadrature error negligible against 2%.
std::pair<double, double> momentsByQuadrature(const Distribution& d) {
  const int panels = 20000;
  const double a = d.lower();
  const double b = d.upper();
  const double h = (b - a) / panels;
  double m0 = 0.0, m1 = 0.0, m2 = 0.0;
  for (int i = 0; i <= panels; ++i) {
    const double x = a + i * h;
    const double w = (i == 0 || i == panels) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    const double f = d.pdf(x) * w;
    m0 += f;
    m1 += f * x;
    m2 += f * x * x;
  }
  const double mean = m1 / m0;
  return {mean, std::sqrt(m2 / m0 - mean * mean)};
}

std::pair<double, double> sampleMoments(const std::vector<double>& x) {
  double sum = 0.0, sum2 = 0.0;
  for (double v : x) sum += v;
  const double mean = sum / x.size();
  for (double v : x) sum2 += (v - mean) * (v - mean);
  return {mean, std::sqrt(sum2 / (x.size() - 1))};
}

struct Case {
  const char* name;
  DistributionSpec spec;
};

// The families of Table 1 (Xiangjiaba), untruncated and truncated as in the table.
const Case kCases[] = {
    {"normal", spec(DistributionKind::Normal, 85.24, 13.32)},
    {"lognormal", spec(DistributionKind::Lognormal, 0.60, 0.79)},
    {"uniform", spec(DistributionKind::Uniform, 36.77, 11.44)},
    {"exponential", spec(DistributionKind::Exponential, 2.5, 0.0)},
    {"normal truncated", spec(DistributionKind::Normal, 85.24, 13.32, 45.54, 115.54)},
    {"lognormal truncated", spec(DistributionKind::Lognormal, 69.33, 9.83, 58.30, 88.30)},
    {"uniform truncated", spec(DistributionKind::Uniform, 345.84, 8.84, 326.57, 360.0)},
    {"exponential truncated", spec(DistributionKind::Exponential, 2.5, 0.0, 0.5, 6.0)},
};

TEST(Distribution, KolmogorovSmirnovForEveryFamily) {
  std::uint64_t seed = 11;
  for (const Case& c : kCases) {
    const Distribution d(c.spec);
    const std::vector<double> x = draw(d, kSamples, seed++);
    EXPECT_LT(ksStatistic(x, d), kKsCritical) << c.name;
    for (double v : x) {
      ASSERT_GE(v, d.lower()) << c.name;
      ASSERT_LE(v, d.upper()) << c.name;
    }
  }
}

TEST(Distribution, KolmogorovSmirnovDetectsAWrongDistribution) {
  // The test itself must be able to fail: lognormal samples against a normal of the same
  // mean and std are rejected.
  const Distribution lognormal(spec(DistributionKind::Lognormal, 0.60, 0.79));
  const Distribution normal(spec(DistributionKind::Normal, 0.60, 0.79));
  EXPECT_GT(ksStatistic(draw(lognormal, kSamples, 5), normal), 10 * kKsCritical);
}

TEST(Distribution, UntruncatedMomentsAreTheGivenMeanAndStd) {
  // n = 10^5; the heaviest case (lognormal CV 1.3) has a standard error of the mean of
  // 0.4% and of the std about 1.5%, so 2% on the mean and 5% on the std are safe.
  for (const Case& c : kCases) {
    if (c.spec.min || c.spec.max) continue;
    const Distribution d(c.spec);
    const auto [mean, std] = sampleMoments(draw(d, 100'000, 3));
    const double expected_std =
        c.spec.kind == DistributionKind::Exponential ? c.spec.mean : c.spec.std;
    EXPECT_NEAR(mean, c.spec.mean, 0.02 * c.spec.mean) << c.name;
    EXPECT_NEAR(std, expected_std, 0.05 * expected_std) << c.name;
  }
}

TEST(Distribution, TruncatedMomentsWithinTwoPercent) {
  // The target is the truncated distribution's own mean and std (quadrature of its
  // density). With n = 10^4 the standard errors are below 1%.
  for (const Case& c : kCases) {
    if (!c.spec.min && !c.spec.max) continue;
    const Distribution d(c.spec);
    const auto [target_mean, target_std] = momentsByQuadrature(d);
    const auto [mean, std] = sampleMoments(draw(d, kSamples, 4));
    EXPECT_NEAR(mean, target_mean, 0.02 * target_mean) << c.name;
    EXPECT_NEAR(std, target_std, 0.02 * target_std) << c.name;
  }
}

TEST(Distribution, TruncatedNormalMeanMatchesTheClosedForm) {
  // Johnson, Kotz & Balakrishnan: E = mu + sigma (phi(alpha) - phi(beta)) / Z. Checks the
  // density used by the quadrature above; 1e-6 is the quadrature's accuracy.
  const Distribution d(spec(DistributionKind::Normal, 85.24, 13.32, 45.54, 115.54));
  const auto phi = [](double z) { return std::exp(-0.5 * z * z) / std::sqrt(2 * M_PI); };
  const auto big_phi = [](double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); };
  const double alpha = (45.54 - 85.24) / 13.32;
  const double beta = (115.54 - 85.24) / 13.32;
  const double expected =
      85.24 + 13.32 * (phi(alpha) - phi(beta)) / (big_phi(beta) - big_phi(alpha));
  EXPECT_NEAR(momentsByQuadrature(d).first, expected, 1e-6);
  EXPECT_NEAR(d.windowMass(), big_phi(beta) - big_phi(alpha), 1e-15);
}

TEST(Distribution, DensityIsTheDerivativeOfTheCdf) {
  // Central differences with h = 1e-5 are accurate to ~1e-9 relative here; 1e-6 is ample.
  for (const Case& c : kCases) {
    const Distribution d(c.spec);
    const double spread = std::max(c.spec.std, c.spec.mean);
    const double lo = std::isfinite(d.lower()) ? d.lower() : c.spec.mean - 3 * spread;
    const double hi = std::isfinite(d.upper()) ? d.upper() : c.spec.mean + 3 * spread;
    for (double p : {0.1, 0.3, 0.5, 0.7, 0.9}) {
      const double x = lo + p * (hi - lo);
      const double h = 1e-5 * std::max(1.0, std::abs(x));
      const double numeric = (d.cdf(x + h) - d.cdf(x - h)) / (2 * h);
      EXPECT_NEAR(numeric, d.pdf(x), 1e-6 * std::max(1.0, d.pdf(x))) << c.name << " at " << x;
    }
  }
}

TEST(Distribution, ConstantAlwaysGivesItsValue) {
  const Distribution d(spec(DistributionKind::Constant, 2.01, 0.0));
  Rng rng = makeRng(1, 0);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(d.sample(rng), 2.01);
  EXPECT_EQ(d.cdf(2.0), 0.0);
  EXPECT_EQ(d.cdf(2.01), 1.0);
}

TEST(Distribution, BadSpecsAreRejectedWithTheReason) {
  const auto message = [](const DistributionSpec& s) {
    try {
      Distribution d(s);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(spec(DistributionKind::Lognormal, 0.6, 0.0)),
            "expected std > 0 for a lognormal distribution, got 0");
  EXPECT_EQ(message(spec(DistributionKind::Lognormal, -1.0, 0.5)),
            "expected mean > 0 for a lognormal distribution, got -1");
  EXPECT_EQ(message(spec(DistributionKind::Normal, 1.0, 1.0, 5.0, 2.0)),
            "min (5) is greater than max (2)");
  EXPECT_EQ(message(spec(DistributionKind::Normal, 0.0, 1.0, 50.0, 60.0)),
            "the truncation window [50, 60] holds only 0 of the probability mass of "
            "normal(mean=0, std=1) truncated to [50, 60] (at least 0.001 is needed); check min, "
            "max, mean and std");
  EXPECT_EQ(message(spec(DistributionKind::Uniform, 10.0, 1.0, 20.0, 30.0)),
            "the truncation window [20, 30] holds only 0 of the probability mass of "
            "uniform(mean=10, std=1) truncated to [20, 30] (at least 0.001 is needed); check "
            "min, max, mean and std");
}

TEST(Distribution, NarrowButPossibleWindowStillSamples) {
  // 3.5 to 4 standard deviations hold 2.0e-4, below the limit; 3 to 4 hold 1.3e-3: kept.
  EXPECT_THROW(Distribution(spec(DistributionKind::Normal, 0.0, 1.0, 3.5, 4.0)),
               std::invalid_argument);
  const Distribution d(spec(DistributionKind::Normal, 0.0, 1.0, 3.0, 4.0));
  EXPECT_NEAR(d.windowMass(), 1.3182e-3, 1e-6);
  EXPECT_LT(ksStatistic(draw(d, 2000, 9), d), 1.949 / std::sqrt(2000.0));
}

}  // namespace
}  // namespace rockmass::geometry
