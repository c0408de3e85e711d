// RQD along a scanline: exact small cases, and the Priest & Hudson (1976) expectation
// RQD(t) = 100 (1 + lambda t) exp(-lambda t) for Poisson fracture hits (Priest, S. D. &
// Hudson, J. A., "Discontinuity spacings in rock", Int. J. Rock Mech. Min. Sci. 13, 1976).
#include "rqd/scanline_rqd.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "geometry/random.h"

namespace rockmass::rqd {
namespace {

using Values = std::vector<double>;

// Results that involve only short binary fractions (0.5, 1.5, 3.0, 5.0, ...) are exact; the
// others are compared to 1e-12, a few ulps of numbers of order 100.
constexpr double kRoundingTolerance = 1e-12;

TEST(ScanlineRqd, NoHitsIsFullyIntact) {
  EXPECT_EQ(intactPieces(Values{}, 5.0), Values{5.0});
  const Values rqds = rqd(Values{}, 5.0, Values{0.1, 1.0, 5.0});
  EXPECT_EQ(rqds, (Values{100.0, 100.0, 100.0}));
}

TEST(ScanlineRqd, ThreePiecesOnFiveMetres) {
  const Values hits = {0.5, 2.0};
  EXPECT_EQ(intactPieces(hits, 5.0), (Values{0.5, 1.5, 3.0}));
  // t = 1: (1.5 + 3.0) / 5 = 90 %; t = 0.1: all; t = 2: 3.0 / 5 = 60 %; t = 4: none.
  const Values rqds = rqd(hits, 5.0, Values{1.0, 0.1, 2.0, 4.0});
  ASSERT_EQ(rqds.size(), 4u);
  EXPECT_NEAR(rqds[0], 90.0, kRoundingTolerance);
  EXPECT_NEAR(rqds[1], 100.0, kRoundingTolerance);
  EXPECT_NEAR(rqds[2], 60.0, kRoundingTolerance);
  EXPECT_EQ(rqds[3], 0.0);
}

TEST(ScanlineRqd, PieceEqualToThresholdCounts) {
  // The pieces 1.5 and 3.0 are exact, so "equal" is exact equality here.
  const Values rqds = rqd(Values{0.5, 2.0}, 5.0, Values{1.5, 3.0, std::nextafter(3.0, 4.0)});
  ASSERT_EQ(rqds.size(), 3u);
  EXPECT_NEAR(rqds[0], 90.0, kRoundingTolerance);
  EXPECT_NEAR(rqds[1], 60.0, kRoundingTolerance);
  EXPECT_EQ(rqds[2], 0.0);
}

TEST(ScanlineRqd, HitsWithinMergeDistanceAreOneFracture) {
  // Two hits 0.5 mm apart: one fracture with the default 1 mm merge distance.
  const Values hits = {1.0, 1.0005};
  EXPECT_EQ(intactPieces(hits, 2.0), (Values{1.0, 1.0}));
  EXPECT_NEAR(rqd(hits, 2.0, Values{1.0})[0], 100.0, kRoundingTolerance);
  // Without merging, the 0.5 mm sliver splits the second metre below the threshold.
  const Values unmerged = intactPieces(hits, 2.0, /*merge_distance=*/0.0);
  ASSERT_EQ(unmerged.size(), 3u);
  EXPECT_EQ(unmerged[0], 1.0);
  EXPECT_NEAR(unmerged[1], 0.0005, kRoundingTolerance);
  EXPECT_NEAR(unmerged[2], 0.9995, kRoundingTolerance);
  EXPECT_NEAR(rqd(hits, 2.0, Values{1.0}, /*merge_distance=*/0.0)[0], 50.0, kRoundingTolerance);
}

TEST(ScanlineRqd, MergeDistanceIsMeasuredFromPreviousKeptHit) {
  // 1.0008 merges into 1.0; 1.0016 is 1.6 mm from the kept hit 1.0, so it is a new fracture
  // even though it is only 0.8 mm from the dropped hit.
  const Values pieces = intactPieces(Values{1.0, 1.0008, 1.0016}, 2.0);
  ASSERT_EQ(pieces.size(), 3u);
  EXPECT_EQ(pieces[0], 1.0);
  EXPECT_NEAR(pieces[1], 0.0016, kRoundingTolerance);
  EXPECT_NEAR(pieces[2], 0.9984, kRoundingTolerance);
}

TEST(ScanlineRqd, HitsAtTheEndsAddNoPiece) {
  // Hits at 0 and at L bound the scanline anyway: same pieces and RQD as without them, for
  // every threshold including t = 0.
  const Values with_ends = {0.0, 0.0, 2.0, 5.0};
  EXPECT_EQ(intactPieces(with_ends, 5.0), (Values{2.0, 3.0}));
  EXPECT_EQ(intactPieces(with_ends, 5.0, /*merge_distance=*/0.0), (Values{2.0, 3.0}));
  const Values thresholds = {0.0, 2.5, 3.0};
  EXPECT_EQ(rqd(with_ends, 5.0, thresholds), rqd(Values{2.0}, 5.0, thresholds));
  EXPECT_NEAR(rqd(with_ends, 5.0, thresholds)[1], 60.0, kRoundingTolerance);
}

TEST(ScanlineRqd, RejectsInvalidInput) {
  const Values none;
  const Values thresholds = {0.1};
  EXPECT_THROW(rqd(none, -1.0, thresholds), std::invalid_argument);
  EXPECT_THROW(rqd(none, 0.0, thresholds), std::invalid_argument);
  EXPECT_THROW(rqd(Values{2.0, 1.0}, 5.0, thresholds), std::invalid_argument);
  EXPECT_THROW(rqd(Values{-0.1, 1.0}, 5.0, thresholds), std::invalid_argument);
  EXPECT_THROW(rqd(Values{1.0, 5.1}, 5.0, thresholds), std::invalid_argument);
  EXPECT_THROW(rqd(Values{std::nan("")}, 5.0, thresholds), std::invalid_argument);
  EXPECT_THROW(rqd(none, 5.0, Values{-0.1}), std::invalid_argument);
  EXPECT_THROW(intactPieces(none, 5.0, /*merge_distance=*/-1e-3), std::invalid_argument);
  EXPECT_THROW(priestHudsonRqd(-1.0, 0.1), std::invalid_argument);
  EXPECT_THROW(priestHudsonRqd(1.0, -0.1), std::invalid_argument);
}

TEST(PriestHudsonRqd, ClosedFormValues) {
  // No fractures, or t = 0: everything counts. lambda t = 1: 200 / e. Priest & Hudson's
  // classic lambda = 6 /m, t = 0.1 m: 100 * 1.6 * exp(-0.6) = 87.81 %.
  EXPECT_EQ(priestHudsonRqd(0.0, 0.1), 100.0);
  EXPECT_EQ(priestHudsonRqd(6.0, 0.0), 100.0);
  EXPECT_NEAR(priestHudsonRqd(2.0, 0.5), 200.0 / std::exp(1.0), kRoundingTolerance);
  EXPECT_NEAR(priestHudsonRqd(6.0, 0.1), 160.0 * std::exp(-0.6), kRoundingTolerance);
}

TEST(PriestHudsonRqd, MatchesPoissonHitsOnLongScanline) {
  // Poisson hits, lambda = 2 /m, on L = 1e5 m (about 2e5 pieces). No merging: the formula
  // assumes none. Standard error of RQD(t), from the renewal-reward central limit theorem
  // with piece length s ~ Exp(lambda), reward Y = s [s >= t], r = RQD/100, a = lambda t:
  //   Var(RQD/100) = [(1 - 2r) e^-a (a^2 + 2a + 2) + 2 r^2] / (lambda L),
  // i.e. 0.012, 0.10 and 0.17 percentage points for t = 0.1, 0.5 and 1 m. The two clipped
  // end pieces shift RQD by < 1e-3 points. The 1-point tolerance is thus > 5 standard errors.
  constexpr double kFrequency = 2.0;  // 1/m
  constexpr double kLength = 1e5;     // m
  geometry::Rng rng = geometry::makeRng(/*seed=*/1976, /*stream=*/0);
  std::exponential_distribution<double> spacing(kFrequency);
  Values hits;
  for (double x = spacing(rng); x < kLength; x += spacing(rng)) hits.push_back(x);

  const Values thresholds = {0.1, 0.5, 1.0};
  const Values rqds = rqd(hits, kLength, thresholds, /*merge_distance=*/0.0);
  ASSERT_EQ(rqds.size(), thresholds.size());
  for (std::size_t i = 0; i < thresholds.size(); ++i) {
    EXPECT_NEAR(rqds[i], priestHudsonRqd(kFrequency, thresholds[i]), 1.0)
        << "threshold " << thresholds[i] << " m";
  }
}

TEST(ScanlineRqd, BufferFormGivesTheSameBitsAndChecksItsSize) {
  // The allocation-free form used by RQD volumes: identical values (same summation order),
  // and a buffer of the wrong size is refused rather than overrun.
  const Values hits = {0.3, 0.3005, 1.7, 4.2, 4.9};
  const Values thresholds = {0.1, 1.0, 2.5};
  Values out(3);
  rqd(hits, 6.0, thresholds, out);
  EXPECT_EQ(out, rqd(hits, 6.0, thresholds));
  Values short_buffer(2);
  EXPECT_THROW(rqd(hits, 6.0, thresholds, short_buffer), std::invalid_argument);
}

}  // namespace
}  // namespace rockmass::rqd
