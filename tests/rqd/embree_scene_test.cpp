// Embree scene of fracture discs: every disc a segment crosses, checked against a
// double-precision brute force (Disc::intersectLine over all discs, t in the closed
// interval [0, L]) on 10^5 random segments, and on small hand-made cases (shared fan edges,
// segment ends, ordering).
#include "rqd/embree_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <set>
#include <thread>
#include <utility>
#include <vector>

#include "geometry/fisher.h"
#include "geometry/fracture_network.h"
#include "geometry/random.h"

namespace rockmass::rqd {
namespace {

using geometry::Disc;
using geometry::FractureNetwork;
using geometry::Vec3;

constexpr int kSegments = 24;  // fan triangles per disc in the triangulated form
constexpr int kRays = 100000;  // random segments per comparison

// Both sides compute t with the same double-precision Disc::intersectLine; they can only
// differ through the order of operations (none today), so 1e-9 m is a wide margin that
// still tells a wrong disc or a float distance (errors of ~1e-6 m) apart.
constexpr double kExactTTolerance = 1e-9;
// Triangulated scene vs polygon discs: t comes from the ellipse's plane on one side and
// from the polygon's Newell plane through its centroid on the other; the two planes agree
// to rounding (~1e-15 relative), amplified by 1/sin(angle) for grazing segments, so 1e-6 m
// is ample and still far below any spacing RQD cares about (1e-3 m merge distance).
constexpr double kTriangulatedTTolerance = 1e-6;
// Embree tests triangles in float: coordinates of ~30 m carry rounding of ~2e-6 m, so a
// segment passing closer than this to a polygon edge may be decided differently than the
// double-precision polygon test; 1e-5 m is five times that rounding.
constexpr double kEdgeTolerance = 1e-5;

geometry::DistributionSpec normal(double mean, double std) {
  return {geometry::DistributionKind::Normal, mean, std, {}, {}};
}
geometry::DistributionSpec lognormal(double mean, double std) {
  return {geometry::DistributionKind::Lognormal, mean, std, {}, {}};
}

geometry::JointSetSpec jointSet(const char* name, double dip_direction, double dip) {
  geometry::JointSetSpec s;
  s.name = name;
  s.orientation.dip_direction = normal(dip_direction, 10.0);
  s.orientation.dip = normal(dip, 8.0);
  s.spacing = lognormal(0.8, 0.6);
  s.trace_length = lognormal(3.0, 1.5);
  s.shape.aspect_ratio = 0.6;
  s.min_cut_size = 3.0;  // some discs do not cut blocks: they must still be in the scene
  return s;
}

/// Two joint sets in a 30 m cube: a few thousand discs.
const FractureNetwork& randomNetwork() {
  static const FractureNetwork network = [] {
    geometry::DfnSpec spec;
    spec.domain = geometry::Box{{0, 0, 0}, {30, 30, 30}};
    spec.joint_sets.push_back(jointSet("J1", 120.0, 40.0));
    spec.joint_sets.push_back(jointSet("J2", 250.0, 75.0));
    return geometry::generateNetwork(spec, 2024);
  }();
  return network;
}

struct Segment {
  Vec3 start;
  Vec3 end;
};

/// Segments with both ends in the cube grown by 5 m, random directions, lengths 0.5-45 m.
std::vector<Segment> randomSegments(int count, std::uint64_t seed) {
  geometry::Rng rng = geometry::makeRng(seed, 0);
  std::uniform_real_distribution<double> coordinate(-5.0, 35.0);
  std::normal_distribution<double> gaussian;
  std::uniform_real_distribution<double> length(0.5, 45.0);
  std::vector<Segment> segments;
  for (int i = 0; i < count; ++i) {
    const Vec3 start(coordinate(rng), coordinate(rng), coordinate(rng));
    Vec3 dir(gaussian(rng), gaussian(rng), gaussian(rng));
    dir.normalize();
    segments.push_back({start, start + length(rng) * dir});
  }
  return segments;
}

/// Double-precision reference: every disc whose intersectLine t lies in [0, L].
std::vector<ScanlineHit> bruteForce(const std::vector<Disc>& discs, const Segment& s) {
  const double length = (s.end - s.start).norm();
  const Vec3 dir = (s.end - s.start) / length;
  std::vector<ScanlineHit> hits;
  for (const Disc& disc : discs) {
    // Speed only: a line farther than `a` from the centre cannot touch the disc (every
    // point of an ellipse or of a discFromPolygon polygon lies within `a` of it); the margin
    // keeps rounding from rejecting a true hit.
    const Vec3 offset = disc.center - s.start;
    if ((offset - offset.dot(dir) * dir).norm() > disc.a * (1.0 + 1e-9) + 1e-9) continue;
    const auto t = disc.intersectLine(s.start, dir);
    if (t && *t >= 0.0 && *t <= length) hits.push_back({*t, disc.id});
  }
  std::sort(hits.begin(), hits.end(), [](const ScanlineHit& p, const ScanlineHit& q) {
    return p.t != q.t ? p.t < q.t : p.disc_id < q.disc_id;
  });
  return hits;
}

bool sortedByT(const std::vector<ScanlineHit>& hits) {
  return std::is_sorted(hits.begin(), hits.end(), [](const ScanlineHit& p, const ScanlineHit& q) {
    return p.t != q.t ? p.t < q.t : p.disc_id < q.disc_id;
  });
}

std::vector<std::int64_t> ids(const std::vector<ScanlineHit>& hits) {
  std::vector<std::int64_t> out;
  for (const ScanlineHit& h : hits) out.push_back(h.disc_id);
  return out;
}

/// Shortest distance between segments [p0, p1] and [q0, q1] (Ericson, Real-Time Collision
/// Detection, 5.1.9).
double segmentDistance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  if (a <= 1e-300 && e <= 1e-300) return r.norm();
  if (a <= 1e-300) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= 1e-300) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return ((p0 + s * d1) - (q0 + t * d2)).norm();
}

/// True when the segment passes within `tolerance` of an edge of the polygon disc.
bool nearPolygonEdge(const Disc& disc, const Segment& s, double tolerance) {
  // Quick reject: every vertex lies within `a` of the centroid (discFromPolygon).
  if (segmentDistance(s.start, s.end, disc.center, disc.center) > disc.a + tolerance) {
    return false;
  }
  const std::size_t n = disc.polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (segmentDistance(s.start, s.end, disc.polygon[i], disc.polygon[(i + 1) % n]) < tolerance) {
      return true;
    }
  }
  return false;
}

TEST(EmbreeScene, ExactFormMatchesBruteForce) {
  const FractureNetwork& network = randomNetwork();
  ASSERT_GT(network.discs.size(), 2000u);
  ASSERT_LT(network.discs.size(), 10000u);
  ASSERT_TRUE(std::any_of(network.discs.begin(), network.discs.end(),
                          [](const Disc& d) { return !d.cuts; }));
  const ScanlineScene scene(network, DiscForm::ExactEllipse);
  std::int64_t total_hits = 0;
  int mismatches = 0;
  for (const Segment& s : randomSegments(kRays, 1)) {
    const std::vector<ScanlineHit> expected = bruteForce(network.discs, s);
    const std::vector<ScanlineHit> got = scene.hits(s.start, s.end);
    total_hits += static_cast<std::int64_t>(expected.size());
    ASSERT_TRUE(sortedByT(got));
    if (ids(got) != ids(expected)) {
      ++mismatches;
      continue;
    }
    for (std::size_t i = 0; i < got.size(); ++i) {
      ASSERT_NEAR(got[i].t, expected[i].t, kExactTTolerance);
    }
  }
  EXPECT_EQ(mismatches, 0);
  // The comparison is only meaningful when segments actually cross many discs.
  EXPECT_GT(total_hits, 10 * kRays);
  std::printf("[          ] exact form: %d segments, %lld hits, %d mismatches (%zu discs)\n", kRays,
              static_cast<long long>(total_hits), mismatches, network.discs.size());
}

TEST(EmbreeScene, TriangulatedFormMatchesPolygonBruteForceAwayFromEdges) {
  const FractureNetwork& network = randomNetwork();
  std::vector<Disc> polygons;
  for (const Disc& disc : network.discs) {
    Disc polygon = geometry::discFromPolygon(disc.outline(kSegments));
    polygon.id = disc.id;
    polygons.push_back(std::move(polygon));
  }
  std::vector<const Disc*> by_id(network.discs.size() + 1, nullptr);
  for (const Disc& p : polygons) by_id[static_cast<std::size_t>(p.id)] = &p;

  const ScanlineScene scene(network, DiscForm::Triangulated, kSegments);
  std::int64_t total_hits = 0;
  int mismatched_rays = 0, near_edge_rays = 0, unexplained = 0;
  for (const Segment& s : randomSegments(kRays, 2)) {
    const std::vector<ScanlineHit> expected = bruteForce(polygons, s);
    const std::vector<ScanlineHit> got = scene.hits(s.start, s.end);
    total_hits += static_cast<std::int64_t>(expected.size());
    ASSERT_TRUE(sortedByT(got));
    // Near-edge rays, counted over the discs either side reports (a disc neither side
    // reports cannot cause a mismatch).
    bool near_edge = false;
    for (const std::vector<ScanlineHit>* list : {&got, &expected}) {
      for (const ScanlineHit& h : *list) {
        near_edge = near_edge ||
                    nearPolygonEdge(*by_id[static_cast<std::size_t>(h.disc_id)], s, kEdgeTolerance);
      }
    }
    if (near_edge) ++near_edge_rays;
    if (ids(got) == ids(expected)) {
      for (std::size_t i = 0; i < got.size(); ++i) {
        ASSERT_NEAR(got[i].t, expected[i].t, kTriangulatedTTolerance);
      }
      continue;
    }
    ++mismatched_rays;
    // Every disc found by one side only must have an edge within kEdgeTolerance.
    std::vector<std::int64_t> a = ids(got), b = ids(expected), difference;
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    std::set_symmetric_difference(a.begin(), a.end(), b.begin(), b.end(),
                                  std::back_inserter(difference));
    for (std::int64_t id : difference) {
      if (!nearPolygonEdge(*by_id[static_cast<std::size_t>(id)], s, kEdgeTolerance)) {
        ++unexplained;
      }
    }
  }
  EXPECT_EQ(unexplained, 0);
  EXPECT_LE(mismatched_rays, near_edge_rays);
  EXPECT_GT(total_hits, 10 * kRays);
  std::printf(
      "[          ] triangulated form: %d segments, %lld hits, %d within %g m of a polygon "
      "edge, %d mismatched (%d unexplained)\n",
      kRays, static_cast<long long>(total_hits), near_edge_rays, kEdgeTolerance, mismatched_rays,
      unexplained);
}

TEST(EmbreeScene, ConcurrentQueriesMatchSerialOnes) {
  const ScanlineScene scene(randomNetwork(), DiscForm::Triangulated, kSegments);
  const std::vector<Segment> segments = randomSegments(2000, 3);
  std::vector<std::vector<ScanlineHit>> serial;
  for (const Segment& s : segments) serial.push_back(scene.hits(s.start, s.end));
  std::vector<std::vector<ScanlineHit>> parallel(segments.size());
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < 4; ++k) {
    threads.emplace_back([&, k] {
      for (std::size_t i = k; i < segments.size(); i += 4) {
        parallel[i] = scene.hits(segments[i].start, segments[i].end);
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (std::size_t i = 0; i < segments.size(); ++i) {
    ASSERT_EQ(ids(parallel[i]), ids(serial[i]));
  }
}

/// One horizontal disc: centre (0, 0, z), major axis x, a = 2, b = 1.
Disc horizontalDisc(std::int64_t id, double z) {
  Disc disc;
  disc.id = id;
  disc.center = Vec3(0, 0, z);
  disc.normal = Vec3::UnitZ();
  disc.major = Vec3::UnitX();
  disc.a = 2.0;
  disc.b = 1.0;
  return disc;
}

FractureNetwork networkOf(std::vector<Disc> discs) {
  FractureNetwork network;
  network.domain = geometry::Box{{-3, -3, -3}, {3, 3, 10}};
  network.discs = std::move(discs);
  return network;
}

TEST(EmbreeScene, SharedTriangleEdgesCountTheDiscOnce) {
  const FractureNetwork network = networkOf({horizontalDisc(7, 0.0)});
  const Disc& disc = network.discs.front();
  const std::vector<Vec3> outline = disc.outline(kSegments);
  const auto vertex = [&](int k) { return outline[static_cast<std::size_t>(k % kSegments)]; };
  // Points on the edges two triangles share in the triangulated form's strips (see
  // embree_scene.cpp: chains A_i = v_i and B_i = v_(n-i)): the chord A_i B_i between strips
  // i - 1 and i, and the diagonal A_i+1 B_i splitting strip i into two triangles; also
  // the centre and the old fan edges (any interior point must give one crossing).
  std::vector<Vec3> points{Vec3::Zero(), 0.5 * vertex(3), 0.5 * vertex(10)};
  for (int i = 1; i < kSegments / 2; ++i) {
    points.push_back(0.5 * (vertex(i) + vertex(kSegments - i)));  // chord midpoint
    // On the diagonal (the last strip, i = n/2 - 1, is a triangle: no diagonal).
    if (i + 1 < kSegments / 2) points.push_back(0.3 * vertex(i + 1) + 0.7 * vertex(kSegments - i));
  }
  for (DiscForm form : {DiscForm::ExactEllipse, DiscForm::Triangulated}) {
    const ScanlineScene scene(network, form, kSegments);
    // Straight down through the centre.
    std::vector<ScanlineHit> hits = scene.hits({0, 0, -1}, {0, 0, 1});
    ASSERT_EQ(hits.size(), 1u);
    EXPECT_EQ(hits[0].disc_id, 7);
    EXPECT_EQ(hits[0].t, 1.0);
    // Vertically and obliquely through each shared-edge point.
    for (std::size_t p = 0; p < points.size(); ++p) {
      for (const Vec3& offset : {Vec3(0, 0, 1), Vec3(0.3, -0.2, 1.0)}) {
        hits = scene.hits(points[p] - offset, points[p] + offset);
        ASSERT_EQ(hits.size(), 1u) << "point " << p;
        EXPECT_EQ(hits[0].disc_id, 7);
        // Exact to rounding of the double-precision plane hit: t = |offset|.
        EXPECT_NEAR(hits[0].t, offset.norm(), 1e-12);
      }
    }
  }
}

TEST(EmbreeScene, SegmentEndsAreAClosedInterval) {
  // Convention: a segment of length L covers t in [0, L]; a disc exactly at either end is
  // crossed. Horizontal disc at z = 5, vertical segments: all values exact in binary.
  const FractureNetwork network = networkOf({horizontalDisc(3, 5.0)});
  for (DiscForm form : {DiscForm::ExactEllipse, DiscForm::Triangulated}) {
    const ScanlineScene scene(network, form, kSegments);
    EXPECT_TRUE(scene.hits({0.25, 0.5, 0}, {0.25, 0.5, 4.9}).empty());
    std::vector<ScanlineHit> hits = scene.hits({0.25, 0.5, 0}, {0.25, 0.5, 5});
    ASSERT_EQ(hits.size(), 1u);
    EXPECT_EQ(hits[0].t, 5.0);
    hits = scene.hits({0.25, 0.5, 5}, {0.25, 0.5, 8});
    ASSERT_EQ(hits.size(), 1u);
    EXPECT_EQ(hits[0].t, 0.0);
    // Beyond the rim: no hit even though the plane is crossed.
    EXPECT_TRUE(scene.hits({2.5, 0, 0}, {2.5, 0, 10}).empty());
    // A zero-length segment hits nothing.
    EXPECT_TRUE(scene.hits({0, 0, 5}, {0, 0, 5}).empty());
  }
}

TEST(EmbreeScene, HitsAreSortedByDistance) {
  const FractureNetwork network =
      networkOf({horizontalDisc(3, 1.0), horizontalDisc(1, 2.0), horizontalDisc(2, 3.0),
                 horizontalDisc(4, 3.0)});  // 2 and 4 coincide: tie broken by id
  for (DiscForm form : {DiscForm::ExactEllipse, DiscForm::Triangulated}) {
    const ScanlineScene scene(network, form, kSegments);
    const std::vector<ScanlineHit> hits = scene.hits({0.1, 0.1, 4}, {0.1, 0.1, 0});
    ASSERT_EQ(hits.size(), 4u);
    EXPECT_EQ(ids(hits), (std::vector<std::int64_t>{2, 4, 1, 3}));
    EXPECT_EQ(hits[0].t, 1.0);
    EXPECT_EQ(hits[1].t, 1.0);
    EXPECT_EQ(hits[2].t, 2.0);
    EXPECT_EQ(hits[3].t, 3.0);
  }
}

// The exact form decides rim hits with a faster test than Disc::intersectLine (inverse
// semi-axes, falling back to intersectLine within 1e-12 of the rim): on segments aimed at
// points 0, +-1, +-2, +-4 ulps-scale steps (1e-16 .. 4e-15 relative) around the rim of a
// tilted ellipse with awkward semi-axes, and through a square polygon disc, the hit and
// its t must be exactly (bit for bit) what intersectLine gives.
TEST(EmbreeScene, ExactFormDecidesRimHitsLikeIntersectLine) {
  Disc ellipse;
  ellipse.id = 11;
  ellipse.center = Vec3(0.3, -0.2, 1.1);
  ellipse.normal = Vec3(0.3, -0.5, 1.0).normalized();
  Vec3 unused;
  geometry::orthonormalBasis(ellipse.normal, ellipse.major, unused);
  ellipse.a = 2.9;
  ellipse.b = 0.7;
  Disc square;
  square.id = 12;
  square.normal = Vec3::UnitZ();
  square.major = Vec3::UnitX();
  square.polygon = {{-1, -1, 4}, {1, -1, 4}, {1, 1, 4}, {-1, 1, 4}};
  square.center = Vec3(0, 0, 4);
  square.a = std::sqrt(2.0);
  square.b = std::sqrt(2.0);
  const FractureNetwork network = networkOf({ellipse, square});
  const ScanlineScene scene(network, DiscForm::ExactEllipse);
  const Vec3 dir = Vec3(0.1, 0.2, 1.0).normalized();
  int hits = 0;
  int misses = 0;
  for (int k = 0; k < 90; ++k) {
    const double phi = 0.07 * k;
    const Vec3 rim =
        ellipse.a * std::cos(phi) * ellipse.major + ellipse.b * std::sin(phi) * ellipse.minor();
    // Scales within about 1e-15 of 1 are decided by intersectLine itself; 1 +- 3e-5 .. 1e-3
    // lie just outside the rim band of the float axes (1e-5 x aspect 4.1 in x^2 + y^2), where
    // the record's float test decides: both must agree with intersectLine, t to the bit.
    for (double scale :
         {1.0 - 1e-3, 1.0 - 1e-4, 1.0 - 3e-5, 1.0 - 4e-15, 1.0 - 2e-16, 1.0 - 1e-16, 1.0,
          1.0 + 1e-16, 1.0 + 2e-16, 1.0 + 4e-15, 1.0 + 3e-5, 1.0 + 1e-4, 1.0 + 1e-3}) {
      const Vec3 target = ellipse.center + scale * rim;
      const Vec3 start = target - 1.5 * dir;
      const Vec3 end = start + 3.0 * dir;
      const std::vector<ScanlineHit> got = scene.hits(start, end);
      // The brute force's line: start and the unit direction of the segment.
      const double length = (end - start).norm();
      const std::optional<double> expected = ellipse.intersectLine(start, (end - start) / length);
      const bool expect_hit = expected && *expected >= 0.0 && *expected <= length;
      ASSERT_EQ(got.size(), expect_hit ? 1u : 0u) << "phi " << phi << " scale " << scale;
      if (expect_hit) {
        EXPECT_EQ(got[0].disc_id, 11);
        EXPECT_EQ(got[0].t, *expected);  // same bits
        ++hits;
      } else {
        ++misses;
      }
    }
  }
  // Both outcomes must occur, or the segments missed the rim they were aimed at.
  EXPECT_GT(hits, 90);
  EXPECT_GT(misses, 90);
  // The polygon disc goes through Disc::intersectLine itself: inside, on the edge x = 1
  // (the crossing-number test counts the left/bottom edges in), and outside.
  for (const auto& [x, inside] : {std::pair{0.5, true}, std::pair{1.0 + 1e-12, false},
                                  std::pair{0.999999, true}, std::pair{1.5, false}}) {
    const std::vector<ScanlineHit> got = scene.hits({x, 0.2, 3}, {x, 0.2, 5});
    ASSERT_EQ(got.size(), inside ? 1u : 0u) << "x " << x;
    if (inside) {
      EXPECT_EQ(got[0].t, 1.0);
    }
  }
}

// Semi-axes outside float's range: the exact form keeps its per-disc axes in float (1 / a
// and a / b), which would overflow here; such discs must go to Disc::intersectLine, which
// finds a segment through the centre (x = y = 0) and misses one 1 m to the side.
TEST(EmbreeScene, ExactFormHandlesSemiAxesBeyondFloatRange) {
  Disc tiny;  // 1 / a overflows float
  tiny.id = 21;
  tiny.center = Vec3(0, 0, 1);
  tiny.normal = Vec3::UnitZ();
  tiny.major = Vec3::UnitX();
  tiny.a = 1e-39;
  tiny.b = 1e-39;
  Disc sliver;  // a / b overflows float
  sliver.id = 22;
  sliver.center = Vec3(0, 0, 2);
  sliver.normal = Vec3::UnitZ();
  sliver.major = Vec3::UnitX();
  sliver.a = 1.0;
  sliver.b = 1e-39;
  const FractureNetwork network = networkOf({tiny, sliver});
  const ScanlineScene scene(network, DiscForm::ExactEllipse);
  const std::vector<ScanlineHit> through = scene.hits({0, 0, 0}, {0, 0, 3});
  ASSERT_EQ(through.size(), 2u);
  EXPECT_EQ(through[0].disc_id, 21);
  EXPECT_EQ(through[0].t, 1.0);
  EXPECT_EQ(through[1].disc_id, 22);
  EXPECT_EQ(through[1].t, 2.0);
  EXPECT_TRUE(scene.hits({0, 1, 0}, {0, 1, 3}).empty());
}

// Polygon and ellipse discs in one scene, listed polygon first: the triangulated form
// reorders the discs (ellipses first, so that a quad's disc is a division) and must still
// name every disc right; both forms must agree on the crossings (hand-computed below).
TEST(EmbreeScene, PolygonAndEllipseDiscsMixInBothForms) {
  Disc square;
  square.id = 12;
  square.polygon = {{-1, -1, 4}, {1, -1, 4}, {1, 1, 4}, {-1, 1, 4}};
  square.center = Vec3(0, 0, 4);
  square.a = square.b = std::sqrt(2.0);
  Disc triangle;
  triangle.id = 13;
  triangle.polygon = {{-1, -1, 6}, {2, -1, 6}, {0.5, 2, 6}};
  triangle.center = Vec3(0.5, 0, 6);  // its centroid
  triangle.a = triangle.b = 2.0;
  Disc low = horizontalDisc(7, 0.0);
  Disc high = horizontalDisc(8, 2.0);
  const FractureNetwork network = networkOf({square, low, triangle, high});
  for (DiscForm form : {DiscForm::ExactEllipse, DiscForm::Triangulated}) {
    const ScanlineScene scene(network, form);
    // x = 0.5: inside all four (the triangle spans x in [-0.4, 1.4] at y = 0.2).
    const std::vector<ScanlineHit> all = scene.hits({0.5, 0.2, -1}, {0.5, 0.2, 7});
    EXPECT_EQ(ids(all), (std::vector<std::int64_t>{7, 8, 12, 13}));
    ASSERT_EQ(all.size(), 4u);
    EXPECT_NEAR(all[0].t, 1.0, 1e-12);
    EXPECT_NEAR(all[3].t, 7.0, 1e-12);
    // x = 1.5: inside the ellipses (1.5^2/4 + 0.2^2 = 0.6), outside both polygons.
    EXPECT_EQ(ids(scene.hits({1.5, 0.2, -1}, {1.5, 0.2, 7})), (std::vector<std::int64_t>{7, 8}));
  }
}

TEST(EmbreeScene, MovedSceneStillAnswers) {
  ScanlineScene scene(networkOf({horizontalDisc(5, 0.0)}), DiscForm::ExactEllipse);
  ScanlineScene moved(std::move(scene));
  EXPECT_EQ(moved.hits({0, 0, -1}, {0, 0, 1}).size(), 1u);
  EXPECT_THROW(ScanlineScene(networkOf({}), DiscForm::Triangulated, 2), std::invalid_argument);
}

}  // namespace
}  // namespace rockmass::rqd
