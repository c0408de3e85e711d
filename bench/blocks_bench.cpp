// Block cutting: the density and size series of issue 3 and the disc_segments column, for
// both cutters (plus the constant-intensity size series, FastConstP32). Each series runs alone with
// --benchmark_filter, e.g. 'FastSize', 'ExactDensity/(10|30|100)$', 'Segments', '/100$' (both
// cutters at 100 discs). Scenes come from scenarios/disc_scenes.h, so another cutter can run the
// very same series: add a BM_<Cutter>Density / BM_<Cutter>Size pair below that calls it. Prints
// Google Benchmark's table, then comparisons as ratios measured in this run.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include "bench/bench_support.h"
#include "blocks/exact_cutter.h"
#include "blocks/fast_cutter.h"
#include "scenarios/disc_scenes.h"

namespace {

using namespace rockmass::blocks;

/// CPU seconds of the whole process (all threads) since it started: with other jobs on the
/// machine, CPU time per cut is steadier than wall time.
double processCpuSeconds() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

/// Cuts `spec` with the fast cutter, reporting blocks and pieces.
void fastCut(benchmark::State& state, const DiscSceneSpec& spec, int segments,
             const FastCutOptions& options = {}) {
  const rockmass::geometry::FractureNetwork network = randomDiscNetwork(spec);
  const CutInput input = boxCutInput(network, segments);
  FastCutReport report;
  std::size_t blocks = 0;
  const double cpu_start = processCpuSeconds();
  for (auto _ : state) {
    const BlockModel model = cutFast(input, options, &report);
    blocks = model.blocks.size();
    benchmark::DoNotOptimize(model.blocks.data());
  }
  state.counters["cpu_s"] =
      (processCpuSeconds() - cpu_start) / static_cast<double>(state.iterations());
  state.counters["discs"] = spec.discs;
  state.counters["blocks"] = static_cast<double>(blocks);
  state.counters["pieces"] = report.pieces;
  state.counters["cut_s"] = report.cut_seconds;
  state.counters["assemble_s"] = report.assemble_seconds;
  state.counters["cover_s"] = report.coverage_seconds;
  state.counters["contact_s"] = report.contact_seconds;
}

/// Density series: n discs of radius 3-7 m (aspect 0.6, 24 segments) in one 10 m cube.
void BM_FastDensity(benchmark::State& state) {
  DiscSceneSpec spec;
  spec.discs = static_cast<int>(state.range(0));
  fastCut(state, spec, 24);
}
BENCHMARK(BM_FastDensity)
    ->Arg(10)
    ->Arg(30)
    ->Arg(100)
    ->Arg(200)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

/// The density series with the fast cutter's other strategy (FastStrategy::EdgePlanes, the
/// issue's original design), for the piece counts and times of both in one run.
void BM_FastEdgeDensity(benchmark::State& state) {
  DiscSceneSpec spec;
  spec.discs = static_cast<int>(state.range(0));
  FastCutOptions options;
  options.strategy = FastStrategy::EdgePlanes;
  fastCut(state, spec, 24, options);
}
BENCHMARK(BM_FastEdgeDensity)
    ->Arg(10)
    ->Arg(30)
    ->Arg(100)
    ->Arg(200)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

/// The density series with the contact search of the previous sessions (every plane
/// searched geometrically, FastCutOptions::track_contacts = false), for the gain of tracking
/// the face neighbours through the splits, measured in the same run.
void BM_FastSearchDensity(benchmark::State& state) {
  DiscSceneSpec spec;
  spec.discs = static_cast<int>(state.range(0));
  FastCutOptions options;
  options.track_contacts = false;
  fastCut(state, spec, 24, options);
}
BENCHMARK(BM_FastSearchDensity)
    ->Arg(10)
    ->Arg(30)
    ->Arg(100)
    ->Arg(200)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

/// Size series: n discs at the density of the 100-disc case, cube side 10 (n/100)^(1/3) m.
void BM_FastSize(benchmark::State& state) {
  fastCut(state, sizeSeriesScene(static_cast<int>(state.range(0))), 24);
}
BENCHMARK(BM_FastSize)
    ->Arg(100)
    ->Arg(300)
    ->Arg(1000)
    ->Arg(3000)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

/// Constant-intensity size series (scenarios/disc_scenes.h, constantIntensityScene): the cube
/// of the size series, discs centred in the cube grown by 7 m at the same density, so P32
/// inside the cube is the same for every n (the size series' P32 grows with n: fewer of its
/// discs stick out of a larger cube). Work per unit volume is constant: time should grow
/// like n. Counters: p32 (m2/m3 inside the cube, Disc::areaInside), generated discs.
void BM_FastConstP32(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const DiscSceneSpec spec = constantIntensityScene(n);
  const rockmass::geometry::FractureNetwork network = randomDiscNetwork(spec);
  double area = 0.0;
  for (const rockmass::geometry::Disc& d : network.discs) area += d.areaInside(network.domain);
  fastCut(state, spec, 24);
  state.counters["discs"] = n;
  state.counters["generated"] = spec.discs;
  state.counters["p32"] = area / network.domain.size().prod();
}
BENCHMARK(BM_FastConstP32)
    ->Arg(100)
    ->Arg(300)
    ->Arg(1000)
    ->Arg(3000)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

/// Cuts `spec` with the exact cutter (default options: kd regions of at most 30 discs, all
/// cores, no referee), reporting blocks, pieces and regions. One iteration: a cut takes
/// seconds.
void exactCut(benchmark::State& state, const DiscSceneSpec& spec, int segments) {
  const rockmass::geometry::FractureNetwork network = randomDiscNetwork(spec);
  const CutInput input = boxCutInput(network, segments);
  ExactCutReport report;
  std::size_t blocks = 0;
  const double cpu_start = processCpuSeconds();
  for (auto _ : state) {
    const BlockModel model = cutExact(input, {}, &report);
    blocks = model.blocks.size();
    benchmark::DoNotOptimize(model.blocks.data());
  }
  state.counters["cpu_s"] =
      (processCpuSeconds() - cpu_start) / static_cast<double>(state.iterations());
  state.counters["discs"] = spec.discs;
  state.counters["blocks"] = static_cast<double>(blocks);
  state.counters["pieces"] = report.pieces;
  state.counters["regions"] = report.regions;
  state.counters["split_cpu_s"] = report.split_seconds;
  state.counters["extract_cpu_s"] = report.extract_seconds;
  state.counters["glue_s"] = report.glue_seconds;
}

void BM_ExactDensity(benchmark::State& state) {
  DiscSceneSpec spec;
  spec.discs = static_cast<int>(state.range(0));
  exactCut(state, spec, 24);
}
BENCHMARK(BM_ExactDensity)
    ->Arg(10)
    ->Arg(30)
    ->Arg(100)
    ->Arg(200)
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_ExactSize(benchmark::State& state) {
  exactCut(state, sizeSeriesScene(static_cast<int>(state.range(0))), 24);
}
BENCHMARK(BM_ExactSize)
    ->Arg(100)
    ->Arg(300)
    ->Arg(1000)
    ->Arg(3000)
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

/// disc_segments column at 100 discs in the 10 m cube: time, and the volume error against
/// the same cutter with 96 segments, two ways:
/// - volume_error: the L1 distance between the sorted block volumes (shorter list padded
///   with zeros) over the domain volume, i.e. the share of the rock that changes block size;
/// - block_error: per block of the 96-segment model, the relative volume error of the block
///   whose centroid is nearest, averaged over the blocks; blocks_off_1pct: the share of
///   blocks off by more than 1%;
/// - total_error: |sum of block volumes - domain volume| / domain volume (conservation).
/// The 96-segment reference is cut once per cutter and kept.
std::vector<double> sortedVolumes(const BlockModel& model) {
  std::vector<double> v;
  for (const Block& b : model.blocks) v.push_back(b.mass.volume);
  std::sort(v.begin(), v.end(), std::greater<>());
  return v;
}
double sortedVolumeError(const BlockModel& model, const BlockModel& reference) {
  std::vector<double> a = sortedVolumes(model);
  std::vector<double> b = sortedVolumes(reference);
  a.resize(std::max(a.size(), b.size()), 0.0);
  b.resize(a.size(), 0.0);
  double l1 = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) l1 += std::abs(a[i] - b[i]);
  return l1 / reference.domain_volume;
}
/// Per block of `reference`, the block of `model` whose centroid is nearest; returns the
/// mean relative volume error over the reference blocks and the share of them off by > 1%.
std::pair<double, double> blockErrors(const BlockModel& model, const BlockModel& reference) {
  double sum = 0.0;
  int off = 0;
  for (const Block& r : reference.blocks) {
    const rockmass::geometry::Vec3 c = r.mass.centroid();
    const Block* nearest = nullptr;
    double best = std::numeric_limits<double>::infinity();
    for (const Block& b : model.blocks) {
      const double d = (b.mass.centroid() - c).squaredNorm();
      if (d < best) {
        best = d;
        nearest = &b;
      }
    }
    const double e = nearest ? std::abs(nearest->mass.volume - r.mass.volume) / r.mass.volume : 1.0;
    sum += e;
    off += e > 0.01;
  }
  const double n = std::max<double>(1.0, static_cast<double>(reference.blocks.size()));
  return {sum / n, off / n};
}
/// Sets the segment column's counters of `model` against the cached 96-segment reference.
void segmentErrors(benchmark::State& state, const BlockModel& model, const BlockModel& reference) {
  state.counters["volume_error"] = sortedVolumeError(model, reference);
  const auto [mean, off] = blockErrors(model, reference);
  state.counters["block_error"] = mean;
  state.counters["blocks_off_1pct"] = off;
  state.counters["total_error"] =
      std::abs(std::accumulate(model.blocks.begin(), model.blocks.end(), 0.0,
                               [](double s, const Block& b) { return s + b.mass.volume; }) -
               reference.domain_volume) /
      reference.domain_volume;
}

const rockmass::geometry::FractureNetwork& segmentsNetwork() {
  static const rockmass::geometry::FractureNetwork network = [] {
    DiscSceneSpec spec;
    spec.discs = 100;
    return randomDiscNetwork(spec);
  }();
  return network;
}

void BM_FastSegments(benchmark::State& state) {
  const int segments = static_cast<int>(state.range(0));
  const CutInput input = boxCutInput(segmentsNetwork(), segments);
  FastCutReport report;
  BlockModel model;
  const double cpu_start = processCpuSeconds();
  for (auto _ : state) {
    model = cutFast(input, &report);
    benchmark::DoNotOptimize(model.blocks.data());
  }
  state.counters["cpu_s"] =
      (processCpuSeconds() - cpu_start) / static_cast<double>(state.iterations());
  static const BlockModel reference = cutFast(boxCutInput(segmentsNetwork(), 96));
  state.counters["blocks"] = static_cast<double>(model.blocks.size());
  state.counters["pieces"] = report.pieces;
  segmentErrors(state, model, reference);
}
BENCHMARK(BM_FastSegments)
    ->Arg(8)
    ->Arg(16)
    ->Arg(24)
    ->Arg(48)
    ->Arg(96)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_ExactSegments(benchmark::State& state) {
  const int segments = static_cast<int>(state.range(0));
  const CutInput input = boxCutInput(segmentsNetwork(), segments);
  ExactCutReport report;
  BlockModel model;
  const double cpu_start = processCpuSeconds();
  for (auto _ : state) {
    model = cutExact(input, {}, &report);
    benchmark::DoNotOptimize(model.blocks.data());
  }
  state.counters["cpu_s"] =
      (processCpuSeconds() - cpu_start) / static_cast<double>(state.iterations());
  static const BlockModel reference = cutExact(boxCutInput(segmentsNetwork(), 96), {});
  state.counters["blocks"] = static_cast<double>(model.blocks.size());
  state.counters["pieces"] = report.pieces;
  segmentErrors(state, model, reference);
}
BENCHMARK(BM_ExactSegments)
    ->Arg(8)
    ->Arg(16)
    ->Arg(24)
    ->Arg(48)
    ->Arg(96)
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

/// One FAB-like circle of n vertices (radius 4 m, tilted) ending inside a 10 m cube: a crack
/// whose covered part of the cells' faces is the n-gon. The fast cutter's cost should grow
/// like n (over 64 edges it clips the polygon by the faces, not the faces by its n edges).
void BM_FastManyVertexPolygon(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  rockmass::geometry::FractureNetwork network;
  network.domain = {rockmass::geometry::Vec3::Zero(), rockmass::geometry::Vec3::Constant(10.0)};
  const rockmass::geometry::Vec3 normal = rockmass::geometry::Vec3(0.2, 0.1, 1.0).normalized();
  const rockmass::geometry::Vec3 u = normal.unitOrthogonal();
  const rockmass::geometry::Vec3 v = normal.cross(u);
  std::vector<rockmass::geometry::Vec3> points;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n;
    points.push_back(rockmass::geometry::Vec3::Constant(5.0) +
                     4.0 * (std::cos(t) * u + std::sin(t) * v));
  }
  network.discs.push_back(rockmass::geometry::discFromPolygon(points));
  network.discs.back().id = 1;
  const CutInput input = boxCutInput(network);
  BlockModel model;
  for (auto _ : state) {
    model = cutFast(input);
    benchmark::DoNotOptimize(model.blocks.data());
  }
  state.counters["vertices"] = n;
  state.counters["blocks"] = static_cast<double>(model.blocks.size());
}
BENCHMARK(BM_FastManyVertexPolygon)
    ->Arg(1000)
    ->Arg(10000)
    ->Arg(100000)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  rockmass::bench::RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  // Registered names carry the run options (".../iterations:1/real_time"): look up by prefix.
  const auto find = [&](const std::string& prefix) -> const rockmass::bench::Record* {
    return reporter.find(prefix);
  };
  std::printf("\nSize series, time growth (same run; growth/linear 1.0 = linear):\n");
  for (const std::string series : {"FastSize", "ExactSize", "FastConstP32"}) {
    const std::string cutter = series;
    const auto* base = find("BM_" + series + "/100");
    std::vector<double> log_n, log_t, log_c, log_p;
    for (int n : {100, 300, 1000, 3000}) {
      const std::string name = "BM_" + series + "/" + std::to_string(n);
      const auto* r = find(name);
      if (!r) continue;
      log_n.push_back(std::log(n));
      log_t.push_back(std::log(r->real_time));
      log_c.push_back(std::log(r->counters.at("cpu_s")));
      log_p.push_back(std::log(r->counters.at("pieces")));
      std::printf("  %-16s pieces %9.0f  CPU per piece %6.2f us\n", name.c_str(),
                  r->counters.at("pieces"),
                  1e6 * r->counters.at("cpu_s") / r->counters.at("pieces"));
      if (base && n > 100) {
        const double wall = r->real_time / base->real_time;
        const double cpu = r->counters.at("cpu_s") / base->counters.at("cpu_s");
        std::printf(
            "  %-16s n/100 = %5.1f  wall t/t(100) = %7.2f (growth/linear %.2f)  CPU %7.2f "
            "(growth/linear %.2f)\n",
            name.c_str(), n / 100.0, wall, wall / (n / 100.0), cpu, cpu / (n / 100.0));
      }
    }
    if (log_n.size() >= 2) {
      // Least-squares slope of log t (and log pieces) against log n: time ~ n^slope.
      const auto slope = [&](const std::vector<double>& y) {
        const double mx = std::accumulate(log_n.begin(), log_n.end(), 0.0) / log_n.size();
        const double my = std::accumulate(y.begin(), y.end(), 0.0) / y.size();
        double sxy = 0.0, sxx = 0.0;
        for (std::size_t i = 0; i < log_n.size(); ++i) {
          sxy += (log_n[i] - mx) * (y[i] - my);
          sxx += (log_n[i] - mx) * (log_n[i] - mx);
        }
        return sxy / sxx;
      };
      std::printf(
          "  %-12s fitted over %zu sizes: wall ~ n^%.2f, CPU ~ n^%.2f, pieces ~ n^%.2f"
          " (target: growth within 1.3x of linear)\n",
          cutter.c_str(), log_n.size(), slope(log_t), slope(log_c), slope(log_p));
    }
  }
  if (const auto* small = find("BM_FastManyVertexPolygon/1000")) {
    std::printf("One polygon of n vertices, time over n = 1000 (same run; linear = n/1000):\n");
    for (int n : {10000, 100000}) {
      if (const auto* r = find("BM_FastManyVertexPolygon/" + std::to_string(n))) {
        std::printf("  %6d vertices: %8.1f ms, t/t(1000) = %6.1f (n/1000 = %d)\n", n, r->real_time,
                    r->real_time / small->real_time, n / 1000);
      }
    }
  }
  std::printf("Exact over fast, same scene (same run; target >= 50 at 100 discs):\n");
  for (const std::string series : {"Density", "Size"}) {
    for (int n : {10, 30, 100, 200, 300, 1000, 3000}) {
      const auto* exact = find("BM_Exact" + series + "/" + std::to_string(n));
      const auto* fast = find("BM_Fast" + series + "/" + std::to_string(n));
      if (exact && fast) {
        std::printf(
            "  %-8s %5d discs: wall exact %9.1f ms  fast %8.1f ms  exact/fast = %6.1f;"
            "  CPU exact/fast = %6.1f\n",
            series.c_str(), n, exact->real_time, fast->real_time,
            exact->real_time / fast->real_time,
            exact->counters.at("cpu_s") / fast->counters.at("cpu_s"));
      }
    }
  }
  std::printf("Fast cutter, plane search over tracked contacts (same run):\n");
  for (int n : {10, 30, 100, 200}) {
    const auto* search = find("BM_FastSearchDensity/" + std::to_string(n));
    const auto* tracked = find("BM_FastDensity/" + std::to_string(n));
    if (search && tracked) {
      std::printf("  %5d discs: CPU %5.2f  wall %5.2f  contact phase (wall) %5.2f\n", n,
                  search->counters.at("cpu_s") / tracked->counters.at("cpu_s"),
                  search->real_time / tracked->real_time,
                  search->counters.at("contact_s") / tracked->counters.at("contact_s"));
    }
  }
  std::printf("Fast cutter, EdgePlanes over FullPlanes (same run):\n");
  for (int n : {10, 30, 100, 200}) {
    const auto* edge = find("BM_FastEdgeDensity/" + std::to_string(n));
    const auto* full = find("BM_FastDensity/" + std::to_string(n));
    if (edge && full) {
      std::printf("  %5d discs: pieces %8.0f / %8.0f = %5.2f;  CPU %5.2f\n", n,
                  edge->counters.at("pieces"), full->counters.at("pieces"),
                  edge->counters.at("pieces") / full->counters.at("pieces"),
                  edge->counters.at("cpu_s") / full->counters.at("cpu_s"));
    }
  }
  std::printf("Segments, time against 24 segments of the same cutter (same run):\n");
  for (const std::string cutter : {"Fast", "Exact"}) {
    const auto* base = find("BM_" + cutter + "Segments/24");
    for (int s : {8, 16, 48, 96}) {
      const std::string name = "BM_" + cutter + "Segments/" + std::to_string(s);
      const auto* r = find(name);
      if (base && r) std::printf("  %-22s %.2f\n", name.c_str(), r->real_time / base->real_time);
    }
  }
  benchmark::Shutdown();
  return 0;
}
