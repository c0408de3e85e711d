// Block cutting: the density and size series of issue 3 and the disc_segments column.
// Scenes come from blocks/disc_scenes.h, so another cutter can run the very same series:
// add a BM_<Cutter>Density / BM_<Cutter>Size pair below that calls it.
// Prints Google Benchmark's table, then comparisons as ratios measured in this run.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "bench/bench_support.h"
#include "blocks/disc_scenes.h"
#include "blocks/exact_cutter.h"
#include "blocks/fast_cutter.h"

namespace {

using namespace rockmass::blocks;

/// Cuts `spec` with the fast cutter, reporting blocks and pieces.
void fastCut(benchmark::State& state, const DiscSceneSpec& spec, int segments) {
  const rockmass::geometry::FractureNetwork network = randomDiscNetwork(spec);
  const CutInput input = boxCutInput(network, segments);
  FastCutReport report;
  std::size_t blocks = 0;
  for (auto _ : state) {
    const BlockModel model = cutFast(input, &report);
    blocks = model.blocks.size();
    benchmark::DoNotOptimize(model.blocks.data());
  }
  state.counters["discs"] = spec.discs;
  state.counters["blocks"] = static_cast<double>(blocks);
  state.counters["pieces"] = report.pieces;
  state.counters["cut_s"] = report.cut_seconds;
  state.counters["assemble_s"] = report.assemble_seconds;
}

/// Density series: n discs of radius 3-7 m (aspect 0.6, 24 segments) in one 10 m cube.
void BM_FastDensity(benchmark::State& state) {
  DiscSceneSpec spec;
  spec.discs = static_cast<int>(state.range(0));
  fastCut(state, spec, 24);
}
BENCHMARK(BM_FastDensity)->Arg(10)->Arg(30)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);

/// Size series: n discs at the density of the 100-disc case, cube side 10 (n/100)^(1/3) m.
void BM_FastSize(benchmark::State& state) {
  fastCut(state, sizeSeriesScene(static_cast<int>(state.range(0))), 24);
}
BENCHMARK(BM_FastSize)->Arg(100)->Arg(300)->Arg(1000)->Arg(3000)->Unit(benchmark::kMillisecond);

/// Cuts `spec` with the exact cutter (default options: kd regions of at most 30 discs, all
/// cores, no referee), reporting blocks, pieces and regions. One iteration: a cut takes
/// seconds.
void exactCut(benchmark::State& state, const DiscSceneSpec& spec, int segments) {
  const rockmass::geometry::FractureNetwork network = randomDiscNetwork(spec);
  const CutInput input = boxCutInput(network, segments);
  ExactCutReport report;
  std::size_t blocks = 0;
  for (auto _ : state) {
    const BlockModel model = cutExact(input, {}, &report);
    blocks = model.blocks.size();
    benchmark::DoNotOptimize(model.blocks.data());
  }
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
/// 96 segments: the L1 distance between the sorted block volumes (shorter list padded with
/// zeros) over the domain volume, i.e. the share of the rock that changes block size.
std::vector<double> sortedVolumes(const BlockModel& model) {
  std::vector<double> v;
  for (const Block& b : model.blocks) v.push_back(b.mass.volume);
  std::sort(v.begin(), v.end(), std::greater<>());
  return v;
}
void BM_FastSegments(benchmark::State& state) {
  const int segments = static_cast<int>(state.range(0));
  DiscSceneSpec spec;
  spec.discs = 100;
  fastCut(state, spec, segments);
  const rockmass::geometry::FractureNetwork network = randomDiscNetwork(spec);
  std::vector<double> a = sortedVolumes(cutFast(boxCutInput(network, segments)));
  std::vector<double> b = sortedVolumes(cutFast(boxCutInput(network, 96)));
  a.resize(std::max(a.size(), b.size()), 0.0);
  b.resize(a.size(), 0.0);
  double l1 = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) l1 += std::abs(a[i] - b[i]);
  state.counters["volume_error"] = l1 / network.domain.volume();
}
BENCHMARK(BM_FastSegments)
    ->Arg(8)
    ->Arg(16)
    ->Arg(24)
    ->Arg(48)
    ->Arg(96)
    ->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  rockmass::bench::RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const auto t = reporter.realTimes();
  // Registered names carry the run options (".../iterations:1/real_time"): look up by prefix.
  const auto find = [&](const std::string& prefix) -> const double* {
    const rockmass::bench::Record* record = reporter.find(prefix);
    return record ? &record->real_time : nullptr;
  };
  std::printf("\nSize series, time growth over linear (same run; 1.0 = linear):\n");
  for (const std::string cutter : {"Fast", "Exact"}) {
    const double* base = find("BM_" + cutter + "Size/100");
    for (int n : {300, 1000, 3000}) {
      const std::string name = "BM_" + cutter + "Size/" + std::to_string(n);
      const double* time = find(name);
      if (base && time) {
        std::printf("  %-22s t/t(100) = %7.2f  n/100 = %5.1f  growth/linear = %.2f\n", name.c_str(),
                    *time / *base, n / 100.0, *time / *base / (n / 100.0));
      }
    }
  }
  std::printf("Exact over fast, same scene (same run; target >= 50 at 100 discs):\n");
  for (const std::string series : {"Density", "Size"}) {
    for (int n : {10, 30, 100, 200, 300, 1000, 3000}) {
      const double* exact = find("BM_Exact" + series + "/" + std::to_string(n));
      const double* fast = find("BM_Fast" + series + "/" + std::to_string(n));
      if (exact && fast) {
        std::printf("  %-8s %5d discs: exact %9.1f ms  fast %8.1f ms  exact/fast = %6.1f\n",
                    series.c_str(), n, *exact, *fast, *exact / *fast);
      }
    }
  }
  std::printf("Segments, time against 24 segments:\n");
  for (int s : {8, 16, 48, 96}) {
    const std::string name = "BM_FastSegments/" + std::to_string(s);
    if (t.count(name) && t.count("BM_FastSegments/24")) {
      std::printf("  %-22s %.2f\n", name.c_str(), t.at(name) / t.at("BM_FastSegments/24"));
    }
  }
  benchmark::Shutdown();
  return 0;
}
