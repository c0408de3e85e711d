// RQD volumes: the mean RQD of a cell against a direct evaluation for one plane, RQD 100
// where no fracture is crossed, clipping at the rock domain, determinism, and bad specs.
#include "rqd/rqd_volume.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <stdexcept>
#include <tuple>

#include "rqd/directions.h"

namespace rockmass::rqd {
namespace {

using geometry::Box;
using geometry::Disc;
using geometry::FractureNetwork;
using geometry::Vec3;

const Box kDomain{{0, 0, 0}, {20, 20, 20}};

/// A horizontal disc of radius 1000 m at height z: a plane for every scanline here.
Disc plane(double z) {
  Disc disc;
  disc.id = 1;
  disc.center = Vec3(10, 10, z);
  disc.normal = Vec3::UnitZ();
  disc.major = Vec3::UnitX();
  disc.a = disc.b = 1000.0;
  return disc;
}

FractureNetwork networkOf(std::vector<Disc> discs) {
  FractureNetwork network;
  network.domain = kDomain;
  network.sets.push_back({});
  network.discs = std::move(discs);
  return network;
}

VolumeSpec spec(double cell_size, double length, std::vector<double> thresholds) {
  VolumeSpec s;
  s.region = kDomain;
  s.cell_size = cell_size;
  s.scanline_length = length;
  s.direction_count = 300;
  s.thresholds = std::move(thresholds);
  return s;
}

/// Direct evaluation for one plane at height z0 and a scanline of length L centred at height
/// zc along an axis with vertical component c: the plane is crossed at distance
/// s = |zc - z0| / |c| from the centre when s <= L / 2, giving pieces L/2 + s and L/2 - s.
double planeRqd(double zc, double z0, double c, double length, double threshold) {
  const double s = std::abs(c) > 0.0 ? std::abs(zc - z0) / std::abs(c) : INFINITY;
  if (s > 0.5 * length) return 100.0;
  double intact = 0.0;
  for (double piece : {0.5 * length + s, 0.5 * length - s})
    intact += piece >= threshold ? piece : 0.0;
  return 100.0 * intact / length;
}

TEST(RqdVolume, OnePlaneMatchesADirectEvaluationPerAxis) {
  // Cells of 4 m: centres at z = 2, 6, 10, 14, 18, all at least 2 m from the domain, so
  // scanlines of 4 m are never clipped. The plane at z = 9 is 1 m below the centres at
  // z = 10 and 3 m from those at z = 6 and 12 (out of reach).
  const double z0 = 9.0, length = 4.0;
  const std::vector<double> thresholds{0.5, 1.0, 2.5, 3.5};
  const FractureNetwork network = networkOf({plane(z0)});
  const std::vector<Vec3> axes = scanlineAxes(300);
  for (DiscForm form : {DiscForm::ExactEllipse, DiscForm::Triangulated}) {
    const ScanlineScene scene(network, form);
    const RqdVolume volume = computeRqdVolume(scene, network, spec(4.0, length, thresholds));
    ASSERT_EQ(volume.grid.dims, (std::array<int, 3>{5, 5, 5}));
    for (std::size_t t = 0; t < thresholds.size(); ++t) {
      for (int k = 0; k < 5; ++k) {
        const double zc = volume.grid.cellCenter(0, 0, k).z();
        double expected = 0.0;
        for (const Vec3& axis : axes) expected += planeRqd(zc, z0, axis.z(), length, thresholds[t]);
        expected /= static_cast<double>(axes.size());
        for (int j = 0; j < 5; ++j) {
          for (int i = 0; i < 5; ++i) {
            // Hit distances are evaluated in double for both forms (the triangulated form
            // re-evaluates t on the disc's plane); 1e-9 percent leaves room for rounding only.
            ASSERT_NEAR(volume.mean_rqd[t][volume.grid.index(i, j, k)], expected, 1e-9)
                << "threshold " << thresholds[t] << " cell " << i << ' ' << j << ' ' << k;
          }
        }
        if (zc == 10.0) {
          EXPECT_LT(expected, 99.0);  // the plane really is crossed there
        }
      }
    }
  }
}

TEST(RqdVolume, CellsThatCrossNoFractureHaveRqd100) {
  // The plane at z = 9 is out of reach (>= 3 m) of every 4 m scanline through the centres
  // at z = 2, 6, 14 and 18: nothing is crossed, so every piece is whole and RQD is 100.
  const FractureNetwork network = networkOf({plane(9.0)});
  const ScanlineScene scene(network, DiscForm::ExactEllipse);
  const RqdVolume volume = computeRqdVolume(scene, network, spec(4.0, 4.0, {0.1, 1.0, 4.0}));
  for (std::size_t t = 0; t < 3; ++t) {
    for (std::int64_t cell = 0; cell < volume.grid.cellCount(); ++cell) {
      if (volume.grid.coordinates(cell)[2] == 2) continue;  // z = 10: crosses the plane
      ASSERT_EQ(volume.mean_rqd[t][static_cast<std::size_t>(cell)], 100.0);
    }
  }
}

TEST(RqdVolume, ScanlinesAreClippedToTheRockDomain) {
  // No fractures at all: each scanline is one whole piece. Scanlines of 100 m are clipped to
  // the 20 m cube, so none is longer than its diagonal (34.6 m), giving RQD_35 = 0, and none
  // is shorter than 5 m (centres lie 2.5 m or more inside), giving RQD_0.1 = 100.
  // Unclipped, RQD_35 would be 100.
  const FractureNetwork network = networkOf({});
  const ScanlineScene scene(network, DiscForm::ExactEllipse);
  const RqdVolume volume = computeRqdVolume(scene, network, spec(5.0, 100.0, {0.1, 35.0}));
  for (std::int64_t cell = 0; cell < volume.grid.cellCount(); ++cell) {
    ASSERT_EQ(volume.mean_rqd[0][static_cast<std::size_t>(cell)], 100.0);
    ASSERT_EQ(volume.mean_rqd[1][static_cast<std::size_t>(cell)], 0.0);
    ASSERT_EQ(volume.p32[static_cast<std::size_t>(cell)], 0.0);
  }
}

TEST(RqdVolume, CarriesP32AndTheSpec) {
  const FractureNetwork network = networkOf({plane(9.0)});
  const ScanlineScene scene(network, DiscForm::ExactEllipse);
  const RqdVolume volume = computeRqdVolume(scene, network, spec(4.0, 4.0, {1.0}));
  EXPECT_EQ(volume.thresholds, std::vector<double>{1.0});
  EXPECT_EQ(volume.scanline_length, 4.0);
  EXPECT_EQ(volume.direction_count, 300);
  // The plane z = 9 lies in the cell layer z in [8, 12]: 16 m2 per 64 m3 cell, P32 = 0.25,
  // to the 128-gon clipping's rounding.
  for (std::int64_t cell = 0; cell < volume.grid.cellCount(); ++cell) {
    const double expected = volume.grid.coordinates(cell)[2] == 2 ? 0.25 : 0.0;
    ASSERT_NEAR(volume.p32[static_cast<std::size_t>(cell)], expected, 1e-12);
  }
}

/// A few hundred random discs of two sets in the 20 m cube.
FractureNetwork randomNetwork() {
  geometry::DfnSpec dfn;
  dfn.domain = kDomain;
  for (const auto& [name, dip_direction, dip] :
       {std::tuple{"J1", 30.0, 60.0}, std::tuple{"J2", 200.0, 20.0}}) {
    geometry::JointSetSpec set;
    set.name = name;
    set.orientation.fisher = true;
    set.orientation.fisher_dip_direction = dip_direction;
    set.orientation.fisher_dip = dip;
    set.orientation.kappa = 20.0;
    set.spacing =
        geometry::DistributionSpec{geometry::DistributionKind::Exponential, 1.5, 1.5, {}, {}};
    set.trace_length = {geometry::DistributionKind::Lognormal, 3.0, 1.0, {}, {}};
    dfn.joint_sets.push_back(set);
  }
  return geometry::generateNetwork(dfn, 5);
}

TEST(RqdVolume, DoesNotDependOnTheThreadCountAndReportsProgress) {
  const FractureNetwork network = randomNetwork();
  ASSERT_GT(network.discs.size(), 300u);
  const ScanlineScene scene(network, DiscForm::ExactEllipse);
  VolumeSpec s = spec(2.5, 6.0, {0.1, 1.0, 3.0});
  s.direction_count = 50;
  std::vector<double> fractions;
  const RqdVolume parallel =
      computeRqdVolume(scene, network, s, [&](double f) { fractions.push_back(f); });
  ASSERT_FALSE(fractions.empty());
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_EQ(fractions.back(), 1.0);
  const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  const RqdVolume serial = computeRqdVolume(scene, network, s);
  EXPECT_EQ(serial.mean_rqd, parallel.mean_rqd);  // bit for bit
  EXPECT_EQ(serial.p32, parallel.p32);
  // RQD(t) cannot grow with t, and some cells must see fractures for this to mean anything.
  double lowest = 100.0;
  for (std::size_t cell = 0; cell < parallel.p32.size(); ++cell) {
    ASSERT_GE(parallel.mean_rqd[0][cell], parallel.mean_rqd[1][cell]);
    ASSERT_GE(parallel.mean_rqd[1][cell], parallel.mean_rqd[2][cell]);
    lowest = std::min(lowest, parallel.mean_rqd[2][cell]);
  }
  EXPECT_LT(lowest, 90.0);
}

TEST(RqdVolume, RejectsABadSpec) {
  const FractureNetwork network = networkOf({});
  const ScanlineScene scene(network, DiscForm::ExactEllipse);
  const auto throws = [&](const VolumeSpec& s) {
    EXPECT_THROW(computeRqdVolume(scene, network, s), std::invalid_argument);
  };
  throws(spec(4.0, 4.0, {}));           // no threshold
  throws(spec(4.0, 4.0, {1.0, -1.0}));  // negative threshold
  throws(spec(4.0, 4.0, {NAN}));        // not a number
  throws(spec(4.0, 0.0, {1.0}));        // zero length
  throws(spec(0.0, 4.0, {1.0}));        // zero cell size
  throws(spec(40.0, 4.0, {1.0}));       // region thinner than a cell
  VolumeSpec outside = spec(4.0, 4.0, {1.0});
  outside.region.max.x() = 21.0;  // beyond the domain
  throws(outside);
  VolumeSpec no_axis = spec(4.0, 4.0, {1.0});
  no_axis.direction_count = 0;
  throws(no_axis);
}

TEST(ScanlineAxes, AreTheUpperHalfOfATwiceAsDenseFibonacciSphere) {
  // A line and its reverse give the same RQD, so the axes cover one hemisphere: the z > 0
  // half of fibonacciSphere(2 N), which is exactly its first N points (z_i = 1 - (2i+1)/2N).
  const std::vector<Vec3> axes = scanlineAxes(200);
  const std::vector<Vec3> sphere = fibonacciSphere(400);
  ASSERT_EQ(axes.size(), 200u);
  for (std::size_t i = 0; i < axes.size(); ++i) {
    ASSERT_EQ(axes[i], sphere[i]);
    ASSERT_GT(axes[i].z(), 0.0);
  }
  EXPECT_LT(sphere[200].z(), 0.0);
  EXPECT_THROW(scanlineAxes(0), std::invalid_argument);
}

TEST(ClipSegmentToBox, KeepsThePartInside) {
  const Box box{{0, 0, 0}, {1, 1, 1}};
  const auto inside = clipSegmentToBox({-1, 0.5, 0.5}, {3, 0.5, 0.5}, box);
  ASSERT_TRUE(inside);
  EXPECT_DOUBLE_EQ((*inside)[0], 0.25);
  EXPECT_DOUBLE_EQ((*inside)[1], 0.5);
  EXPECT_FALSE(clipSegmentToBox({-1, 2, 0.5}, {3, 2, 0.5}, box));      // parallel, outside
  EXPECT_FALSE(clipSegmentToBox({-1, -1, 0.5}, {-0.5, 3, 0.5}, box));  // misses
  const auto whole = clipSegmentToBox({0.2, 0.2, 0.2}, {0.8, 0.9, 0.1}, box);
  ASSERT_TRUE(whole);
  EXPECT_EQ(*whole, (std::array<double, 2>{0.0, 1.0}));
}

}  // namespace
}  // namespace rockmass::rqd
