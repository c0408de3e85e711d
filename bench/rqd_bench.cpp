// RQD speed: Embree scanlines against brute force, multi-hit rays per second per core with
// RQD included, an RQD ball, an RQD volume, and what accuracy costs (disc form and number of
// directions). Prints Google Benchmark's table, then ratios and errors measured in this run.
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bench/bench_support.h"
#include "geometry/fisher.h"
#include "geometry/fracture_network.h"
#include "geometry/random.h"
#include "rqd/directions.h"
#include "rqd/embree_scene.h"
#include "rqd/p32_grid.h"
#include "rqd/rqd_volume.h"
#include "rqd/scanline_rqd.h"

namespace {

using namespace rockmass;
using geometry::Disc;
using geometry::FractureNetwork;
using geometry::Vec3;
using rqd::DiscForm;
using rqd::ScanlineHit;
using rqd::ScanlineScene;

constexpr double kCube = 100.0;          // side of the rock cube (m)
constexpr double kSegmentLength = 30.0;  // scanline length of the ray benchmarks (m)
constexpr int kSegmentCount = 4096;      // distinct random segments, cycled
/// The thresholds of a typical run: the classic 0.1 m and 1, 2, ..., 10 m.
const std::vector<double> kThresholds{0.1, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10};

/// `count` elliptical discs in the 100 m cube: three Fisher sets (kappa 20), semi-major axis
/// lognormal with mean 4 m and standard deviation 2 m, b = 0.6 a. For 10^4 discs, P32 is
/// about 0.38 m2/m3 and a 30 m scanline crosses about 6 discs.
FractureNetwork discCube(int count) {
  geometry::Rng rng = geometry::makeRng(2024, 7);
  const double sigma2 = std::log(1.0 + 0.25);  // (std / mean)^2 = 0.25
  std::lognormal_distribution<double> size(std::log(4.0) - 0.5 * sigma2, std::sqrt(sigma2));
  const Vec3 poles[3] = {Vec3(0.2, 0.1, 1).normalized(), Vec3(1, 0.3, 0.1).normalized(),
                         Vec3(-0.2, 1, 0.3).normalized()};
  FractureNetwork network;
  network.domain = geometry::Box{Vec3::Zero(), Vec3::Constant(kCube)};
  network.sets.resize(3);
  for (int i = 0; i < count; ++i) {
    Disc disc;
    disc.id = i + 1;
    disc.set = i % 3;
    disc.center = kCube * Vec3(geometry::uniformOpen01(rng), geometry::uniformOpen01(rng),
                               geometry::uniformOpen01(rng));
    disc.normal = geometry::sampleFisher(poles[i % 3], 20.0, rng);
    Vec3 unused;
    geometry::orthonormalBasis(disc.normal, disc.major, unused);
    disc.a = size(rng);
    disc.b = 0.6 * disc.a;
    network.discs.push_back(disc);
  }
  return network;
}

const FractureNetwork& network(int count) {
  static std::map<int, std::unique_ptr<FractureNetwork>> cache;
  auto& slot = cache[count];
  if (!slot) slot = std::make_unique<FractureNetwork>(discCube(count));
  return *slot;
}

/// A scene per (disc count, form, segments), built once.
const ScanlineScene& scene(int count, DiscForm form, int segments = 24) {
  static std::map<std::tuple<int, DiscForm, int>, std::unique_ptr<ScanlineScene>> cache;
  auto& slot = cache[{count, form, segments}];
  if (!slot) slot = std::make_unique<ScanlineScene>(network(count), form, segments);
  return *slot;
}

struct Segment {
  Vec3 start;
  Vec3 end;
};

/// kSegmentCount segments of 30 m starting uniformly in the cube, isotropic directions.
const std::vector<Segment>& segments() {
  static const std::vector<Segment> all = [] {
    geometry::Rng rng = geometry::makeRng(99, 1);
    std::normal_distribution<double> gaussian;
    std::vector<Segment> out;
    for (int i = 0; i < kSegmentCount; ++i) {
      const Vec3 start = kCube * Vec3(geometry::uniformOpen01(rng), geometry::uniformOpen01(rng),
                                      geometry::uniformOpen01(rng));
      const Vec3 dir = Vec3(gaussian(rng), gaussian(rng), gaussian(rng)).normalized();
      out.push_back({start, start + kSegmentLength * dir});
    }
    return out;
  }();
  return all;
}

/// Brute force: every disc tested with Disc::intersectLine, hits in [0, L] sorted.
void bruteForceHits(const std::vector<Disc>& discs, const Segment& s,
                    std::vector<ScanlineHit>& hits) {
  hits.clear();
  const double length = (s.end - s.start).norm();
  const Vec3 dir = (s.end - s.start) / length;
  for (const Disc& disc : discs) {
    const std::optional<double> t = disc.intersectLine(s.start, dir);
    if (t && *t >= 0.0 && *t <= length) hits.push_back({*t, disc.id});
  }
  std::sort(hits.begin(), hits.end(),
            [](const ScanlineHit& p, const ScanlineHit& q) { return p.t < q.t; });
}

void setRayCounters(benchmark::State& state, std::int64_t hits) {
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["hits_per_ray"] =
      static_cast<double>(hits) / static_cast<double>(state.iterations());
}

// ---- 1. Rays per second: Embree against brute force ---------------------------------------

void BM_BruteForce(benchmark::State& state) {
  const FractureNetwork& net = network(static_cast<int>(state.range(0)));
  std::vector<ScanlineHit> hits;
  std::int64_t total = 0;
  std::size_t i = 0;
  for (auto _ : state) {
    bruteForceHits(net.discs, segments()[i++ % kSegmentCount], hits);
    total += static_cast<std::int64_t>(hits.size());
  }
  setRayCounters(state, total);
}
BENCHMARK(BM_BruteForce)->Arg(1000)->Arg(10000)->Arg(100000);

void embreeRays(benchmark::State& state, DiscForm form) {
  const ScanlineScene& s = scene(static_cast<int>(state.range(0)), form);
  std::vector<ScanlineHit> hits;
  std::int64_t total = 0;
  std::size_t i = 0;
  for (auto _ : state) {
    const Segment& segment = segments()[i++ % kSegmentCount];
    s.hits(segment.start, segment.end, hits);
    total += static_cast<std::int64_t>(hits.size());
  }
  setRayCounters(state, total);
}
void BM_EmbreeExact(benchmark::State& state) {
  embreeRays(state, DiscForm::ExactEllipse);
}
void BM_EmbreeTriangulated(benchmark::State& state) {
  embreeRays(state, DiscForm::Triangulated);
}
BENCHMARK(BM_EmbreeExact)->Arg(1000)->Arg(10000)->Arg(100000);
BENCHMARK(BM_EmbreeTriangulated)->Arg(1000)->Arg(10000)->Arg(100000);

/// The triangulated form at 10^4 discs for other outline resolutions (segments per disc).
void BM_EmbreeTriangulatedSegments(benchmark::State& state) {
  const ScanlineScene& s = scene(10000, DiscForm::Triangulated, static_cast<int>(state.range(0)));
  std::vector<ScanlineHit> hits;
  std::int64_t total = 0;
  std::size_t i = 0;
  for (auto _ : state) {
    const Segment& segment = segments()[i++ % kSegmentCount];
    s.hits(segment.start, segment.end, hits);
    total += static_cast<std::int64_t>(hits.size());
  }
  setRayCounters(state, total);
}
BENCHMARK(BM_EmbreeTriangulatedSegments)->Arg(8)->Arg(12)->Arg(16)->Arg(32);

/// Building the scene (both forms build their BVH at high quality): arg 0 the disc count,
/// arg 1 the form (0 exact, 1 triangulated with 24 segments). Embree builds with its own
/// TBB threads; the time is wall time.
void BM_BuildScene(benchmark::State& state) {
  const FractureNetwork& net = network(static_cast<int>(state.range(0)));
  const DiscForm form = state.range(1) == 0 ? DiscForm::ExactEllipse : DiscForm::Triangulated;
  for (auto _ : state) {
    const ScanlineScene built(net, form);
    benchmark::DoNotOptimize(&built);
  }
}
BENCHMARK(BM_BuildScene)
    ->Args({10000, 0})
    ->Args({10000, 1})
    ->Args({100000, 0})
    ->Args({100000, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// ---- 2. Multi-hit rays per core with RQD evaluation -------------------------------------

/// The reference for section 2: the plainest correct all-hits loop on Embree alone, no
/// RQD, written the way Embree's documentation suggests (an intersection filter that
/// appends each hit to a reused buffer and rejects it, so that one rtcIntersect1 call finds
/// every hit; then the buffer is sorted by distance). Float throughout, default scene flags
/// and build quality, no double-precision re-evaluation, no merging of repeated hits.
/// Two of Embree's own primitives for the discs of the same network:
/// - Triangles: each ellipse's 24-gon fanned from its centre (the triangulated form's
///   triangles, as a plain triangle mesh rather than its robust quads);
/// - OrientedDiscs: RTC_GEOMETRY_TYPE_ORIENTED_DISC_POINT, a circle of the same area
///   (radius sqrt(a b)) in the disc's plane, Embree's built-in disc primitive.
class PlainEmbreeScene {
 public:
  enum class Primitive { Triangles, OrientedDiscs };

  /// `occluded`: the loop runs rtcOccluded1 with an occlusion filter instead of
  /// rtcIntersect1 with an intersection filter (what ScanlineScene does: no ordering of the
  /// nodes' children, the same primitives visited).
  PlainEmbreeScene(const FractureNetwork& net, Primitive primitive, bool occluded = false)
      : occluded_(occluded) {
    device_ = rtcNewDevice(nullptr);
    scene_ = rtcNewScene(device_);
    if (primitive == Primitive::Triangles) {
      addTriangles(net);
    } else {
      addOrientedDiscs(net);
    }
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw std::runtime_error("Embree failed");
  }
  ~PlainEmbreeScene() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  PlainEmbreeScene(const PlainEmbreeScene&) = delete;
  PlainEmbreeScene& operator=(const PlainEmbreeScene&) = delete;

  /// One (float distance, primitive id) per hit along the segment, sorted by distance.
  void hits(const Segment& s, std::vector<std::pair<float, unsigned int>>& out) const {
    out.clear();
    const Vec3 d = s.end - s.start;
    const double length = d.norm();
    Context context;
    rtcInitIntersectContext(&context.embree);
    context.out = &out;
    RTCRayHit ray{};
    ray.ray.org_x = static_cast<float>(s.start.x());
    ray.ray.org_y = static_cast<float>(s.start.y());
    ray.ray.org_z = static_cast<float>(s.start.z());
    ray.ray.dir_x = static_cast<float>(d.x() / length);
    ray.ray.dir_y = static_cast<float>(d.y() / length);
    ray.ray.dir_z = static_cast<float>(d.z() / length);
    ray.ray.tnear = 0.0f;
    ray.ray.tfar = static_cast<float>(length);
    ray.ray.mask = ~0u;
    ray.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    if (occluded_) {
      rtcOccluded1(scene_, &context.embree, &ray.ray);
    } else {
      rtcIntersect1(scene_, &context.embree, &ray);
    }
    std::sort(out.begin(), out.end());
  }

 private:
  struct Context {
    RTCIntersectContext embree;
    std::vector<std::pair<float, unsigned int>>* out;
  };
  static void collect(const RTCFilterFunctionNArguments* args) {
    auto& out = *reinterpret_cast<const Context*>(args->context)->out;
    for (unsigned int i = 0; i < args->N; ++i) {
      if (args->valid[i] == 0) continue;
      args->valid[i] = 0;
      out.emplace_back(RTCRayN_tfar(args->ray, args->N, i), RTCHitN_primID(args->hit, args->N, i));
    }
  }
  void attach(RTCGeometry geometry) {
    rtcSetGeometryIntersectFilterFunction(geometry, &collect);
    rtcSetGeometryOccludedFilterFunction(geometry, &collect);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
  }
  void addTriangles(const FractureNetwork& net) {
    constexpr unsigned int kSegments = 24;
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), net.discs.size() * (kSegments + 1)));
    auto* indices = static_cast<unsigned int*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned int), net.discs.size() * kSegments));
    unsigned int v = 0;
    unsigned int t = 0;
    for (const Disc& disc : net.discs) {
      const unsigned int first = v;
      for (int k = 0; k < 3; ++k) vertices[3 * v + k] = static_cast<float>(disc.center[k]);
      ++v;
      for (const Vec3& p : disc.outline(kSegments)) {
        for (int k = 0; k < 3; ++k) vertices[3 * v + k] = static_cast<float>(p[k]);
        ++v;
      }
      for (unsigned int k = 0; k < kSegments; ++k, ++t) {
        indices[3 * t] = first;
        indices[3 * t + 1] = first + 1 + k;
        indices[3 * t + 2] = first + 1 + (k + 1) % kSegments;
      }
    }
    attach(geometry);
  }
  void addOrientedDiscs(const FractureNetwork& net) {
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_ORIENTED_DISC_POINT);
    auto* points = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                               RTC_FORMAT_FLOAT4, 4 * sizeof(float),
                                                               net.discs.size()));
    auto* normals = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_NORMAL, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), net.discs.size()));
    for (std::size_t i = 0; i < net.discs.size(); ++i) {
      const Disc& disc = net.discs[i];
      for (int k = 0; k < 3; ++k) {
        points[4 * i + k] = static_cast<float>(disc.center[k]);
        normals[3 * i + k] = static_cast<float>(disc.normal[k]);
      }
      points[4 * i + 3] = static_cast<float>(std::sqrt(disc.a * disc.b));
    }
    attach(geometry);
  }

  bool occluded_ = false;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

void plainEmbreeRays(benchmark::State& state, PlainEmbreeScene::Primitive primitive,
                     bool occluded = false) {
  static std::map<std::pair<PlainEmbreeScene::Primitive, bool>, std::unique_ptr<PlainEmbreeScene>>
      cache;
  auto& slot = cache[{primitive, occluded}];
  if (!slot) slot = std::make_unique<PlainEmbreeScene>(network(10000), primitive, occluded);
  std::vector<std::pair<float, unsigned int>> hits;
  std::int64_t total = 0;
  std::size_t i = 0;
  for (auto _ : state) {
    slot->hits(segments()[i++ % kSegmentCount], hits);
    total += static_cast<std::int64_t>(hits.size());
  }
  setRayCounters(state, total);
}
/// Plain Embree multi-hit loop, triangle fans (no RQD).
void BM_PlainEmbreeTriangles(benchmark::State& state) {
  plainEmbreeRays(state, PlainEmbreeScene::Primitive::Triangles);
}
/// Plain Embree multi-hit loop, Embree's oriented disc points (no RQD).
void BM_PlainEmbreeDiscs(benchmark::State& state) {
  plainEmbreeRays(state, PlainEmbreeScene::Primitive::OrientedDiscs);
}
/// The same on Embree's oriented disc points, by rtcOccluded1 and an occlusion filter.
void BM_PlainEmbreeDiscsOccluded(benchmark::State& state) {
  plainEmbreeRays(state, PlainEmbreeScene::Primitive::OrientedDiscs, /*occluded=*/true);
}
BENCHMARK(BM_PlainEmbreeTriangles);
BENCHMARK(BM_PlainEmbreeDiscs);
BENCHMARK(BM_PlainEmbreeDiscsOccluded);

/// One scanline: all hits, then RQD for the 11 thresholds (as an RQD ball or volume does).
double scanlineRqd(const ScanlineScene& s, const Vec3& start, const Vec3& end,
                   std::vector<ScanlineHit>& hits, std::vector<double>& distances,
                   std::vector<double>& values) {
  s.hits(start, end, hits);
  distances.clear();
  const double length = (end - start).norm();
  for (const ScanlineHit& hit : hits) distances.push_back(std::min(hit.t, length));
  rqd::rqd(distances, length, kThresholds, values);
  return values.front();
}

void rqdRays(benchmark::State& state, DiscForm form) {
  const ScanlineScene& s = scene(10000, form);
  std::vector<ScanlineHit> hits;
  std::vector<double> distances;
  std::vector<double> values(kThresholds.size());
  std::size_t i = 0;
  for (auto _ : state) {
    const Segment& segment = segments()[i++ % kSegmentCount];
    benchmark::DoNotOptimize(scanlineRqd(s, segment.start, segment.end, hits, distances, values));
  }
  state.counters["rays_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
void BM_RqdRaysExact(benchmark::State& state) {
  rqdRays(state, DiscForm::ExactEllipse);
}
void BM_RqdRaysTriangulated(benchmark::State& state) {
  rqdRays(state, DiscForm::Triangulated);
}
BENCHMARK(BM_RqdRaysExact);
BENCHMARK(BM_RqdRaysTriangulated);

// ---- 2b. Paired ratios: interleaved batches, robust to a changing machine load -----------
//
// The benchmarks above run one after the other, so on a machine shared with other jobs
// their ratios also measure how the load changed between them. Here the contenders take
// turns in small batches of the same segments inside one benchmark, and each one's thread
// CPU time is summed: every contender sees the same load, caches evicted by the same
// neighbours. The counters are the ratios (> 1: ours faster).

double threadCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

/// Times `run(segment)` over `count` segments from `first` (cycled), thread CPU seconds.
template <typename Run>
double timeBatch(std::size_t first, std::size_t count, Run&& run) {
  const double start = threadCpuSeconds();
  for (std::size_t k = 0; k < count; ++k) run(segments()[(first + k) % kSegmentCount]);
  return threadCpuSeconds() - start;
}

/// Ours with RQD (arg 0: exact; 1: triangulated, 24 segments) against the plain Embree disc
/// loop (rtcIntersect1, as documented, and rtcOccluded1): batches of 2048 segments in turn
/// (about 2 ms each: long enough for each contender's working set to be loaded once per
/// batch, as in a long run, short enough that load changes hit all three alike).
void BM_PairedRqdVsPlainDiscs(benchmark::State& state) {
  const DiscForm form = state.range(0) == 0 ? DiscForm::ExactEllipse : DiscForm::Triangulated;
  const ScanlineScene& ours = scene(10000, form);
  static const PlainEmbreeScene plain(network(10000), PlainEmbreeScene::Primitive::OrientedDiscs);
  static const PlainEmbreeScene plain_occluded(network(10000),
                                               PlainEmbreeScene::Primitive::OrientedDiscs, true);
  std::vector<ScanlineHit> hits;
  std::vector<double> distances;
  std::vector<double> values(kThresholds.size());
  std::vector<std::pair<float, unsigned int>> plain_hits;
  constexpr std::size_t kBatch = 2048;
  double t_ours = 0.0, t_plain = 0.0, t_plain_occluded = 0.0;
  std::size_t first = 0;
  for (auto _ : state) {
    t_plain += timeBatch(first, kBatch, [&](const Segment& s) { plain.hits(s, plain_hits); });
    t_ours += timeBatch(first, kBatch, [&](const Segment& s) {
      benchmark::DoNotOptimize(scanlineRqd(ours, s.start, s.end, hits, distances, values));
    });
    t_plain_occluded +=
        timeBatch(first, kBatch, [&](const Segment& s) { plain_occluded.hits(s, plain_hits); });
    first += kBatch;
  }
  const double rays = static_cast<double>(state.iterations() * kBatch);
  state.counters["ours_rays_per_s"] = rays / t_ours;
  state.counters["plain_rays_per_s"] = rays / t_plain;
  state.counters["ratio_vs_plain"] = t_plain / t_ours;
  state.counters["ratio_vs_plain_occluded"] = t_plain_occluded / t_ours;
}
BENCHMARK(BM_PairedRqdVsPlainDiscs)->Arg(0)->Arg(1)->MinTime(3.0);

/// Speed-up over brute force at 10^4 discs (arg 0: exact; n > 0: triangulated with n
/// segments): 16 brute-force segments (about 1.6 ms), then all 4096 segments through Embree
/// (2-10 ms), in turn. The brute force streams every disc through the cache and so evicts
/// Embree's BVH: each Embree batch starts cold, which short batches would overweight.
void BM_PairedSpeedup(benchmark::State& state) {
  const int segments_arg = static_cast<int>(state.range(0));
  const ScanlineScene& s = segments_arg == 0 ? scene(10000, DiscForm::ExactEllipse)
                                             : scene(10000, DiscForm::Triangulated, segments_arg);
  const FractureNetwork& net = network(10000);
  std::vector<ScanlineHit> hits;
  constexpr std::size_t kBrute = 16;
  constexpr std::size_t kEmbree = kSegmentCount;
  double t_brute = 0.0, t_embree = 0.0;
  std::size_t first = 0;
  for (auto _ : state) {
    t_brute += timeBatch(first, kBrute,
                         [&](const Segment& segment) { bruteForceHits(net.discs, segment, hits); });
    t_embree += timeBatch(
        first, kEmbree, [&](const Segment& segment) { s.hits(segment.start, segment.end, hits); });
    first += kBrute;
  }
  const double per_brute = t_brute / static_cast<double>(state.iterations() * kBrute);
  const double per_embree = t_embree / static_cast<double>(state.iterations() * kEmbree);
  state.counters["brute_us"] = 1e6 * per_brute;
  state.counters["embree_us"] = 1e6 * per_embree;
  state.counters["speedup"] = per_brute / per_embree;
}
BENCHMARK(BM_PairedSpeedup)->Arg(0)->Arg(24)->Arg(8)->MinTime(3.0);

// ---- 3. An RQD ball and an RQD volume -----------------------------------------------------

/// Mean RQD(0.1 m) of a ball of `directions` scanlines of 30 m through `center`.
double ball(const ScanlineScene& s, const Vec3& center, const std::vector<Vec3>& directions,
            std::vector<double>& per_threshold_mean) {
  std::vector<ScanlineHit> hits;
  std::vector<double> distances;
  std::vector<double> values(kThresholds.size());
  per_threshold_mean.assign(kThresholds.size(), 0.0);
  for (const Vec3& d : directions) {
    scanlineRqd(s, center - 0.5 * kSegmentLength * d, center + 0.5 * kSegmentLength * d, hits,
                distances, values);
    for (std::size_t t = 0; t < values.size(); ++t) per_threshold_mean[t] += values[t];
  }
  for (double& v : per_threshold_mean) v /= static_cast<double>(directions.size());
  return per_threshold_mean.front();
}

void BM_RqdBall2000x11(benchmark::State& state) {
  const DiscForm form = state.range(0) == 0 ? DiscForm::ExactEllipse : DiscForm::Triangulated;
  const ScanlineScene& s = scene(10000, form);
  const std::vector<Vec3> directions = rqd::fibonacciSphere(2000);
  std::vector<double> means;
  for (auto _ : state) {
    benchmark::DoNotOptimize(ball(s, Vec3::Constant(0.5 * kCube), directions, means));
  }
}
BENCHMARK(BM_RqdBall2000x11)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

/// 50 x 50 x 40 = 10^5 cells of 2 m, 200 axes, 20 m scanlines, 11 thresholds, on the
/// threads given (the machine has 2 cores).
void BM_RqdVolume1e5Cells(benchmark::State& state) {
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(state.range(0)));
  const FractureNetwork& net = network(10000);
  const ScanlineScene& s = scene(10000, DiscForm::ExactEllipse);
  rqd::VolumeSpec spec;
  spec.region = geometry::Box{Vec3(0, 0, 10), Vec3(100, 100, 90)};
  spec.cell_size = 2.0;
  spec.scanline_length = 20.0;
  spec.direction_count = 200;
  spec.thresholds = kThresholds;
  for (auto _ : state) {
    // std::clock: CPU time of the whole process, all threads (Google Benchmark's CPU time is
    // the main thread's only). On a loaded machine, process CPU / threads is the wall time
    // the run would take with the threads' cores to itself.
    const std::clock_t cpu_start = std::clock();
    const rqd::RqdVolume volume = rqd::computeRqdVolume(s, net, spec);
    const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    benchmark::DoNotOptimize(volume.p32.data());
    state.counters["cells"] = static_cast<double>(volume.grid.cellCount());
    state.counters["process_cpu_s"] = cpu;
    state.counters["cpu_per_thread_s"] = cpu / static_cast<double>(state.range(0));
  }
}
BENCHMARK(BM_RqdVolume1e5Cells)->Arg(2)->Unit(benchmark::kSecond)->Iterations(1);

/// The P32 part of the volume alone (10^5 cells, 10^4 discs).
void BM_P32Volume1e5Cells(benchmark::State& state) {
  const FractureNetwork& net = network(10000);
  const rqd::CellGrid grid =
      rqd::cellGridIn(geometry::Box{Vec3(0, 0, 10), Vec3(100, 100, 90)}, 2.0);
  for (auto _ : state) benchmark::DoNotOptimize(rqd::p32Grid(net, grid).data());
}
BENCHMARK(BM_P32Volume1e5Cells)->Unit(benchmark::kMillisecond);

// ---- 4. Accuracy against time -------------------------------------------------------------

/// Balls at a few centres: the per-direction RQD values (all thresholds) of a setting.
std::vector<double> ballValues(const ScanlineScene& s, int directions) {
  const std::vector<Vec3> axes = rqd::fibonacciSphere(directions);
  std::vector<double> values;
  std::vector<ScanlineHit> hits;
  std::vector<double> distances;
  for (const Vec3& center : {Vec3(30, 40, 50), Vec3(50, 50, 50), Vec3(70, 60, 40)}) {
    for (const Vec3& d : axes) {
      s.hits(center - 0.5 * kSegmentLength * d, center + 0.5 * kSegmentLength * d, hits);
      distances.clear();
      for (const ScanlineHit& hit : hits) distances.push_back(std::min(hit.t, kSegmentLength));
      for (double v : rqd::rqd(distances, kSegmentLength, kThresholds)) values.push_back(v);
    }
  }
  return values;
}

/// Disc form: time per scanline (RQD included) and the mean absolute RQD difference per
/// scanline and threshold against the exact ellipse (2000 directions at 3 centres).
/// Arg 0: exact; n > 0: triangulated with n segments.
void BM_AccuracyForm(benchmark::State& state) {
  const int segments_arg = static_cast<int>(state.range(0));
  const DiscForm form = segments_arg == 0 ? DiscForm::ExactEllipse : DiscForm::Triangulated;
  const ScanlineScene& s = scene(10000, form, segments_arg == 0 ? 24 : segments_arg);
  std::vector<double> values;
  for (auto _ : state) values = ballValues(s, 2000);
  const std::vector<double> reference = ballValues(scene(10000, DiscForm::ExactEllipse), 2000);
  double error = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) error += std::abs(values[i] - reference[i]);
  state.counters["rqd_error"] = error / static_cast<double>(values.size());
  state.counters["rays_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * 3 * 2000, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_AccuracyForm)
    ->Arg(0)
    ->Arg(8)
    ->Arg(16)
    ->Arg(32)
    ->Arg(64)
    ->Unit(benchmark::kMillisecond);

/// Direction count: the ball's mean RQD over directions (what a volume cell stores), its
/// error against 32 000 directions (largest over thresholds and 3 centres), and the time.
void BM_AccuracyDirections(benchmark::State& state) {
  const int directions = static_cast<int>(state.range(0));
  const ScanlineScene& s = scene(10000, DiscForm::ExactEllipse);
  const std::vector<Vec3> centers{Vec3(30, 40, 50), Vec3(50, 50, 50), Vec3(70, 60, 40)};
  const auto means = [&](int count) {
    std::vector<double> all;
    std::vector<double> per_threshold;
    for (const Vec3& c : centers) {
      ball(s, c, rqd::fibonacciSphere(count), per_threshold);
      all.insert(all.end(), per_threshold.begin(), per_threshold.end());
    }
    return all;
  };
  std::vector<double> values;
  for (auto _ : state) values = means(directions);
  static const std::vector<double> reference = means(32000);
  double worst = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    worst = std::max(worst, std::abs(values[i] - reference[i]));
  }
  state.counters["mean_rqd_error"] = worst;
}
BENCHMARK(BM_AccuracyDirections)
    ->Arg(100)
    ->Arg(500)
    ->Arg(2000)
    ->Arg(8000)
    ->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  rockmass::bench::RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  // CPU time: the ratios compare single-threaded benchmarks, and on a machine shared with
  // other jobs the wall time also counts the time the thread waited for a core.
  const auto t = reporter.cpuTimes();
  std::printf("\nSpeed-up over brute force (same run, CPU time per ray):\n");
  for (const char* n : {"1000", "10000", "100000"}) {
    const std::string brute = std::string("BM_BruteForce/") + n;
    for (const char* form : {"BM_EmbreeExact/", "BM_EmbreeTriangulated/"}) {
      const std::string embree = form + std::string(n);
      if (t.count(brute) && t.count(embree)) {
        std::printf("  %-30s %8.1fx\n", embree.c_str(), t.at(brute) / t.at(embree));
      }
    }
  }
  for (const char* segments : {"8", "12", "16", "32"}) {
    const std::string name = std::string("BM_EmbreeTriangulatedSegments/") + segments;
    if (t.count("BM_BruteForce/10000") && t.count(name)) {
      std::printf("  %-30s %8.1fx  (triangulated, %s segments, 10^4 discs)\n", name.c_str(),
                  t.at("BM_BruteForce/10000") / t.at(name), segments);
    }
  }
  std::printf(
      "\nMulti-hit rays per second, ours with RQD (11 thresholds) over a plain Embree "
      "multi-hit loop without RQD\n(same run, one thread, CPU time; target >= 1):\n");
  for (const char* ours : {"BM_RqdRaysExact", "BM_RqdRaysTriangulated"}) {
    for (const char* plain :
         {"BM_PlainEmbreeDiscs", "BM_PlainEmbreeDiscsOccluded", "BM_PlainEmbreeTriangles"}) {
      if (t.count(ours) && t.count(plain)) {
        std::printf("  %-24s / %-28s = %.3f  (%.0f k / %.0f k rays/s)\n", ours, plain,
                    t.at(plain) / t.at(ours), 1e6 / t.at(ours), 1e6 / t.at(plain));
      }
    }
  }
  std::printf("\nPaired (interleaved batches, thread CPU time; robust to load changes):\n");
  for (const auto& [name, value] : reporter.counterValues("ratio_vs_plain")) {
    std::printf("  %-36s ours / plain Embree discs = %.3f (intersect), %.3f (occluded)\n",
                name.c_str(), value, reporter.counterValues("ratio_vs_plain_occluded").at(name));
  }
  for (const auto& [name, value] : reporter.counterValues("speedup")) {
    std::printf("  %-36s speed-up over brute force at 10^4 discs = %.1fx\n", name.c_str(), value);
  }
  std::printf("\nRatios (same run, CPU time):\n");
  const auto ratio = [&](const std::string& a, const std::string& b) {
    if (t.count(a) && t.count(b))
      std::printf("  %-32s / %-32s = %.3f\n", a.c_str(), b.c_str(), t.at(a) / t.at(b));
  };
  ratio("BM_RqdRaysTriangulated", "BM_RqdRaysExact");
  ratio("BM_RqdRaysExact", "BM_EmbreeExact/10000");
  for (const char* segments : {"8", "16", "32", "64"}) {
    ratio(std::string("BM_AccuracyForm/") + segments, "BM_AccuracyForm/0");
  }
  for (const char* count : {"500", "2000", "8000"}) {
    ratio(std::string("BM_AccuracyDirections/") + count, "BM_AccuracyDirections/100");
  }
  benchmark::Shutdown();
  return 0;
}
