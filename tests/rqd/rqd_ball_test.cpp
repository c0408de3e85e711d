// RQD balls against theory: the finite-scanline RQD of a Poisson disc field (analytic ball
// of issue 4, rqd/analytic_rqd.h), isotropy of a uniform network, the flattening of a
// one-set ball along the set's normal; the shape summary on exact inputs; determinism.
#include "rqd/rqd_ball.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "geometry/fracture_network.h"
#include "geometry/orientation.h"
#include "rqd/analytic_rqd.h"
#include "rqd/directions.h"

namespace rockmass::rqd {
namespace {

using geometry::Vec3;

geometry::DistributionSpec constant(double value) {
  return {geometry::DistributionKind::Constant, value, 0.0, {}, {}};
}

/// A joint set of identical circular discs (diameter (4/pi) trace) with one orientation.
geometry::JointSetSpec fixedSet(const char* name, double dip_direction, double dip, double p32) {
  geometry::JointSetSpec s;
  s.name = name;
  s.orientation.dip_direction = constant(dip_direction);
  s.orientation.dip = constant(dip);
  s.p32 = p32;
  s.trace_length = constant(3.0);
  return s;
}

/// A joint set with (almost) uniformly distributed normals: Fisher with kappa -> 0.
geometry::JointSetSpec uniformSet(double p32) {
  geometry::JointSetSpec s = fixedSet("U", 0.0, 0.0, p32);
  s.orientation.fisher = true;
  s.orientation.kappa = 1e-6;
  return s;
}

constexpr double kDomain = 128.0;  // cube edge (m)
constexpr double kLength = 20.0;   // ball scanline length (m)
constexpr int kDirections = 200;   // ball directions
const std::vector<double> kThresholds{0.1, 0.5, 1.0, 2.0};

/// 64 ball centres at 16 + 32 i (i = 0..3) on each axis: 32 m apart, so that their 20 m
/// scanlines and the 1.9 m discs they cross never meet; each is an independent sample of
/// the ball.
std::vector<Vec3> ballCentres() {
  std::vector<Vec3> centres;
  for (int i = 0; i < 64; ++i) {
    centres.emplace_back(16.0 + 32.0 * (i % 4), 16.0 + 32.0 * (i / 4 % 4), 16.0 + 32.0 * (i / 16));
  }
  return centres;
}

/// RQD per direction and threshold, averaged over `realizations` networks x 64 centres.
BallResult averageBall(const std::vector<geometry::JointSetSpec>& sets, int realizations) {
  geometry::DfnSpec spec;
  spec.domain = {Vec3::Zero(), Vec3::Constant(kDomain)};
  spec.joint_sets = sets;
  BallResult mean;
  int samples = 0;
  for (int r = 0; r < realizations; ++r) {
    const geometry::FractureNetwork network = geometry::generateNetwork(spec, 1000 + r);
    const ScanlineScene scene(network, DiscForm::ExactEllipse);
    for (const Vec3& centre : ballCentres()) {
      const BallResult ball =
          evaluateBall(scene, {centre, kLength, kDirections, std::nullopt}, kThresholds);
      if (mean.rqd.empty()) {
        mean = ball;
      } else {
        for (std::size_t i = 0; i < mean.rqd.size(); ++i) mean.rqd[i] += ball.rqd[i];
      }
      ++samples;
    }
  }
  for (double& v : mean.rqd) v /= samples;
  return mean;
}

TEST(RqdBall, TwoSetsMatchTheAnalyticFiniteScanlineBall) {
  // Source: issue 4, E[RQD_t] on a finite scanline for a Poisson field with
  // lambda(s) = sum P32 |n . s| (rqd/analytic_rqd.h). Two sets: horizontal (P32 1.0) and
  // dipping 60 to the East (P32 0.8), so lambda ranges from 0.4 to 1.6 per metre.
  const geometry::JointSetSpec a = fixedSet("A", 0.0, 0.0, 1.0);
  const geometry::JointSetSpec b = fixedSet("B", 90.0, 60.0, 0.8);
  const BallResult ball = averageBall({a, b}, /*realizations=*/4);
  const std::vector<PlaneSetIntensity> sets{{geometry::normalFromOrientation({0.0, 0.0}), 1.0},
                                            {geometry::normalFromOrientation({90.0, 60.0}), 0.8}};
  // Directions are compared in 6 groups, sorted by the analytic RQD. The directions of one
  // ball all pass through its centre, so they are strongly correlated: the independent
  // samples are the 256 balls (4 networks x 64 centres). The mean RQD of one ball over a
  // group has a standard deviation of up to ~10 points (t = 2 m, measured), so the
  // group averages carry ~0.6 points of noise, and 2 RQD points (the tolerance)
  // is over 3 standard errors. A wrong frequency (P32 counting both faces, or lambda
  // without |n . s|) moves the groups by 10 points or more.
  for (std::size_t k = 0; k < kThresholds.size(); ++k) {
    std::vector<double> analytic(ball.directions.size());
    for (std::size_t d = 0; d < ball.directions.size(); ++d) {
      analytic[d] =
          finiteScanlineRqd(lineFrequency(sets, ball.directions[d]), kThresholds[k], kLength);
    }
    std::vector<std::size_t> order(analytic.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](std::size_t p, std::size_t q) { return analytic[p] < analytic[q]; });
    constexpr std::size_t kGroups = 6;
    const std::size_t per_group = order.size() / kGroups;
    for (std::size_t g = 0; g < kGroups; ++g) {
      double simulated = 0.0;
      double expected = 0.0;
      for (std::size_t i = g * per_group; i < (g + 1) * per_group; ++i) {
        simulated += ball.at(order[i], k) / per_group;
        expected += analytic[order[i]] / per_group;
      }
      EXPECT_NEAR(simulated, expected, 2.0) << "threshold " << kThresholds[k] << ", group " << g;
    }
  }
}

TEST(RqdBall, UniformNetworkGivesARoundBall) {
  // Fisher kappa -> 0: normals uniform on the sphere, lambda = P32 / 2 in every direction,
  // so the ball is a sphere; the issue asks for an anisotropy ratio below 1.05. Thresholds
  // 1 and 2 m give RQD of about 83 and 56 (P32 = 1.5): far from both 0 and 100.
  const BallResult ball = averageBall({uniformSet(1.5)}, /*realizations=*/2);
  for (const std::size_t k : {2u, 3u}) {
    const BallShape shape = ballShape(ball.directions, ball.column(k));
    ASSERT_TRUE(shape.anisotropy.has_value());
    EXPECT_LT(*shape.anisotropy, 1.05) << "threshold " << kThresholds[k];
    // The mean matches the analytic value with lambda = 0.75 (same noise budget as above).
    EXPECT_NEAR(shape.mean, finiteScanlineRqd(0.75, kThresholds[k], kLength), 2.0);
  }
}

TEST(RqdBall, OneSetFlattensTheBallAlongItsNormal) {
  // One set of planes dipping 50 towards 120: scanlines along its normal cross the most
  // fractures (Terzaghi), those in its plane none, so the ball is flattened along the normal.
  const Vec3 normal = geometry::normalFromOrientation({120.0, 50.0});
  const BallResult ball = averageBall({fixedSet("A", 120.0, 50.0, 1.2)}, /*realizations=*/2);
  const std::size_t k = 2;  // t = 1 m
  const BallShape shape = ballShape(ball.directions, ball.column(k));
  ASSERT_EQ(shape.principal.size(), 3u);
  // The smallest principal RQD lies along the normal: within 5 degrees (the tensor of the
  // ball averaged over 128 balls; its noise tilts the axes by ~1 degree).
  const double angle = geometry::degrees(
      std::acos(std::min(1.0, std::abs(shape.principal.back().direction.dot(normal)))));
  EXPECT_LT(angle, 5.0);
  // The principal values match those of the analytic ball's tensor within 2 points.
  std::vector<double> analytic;
  const std::vector<PlaneSetIntensity> sets{{normal, 1.2}};
  for (const Vec3& d : ball.directions) {
    analytic.push_back(finiteScanlineRqd(lineFrequency(sets, d), kThresholds[k], kLength));
  }
  const BallShape exact = ballShape(ball.directions, analytic);
  for (std::size_t j = 0; j < 3; ++j) {
    EXPECT_NEAR(shape.principal[j].rqd, exact.principal[j].rqd, 2.0) << j;
  }
  // Flattened: clearly anisotropic (the analytic ratio is ~1.7).
  ASSERT_TRUE(shape.anisotropy && exact.anisotropy);
  EXPECT_GT(*shape.anisotropy, 1.4);
  EXPECT_NEAR(*shape.anisotropy, *exact.anisotropy, 0.1);
}

TEST(BallShape, RecoversAnExactQuadraticFormAndItsAxes) {
  // RQD(d) = d^T A d with A = diag(90, 60, 30) rotated: the fit is exact, so the principal
  // values and axes come back to rounding (1e-9).
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d a = rotation * Vec3(90, 60, 30).asDiagonal() * rotation.transpose();
  const std::vector<Vec3> directions = fibonacciSphere(200);
  std::vector<double> rqd;
  for (const Vec3& d : directions) rqd.push_back(d.dot(a * d));
  const BallShape shape = ballShape(directions, rqd);
  ASSERT_EQ(shape.principal.size(), 3u);
  const double values[] = {90, 60, 30};
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(shape.principal[j].rqd, values[j], 1e-9);
    EXPECT_NEAR(std::abs(shape.principal[j].direction.dot(rotation.col(j))), 1.0, 1e-9);
  }
  ASSERT_TRUE(shape.anisotropy.has_value());
  EXPECT_NEAR(*shape.anisotropy, 3.0, 1e-9);
  // The mean of d^T A d over the sphere is trace(A) / 3 = 60; the Fibonacci average
  // converges like 1/N (about 0.01 here).
  EXPECT_NEAR(shape.mean, 60.0, 0.1);
}

TEST(BallShape, ZeroRqdGivesAnUnboundedOrUnitRatio) {
  const std::vector<Vec3> directions = fibonacciSphere(400);
  // RQD 100 within 18 degrees of the poles, 0 elsewhere: its constant and degree-2 parts
  // are 5 + 23 P2(z) (Legendre expansion of the indicator of |z| > 0.95), whose minimum
  // 5 - 23/2 at the equator is negative: the ratio is unbounded.
  std::vector<double> rqd;
  for (const Vec3& d : directions) rqd.push_back(std::abs(d.z()) > 0.95 ? 100.0 : 0.0);
  const BallShape belt = ballShape(directions, rqd);
  EXPECT_EQ(belt.sampled_min.rqd, 0.0);
  EXPECT_EQ(belt.sampled_max.rqd, 100.0);
  EXPECT_FALSE(belt.anisotropy.has_value());
  // RQD 0 everywhere: a point, round by definition (ratio exactly 1).
  const BallShape zero = ballShape(directions, std::vector<double>(directions.size(), 0.0));
  EXPECT_LT(belt.principal.back().rqd, 0.0);
  ASSERT_TRUE(zero.anisotropy.has_value());
  EXPECT_EQ(*zero.anisotropy, 1.0);
  // Fewer than 6 directions cannot fix the 6 coefficients: no tensor, no ratio.
  const std::vector<Vec3> few = fibonacciSphere(5);
  const BallShape small = ballShape(few, std::vector<double>(5, 50.0));
  EXPECT_TRUE(small.principal.empty());
  EXPECT_FALSE(small.anisotropy.has_value());
}

TEST(ClipSegment, KeepsThePartInsideTheBox) {
  const geometry::Box box{Vec3::Zero(), Vec3(10, 10, 10)};
  const auto inside = clipSegment({Vec3(-5, 5, 5), Vec3(15, 5, 5)}, box);
  ASSERT_TRUE(inside.has_value());
  EXPECT_NEAR((inside->start - Vec3(0, 5, 5)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((inside->end - Vec3(10, 5, 5)).norm(), 0.0, 1e-12);
  // Entirely inside: unchanged, bit for bit.
  const auto whole = clipSegment({Vec3(1, 2, 3), Vec3(4, 5, 6)}, box);
  ASSERT_TRUE(whole.has_value());
  EXPECT_EQ(whole->start, Vec3(1, 2, 3));
  EXPECT_EQ(whole->end, Vec3(4, 5, 6));
  // Parallel to a face and outside, or touching a corner only: nothing.
  EXPECT_FALSE(clipSegment({Vec3(-1, -1, 5), Vec3(-1, 11, 5)}, box).has_value());
  EXPECT_FALSE(clipSegment({Vec3(-1, 1, 0), Vec3(1, -1, 0)}, box).has_value());
}

TEST(RqdBall, ClippedScanlinesMeasureOnlyTheDomain) {
  // No fractures: the clipped scanline is one intact piece, so RQD(t) is 100 when the
  // clipped length (from the centre of a 10 m cube: 5 / max|d_i| on each side) reaches t,
  // and 0 when it does not, although the unclipped 40 m would always reach it.
  geometry::FractureNetwork empty;
  empty.domain = {Vec3::Zero(), Vec3(10, 10, 10)};
  const ScanlineScene scene(empty, DiscForm::ExactEllipse);
  const std::vector<double> thresholds{5.0, 15.0};
  const BallResult ball = evaluateBall(scene, {Vec3(5, 5, 5), 40.0, 50, empty.domain}, thresholds);
  for (std::size_t d = 0; d < ball.directions.size(); ++d) {
    const double clipped = 10.0 / ball.directions[d].cwiseAbs().maxCoeff();
    EXPECT_EQ(ball.at(d, 0), 100.0);
    EXPECT_EQ(ball.at(d, 1), clipped >= 15.0 ? 100.0 : 0.0) << d;
  }
  EXPECT_THROW(evaluateBall(scene, {Vec3(0, 5, 5), 40.0, 50, empty.domain}, thresholds),
               std::invalid_argument);
}

TEST(RqdBall, ResultDoesNotDependOnTheNumberOfThreads) {
  geometry::DfnSpec spec;
  spec.domain = {Vec3::Zero(), Vec3::Constant(30.0)};
  spec.joint_sets = {uniformSet(1.0)};
  const geometry::FractureNetwork network = geometry::generateNetwork(spec, 5);
  const ScanlineScene scene(network, DiscForm::ExactEllipse);
  const BallSpec ball{Vec3::Constant(15.0), 20.0, 500, spec.domain};
  const BallResult parallel = evaluateBall(scene, ball, kThresholds);
  const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  const BallResult serial = evaluateBall(scene, ball, kThresholds);
  EXPECT_EQ(parallel.rqd, serial.rqd);  // exact: each direction is computed the same way
}

}  // namespace
}  // namespace rockmass::rqd
