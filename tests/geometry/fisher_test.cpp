// Fisher orientations: Wood's sampler and the (N - 1) / (N - R) estimator.
#include "geometry/fisher.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "geometry/orientation.h"

namespace rockmass::geometry {
namespace {

std::vector<Vec3> sample(const Vec3& mean, double kappa, int n, std::uint64_t seed) {
  Rng rng = makeRng(seed, 0);
  std::vector<Vec3> out(n);
  for (Vec3& v : out) v = sampleFisher(mean, kappa, rng);
  return out;
}

TEST(Fisher, KappaIsRecoveredWithinFivePercent) {
  // n = 10^4: the estimator's relative standard error is about 1/sqrt(n) = 1%, so 5% is a
  // 5-sigma bound on a fixed seed.
  const Vec3 mean = normalFromOrientation({85.0, 37.0});
  for (double kappa : {10.0, 50.0, 200.0}) {
    const FisherEstimate estimate = estimateFisher(sample(mean, kappa, 10'000, 7));
    EXPECT_NEAR(estimate.kappa, kappa, 0.05 * kappa) << "kappa " << kappa;
    // The mean direction is off by about 1 / sqrt(n kappa) radians.
    EXPECT_GT(estimate.mean.dot(mean), std::cos(5.0 / std::sqrt(10'000 * kappa)));
  }
}

TEST(Fisher, MeanCosineIsTheLangevinFunction) {
  // E[cos theta] = coth(kappa) - 1/kappa (Fisher, Lewis & Embleton 1987, eq. 4.24).
  // The std of cos theta is below 0.6, so n = 10^5 gives a standard error below 0.002.
  const Vec3 mean(0, 0, 1);
  for (double kappa : {0.5, 2.0, 20.0}) {
    double sum = 0.0;
    for (const Vec3& v : sample(mean, kappa, 100'000, 3)) sum += v.z();
    EXPECT_NEAR(sum / 100'000, 1.0 / std::tanh(kappa) - 1.0 / kappa, 0.01) << kappa;
  }
}

TEST(Fisher, StableForVeryLargeKappa) {
  // For large kappa, 1 - cos theta is exponential with mean 1/kappa. n = 10^4 gives a 1%
  // standard error; 4% is the bound. The naive form exp(kappa) overflows for 1e4.
  const Vec3 mean = Vec3(1, 2, 3).normalized();
  for (double kappa : {1e4, 1e6}) {
    double sum = 0.0;
    for (const Vec3& v : sample(mean, kappa, 10'000, 5)) {
      ASSERT_TRUE(v.allFinite());
      ASSERT_NEAR(v.norm(), 1.0, 1e-14);
      sum += 1.0 - v.dot(mean);
    }
    EXPECT_NEAR(sum / 10'000 * kappa, 1.0, 0.04) << kappa;
  }
}

TEST(Fisher, EstimateIgnoresTheSignOfAxes) {
  // Plane normals carry no sign: flipping half of them changes nothing.
  std::vector<Vec3> axes = sample(Vec3(0, 1, 0), 50.0, 2000, 9);
  const FisherEstimate straight = estimateFisher(axes);
  for (std::size_t i = 0; i < axes.size(); i += 2) axes[i] = -axes[i];
  const FisherEstimate flipped = estimateFisher(axes);
  EXPECT_NEAR(flipped.kappa, straight.kappa, 1e-9 * straight.kappa);
  EXPECT_NEAR(std::abs(flipped.mean.dot(straight.mean)), 1.0, 1e-12);
}

TEST(Fisher, OrthonormalBasisForEveryAxis) {
  for (const Vec3& n : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, -1), Vec3(1, 1, 1).normalized()}) {
    Vec3 u, v;
    orthonormalBasis(n, u, v);
    EXPECT_NEAR(u.norm(), 1.0, 1e-15);
    EXPECT_NEAR(v.norm(), 1.0, 1e-15);
    EXPECT_NEAR(u.dot(n), 0.0, 1e-15);
    EXPECT_NEAR(v.dot(n), 0.0, 1e-15);
    EXPECT_NEAR(u.cross(v).dot(n), 1.0, 1e-15);
  }
}

}  // namespace
}  // namespace rockmass::geometry
