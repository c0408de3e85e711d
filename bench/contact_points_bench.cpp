// What the number of contact points costs and buys (docs/stability.md, "Contact points"):
// the overload factor K_s of a 20 x 20 x 30 m concrete block on a fixed rock slab, pushed by a
// horizontal thrust H = 62.5 MN x K at 8.33 m above its base (the resultant of water 25 m
// deep on its 20 m wide upstream face), f = 0.6, rigid, static runs, bisection to 0.01.
//
// The base carries its four corners (DdaSettings::contact_point_spacing 0) or, with a
// spacing of L / m, m x m sub-contact points more, each with its cell's area (m = 2, 4, 8,
// 16).
//
// Cases:
//   frictional  c = 0: K = f W / H = 2.765 for any m (Wyllie & Mah ch. 6).
//   cohesive    c = 200 kPa, plastic joints: at K_s the resultant lies 6.3 m from the base's
//               centre, beyond the middle third (3.33 m), so the heel lifts and only the
//               compressed length L_c = 3 (L/2 - e) keeps its cohesion: the cracked-base
//               analysis of gravity dams (USACE EM 1110-2-2200, ch. 4; USBR Design of Small
//               Dams ch. 8), K = (f W + 1.5 c B L) / (H (1 + 3 c B h / W)) = 3.477 on a
//               no-tension base of uniform stiffness. The full-base factor (f W + c A) / H is
//               4.045.
//   brittle     the same with brittle joints (cohesion lost where a contact slides): below
//               the plastic factor, by how much depends on the load path.
// Counters: K_s, its error against the hand value (%), contact points of the base, runs, steps.
// main() prints, per case, K_s and the CPU time of each m against the corners, one run.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench/bench_support.h"
#include "dda3d/stability.h"
#include "scenarios/dda_scenes.h"

namespace {

using namespace rockmass::dda3d;
using rockmass::geometry::Vec3;

constexpr double kG = 9.81;
constexpr double kConcrete = 24.0e3 / kG;                    // kg/m3 (24 kN/m3)
constexpr double kB = 20.0, kL = 20.0, kH = 30.0;            // m: across, along the thrust, high
constexpr double kThrust = 0.5 * 10.0e3 * 25.0 * 25.0 * kB;  // N, water 25 m deep
constexpr double kArm = 25.0 / 3.0;                          // m above the base
constexpr double kFriction = 0.6;
constexpr double kCohesion = 200.0e3;  // Pa

enum class Case { Frictional, Cohesive, Brittle };

double weight() {
  return kConcrete * kG * kB * kL * kH;
}

double handFactor(Case c) {
  const double w = weight();
  if (c == Case::Frictional) return kFriction * w / kThrust;
  return (kFriction * w + 1.5 * kCohesion * kB * kL) /
         (kThrust * (1.0 + 3.0 * kCohesion * kB * kArm / w));
}

/// The block on its slab, the thrust as a point load.
DdaModel model(Case c) {
  DdaModel m;
  m.materials = {DdaMaterial{2600.0, 7.0e9, 0.25}, DdaMaterial{kConcrete, 17.6e9, 0.167}};
  DdaJoint joint{kFriction, c == Case::Frictional ? 0.0 : kCohesion, 0.0};
  if (c == Case::Brittle) joint.model = JointModel::Brittle;
  m.joints = {joint};
  m.blocks.push_back(scenes::boxBlock({-50, -20, -20}, {50, 40, 0}, 0, true));
  m.blocks.push_back(scenes::boxBlock({0, 0, 0}, {kL, kB, kH}, 1, false));
  m.gravity = Vec3(0, 0, -kG);
  m.point_loads.push_back({1, Vec3(0.0, 0.5 * kB, kArm), Vec3(kThrust, 0, 0)});
  m.monitors.push_back({"top", Vec3(0.5 * kL, 0.5 * kB, kH), 1});
  return m;
}

void BM_ContactPoints(benchmark::State& state) {
  const Case c = static_cast<Case>(state.range(0));
  const int m = static_cast<int>(state.range(1));  // cells along the base, 0: corners only
  DdaSettings settings;
  settings.contact_point_spacing = m > 0 ? kL / m : 0.0;
  settings.kinematics = Kinematics::Rigid;
  settings.mode = AnalysisMode::Static;
  settings.time_step = 2e-3;
  FactorSearch search;
  search.factors = {1.0, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5};
  search.tolerance = 0.01;
  search.sweep_all = false;
  search.equilibrium.max_steps = 150;
  LoadScaling scaling;
  scaling.point_loads = true;
  FactorSearchResult result;
  for (auto _ : state) result = runOverload(model(c), settings, scaling, search);
  long steps = 0;
  for (const FactorRun& run : result.runs) steps += run.equilibrium.steps;
  const double expected = handFactor(c);
  const double k = result.critical.value_or(0.0);
  state.counters["K_s"] = k;
  state.counters["error_pct"] = 100.0 * (k / expected - 1.0);
  state.counters["points"] = 4.0 + m * m;
  state.counters["runs"] = static_cast<double>(result.runs.size());
  state.counters["steps"] = static_cast<double>(steps);
}

const char* caseName(Case c) {
  return c == Case::Frictional ? "frictional" : c == Case::Cohesive ? "cohesive" : "brittle";
}

}  // namespace

BENCHMARK(BM_ContactPoints)
    ->ArgsProduct({{0, 1, 2}, {0, 2, 4, 8, 16}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  rockmass::bench::RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  std::printf("\nK_s against the hand value, and CPU time against the corners (same run):\n");
  std::printf("%-11s %4s %7s %8s %9s %8s %6s %10s\n", "case", "m", "points", "K_s", "hand",
              "error %", "steps", "time ratio");
  for (const Case c : {Case::Frictional, Case::Cohesive, Case::Brittle}) {
    const std::string prefix = "BM_ContactPoints/" + std::to_string(static_cast<int>(c)) + "/";
    const rockmass::bench::Record* base = reporter.find(prefix + "0");
    for (int m : {0, 2, 4, 8, 16}) {
      const rockmass::bench::Record* r = reporter.find(prefix + std::to_string(m));
      if (!r || !base) continue;
      std::printf("%-11s %4d %7.0f %8.3f %9.3f %8.2f %6.0f %10.2f\n", caseName(c), m,
                  r->counters.at("points"), r->counters.at("K_s"), handFactor(c),
                  r->counters.at("error_pct"), r->counters.at("steps"),
                  r->cpu_time / base->cpu_time);
    }
  }
  benchmark::Shutdown();
  return 0;
}
