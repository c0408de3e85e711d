#include "rqd/directions.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

namespace rockmass::rqd {
namespace {

TEST(FibonacciSphere, UnitVectorsWithZeroMean) {
  const std::vector<geometry::Vec3> directions = fibonacciSphere(2000);
  ASSERT_EQ(directions.size(), 2000u);
  geometry::Vec3 sum = geometry::Vec3::Zero();
  for (const geometry::Vec3& d : directions) {
    EXPECT_NEAR(d.norm(), 1.0, 1e-12);  // round-off of sqrt(1 - z^2) only
    sum += d;
  }
  // An even spread has a resultant near zero; the spiral's z values are symmetric about 0
  // exactly, so the bound is set by the x and y sums, which are O(1) for N points.
  EXPECT_LT(sum.norm() / 2000.0, 1e-3);
}

TEST(FibonacciSphere, EqualAreaShares) {
  // Each direction owns 4 pi / N of solid angle, so the count in a polar cap of half-angle
  // alpha is N (1 - cos alpha) / 2. For N = 10^4 and alpha = 60 deg: 2500, and the lattice
  // error is below 1 point per ring of the spiral (~sqrt(N) = 100 rings): allow 0.5 %.
  const std::vector<geometry::Vec3> directions = fibonacciSphere(10000);
  int in_cap = 0;
  for (const geometry::Vec3& d : directions) in_cap += d.z() > 0.5 ? 1 : 0;
  EXPECT_NEAR(in_cap, 2500, 12.5);
  // The mean of |d . a| over the sphere is 1/2 for any axis a (used by the analytic ball).
  double mean_abs = 0.0;
  const geometry::Vec3 axis = geometry::Vec3(1.0, 2.0, 3.0).normalized();
  for (const geometry::Vec3& d : directions) mean_abs += std::abs(d.dot(axis));
  EXPECT_NEAR(mean_abs / 10000.0, 0.5, 1e-3);
}

TEST(FibonacciSphere, RejectsEmptySet) {
  EXPECT_THROW(fibonacciSphere(0), std::invalid_argument);
  EXPECT_EQ(fibonacciSphere(1).size(), 1u);
}

}  // namespace
}  // namespace rockmass::rqd
