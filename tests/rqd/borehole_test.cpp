// Virtual boreholes: core runs partition the hole, RQD per run with pieces measured
// between natural fractures across run boundaries, log errors.
#include "rqd/borehole.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "geometry/fracture_network.h"

namespace rockmass::rqd {
namespace {

using geometry::Vec3;

TEST(CoreRuns, PartitionTheHoleExactly) {
  for (const auto& [length, run] : std::vector<std::pair<double, double>>{
           {60.0, 3.0}, {61.3, 3.0}, {2.0, 3.0}, {0.3, 0.1}, {10.0, 10.0 / 3.0}}) {
    const std::vector<DepthInterval> runs = coreRuns(length, run);
    ASSERT_FALSE(runs.empty());
    EXPECT_EQ(runs.front().from, 0.0);
    EXPECT_EQ(runs.back().to, length);  // exactly the hole's end
    for (std::size_t i = 0; i < runs.size(); ++i) {
      EXPECT_GT(runs[i].to, runs[i].from);                      // no empty run
      EXPECT_LE(runs[i].to - runs[i].from, run * (1 + 1e-15));  // none longer than a run
      if (i > 0) {
        EXPECT_EQ(runs[i].from, runs[i - 1].to);  // bit-for-bit shared boundary
      }
    }
    EXPECT_EQ(runs.size(), static_cast<std::size_t>(std::ceil(length / run - 1e-12)));
  }
  // The last run is the shorter one: 61.3 m in 3 m runs ends with 1.3 m.
  EXPECT_NEAR(coreRuns(61.3, 3.0).back().from, 60.0, 1e-12);
  EXPECT_THROW(coreRuns(-5.0, 3.0), std::invalid_argument);
  EXPECT_THROW(coreRuns(5.0, 0.0), std::invalid_argument);
}

TEST(IntervalsRqd, HundredWithoutHitsAndZeroWhenEveryPieceIsShort) {
  const std::vector<DepthInterval> runs = coreRuns(9.0, 3.0);
  const std::vector<double> thresholds{0.1, 1.0, 10.0};
  // No fracture: one intact 9 m piece; t = 10 m is longer than the whole hole.
  const std::vector<double> intact = intervalsRqd({}, 9.0, runs, thresholds);
  for (std::size_t r = 0; r < runs.size(); ++r) {
    EXPECT_EQ(intact[r * 3 + 0], 100.0);
    EXPECT_EQ(intact[r * 3 + 1], 100.0);
    EXPECT_EQ(intact[r * 3 + 2], 0.0);
  }
  // Fractures every 0.25 m: every piece is shorter than 1 m.
  std::vector<double> hits;
  for (double x = 0.25; x < 9.0; x += 0.25) hits.push_back(x);
  const std::vector<double> broken = intervalsRqd(hits, 9.0, runs, thresholds);
  for (std::size_t r = 0; r < runs.size(); ++r) {
    EXPECT_EQ(broken[r * 3 + 0], 100.0);  // all pieces >= 0.1 m
    EXPECT_EQ(broken[r * 3 + 1], 0.0);
  }
}

TEST(IntervalsRqd, PiecesCrossRunBoundaries) {
  // Fractures at 2.5 and 7 m on a 9 m hole: pieces [0, 2.5], [2.5, 7] (4.5 m), [7, 9].
  // With t = 3 only the 4.5 m piece counts: it gives run [0, 3] 0.5 m, run [3, 6] all 3 m,
  // run [6, 9] 1 m, although it is cut by two run boundaries.
  const std::vector<double> hits{2.5, 7.0};
  const std::vector<DepthInterval> runs = coreRuns(9.0, 3.0);
  const std::vector<double> thresholds{3.0};
  const std::vector<double> values = intervalsRqd(hits, 9.0, runs, thresholds);
  EXPECT_NEAR(values[0], 100.0 * 0.5 / 3.0, 1e-12);
  EXPECT_NEAR(values[1], 100.0, 1e-12);
  EXPECT_NEAR(values[2], 100.0 * 1.0 / 3.0, 1e-12);
  // The length-weighted mean of the runs is the whole-hole (scanline) RQD.
  const DepthInterval whole{0.0, 9.0};
  const double hole = intervalsRqd(hits, 9.0, {&whole, 1}, thresholds)[0];
  EXPECT_NEAR(hole, (values[0] + values[1] + values[2]) / 3.0, 1e-12);
  EXPECT_NEAR(hole, rqd(hits, 9.0, thresholds)[0], 1e-12);
  const DepthInterval outside{8.0, 9.5};
  EXPECT_THROW(intervalsRqd(hits, 9.0, {&outside, 1}, thresholds), std::invalid_argument);
}

TEST(Borehole, DirectionFromAzimuthAndPlunge) {
  // Straight down; then towards the East, 60 degrees below the horizontal.
  EXPECT_NEAR((Borehole{"a", Vec3::Zero(), 0.0, 90.0, 10.0}.direction() - Vec3(0, 0, -1)).norm(),
              0.0, 1e-15);
  const Borehole inclined{"b", Vec3(180, 10, 0), 90.0, 60.0, 60.0};
  EXPECT_NEAR((inclined.end() - Vec3(210, 10, -60 * std::sin(M_PI / 3))).norm(), 0.0, 1e-12);
}

TEST(Borehole, HitsOfAVerticalHoleThroughHorizontalDiscs) {
  geometry::FractureNetwork network;
  network.domain = {Vec3(-10, -10, -20), Vec3(10, 10, 0)};
  for (const double z : {-2.0, -7.5, -15.0}) {
    geometry::Disc disc;
    disc.id = static_cast<std::int64_t>(network.discs.size()) + 1;
    disc.center = Vec3(0, 0, z);
    disc.a = disc.b = 5.0;
    network.discs.push_back(disc);
  }
  const ScanlineScene scene(network, DiscForm::ExactEllipse);
  const std::vector<double> hits = boreholeHits(scene, {"h", Vec3(1, 1, 0), 0.0, 90.0, 10.0});
  ASSERT_EQ(hits.size(), 2u);  // the disc at -15 m lies below the 10 m hole
  EXPECT_NEAR(hits[0], 2.0, 1e-12);
  EXPECT_NEAR(hits[1], 7.5, 1e-12);
}

TEST(LogError, LengthWeightedBiasAndRms) {
  // Differences +10 over 1 m and -5 over 3 m: bias (10 - 15) / 4 = -1.25,
  // rms sqrt((100 + 75) / 4).
  const std::vector<LoggedInterval> measured{{0, {0.0, 1.0}, 50.0}, {1, {0.0, 3.0}, 80.0}};
  const std::vector<double> simulated{60.0, 75.0};
  const LogError error = logError(simulated, measured);
  EXPECT_DOUBLE_EQ(error.bias, -1.25);
  EXPECT_DOUBLE_EQ(error.rms, std::sqrt(175.0 / 4.0));
  EXPECT_EQ(error.intervals, 2);
  const std::vector<LogError> per_hole = logErrorPerHole(simulated, measured, 3);
  EXPECT_DOUBLE_EQ(per_hole[0].bias, 10.0);
  EXPECT_DOUBLE_EQ(per_hole[1].rms, 5.0);
  EXPECT_EQ(per_hole[2].intervals, 0);
}

}  // namespace
}  // namespace rockmass::rqd
