// Intensity calibration with common random numbers: thinning variates, scaled specs,
// monotone bias, and recovery of a known multiplier from logs simulated with it.
#include "rqd/calibration.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/fracture_network.h"

namespace rockmass::rqd {
namespace {

using geometry::Vec3;

TEST(ThinningUniform, DeterministicUniformInTheOpenInterval) {
  // 1e5 variates: mean 1/2 and variance 1/12 within 5 standard errors (0.0046, 0.0014).
  constexpr int kCount = 100000;
  double sum = 0.0;
  double squares = 0.0;
  for (int id = 1; id <= kCount; ++id) {
    const double u = thinningUniform(42, id);
    ASSERT_GT(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    squares += (u - 0.5) * (u - 0.5);
  }
  EXPECT_NEAR(sum / kCount, 0.5, 0.0046);
  EXPECT_NEAR(squares / kCount, 1.0 / 12.0, 0.0014);
  EXPECT_EQ(thinningUniform(42, 17), thinningUniform(42, 17));
  EXPECT_NE(thinningUniform(42, 17), thinningUniform(43, 17));
}

geometry::JointSetSpec jointSet(const char* name, double dip_direction, double dip) {
  geometry::JointSetSpec s;
  s.name = name;
  s.orientation.fisher = true;
  s.orientation.fisher_dip_direction = dip_direction;
  s.orientation.fisher_dip = dip;
  s.orientation.kappa = 30.0;
  s.spacing = {geometry::DistributionKind::Lognormal, 1.2, 0.8, {}, {}};
  s.trace_length = {geometry::DistributionKind::Lognormal, 4.0, 2.0, {}, {}};
  return s;
}

TEST(ScaleIntensity, ScalesP32AndSpacingOfTheGroupOnly) {
  geometry::DfnSpec spec;
  spec.joint_sets = {jointSet("A", 0, 10), jointSet("B", 90, 70)};
  spec.joint_sets[1].spacing.reset();
  spec.joint_sets[1].p32 = 0.5;
  const int both[] = {0, 1};
  const geometry::DfnSpec scaled = scaleIntensity(spec, both, 2.0);
  EXPECT_DOUBLE_EQ(scaled.joint_sets[0].spacing->mean, 0.6);
  EXPECT_DOUBLE_EQ(scaled.joint_sets[0].spacing->std, 0.4);
  EXPECT_DOUBLE_EQ(*scaled.joint_sets[1].p32, 1.0);
  const int second[] = {1};
  EXPECT_DOUBLE_EQ(scaleIntensity(spec, second, 3.0).joint_sets[0].spacing->mean, 1.2);
  EXPECT_THROW(scaleIntensity(spec, second, 0.0), std::invalid_argument);
  const int bad[] = {2};
  EXPECT_THROW(scaleIntensity(spec, bad, 2.0), std::invalid_argument);
}

/// Four vertical 50 m holes in a network of two sets generated at multiplier 4, the set
/// group being set A only (set B stays as it is).
struct Fixture {
  std::vector<Borehole> holes;
  std::vector<ThinnedHole> thinned;
  Fixture() {
    geometry::DfnSpec spec;
    spec.domain = {Vec3(0, 0, -60), Vec3(40, 40, 0)};
    spec.joint_sets = {jointSet("A", 0, 10), jointSet("B", 90, 70)};
    const int group[] = {0};
    const geometry::FractureNetwork network =
        geometry::generateNetwork(scaleIntensity(spec, group, 4.0), 3);
    const ScanlineScene scene(network, DiscForm::ExactEllipse);
    for (int i = 0; i < 4; ++i) {
      std::string id = "H";
      id += std::to_string(i);
      holes.push_back({id, Vec3(10 + 20 * (i % 2), 10 + 20 * (i / 2), 0), 0.0, 90.0, 50.0});
    }
    thinned = thinnedHoles(scene, network, holes, group, 3, 4.0);
  }
};

/// A log of 3 m runs on every hole, with RQD(1 m) simulated at `multiplier`. The 1 m
/// threshold keeps the log sensitive to the intensity at every multiplier of the bracket;
/// RQD(0.1 m) stays near 100 in sparse rock and only moves when a piece under 0.1 m
/// appears, so it pins the multiplier down far less.
std::vector<LoggedInterval> simulatedLog(const Fixture& f, double multiplier) {
  std::vector<LoggedInterval> log;
  for (int h = 0; h < 4; ++h) {
    for (const DepthInterval& run : coreRuns(50.0, 3.0)) log.push_back({h, run, 0.0});
  }
  const std::vector<double> values =
      simulateIntervals(f.thinned, log, multiplier, /*threshold=*/1.0);
  for (std::size_t i = 0; i < log.size(); ++i) log[i].rqd = values[i];
  return log;
}

TEST(Calibration, RecoversAKnownMultiplier) {
  const Fixture f;
  for (const double truth : {0.6, 1.7, 2.5}) {
    const std::vector<LoggedInterval> measured = simulatedLog(f, truth);
    CalibrationSettings settings;
    settings.threshold = 1.0;
    settings.tolerance = 0.0;  // only a log identical to the measured one is a root
    const CalibrationResult result = calibrateMultiplier(f.thinned, measured, settings);
    EXPECT_TRUE(result.bracketed);
    EXPECT_TRUE(result.converged);
    EXPECT_EQ(result.error.bias, 0.0);
    EXPECT_EQ(result.error.rms, 0.0);
    // The exact answer is the range of multipliers whose log equals the measured one: it
    // ends at the nearest births (below and above the truth) whose disc changes RQD(1 m).
    // The result must lie in it, and the range must be narrow for the test to mean much.
    std::vector<double> births;
    for (const ThinnedHole& hole : f.thinned) {
      for (const double birth : hole.birth) {
        if (birth >= 0.0) births.push_back(birth);
      }
    }
    std::sort(births.begin(), births.end());
    const auto same_log = [&](double m) {
      return simulateIntervals(f.thinned, measured, m, 1.0) ==
             simulateIntervals(f.thinned, measured, truth, 1.0);
    };
    double below = 0.0;
    double above = settings.max_multiplier;
    for (auto it = std::lower_bound(births.begin(), births.end(), truth); it != births.end();
         ++it) {
      if (!same_log(std::nextafter(*it, 10.0))) {
        above = *it;
        break;
      }
    }
    for (auto it = std::lower_bound(births.begin(), births.end(), truth); it != births.begin();) {
      --it;
      if (!same_log(*it)) {
        below = *it;
        break;
      }
    }
    EXPECT_GT(result.multiplier, below) << truth;
    EXPECT_LE(result.multiplier, above) << truth;
    EXPECT_LT(above - below, 0.1 * truth);
    // Secant steps with the Illinois fix: fewer evaluations than the ~22 bisection needs to
    // shrink the bracket to a step of ~1e-3 (the births are ~5e-3 apart here).
    EXPECT_LE(result.evaluations, 20);
    // With common random numbers the bias never increases with m.
    std::vector<CalibrationStep> steps = result.steps;
    std::sort(steps.begin(), steps.end(),
              [](const auto& p, const auto& q) { return p.multiplier < q.multiplier; });
    for (std::size_t i = 1; i < steps.size(); ++i) {
      EXPECT_LE(steps[i].error.bias, steps[i - 1].error.bias + 1e-12);
    }
  }
}

TEST(Calibration, ReportsAnUnbracketedRoot) {
  // A log of perfect rock (RQD 100 at t = 10 m on every run) is better than any multiplier
  // in the bracket gives: the lowest multiplier is the best, and not a root.
  const Fixture f;
  std::vector<LoggedInterval> measured = simulatedLog(f, 1.0);
  for (LoggedInterval& entry : measured) entry.rqd = 100.0;
  CalibrationSettings settings;
  settings.threshold = 10.0;
  const CalibrationResult result = calibrateMultiplier(f.thinned, measured, settings);
  EXPECT_FALSE(result.bracketed);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.multiplier, settings.min_multiplier);
  EXPECT_EQ(result.evaluations, 2);
  EXPECT_LT(result.error.bias, 0.0);
}

}  // namespace
}  // namespace rockmass::rqd
