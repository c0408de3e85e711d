// CHOLMOD's factorization of one DDA matrix on whichever BLAS this process loads: the
// program is linked without the other programs' pinned ATLAS (bench/CMakeLists.txt), so
// LD_LIBRARY_PATH chooses (docs/performance.md, "CHOLMOD's BLAS"). The matrix is a Matrix
// Market file of `rockmass dda --debug-step N` (debug_step<N>_K.mtx).
//
//   factorize_bench K.mtx [repeats]
#include <suitesparse/cholmod.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "dda3d/linear_solver.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: factorize_bench K.mtx [repeats]\n");
    return 2;
  }
  const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
  cholmod_common common;
  cholmod_start(&common);
  FILE* file = std::fopen(argv[1], "r");
  if (!file) {
    std::fprintf(stderr, "factorize_bench: cannot open %s\n", argv[1]);
    return 2;
  }
  cholmod_sparse* a = cholmod_read_sparse(file, &common);
  std::fclose(file);
  if (!a) {
    std::fprintf(stderr, "factorize_bench: %s: not a Matrix Market sparse matrix\n", argv[1]);
    return 2;
  }
  if (a->stype == 0) {  // unsymmetric storage of a symmetric matrix: its lower triangle
    cholmod_sparse* lower = cholmod_copy(a, -1, 1, &common);
    cholmod_free_sparse(&a, &common);
    a = lower;
  }
  cholmod_factor* factor = cholmod_analyze(a, &common);
  const double flops = common.fl, factor_entries = common.lnz;
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    cholmod_factorize(a, factor, &common);
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  std::printf("BLAS %s\n", rockmass::dda3d::loadedLibrary("libblas.so.3").c_str());
  std::printf("unknowns %ld, factor entries %.3g, flops %.3g\n", static_cast<long>(a->nrow),
              factor_entries, flops);
  std::printf("factorization %.4f s (best of %d), %.2f GFlop/s, %s\n", best, repeats,
              flops / best * 1e-9, common.status == CHOLMOD_OK ? "positive definite" : "FAILED");
  cholmod_free_factor(&factor, &common);
  cholmod_free_sparse(&a, &common);
  cholmod_finish(&common);
  return 0;
}
