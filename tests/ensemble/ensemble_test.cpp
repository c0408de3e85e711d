// The ensemble's sampling (seeds, Monte Carlo and Latin hypercube draws, inverse distribution
// functions) and the aggregate's statistics, each against a known answer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <vector>

#include "ensemble/aggregate.h"
#include "ensemble/sampling.h"

namespace rockmass::ensemble {
namespace {

io::UncertainInput input(std::string kind, double mean, double std) {
  io::UncertainInput in;
  in.key.assign(1, 'k');
  in.distribution.swap(kind);
  in.mean = mean;
  in.std = std;
  return in;
}

TEST(EnsembleSampling, SeedsDependOnTheSceneSeedAndIndexOnly) {
  // The derivation is part of the contract (realization i is the same in every version that
  // keeps it): SplitMix64-based, pinned here.
  EXPECT_EQ(realizationSeed(42, 0), realizationSeed(42, 0));
  EXPECT_NE(realizationSeed(42, 0), realizationSeed(42, 1));
  EXPECT_NE(realizationSeed(42, 0), realizationSeed(43, 0));
  EXPECT_NE(realizationSeed(42, 0), 42u);
  std::set<std::uint64_t> seeds;
  for (int i = 0; i < 10000; ++i) seeds.insert(realizationSeed(7, i));
  EXPECT_EQ(seeds.size(), 10000u);
}

TEST(EnsembleSampling, MonteCarloDrawsAreUniform) {
  io::Uncertainty u;
  u.inputs = {input("normal", 0, 1), input("normal", 0, 1)};
  const int n = 20000;
  double sum = 0.0, cross = 0.0;
  int below_tenth = 0;
  for (int i = 0; i < n; ++i) {
    const double a = probabilityOf(u, 1, i, 0), b = probabilityOf(u, 1, i, 1);
    ASSERT_GT(a, 0.0);
    ASSERT_LT(a, 1.0);
    sum += a;
    cross += (a - 0.5) * (b - 0.5);
    below_tenth += a < 0.1;
  }
  // Mean 1/2 (sd of the mean 0.289 / sqrt(n) = 0.002: 4 sd), the two inputs uncorrelated
  // (sd of the covariance 1/12 / sqrt(n) = 0.0006), the lowest decile 10 % (sd 0.21 %).
  EXPECT_NEAR(sum / n, 0.5, 0.008);
  EXPECT_NEAR(cross / n, 0.0, 0.0024);
  EXPECT_NEAR(static_cast<double>(below_tenth) / n, 0.1, 0.0085);
}

TEST(EnsembleSampling, LatinHypercubePutsOneRealizationInEachStratum) {
  // McKay, Beckman & Conover (1979): each of the n strata of every input holds one of the n
  // realizations, the inputs' permutations independent.
  io::Uncertainty u;
  u.latin_hypercube = true;
  u.size = 50;
  u.inputs = {input("normal", 0, 1), input("normal", 0, 1)};
  std::set<int> first, second;
  int same = 0;
  for (int i = 0; i < u.size; ++i) {
    const int a = static_cast<int>(std::floor(probabilityOf(u, 3, i, 0) * u.size));
    const int b = static_cast<int>(std::floor(probabilityOf(u, 3, i, 1) * u.size));
    first.insert(a);
    second.insert(b);
    same += a == b;
  }
  EXPECT_EQ(first.size(), 50u);
  EXPECT_EQ(second.size(), 50u);
  EXPECT_LT(same, 5);  // two random permutations agree at ~1 place
  EXPECT_THROW(probabilityOf(u, 3, 50, 0), std::out_of_range);
}

TEST(EnsembleSampling, QuantilesAreTheDistributionsInverses) {
  // Normal: the 97.5 % point is the mean + 1.959964 sd.
  EXPECT_NEAR(quantile(input("normal", 0.6, 0.1), 0.975), 0.6 + 0.1959964, 1e-6);
  // Truncated to [0.5, 0.7] (symmetric): its median is the mean, every value inside.
  io::UncertainInput t = input("normal", 0.6, 0.1);
  t.min = 0.5;
  t.max = 0.7;
  EXPECT_NEAR(quantile(t, 0.5), 0.6, 1e-12);
  EXPECT_GE(quantile(t, 1e-9), 0.5);
  EXPECT_LE(quantile(t, 1 - 1e-9), 0.7);
  // Truncated on one side at the mean: half the mass, so p = 0.5 is the 75 % point.
  io::UncertainInput half = input("normal", 0.0, 1.0);
  half.min = 0.0;
  EXPECT_NEAR(quantile(half, 0.5), 0.6744898, 1e-6);
  // Uniform, triangular (mode at max: F = ((x - a) / (b - a))^2, median a + (b - a)/sqrt 2).
  io::UncertainInput uni = input("uniform", 0, 0);
  uni.min = 2.0;
  uni.max = 4.0;
  EXPECT_DOUBLE_EQ(quantile(uni, 0.25), 2.5);
  io::UncertainInput tri = input("triangular", 0, 0);
  tri.min = 1.0;
  tri.max = 3.0;
  tri.mode = 3.0;
  EXPECT_NEAR(quantile(tri, 0.5), 1.0 + 2.0 / std::sqrt(2.0), 1e-9);
  // Lognormal given the value's mean and sd: a Latin hypercube of 20 000 reproduces both.
  io::Uncertainty u;
  u.latin_hypercube = true;
  u.size = 20000;
  u.inputs = {input("lognormal", 2.0, 1.5)};
  std::vector<double> values;
  for (int i = 0; i < u.size; ++i) values.push_back(sampleInputs(u, 5, i)[0]);
  const Stats s = statsOf(values);
  EXPECT_NEAR(s.mean, 2.0, 0.005 * 2.0);
  EXPECT_NEAR(s.std, 1.5, 0.03 * 1.5);  // the heavy tail converges slower
  EXPECT_GT(s.min, 0.0);
}

TEST(EnsembleSampling, ListInputsTakeTheirValuesInTurn) {
  io::Uncertainty u;
  io::UncertainInput list = input("list", 0, 0);
  list.values = {10, 20, 30};
  u.inputs = {list};
  EXPECT_EQ(sampleInputs(u, 1, 0)[0], 10);
  EXPECT_EQ(sampleInputs(u, 1, 4)[0], 20);
  EXPECT_EQ(sampleInputs(u, 99, 5)[0], 30);
}

TEST(EnsembleAggregate, StatisticsOfAKnownSample) {
  // 1..10: mean 5.5, sample sd sqrt(55/6) = 3.02765; numpy's default percentiles (linear
  // between order statistics): p05 = 1.45, p50 = 5.5, p95 = 9.55. NaN is left out.
  std::vector<double> v{4, 1, 9, 10, 2, std::numeric_limits<double>::quiet_NaN(), 3, 8, 5, 7, 6};
  const Stats s = statsOf(v);
  EXPECT_EQ(s.n, 10);
  EXPECT_DOUBLE_EQ(s.mean, 5.5);
  EXPECT_NEAR(s.std, std::sqrt(55.0 / 6.0), 1e-12);
  EXPECT_NEAR(s.p05, 1.45, 1e-12);
  EXPECT_NEAR(s.p50, 5.5, 1e-12);
  EXPECT_NEAR(s.p95, 9.55, 1e-12);
  EXPECT_EQ(s.min, 1.0);
  EXPECT_EQ(s.max, 10.0);
  EXPECT_NEAR(s.ci95, 1.959963984540054 * std::sqrt(55.0 / 6.0) / std::sqrt(10.0), 1e-12);
  EXPECT_EQ(statsOf({}).n, 0);
}

TEST(EnsembleAggregate, SpearmanRankCorrelation) {
  const std::vector<double> x{1, 2, 3, 4, 5, 6};
  std::vector<double> cube, reverse;
  for (double a : x) {
    cube.push_back(a * a * a);
    reverse.push_back(-a);
  }
  EXPECT_DOUBLE_EQ(spearman(x, cube), 1.0);  // monotone, not linear
  EXPECT_DOUBLE_EQ(spearman(x, reverse), -1.0);
  // Ties take their mean rank (scipy.stats.spearmanr([1, 2, 2, 3], [1, 3, 2, 4]) = 0.9486833).
  EXPECT_NEAR(spearman({1, 2, 2, 3}, {1, 3, 2, 4}), 0.9486832980505138, 1e-12);
  EXPECT_TRUE(std::isnan(spearman({1, 1, 1}, {1, 2, 3})));  // a constant input
}

TEST(EnsembleAggregate, ProbabilityBelowATargetCountsTheKnownValues) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Probability p = probabilityBelow({0.8, 1.2, 0.9, nan, 1.5}, 1.0);
  EXPECT_EQ(p.below, 2);
  EXPECT_EQ(p.known, 4);
  EXPECT_EQ(p.undetermined, 1);
  EXPECT_DOUBLE_EQ(p.p, 0.5);
  EXPECT_DOUBLE_EQ(p.standard_error, std::sqrt(0.25 / 4));
  // Factors outside the list tried: decided by their bracket where it reaches the target.
  const Probability q =
      probabilityBelow({nan, nan, nan, 1.2}, 1.0, {1.5, nan, 0.8, 1.1}, {nan, 0.7, 1.2, 1.3});
  EXPECT_EQ(q.known, 3);  // stable at 1.5 >= 1: not below; unstable at 0.7 <= 1: below
  EXPECT_EQ(q.below, 1);
  EXPECT_EQ(q.undetermined, 1);  // between 0.8 and 1.2
}

}  // namespace
}  // namespace rockmass::ensemble
