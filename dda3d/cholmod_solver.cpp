// CHOLMOD supernodal Cholesky (SuiteSparse) through Eigen's CholmodSupport: the production
// backend. The symbolic analysis (AMD/METIS ordering, supernodes) is the expensive part for
// a DDA matrix whose pattern changes only when contacts appear or vanish, so it is kept.
#include <Eigen/CholmodSupport>

#if defined(__linux__)
#include <link.h>
#include <pthread.h>
#include <sched.h>
#endif

#include <filesystem>
#include <string>

#include "dda3d/solver_backends.h"
#include "dda3d/sparsity_pattern.h"

namespace rockmass::dda3d {
namespace {

/// Holds the calling thread on the CPU it runs on while it lives, then gives back its former
/// CPU set. A single-threaded CHOLMOD factorization of the Xiangjiaba region (5 520 unknowns)
/// took 0.044-0.046 s when the thread could move between this machine's two cores and
/// 0.023-0.025 s held on one, whatever the TBB and OpenMP threads (docs/performance.md): the
/// scheduler moved it off its warm caches. Only the thread's placement changes, never the
/// arithmetic. Elsewhere than Linux, nothing.
class HeldOnThisCpu {
 public:
  HeldOnThisCpu() {
#if defined(__linux__)
    const int cpu = sched_getcpu();
    if (cpu < 0 || pthread_getaffinity_np(pthread_self(), sizeof(old_), &old_) != 0) return;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(cpu, &one);
    held_ = pthread_setaffinity_np(pthread_self(), sizeof(one), &one) == 0;
#endif
  }
  ~HeldOnThisCpu() {
#if defined(__linux__)
    if (held_) pthread_setaffinity_np(pthread_self(), sizeof(old_), &old_);
#endif
  }
  HeldOnThisCpu(const HeldOnThisCpu&) = delete;
  HeldOnThisCpu& operator=(const HeldOnThisCpu&) = delete;

 private:
#if defined(__linux__)
  cpu_set_t old_{};
#endif
  bool held_ = false;
};

/// CHOLMOD supernodal LL^T of the upper triangle, analysis reused while the pattern holds.
/// K comes with both triangles, equal (BlockSystem::matrix); CHOLMOD factorizes the permuted
/// lower triangle, which it makes from an upper one in one transpose and from a lower one in
/// two (cholmod_factorize_p): the same values, one pass fewer over K.
class CholmodSolver final : public LinearSolver {
 public:
  explicit CholmodSolver(bool report_residual) : report_residual_(report_residual) {
    // A matrix that is not positive definite is an expected outcome reported through
    // factorize()'s result, not a message on stderr.
    llt_.cholmod().print = 0;
  }

  /// The symbolic analysis of K's pattern (kept for the factorizations that follow while
  /// the pattern holds); returns CHOLMOD's count of the factorization's flops.
  double analyze(const SparseMatrix& k) {
    const SparseMatrix& a = compressed(k);
    llt_.analyzePattern(a);
    pattern_.remember(a);
    analyzed_ahead_ = true;
    return llt_.cholmod().fl;
  }

  bool factorize(const SparseMatrix& k) override {
    stats_ = {};
    // An analysis done by analyze() counts as this factorization's.
    stats_.analyzed = analyzed_ahead_;
    analyzed_ahead_ = false;
    const SparseMatrix& a = compressed(k);
    if (!pattern_.matches(a)) {
      llt_.analyzePattern(a);
      pattern_.remember(a);
      stats_.analyzed = true;
    }
    {
      const HeldOnThisCpu held;
      llt_.factorize(a);
    }
    stats_.converged = llt_.info() == Eigen::Success;
    // After a failed factorization CHOLMOD may leave the factor in a partial state: analyse
    // afresh next time rather than trust it.
    if (!stats_.converged) pattern_.forget();
    return stats_.converged;
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& f) override {
    Eigen::VectorXd x = llt_.solve(f);
    if (report_residual_) stats_.residual = relativeResidual(k_, x, f);
    return x;
  }
  SolveStats stats() const override { return stats_; }
  std::string name() const override { return "cholmod"; }

 private:
  /// K itself when it is compressed and no residual is reported, else its compressed copy
  /// (k_, kept for the residual).
  const SparseMatrix& compressed(const SparseMatrix& k) {
    if (!report_residual_ && k.isCompressed()) return k;
    k_ = k;
    k_.makeCompressed();
    return k_;
  }

  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Upper> llt_;
  SparsityPattern pattern_;
  SparseMatrix k_;  ///< the factorized matrix, for the residual
  SolveStats stats_;
  bool report_residual_ = true;
  bool analyzed_ahead_ = false;  ///< analyze() ran since the last factorize
};

}  // namespace

std::unique_ptr<LinearSolver> makeCholmodSolver(bool report_residual) {
  return std::make_unique<CholmodSolver>(report_residual);
}

std::unique_ptr<LinearSolver> makeAnalyzedCholmodSolver(const SparseMatrix& k, double& flops,
                                                        bool report_residual) {
  auto solver = std::make_unique<CholmodSolver>(report_residual);
  flops = solver->analyze(k);
  return solver;
}

double cholmodFactorFlops(const SparseMatrix& k) {
  double flops = 0.0;
  makeAnalyzedCholmodSolver(k, flops);
  return flops;
}

std::string loadedLibrary(const std::string& soname) {
  struct Search {
    const std::string* soname;
    std::string found;
  } search{&soname, {}};
#if defined(__linux__)
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* data) {
        Search& s = *static_cast<Search*>(data);
        const std::string name = info->dlpi_name ? info->dlpi_name : "";
        if (std::filesystem::path(name).filename() != *s.soname) return 0;
        std::error_code error;
        const std::filesystem::path file = std::filesystem::canonical(name, error);
        s.found = error ? name : file.string();
        return 1;
      },
      &search);
#endif
  return search.found;
}

}  // namespace rockmass::dda3d
