// DFN generation: intensity targets, the trace-length relation, determinism, deterministic
// features.
#include "geometry/fracture_network.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "geometry/orientation.h"

namespace rockmass::geometry {
namespace {

DistributionSpec normal(double mean, double std) {
  return {DistributionKind::Normal, mean, std, {}, {}};
}
DistributionSpec lognormal(double mean, double std) {
  return {DistributionKind::Lognormal, mean, std, {}, {}};
}
DistributionSpec constant(double value) {
  return {DistributionKind::Constant, value, 0, {}, {}};
}

/// A joint set dipping 40 towards 120 with normal scatter, lognormal traces.
JointSetSpec jointSet(double spacing, double trace_mean, double trace_std) {
  JointSetSpec s;
  s.name = "J";
  s.orientation.dip_direction = normal(120.0, 15.0);
  s.orientation.dip = normal(40.0, 10.0);
  s.spacing = DistributionSpec{DistributionKind::Lognormal, spacing, spacing, {}, {}};
  s.trace_length = lognormal(trace_mean, trace_std);
  s.shape.aspect_ratio = 0.5;
  return s;
}

DfnSpec singleSet(const JointSetSpec& set, double side) {
  DfnSpec spec;
  spec.domain = Box{{0, 0, 0}, {side, side, side}};
  spec.joint_sets.push_back(set);
  return spec;
}

TEST(FractureNetwork, SpacingTargetIsMetAlongTheMeanNormal) {
  // P10 = 1 / spacing along the set's mean normal, measured two ways on a 200 m cube
  // (~6.6e4 discs): as the mean projected area per volume, and by counting crossings on
  // 100 scanlines. Poisson noise is about 1% for both, so 3% (the bound) holds.
  const FractureNetwork network = generateNetwork(singleSet(jointSet(2.0, 8.0, 4.0), 200.0), 42);
  const std::vector<SetStatistics> stats = measureSets(network);
  ASSERT_EQ(stats.size(), 1u);
  EXPECT_NEAR(stats[0].p10, 0.5, 0.03 * 0.5);
  EXPECT_NEAR(network.sets[0].target_p10, 0.5, 1e-12);

  const Vec3 u = network.sets[0].mean_normal;
  const Box& box = network.domain;
  Vec3 e1, e2;
  // Lines along u through a 10 x 10 grid of points in the middle plane of the cube; each
  // line is clipped to the cube.
  e1 = u.cross(Vec3::UnitZ()).normalized();
  e2 = u.cross(e1);
  long hits = 0;
  double length = 0.0;
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 10; ++j) {
      const Vec3 origin = box.center() + (i - 4.5) * 12.0 * e1 + (j - 4.5) * 12.0 * e2;
      double t0 = -1e9, t1 = 1e9;
      for (int k = 0; k < 3; ++k) {
        const double ta = (box.min[k] - origin[k]) / u[k];
        const double tb = (box.max[k] - origin[k]) / u[k];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
      }
      length += t1 - t0;
      for (const Disc& d : network.discs) {
        const auto t = d.intersectLine(origin, u);
        if (t && *t >= t0 && *t <= t1) ++hits;
      }
    }
  }
  EXPECT_GT(hits, 5000);
  EXPECT_NEAR(hits / length, 0.5, 0.03 * 0.5) << hits << " hits on " << length << " m";
}

TEST(FractureNetwork, P32TargetIsMet) {
  // P32 = disc area inside the domain / volume; 3% as above.
  JointSetSpec set = jointSet(1.0, 6.0, 3.0);
  set.spacing.reset();
  set.p32 = 0.8;
  const FractureNetwork network = generateNetwork(singleSet(set, 150.0), 7);
  const std::vector<SetStatistics> stats = measureSets(network);
  EXPECT_NEAR(stats[0].p32, 0.8, 0.03 * 0.8);
  EXPECT_GT(stats[0].count, 1000);
}

TEST(FractureNetwork, MeanTraceOnAPlaneIsTheFieldMean) {
  // Warburton (1980): the size conversion makes the mean trace length on a plane equal to
  // the mean of the trace-length distribution. Circular discs (the relation is exact for
  // them), dipping 60 degrees, cut by the horizontal plane z = 100 of a 200 m cube. The
  // traces are the full chords, not clipped by the domain. ~2300 traces with a CV near
  // 0.8 give a standard error of ~1.7%; the bound is 4%.
  JointSetSpec set = jointSet(1.5, 10.0, 6.0);
  set.orientation.dip = constant(60.0);
  set.shape.aspect_ratio = 1.0;
  const FractureNetwork network = generateNetwork(singleSet(set, 200.0), 3);
  const double plane_z = 100.0;
  double sum = 0.0;
  int traces = 0;
  for (const Disc& d : network.discs) {
    const double sin_dip = std::hypot(d.normal.x(), d.normal.y());
    const double offset = std::abs(d.center.z() - plane_z) / sin_dip;  // in the disc's plane
    if (offset >= d.a) continue;
    const Vec3 foot = d.center;  // the chord's midpoint must lie in the domain's plan
    if (foot.x() < 0 || foot.x() > 200 || foot.y() < 0 || foot.y() > 200) continue;
    sum += 2.0 * std::sqrt(d.a * d.a - offset * offset);
    ++traces;
  }
  ASSERT_GT(traces, 2000);
  EXPECT_NEAR(sum / traces, 10.0, 0.4);
  // The scale itself: (4 / pi) / (1 + CV^2) for an untruncated distribution.
  EXPECT_NEAR(traceToDiameterScale(lognormal(10.0, 6.0)), 4.0 / kPi / 1.36, 1e-12);
  EXPECT_NEAR(traceToDiameterScale(constant(2.0)), 4.0 / kPi, 1e-15);
}

TEST(FractureNetwork, TruncatedTraceScaleUsesTruncatedMoments) {
  // A uniform on [1, 3] truncated to [1, 2] is a uniform on [1, 2]: E[L] = 1.5,
  // E[L^2] = 7/3, so c = (4 / pi) 2.25 / (7/3). The quadrature is good to 1e-6.
  const DistributionSpec truncated{DistributionKind::Uniform, 2.0, 2.0 / std::sqrt(12.0), 1.0, 2.0};
  EXPECT_NEAR(traceToDiameterScale(truncated), 4.0 / kPi * 2.25 / (7.0 / 3.0), 1e-6);
}

TEST(FractureNetwork, SameSeedSameDiscsOtherSeedOtherDiscs) {
  const DfnSpec spec = singleSet(jointSet(2.0, 5.0, 2.0), 60.0);
  const FractureNetwork a = generateNetwork(spec, 99);
  const FractureNetwork b = generateNetwork(spec, 99);
  const FractureNetwork c = generateNetwork(spec, 100);
  ASSERT_EQ(a.discs.size(), b.discs.size());
  for (std::size_t i = 0; i < a.discs.size(); ++i) {
    ASSERT_EQ(std::memcmp(a.discs[i].center.data(), b.discs[i].center.data(), 24), 0);
    ASSERT_EQ(std::memcmp(a.discs[i].normal.data(), b.discs[i].normal.data(), 24), 0);
    ASSERT_EQ(a.discs[i].a, b.discs[i].a);
    ASSERT_EQ(a.discs[i].id, static_cast<std::int64_t>(i) + 1);
  }
  EXPECT_FALSE(a.discs.size() == c.discs.size() && a.discs[0].center == c.discs[0].center);
}

TEST(FractureNetwork, MinCutSizeMarksSmallDiscs) {
  JointSetSpec set = jointSet(2.0, 5.0, 2.0);
  set.min_cut_size = 6.0;
  const FractureNetwork network = generateNetwork(singleSet(set, 60.0), 5);
  int cutting = 0;
  for (const Disc& d : network.discs) {
    EXPECT_EQ(d.cuts, 2.0 * d.a >= 6.0);
    cutting += d.cuts;
  }
  EXPECT_GT(cutting, 0);
  EXPECT_LT(cutting, static_cast<int>(network.discs.size()));
}

TEST(FractureNetwork, FisherSetKeepsItsConcentration) {
  // Orientation is independent of position and size here, so the discs kept in the domain
  // are a Fisher sample: kappa within 5% for ~10^4 discs (standard error ~1%).
  JointSetSpec set = jointSet(1.0, 4.0, 1.0);
  set.orientation.fisher = true;
  set.orientation.fisher_dip_direction = 300.0;
  set.orientation.fisher_dip = 70.0;
  set.orientation.kappa = 50.0;
  set.shape.aspect_ratio = 1.0;
  const FractureNetwork network = generateNetwork(singleSet(set, 80.0), 1);
  const std::vector<SetStatistics> stats = measureSets(network);
  ASSERT_GT(stats[0].count, 5000);
  EXPECT_NEAR(stats[0].kappa, 50.0, 2.5);
  const PlaneOrientation mean = orientationFromNormal(stats[0].mean_normal);
  EXPECT_NEAR(mean.dip_direction, 300.0, 1.0);
  EXPECT_NEAR(mean.dip, 70.0, 1.0);
}

TEST(FractureNetwork, FaultsFiniteSpanningAndThick) {
  DfnSpec spec;
  spec.domain = Box{{0, 0, -50}, {100, 60, 0}};
  FaultSpec finite;
  finite.name = "F1";
  finite.center = {50, 30, -25};
  finite.dip_direction = 290;
  finite.dip = 75;
  finite.size = std::array<double, 2>{40.0, 20.0};
  FaultSpec spanning;
  spanning.name = "F2";
  spanning.center = {50, 30, -25};
  spanning.dip_direction = 90;
  spanning.dip = 90;
  FaultSpec thick = finite;
  thick.name = "F3";
  thick.thickness = 0.5;
  thick.material = 2;
  spec.faults = {finite, spanning, thick};
  const FractureNetwork network = generateNetwork(spec, 1);
  ASSERT_EQ(network.discs.size(), 4u);
  EXPECT_EQ(network.discs[0].a, 20.0);
  EXPECT_EQ(network.discs[0].b, 10.0);
  // Major axis along strike (azimuth 200).
  EXPECT_NEAR(azimuthDegrees(network.discs[0].major), 200.0, 1e-9);
  // The spanning vertical fault x = 50 cuts the whole 60 x 50 section.
  EXPECT_NEAR(network.discs[1].areaInside(spec.domain), 3000.0, 1e-6);
  // The thick fault: two parallel surfaces 0.5 m apart, recorded as a slab.
  ASSERT_EQ(network.slabs.size(), 1u);
  const Slab& slab = network.slabs[0];
  EXPECT_EQ(slab.material, 2);
  ASSERT_EQ(slab.lower.size(), 1u);
  ASSERT_EQ(slab.upper.size(), 1u);
  const Disc& lower = network.discs[slab.lower[0] - 1];
  const Disc& upper = network.discs[slab.upper[0] - 1];
  EXPECT_NEAR((upper.center - lower.center).dot(lower.normal), 0.5, 1e-12);
  EXPECT_EQ(lower.set, 2);
  EXPECT_EQ(network.sets[2].name, "F3");
}

TEST(FractureNetwork, KneeShapedInterlayerIsAContinuousSlab) {
  DfnSpec spec;
  spec.domain = Box{{0, 0, -120}, {240, 160, 0}};
  InterlayerSpec layer;
  layer.name = "P1";
  layer.profile = {{0, -40}, {100, -45}, {140, -30}, {240, -35}};
  layer.sweep = 'y';
  layer.thickness = 1.0;
  layer.material = 1;
  spec.interlayers.push_back(layer);
  const FractureNetwork network = generateNetwork(spec, 1);
  ASSERT_EQ(network.discs.size(), 6u);  // 3 segments x 2 surfaces
  const Slab& slab = network.slabs.at(0);
  ASSERT_EQ(slab.lower.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    const Disc& lo = network.discs[slab.lower[i] - 1];
    const Disc& hi = network.discs[slab.upper[i] - 1];
    // Each pair of surfaces is parallel and one thickness apart (mitred offsets keep the
    // offset exact along every segment).
    EXPECT_NEAR(std::abs(lo.normal.dot(hi.normal)), 1.0, 1e-12);
    EXPECT_NEAR(std::abs((hi.center - lo.center).dot(lo.normal)), 1.0, 1e-9);
    // Consecutive segments of one surface share their joint edge exactly: no gap.
    if (i + 1 < 3) {
      const Disc& next = network.discs[slab.lower[i + 1] - 1];
      EXPECT_EQ(lo.polygon[1], next.polygon[0]);
      EXPECT_EQ(lo.polygon[2], next.polygon[3]);
    }
    // Swept 1% beyond the domain along y.
    EXPECT_DOUBLE_EQ(lo.polygon[0].y(), -1.6);
    EXPECT_DOUBLE_EQ(lo.polygon[2].y(), 161.6);
  }
  // A hairpin profile cannot be given a thickness.
  InterlayerSpec hairpin = layer;
  hairpin.profile = {{0, 0}, {100, 0}, {0, 1}};
  spec.interlayers = {hairpin};
  EXPECT_THROW(generateNetwork(spec, 1), std::invalid_argument);
}

TEST(FractureNetwork, InterlayerSurfacesReachBeyondTheDomain) {
  // The knee-shaped layer ends on the faces x = 0 and x = 240 with inclined end segments.
  // Offset by +-t/2 normal to the segments, the surface ends would move by up to
  // t/2 |sin| along x, so one surface would stop short of the face and leave a gap in the
  // slab. The ends are extended along the end segments until both surfaces reach 1% of the
  // domain beyond the face (2.4 m), as the sweep does along y.
  DfnSpec spec;
  spec.domain = Box{{0, 0, -120}, {240, 160, 0}};
  InterlayerSpec layer;
  layer.name = "P1";
  layer.profile = {{0, -40}, {100, -45}, {140, -30}, {240, -35}};
  layer.sweep = 'y';
  layer.thickness = 1.0;
  layer.material = 1;
  spec.interlayers.push_back(layer);
  const FractureNetwork network = generateNetwork(spec, 1);
  const Slab& slab = network.slabs.at(0);
  ASSERT_EQ(slab.lower.size(), 3u);
  ASSERT_EQ(slab.upper.size(), 3u);
  const Disc& lower_first = network.discs[slab.lower.front() - 1];
  const Disc& upper_first = network.discs[slab.upper.front() - 1];
  const Disc& lower_last = network.discs[slab.lower.back() - 1];
  const Disc& upper_last = network.discs[slab.upper.back() - 1];
  // polygon[0] is a segment's start, polygon[1] its end (at y = from).
  const double start = std::max(lower_first.polygon[0].x(), upper_first.polygon[0].x());
  const double end = std::min(lower_last.polygon[1].x(), upper_last.polygon[1].x());
  EXPECT_NEAR(start, -2.4, 1e-12 * 240);  // the nearer surface: exactly 1% beyond
  EXPECT_NEAR(end, 242.4, 1e-12 * 240);
  // The other surface lies farther out by t |sin| of the end segment's slope.
  const double slope_first = std::atan2(5.0, 100.0);
  EXPECT_NEAR(std::min(lower_first.polygon[0].x(), upper_first.polygon[0].x()),
              -2.4 - std::sin(slope_first), 1e-9);
  // An end inside the domain stays where the profile puts it (a layer that pinches out).
  layer.profile = {{20, -40}, {100, -45}};
  spec.interlayers = {layer};
  const FractureNetwork inner = generateNetwork(spec, 1);
  ASSERT_EQ(inner.discs.size(), 2u);
  const double d = std::sin(std::atan2(5.0, 80.0)) * 0.5;  // x shift of the offset ends
  EXPECT_NEAR(std::min(inner.discs[0].polygon[0].x(), inner.discs[1].polygon[0].x()), 20.0 - d,
              1e-9);
  EXPECT_NEAR(std::max(inner.discs[0].polygon[1].x(), inner.discs[1].polygon[1].x()), 100.0 + d,
              1e-9);
}

TEST(FractureNetwork, PolygonsAreKeptAsGiven) {
  DfnSpec spec;
  spec.domain = Box{{0, 0, 0}, {10, 10, 10}};
  PolygonSetSpec file;
  file.name = "mapped";
  file.polygons = {{{1, -1, 5}, {11, -1, 5}, {11, 11, 5}, {-1, 11, 5}},
                   {{20, 20, 20}, {21, 20, 20}, {21, 21, 20}}};  // the second is outside
  file.file_sets = {1, 1};
  spec.polygon_sets.push_back(file);
  const FractureNetwork network = generateNetwork(spec, 1);
  ASSERT_EQ(network.discs.size(), 1u);
  EXPECT_EQ(network.discs[0].polygon, file.polygons[0]);
  EXPECT_TRUE(network.discs[0].cuts);
  EXPECT_EQ(network.sets[0].generated, 2);
}

}  // namespace
}  // namespace rockmass::geometry
