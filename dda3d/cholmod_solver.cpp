// CHOLMOD supernodal Cholesky (SuiteSparse) through Eigen's CholmodSupport: the production
// backend. The symbolic analysis (AMD/METIS ordering, supernodes) is the expensive part for
// a DDA matrix whose pattern changes only when contacts appear or vanish, so it is kept.
#include <Eigen/CholmodSupport>

#include "dda3d/solver_backends.h"
#include "dda3d/sparsity_pattern.h"

namespace rockmass::dda3d {
namespace {

/// CHOLMOD supernodal LL^T of the lower triangle, analysis reused while the pattern holds.
class CholmodSolver final : public LinearSolver {
 public:
  CholmodSolver() {
    // A matrix that is not positive definite is an expected outcome reported through
    // factorize()'s result, not a message on stderr.
    llt_.cholmod().print = 0;
  }

  /// The symbolic analysis of K's pattern (kept for the factorizations that follow while
  /// the pattern holds); returns CHOLMOD's count of the factorization's flops.
  double analyze(const SparseMatrix& k) {
    k_ = k;
    k_.makeCompressed();
    llt_.analyzePattern(k_);
    pattern_.remember(k_);
    analyzed_ahead_ = true;
    return llt_.cholmod().fl;
  }

  bool factorize(const SparseMatrix& k) override {
    stats_ = {};
    // An analysis done by analyze() counts as this factorization's.
    stats_.analyzed = analyzed_ahead_;
    analyzed_ahead_ = false;
    k_ = k;
    k_.makeCompressed();
    if (!pattern_.matches(k_)) {
      llt_.analyzePattern(k_);
      pattern_.remember(k_);
      stats_.analyzed = true;
    }
    llt_.factorize(k_);
    stats_.converged = llt_.info() == Eigen::Success;
    // After a failed factorization CHOLMOD may leave the factor in a partial state: analyse
    // afresh next time rather than trust it.
    if (!stats_.converged) pattern_.forget();
    return stats_.converged;
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& f) override {
    Eigen::VectorXd x = llt_.solve(f);
    stats_.residual = relativeResidual(k_, x, f);
    return x;
  }
  SolveStats stats() const override { return stats_; }
  std::string name() const override { return "cholmod"; }

 private:
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> llt_;
  SparsityPattern pattern_;
  SparseMatrix k_;  ///< the factorized matrix, for the residual
  SolveStats stats_;
  bool analyzed_ahead_ = false;  ///< analyze() ran since the last factorize
};

}  // namespace

std::unique_ptr<LinearSolver> makeCholmodSolver() {
  return std::make_unique<CholmodSolver>();
}

std::unique_ptr<LinearSolver> makeAnalyzedCholmodSolver(const SparseMatrix& k, double& flops) {
  auto solver = std::make_unique<CholmodSolver>();
  flops = solver->analyze(k);
  return solver;
}

double cholmodFactorFlops(const SparseMatrix& k) {
  double flops = 0.0;
  makeAnalyzedCholmodSolver(k, flops);
  return flops;
}

}  // namespace rockmass::dda3d
