// DDA engine speed and accuracy against time.
// BM_Pile/N: N rigid cubes dropped into a fixed box; block-steps per second and the share of
// each phase (counters). BM_SlidingAccuracy: error of the sliding-block displacement at
// 0.3 s against 1/2 g (sin theta - cos theta tan phi) t^2, for a time step and a penalty
// factor; the solver is the third argument (0 Eigen LDLT, 1 CHOLMOD, 2 PCG when built).
#include <benchmark/benchmark.h>

#include <cmath>

#include "../tests/dda3d/dda_scenes.h"
#include "dda3d/simulation.h"

namespace {

using namespace rockmass::dda3d;
using rockmass::geometry::Vec3;

DdaModel pile(int blocks) {
  DdaModel model;
  scenes::setRock(model, 30.0);
  const int side = static_cast<int>(std::ceil(std::sqrt(blocks / 8.0)));
  const double width = 1.2 * side + 0.6;
  model.blocks.push_back(scenes::boxBlock({-1, -1, -1}, {width + 1, width + 1, 0}, 0, true));
  for (int k = 0; k < blocks; ++k) {
    const int per_layer = side * side;
    const int layer = k / per_layer, row = (k / side) % side, column = k % side;
    const double shift = layer % 2 == 0 ? 0.0 : 0.3;
    const Vec3 low(0.1 + 1.2 * column + shift, 0.1 + 1.2 * row, 0.05 + 1.2 * layer);
    model.blocks.push_back(scenes::boxBlock(low, low + Vec3(1, 1, 1), 0, false));
  }
  model.gravity = Vec3(0, 0, -9.81);
  return model;
}

void BM_Pile(benchmark::State& state) {
  const int blocks = static_cast<int>(state.range(0));
  DdaSettings settings;
  settings.kinematics = Kinematics::Rigid;
  settings.time_step = 2e-3;
  int steps = 0;
  PhaseTimings timings;
  for (auto _ : state) {
    state.PauseTiming();
    Simulation sim(pile(blocks), settings);
    for (int k = 0; k < 100; ++k) sim.step();  // falling and first impacts
    const PhaseTimings before = sim.timings();
    state.ResumeTiming();
    for (int k = 0; k < 20; ++k) sim.step();
    steps += 20;
    const PhaseTimings& t = sim.timings();
    timings.detect_contacts += t.detect_contacts - before.detect_contacts;
    timings.assemble_block_terms += t.assemble_block_terms - before.assemble_block_terms;
    timings.assemble_contacts += t.assemble_contacts - before.assemble_contacts;
    timings.factorize += t.factorize - before.factorize;
    timings.solve += t.solve - before.solve;
    timings.update_states += t.update_states - before.update_states;
    timings.update_blocks += t.update_blocks - before.update_blocks;
    state.counters["contacts"] = sim.contactCounts().total;
  }
  const double total = timings.total();
  state.counters["block_steps_per_s"] =
      benchmark::Counter(static_cast<double>(blocks) * steps, benchmark::Counter::kIsRate);
  state.counters["steps_per_s"] =
      benchmark::Counter(static_cast<double>(steps), benchmark::Counter::kIsRate);
  state.counters["detect"] = timings.detect_contacts / total;
  state.counters["assemble"] = (timings.assemble_block_terms + timings.assemble_contacts) / total;
  state.counters["factorize"] = timings.factorize / total;
  state.counters["solve"] = timings.solve / total;
  state.counters["states_update"] = (timings.update_states + timings.update_blocks) / total;
}
// 5000 blocks: add ->Arg(5000) once the CHOLMOD backend is in (Eigen LDLT fill-in makes
// it take minutes per step).
BENCHMARK(BM_Pile)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond)->Iterations(1);

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

}  // namespace

BENCHMARK_MAIN();
