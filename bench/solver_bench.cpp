// The DDA linear solve per backend: CHOLMOD supernodal Cholesky, Eigen simplicial LDL^T and
// block-Jacobi PCG at two tolerances, on DDA-shaped systems of 100, 1000 and 5000 blocks
// (scenarios/dda_matrices.h: 12 unknowns per unit-cube block, inertia, elastic terms, a
// soft layer 10^3 softer, contact springs on every shared face, the bottom layer fixed).
// Each iteration is what one open-close iteration costs: the numeric factorization (the
// symbolic analysis is reused, as it is while the contact pattern holds) and one solve.
// BM_Analyze measures the analysis that a change of pattern costs on top.
// Prints Google Benchmark's table, then ratios and errors measured in this run.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "bench/bench_support.h"
#include "dda3d/linear_solver.h"
#include "scenarios/dda_matrices.h"

namespace {

using namespace rockmass;

/// Blocks per axis for a pile of `blocks` blocks.
test::DdaSystemSpec pile(int blocks) {
  test::DdaSystemSpec spec;
  spec.contrast = 1e3;
  if (blocks == 100) {
    spec.nx = 5, spec.ny = 5, spec.nz = 4;
  } else if (blocks == 1000) {
    spec.nx = 10, spec.ny = 10, spec.nz = 10;
  } else {
    spec.nx = 25, spec.ny = 20, spec.nz = 10;
  }
  return spec;
}

/// The system of a pile, built once per size.
struct System {
  dda3d::SparseMatrix k;
  Eigen::VectorXd expected, f;
};
const System& system(int blocks) {
  static std::map<int, System> cache;
  auto it = cache.find(blocks);
  if (it == cache.end()) {
    System s;
    s.k = test::ddaSystemMatrix(pile(blocks));
    s.expected = test::ddaSolution(static_cast<int>(s.k.rows()));
    s.f = s.k * s.expected;
    it = cache.emplace(blocks, std::move(s)).first;
  }
  return it->second;
}

/// Factorize (numeric only after the first call) + solve; counters: the relative error
/// against the known solution, the residual and the CG iterations.
void solve(benchmark::State& state, dda3d::SolverOptions options) {
  const System& s = system(static_cast<int>(state.range(0)));
  options.max_iterations = 100000;
  const std::unique_ptr<dda3d::LinearSolver> solver = dda3d::makeLinearSolver(options);
  if (!solver->factorize(s.k)) state.SkipWithError("not positive definite");
  Eigen::VectorXd x;
  for (auto _ : state) {
    solver->factorize(s.k);
    x = solver->solve(s.f);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["unknowns"] = static_cast<double>(s.k.rows());
  state.counters["error"] = (x - s.expected).norm() / s.expected.norm();
  state.counters["residual"] = solver->stats().residual;
  state.counters["iterations"] = solver->stats().iterations;
}
void BM_Cholmod(benchmark::State& state) {
  solve(state, {.kind = dda3d::SolverKind::Cholmod});
}
void BM_EigenLdlt(benchmark::State& state) {
  solve(state, {.kind = dda3d::SolverKind::Eigen});
}
void BM_Pcg1e6(benchmark::State& state) {
  solve(state, {.kind = dda3d::SolverKind::Pcg, .tolerance = 1e-6});
}
void BM_Pcg1e10(benchmark::State& state) {
  solve(state, {.kind = dda3d::SolverKind::Pcg, .tolerance = 1e-10});
}

/// Symbolic analysis + factorization + solve with a fresh solver: the cost of a step whose
/// contact pattern changed.
void analyze(benchmark::State& state, dda3d::SolverKind kind) {
  const System& s = system(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const std::unique_ptr<dda3d::LinearSolver> solver = dda3d::makeLinearSolver({.kind = kind});
    solver->factorize(s.k);
    benchmark::DoNotOptimize(solver->solve(s.f).data());
  }
}
void BM_CholmodAnalyze(benchmark::State& state) {
  analyze(state, dda3d::SolverKind::Cholmod);
}
void BM_EigenLdltAnalyze(benchmark::State& state) {
  analyze(state, dda3d::SolverKind::Eigen);
}

/// 100, 1000 and 5000 blocks, in milliseconds.
void pileSizes(benchmark::internal::Benchmark* b) {
  b->Arg(100)->Arg(1000)->Arg(5000)->Unit(benchmark::kMillisecond);
}
BENCHMARK(BM_Cholmod)->Apply(pileSizes);
BENCHMARK(BM_EigenLdlt)->Apply(pileSizes);
BENCHMARK(BM_Pcg1e6)->Apply(pileSizes);
BENCHMARK(BM_Pcg1e10)->Apply(pileSizes);
BENCHMARK(BM_CholmodAnalyze)->Apply(pileSizes);
BENCHMARK(BM_EigenLdltAnalyze)->Apply(pileSizes);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  rockmass::bench::RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const auto t = reporter.cpuTimes();
  std::printf(
      "\nRatios to CHOLMOD (same run; CPU time of factorize + solve, analysis reused; the\n"
      "machine is shared, and CPU time is what a single-threaded solve costs):\n");
  std::printf("  %-8s %12s %12s %12s %12s\n", "blocks", "cholmod cpu ms", "eigen/chol", "pcg6/chol",
              "pcg10/chol");
  for (const char* size : {"100", "1000", "5000"}) {
    const std::string c = std::string("BM_Cholmod/") + size;
    if (!t.count(c)) continue;
    const auto ratio = [&](const char* name) {
      const std::string key = std::string(name) + "/" + size;
      return t.count(key) ? t.at(key) / t.at(c) : 0.0;
    };
    std::printf("  %-8s %12.3f %12.3f %12.3f %12.3f\n", size, t.at(c), ratio("BM_EigenLdlt"),
                ratio("BM_Pcg1e6"), ratio("BM_Pcg1e10"));
  }
  std::printf("\nAnalysis + factorize + solve / factorize + solve (what a new pattern costs):\n");
  for (const char* size : {"100", "1000", "5000"}) {
    for (const char* name : {"Cholmod", "EigenLdlt"}) {
      const std::string fresh = std::string("BM_") + name + "Analyze/" + size;
      const std::string reused = std::string("BM_") + name + "/" + size;
      if (t.count(fresh) && t.count(reused)) {
        std::printf("  %-10s %-6s %.3f\n", name, size, t.at(fresh) / t.at(reused));
      }
    }
  }
  std::printf("\nRelative error |d - d*| / |d*|:\n");
  for (const auto& [name, error] : reporter.counterValues("error"))
    std::printf("  %-20s %.3g\n", name.c_str(), error);
  benchmark::Shutdown();
  return 0;
}
