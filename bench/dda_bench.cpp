// DDA engine speed and accuracy against time.
// BM_Pile/SOLVER/N: N rigid cubes dropped on a fixed slab, timed over 10 steps while the
// layers land (--dda_warmup=N untimed steps first, default 60), for each
// solver of --dda_solvers=LIST (cholmod, eigen, pcg = the Auto tolerance, pcg:TOL; default
// "pcg,cholmod"; direct solvers up to 1000 blocks); block-steps per second, the share of each
// phase (counters) and, after the run, the fitted growth exponent of the time per step.
// BM_PileSettling/SOLVER/1000: a 1000-cube pile from release to 0.3 s, every step timed
// (steps/s of a whole settling run), with the first solver of the list.
// BM_SlidingAccuracy: error of the sliding-block displacement at 0.3 s against 1/2 g (sin theta -
// cos theta tan phi) t^2, for a time step and a penalty factor; the solver is the third argument (0
// Eigen LDLT, 1 CHOLMOD, 2 PCG when built).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/bench_support.h"
#include "dda3d/simulation.h"
#include "scenarios/dda_scenes.h"

namespace {

using namespace rockmass::dda3d;
using rockmass::geometry::Vec3;

/// `blocks` unit cubes in staggered layers with `gap` (m) between neighbours and layers,
/// 0.05 m above a fixed slab.
DdaModel pile(int blocks, double gap = 0.2) {
  DdaModel model;
  scenes::setRock(model, 30.0);
  const int side = static_cast<int>(std::ceil(std::sqrt(blocks / 8.0)));
  const double pitch = 1.0 + gap;
  const double width = pitch * side + 0.6;
  model.blocks.push_back(scenes::boxBlock({-1, -1, -1}, {width + 1, width + 1, 0}, 0, true));
  for (int k = 0; k < blocks; ++k) {
    const int per_layer = side * side;
    const int layer = k / per_layer, row = (k / side) % side, column = k % side;
    const double shift = layer % 2 == 0 ? 0.0 : 0.3;
    const Vec3 low(0.1 + pitch * column + shift, 0.1 + pitch * row, 0.05 + pitch * layer);
    model.blocks.push_back(scenes::boxBlock(low, low + Vec3(1, 1, 1), 0, false));
  }
  model.gravity = Vec3(0, 0, -9.81);
  return model;
}

/// A solver given on the command line: "cholmod", "eigen", "pcg" (the Auto tolerance,
/// autoPcgTolerance()) or "pcg:TOL".
struct SolverSpec {
  std::string label;
  SolverOptions options;
  int max_blocks = 5000;  ///< direct solvers stop at 1000 blocks (fill-in)
};

SolverSpec parseSolver(const std::string& text, const DdaSettings& defaults) {
  SolverSpec spec{text, {}, 5000};
  if (text == "cholmod" || text == "eigen") {
    spec.options.kind = text == "cholmod" ? SolverKind::Cholmod : SolverKind::Eigen;
    spec.max_blocks = 1000;
  } else if (text.rfind("pcg", 0) == 0) {
    spec.options.kind = SolverKind::Pcg;
    spec.options.tolerance =
        text.size() > 4 ? std::stod(text.substr(4)) : autoPcgTolerance(defaults);
    char label[32];
    std::snprintf(label, sizeof label, "pcg:%g", spec.options.tolerance);
    spec.label = label;
  } else {
    throw std::invalid_argument("unknown solver '" + text + "' (cholmod, eigen, pcg[:TOL])");
  }
  return spec;
}

/// Untimed steps before the timed ones (--dda_warmup=N): 60 steps of 2 ms = 0.12 s, the
/// bottom layer has landed and the others land during the timed steps. Later, fully dynamic
/// piles hit the scheme's velocity sawtooth (docs/dda3d.md, known limits): dt collapses.
int warm_up_steps = 60;
constexpr int kTimedSteps = 10;  ///< impacts and settling: contacts open, close, slide
/// BM_PileSettling: a compact pile (2 cm gaps: every layer has landed by ~0.15 s), run from
/// release to kSettlingTime (s).
constexpr double kSettlingGap = 0.02;
constexpr double kSettlingTime = 0.3;
/// BM_PileSettling: velocity share carried between steps; below 1 it damps the scheme's
/// sawtooth (docs/dda3d.md), which fully dynamic lets grow in a stack.
constexpr double kSettlingDynamicRatio = 0.98;
constexpr int kSettlingBlocks = 1000;  ///< BM_PileSettling's pile

DdaSettings pileSettings() {
  DdaSettings settings;
  settings.kinematics = Kinematics::Rigid;
  settings.time_step = 2e-3;
  settings.max_displacement_ratio = 0.01;  // g2 of the measurements in docs/performance.md
  return settings;
}

/// Counters with each phase's share of the engine's own timers: contact detection,
/// assembly (block terms and contact terms), factorization (PCG: preconditioner set-up),
/// solve, open-close (contact state updates and step checks), block update.
void setPhaseShares(benchmark::State& state, const StepProfile& t) {
  const double total = t.total();
  state.counters["detect"] = t[StepPhase::DetectContacts] / total;
  state.counters["assemble"] =
      (t[StepPhase::AssembleBlockTerms] + t[StepPhase::AssembleContacts]) / total;
  state.counters["factorize"] = t[StepPhase::Factorize] / total;
  state.counters["solve"] = t[StepPhase::Solve] / total;
  state.counters["open_close"] = t[StepPhase::UpdateStates] / total;
  state.counters["update"] = t[StepPhase::UpdateBlocks] / total;
}

/// One pile run: warm_up_steps untimed, then kTimedSteps timed. Counters: block-steps/s,
/// steps/s, the share of each phase of the engine's own timers, contacts, open-close
/// iterations per step.
void pileRun(benchmark::State& state, const SolverOptions& solver, int blocks,
             Kinematics kinematics = Kinematics::Rigid) {
  DdaSettings settings = pileSettings();
  settings.solver = solver;
  settings.kinematics = kinematics;
  int steps = 0, iterations = 0;
  StepProfile timings;
  for (auto _ : state) {
    state.PauseTiming();
    Simulation sim(pile(blocks), settings);
    for (int k = 0; k < warm_up_steps; ++k) sim.step();
    state.ResumeTiming();
    for (int k = 0; k < kTimedSteps; ++k) {
      const StepReport report = sim.step();
      iterations += report.iterations;
      timings += report.profile;
    }
    steps += kTimedSteps;
    state.counters["contacts"] = sim.contactCounts().total;
  }
  state.counters["block_steps_per_s"] =
      benchmark::Counter(static_cast<double>(blocks) * steps, benchmark::Counter::kIsRate);
  state.counters["steps_per_s"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
  state.counters["iter_per_step"] = static_cast<double>(iterations) / steps;
  setPhaseShares(state, timings);
  state.counters["steps"] = steps;
}

/// A pile of `blocks` cubes from release until kSettlingTime, all of it timed: steps/s of a
/// whole settling run (free fall, impacts layer by layer, settling), and the largest block
/// speed at the end against the largest during the run (how far it has settled).
void pileSettling(benchmark::State& state, const SolverOptions& solver, int blocks) {
  DdaSettings settings = pileSettings();
  settings.solver = solver;
  settings.dynamic_ratio = kSettlingDynamicRatio;
  int steps = 0, iterations = 0;
  double peak_speed = 0.0, final_speed = 0.0, smallest_dt = 0.0;
  int redone = 0;
  StepProfile timings;
  for (auto _ : state) {
    state.PauseTiming();
    Simulation sim(pile(blocks, kSettlingGap), settings);
    smallest_dt = settings.time_step;
    state.ResumeTiming();
    while (sim.time() < kSettlingTime * (1.0 - 1e-12)) {
      const StepReport report = sim.step();
      iterations += report.iterations;
      ++steps;
      smallest_dt = std::min(smallest_dt, report.time_step);
      redone += report.attempts - 1;
      state.PauseTiming();
      final_speed = 0.0;
      for (const BlockState& b : sim.blocks())
        final_speed = std::max(final_speed, b.velocity.head<3>().norm());
      peak_speed = std::max(peak_speed, final_speed);
      state.ResumeTiming();
    }
    timings = sim.timings();
    state.counters["contacts"] = sim.contactCounts().total;
  }
  state.counters["block_steps_per_s"] =
      benchmark::Counter(static_cast<double>(blocks) * steps, benchmark::Counter::kIsRate);
  state.counters["steps_per_s"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
  state.counters["iter_per_step"] = static_cast<double>(iterations) / steps;
  state.counters["steps"] = steps;
  state.counters["peak_speed"] = peak_speed;
  state.counters["final_speed"] = final_speed;
  state.counters["smallest_dt"] = smallest_dt;
  state.counters["redone"] = redone;
  setPhaseShares(state, timings);
}

void BM_SlidingAccuracy(benchmark::State& state) {
  const double dt = 1e-3 * static_cast<double>(state.range(0)) / 4.0;
  const double penalty_factor = static_cast<double>(state.range(1));
  const double theta = 30.0 * M_PI / 180.0, phi = 20.0 * M_PI / 180.0;
  DdaModel model;
  scenes::setRock(model, 20.0);
  model.blocks.push_back(scenes::boxBlock({-3, -1.5, -1}, {3, 1.5, 0}, 0, true));
  model.blocks.push_back(scenes::boxBlock({-2.5, -0.5, 0}, {-1.5, 0.5, 1}, 0, false));
  model.gravity = 9.81 * Vec3(std::sin(theta), 0.0, -std::cos(theta));
  DdaSettings settings;
  settings.time_step = dt;
  settings.penalty_factor = penalty_factor;
  settings.solver.kind = static_cast<SolverKind>(
      state.range(2) == 0 ? SolverKind::Eigen
                          : (state.range(2) == 1 ? SolverKind::Cholmod : SolverKind::Pcg));
  double error = 0.0;
  for (auto _ : state) {
    Simulation sim(model, settings);
    sim.runUntil(0.3);
    const double a = 9.81 * (std::sin(theta) - std::cos(theta) * std::tan(phi));
    const double expected = 0.5 * a * sim.time() * sim.time();
    error = std::abs(sim.centroidDisplacement(1).x() - expected) / expected;
  }
  state.counters["rel_error"] = error;
  state.counters["dt"] = dt;
}
BENCHMARK(BM_SlidingAccuracy)
    ->ArgsProduct({{1, 4, 16}, {10, 40, 160}, {0}})
    ->Unit(benchmark::kMillisecond);

/// Least-squares slope of log y against log x.
double logLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += std::log(x[i]), my += std::log(y[i]);
  mx /= static_cast<double>(x.size()), my /= static_cast<double>(x.size());
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (std::log(x[i]) - mx) * (std::log(y[i]) - my);
    sxx += (std::log(x[i]) - mx) * (std::log(x[i]) - mx);
  }
  return sxy / sxx;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<SolverSpec> solvers;
  std::stringstream list(rockmass::bench::takeFlag(argc, argv, "dda_solvers", "pcg,cholmod"));
  warm_up_steps =
      std::stoi(rockmass::bench::takeFlag(argc, argv, "dda_warmup", std::to_string(warm_up_steps)));
  for (std::string item; std::getline(list, item, ',');) {
    solvers.push_back(parseSolver(item, pileSettings()));
  }
  // --dda_deformable=1: the same piles with 12-unknown blocks too (BM_PileDeformable), and
  // their time per step over the rigid piles' (same run).
  const bool deformable = rockmass::bench::takeFlag(argc, argv, "dda_deformable", "0") == "1";
  const std::vector<int> sizes{100, 1000, 5000};
  for (const SolverSpec& spec : solvers) {
    for (int blocks : sizes) {
      if (blocks > spec.max_blocks) continue;
      const SolverOptions options = spec.options;
      benchmark::RegisterBenchmark(
          ("BM_Pile/" + spec.label + "/" + std::to_string(blocks)).c_str(),
          [options, blocks](benchmark::State& state) { pileRun(state, options, blocks); })
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1);
      // (The direct solvers stop at 1000 blocks, as for rigid piles.)
      if (!deformable) continue;
      benchmark::RegisterBenchmark(
          ("BM_PileDeformable/" + spec.label + "/" + std::to_string(blocks)).c_str(),
          [options, blocks](benchmark::State& state) {
            pileRun(state, options, blocks, Kinematics::Deformable);
          })
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1);
    }
  }
  const SolverOptions settling_solver = solvers.empty() ? SolverOptions{} : solvers[0].options;
  const std::string settling_name = "BM_PileSettling/" +
                                    (solvers.empty() ? std::string("cholmod") : solvers[0].label) +
                                    "/" + std::to_string(kSettlingBlocks);
  benchmark::RegisterBenchmark(settling_name.c_str(),
                               [settling_solver](benchmark::State& state) {
                                 pileSettling(state, settling_solver, kSettlingBlocks);
                               })
      ->Unit(benchmark::kMillisecond)
      ->Iterations(1);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  rockmass::bench::RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);

  std::printf(
      "\nPiles (rigid cubes, %d timed steps after %d untimed; CPU time; phase shares from the\n"
      "engine's timers):\n",
      kTimedSteps, warm_up_steps);
  const auto printRow = [](const std::string& label, int blocks, const rockmass::bench::Record& r) {
    const auto& c = r.counters;
    std::printf("  %-12s %6d %10.0f %9.2f %8.0f %6.2f %7.3f %7.3f %7.3f %7.3f %7.3f %7.3f\n",
                label.c_str(), blocks, c.at("block_steps_per_s"), c.at("steps_per_s"),
                c.at("contacts"), c.at("iter_per_step"), c.at("detect"), c.at("assemble"),
                c.at("factorize"), c.at("solve"), c.at("open_close"), c.at("update"));
  };
  std::printf("  %-12s %6s %10s %9s %8s %6s %7s %7s %7s %7s %7s %7s\n", "solver", "blocks",
              "blk-st/s", "steps/s", "contacts", "it/st", "detect", "assem", "factor", "solve",
              "op-cl", "update");
  for (const SolverSpec& spec : solvers) {
    std::vector<double> n, seconds_per_step;
    for (int blocks : sizes) {
      const rockmass::bench::Record* record =
          reporter.find("BM_Pile/" + spec.label + "/" + std::to_string(blocks));
      if (!record) continue;
      printRow(spec.label, blocks, *record);
      n.push_back(blocks);
      seconds_per_step.push_back(record->cpu_time / 1e3 / record->counters.at("steps"));  // ms
    }
    if (n.size() >= 2) {
      std::printf("  %-12s growth exponent of the time per step: fit %.2f", spec.label.c_str(),
                  logLogSlope(n, seconds_per_step));
      for (std::size_t i = 1; i < n.size(); ++i) {
        std::printf(
            ", %g->%g %.2f", n[i - 1], n[i],
            std::log(seconds_per_step[i] / seconds_per_step[i - 1]) / std::log(n[i] / n[i - 1]));
      }
      std::printf("\n");
    }
  }
  if (deformable) {
    std::printf("\nDeformable piles (12 unknowns a block) against rigid (same run, same steps):\n");
    std::printf("  %-12s %6s %12s %12s %8s %8s\n", "solver", "blocks", "rigid ms/st",
                "deform ms/st", "ratio", "it/st");
    for (const SolverSpec& spec : solvers) {
      for (int blocks : sizes) {
        const std::string tail = spec.label + "/" + std::to_string(blocks);
        const rockmass::bench::Record* rigid = reporter.find("BM_Pile/" + tail);
        const rockmass::bench::Record* twelve = reporter.find("BM_PileDeformable/" + tail);
        if (!rigid || !twelve) continue;
        const double a = rigid->cpu_time / rigid->counters.at("steps");
        const double b = twelve->cpu_time / twelve->counters.at("steps");
        std::printf("  %-12s %6d %12.2f %12.2f %8.2f %8.2f\n", spec.label.c_str(), blocks, a, b,
                    b / a, twelve->counters.at("iter_per_step"));
      }
    }
  }
  if (const rockmass::bench::Record* settling = reporter.find(settling_name)) {
    std::printf(
        "\nSettling pile (%d cubes, 2 cm gaps, dynamic ratio %.2f, release to %.1f s, all steps\n"
        "timed): %.1f "
        "steps/s, largest block speed at the end %.3g m/s (peak %.3g m/s during the run),\n"
        "%.0f steps, smallest time step %.3g s, %.0f attempts redone:\n",
        kSettlingBlocks, kSettlingDynamicRatio, kSettlingTime, settling->counters.at("steps_per_s"),
        settling->counters.at("final_speed"), settling->counters.at("peak_speed"),
        settling->counters.at("steps"), settling->counters.at("smallest_dt"),
        settling->counters.at("redone"));
    printRow(solvers.empty() ? "cholmod" : solvers[0].label, kSettlingBlocks, *settling);
  }
  if (solvers.size() >= 2) {
    std::printf("\nTime per step relative to %s (same run):\n", solvers[0].label.c_str());
    for (int blocks : sizes) {
      const rockmass::bench::Record* base =
          reporter.find("BM_Pile/" + solvers[0].label + "/" + std::to_string(blocks));
      if (!base) continue;
      for (std::size_t s = 1; s < solvers.size(); ++s) {
        const rockmass::bench::Record* other =
            reporter.find("BM_Pile/" + solvers[s].label + "/" + std::to_string(blocks));
        if (!other) continue;
        std::printf("  %6d blocks: %s / %s = %.2f\n", blocks, solvers[s].label.c_str(),
                    solvers[0].label.c_str(), other->cpu_time / base->cpu_time);
      }
    }
  }
  benchmark::Shutdown();
  return 0;
}
