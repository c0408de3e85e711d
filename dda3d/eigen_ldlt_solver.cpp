// Eigen's simplicial LDL^T: no external dependency, the reference the other backends are
// checked against.
#include <Eigen/SparseCholesky>

#include "dda3d/solver_backends.h"
#include "dda3d/sparsity_pattern.h"

namespace rockmass::dda3d {
namespace {

/// Eigen's simplicial LDL^T with the symbolic analysis kept while the pattern is unchanged.
class EigenLdltSolver final : public LinearSolver {
 public:
  bool factorize(const SparseMatrix& k) override {
    stats_ = {};
    k_ = k;
    k_.makeCompressed();
    if (!pattern_.matches(k_)) {
      ldlt_.analyzePattern(k_);
      pattern_.remember(k_);
      stats_.analyzed = true;
    }
    ldlt_.factorize(k_);
    // LDL^T exists for some indefinite matrices too: positive definite means D > 0.
    stats_.converged = ldlt_.info() == Eigen::Success && (ldlt_.vectorD().array() > 0.0).all();
    return stats_.converged;
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& f) override {
    Eigen::VectorXd x = ldlt_.solve(f);
    stats_.residual = relativeResidual(k_, x, f);
    return x;
  }
  SolveStats stats() const override { return stats_; }
  std::string name() const override { return "eigen-ldlt"; }

 private:
  Eigen::SimplicialLDLT<SparseMatrix> ldlt_;
  SparsityPattern pattern_;
  SparseMatrix k_;  ///< the factorized matrix, for the residual
  SolveStats stats_;
};

}  // namespace

std::unique_ptr<LinearSolver> makeEigenLdltSolver() {
  return std::make_unique<EigenLdltSolver>();
}

}  // namespace rockmass::dda3d
