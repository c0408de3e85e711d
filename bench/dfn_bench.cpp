// DFN generation speed, and what disc_segments costs against the area error it leaves.
// Prints Google Benchmark's table, then the comparisons as ratios measured in this run.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "bench/bench_support.h"
#include "geometry/fracture_network.h"
#include "geometry/orientation.h"

namespace {

using namespace rockmass::geometry;

/// A joint set of ~1 m discs with 1 m spacing in a cube of side `side` (m). For side 100
/// it yields about 6.8e5 discs touching the domain, for side 116 about 10^6.
DfnSpec millionDiscScene(double side, bool fisher) {
  JointSetSpec set;
  set.name = "bench";
  if (fisher) {
    set.orientation.fisher = true;
    set.orientation.fisher_dip_direction = 120.0;
    set.orientation.fisher_dip = 40.0;
    set.orientation.kappa = 30.0;
  } else {
    set.orientation.dip_direction = {DistributionKind::Normal, 120.0, 15.0, 60.0, 180.0};
    set.orientation.dip = {DistributionKind::Uniform, 40.0, 10.0, {}, {}};
  }
  set.spacing = DistributionSpec{DistributionKind::Lognormal, 1.0, 1.0, {}, {}};
  set.trace_length = {DistributionKind::Lognormal, 1.2, 0.5, {}, {}};
  set.shape.aspect_ratio = 0.5;
  DfnSpec spec;
  spec.domain = Box{{0, 0, 0}, {side, side, side}};
  spec.joint_sets.push_back(set);
  return spec;
}

/// Generation of ~10^6 discs; discs/s counts the discs kept in the domain.
void generate(benchmark::State& state, bool fisher) {
  const DfnSpec spec = millionDiscScene(static_cast<double>(state.range(0)), fisher);
  std::size_t discs = 0;
  for (auto _ : state) {
    const FractureNetwork network = generateNetwork(spec, 1);
    discs = network.discs.size();
    benchmark::DoNotOptimize(network.discs.data());
  }
  state.counters["discs"] = static_cast<double>(discs);
  state.counters["discs_per_s"] =
      benchmark::Counter(static_cast<double>(discs), benchmark::Counter::kIsIterationInvariantRate);
}
void BM_GenerateIndependentAngles(benchmark::State& state) {
  generate(state, false);
}
void BM_GenerateFisher(benchmark::State& state) {
  generate(state, true);
}
BENCHMARK(BM_GenerateIndependentAngles)->Arg(116)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_GenerateFisher)->Arg(116)->Unit(benchmark::kMillisecond)->MinTime(2.0);

/// Measuring P32/P10 in the domain (clips the discs that cross its boundary).
void BM_MeasureSets(benchmark::State& state) {
  const FractureNetwork network = generateNetwork(millionDiscScene(40.0, false), 1);
  for (auto _ : state) benchmark::DoNotOptimize(measureSets(network).data());
  state.counters["discs"] = static_cast<double>(network.discs.size());
}
BENCHMARK(BM_MeasureSets)->Unit(benchmark::kMillisecond);

/// disc_segments: time to build the polygons of 10^5 ellipses, and the relative area the
/// inscribed polygon loses (1 - sin(2 pi / n) / (2 pi / n)).
void BM_DiscOutline(benchmark::State& state) {
  const int segments = static_cast<int>(state.range(0));
  const FractureNetwork network = generateNetwork(millionDiscScene(20.0, false), 1);
  for (auto _ : state) {
    for (const Disc& d : network.discs) benchmark::DoNotOptimize(d.outline(segments).data());
  }
  const double angle = 2.0 * kPi / segments;
  state.counters["area_error"] = 1.0 - std::sin(angle) / angle;
  state.counters["discs"] = static_cast<double>(network.discs.size());
}
BENCHMARK(BM_DiscOutline)->Arg(8)->Arg(24)->Arg(96)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  rockmass::bench::RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const auto t = reporter.realTimes();
  const auto ratio = [&](const char* a, const char* b) {
    if (t.count(a) && t.count(b)) std::printf("  %-44s / %-32s = %.3f\n", a, b, t.at(a) / t.at(b));
  };
  std::printf("\nRatios (same run):\n");
  ratio("BM_GenerateFisher/116/min_time:2.000", "BM_GenerateIndependentAngles/116/min_time:2.000");
  ratio("BM_DiscOutline/24", "BM_DiscOutline/8");
  ratio("BM_DiscOutline/96", "BM_DiscOutline/24");
  for (const auto& [name, rate] : reporter.counterValues("discs_per_s")) {
    std::printf("  %-44s %.3g discs/s, 10^6 discs in %.2f s\n", name.c_str(), rate, 1e6 / rate);
  }
  benchmark::Shutdown();
  return 0;
}
