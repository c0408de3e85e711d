// Conjugate gradients with a block-Jacobi preconditioner: no factorization, memory linear in
// the number of nonzeros, accuracy set by a tolerance. The accuracy-against-time study
// compares it with the direct backends.
#include <Eigen/IterativeLinearSolvers>

#include "dda3d/block_jacobi_preconditioner.h"
#include "dda3d/solver_backends.h"

namespace rockmass::dda3d {
namespace {

/// Eigen::ConjugateGradient on the full matrix (both triangles) with a block-Jacobi
/// preconditioner; stops at |K d - F| <= tolerance |F| or after max_iterations.
class PcgSolver final : public LinearSolver {
 public:
  explicit PcgSolver(const SolverOptions& options) {
    cg_.preconditioner().setBlockSize(options.block_size);
    cg_.setTolerance(options.tolerance);
    cg_.setMaxIterations(options.max_iterations);
  }

  bool factorize(const SparseMatrix& k) override {
    stats_ = {};
    // The solver keeps a reference to the matrix it was given: hand it our own copy, since
    // the caller's K need not outlive this call.
    k_ = k;
    cg_.compute(k_);
    // CG needs a positive definite K; an indefinite diagonal block proves K is not.
    stats_.converged = cg_.preconditioner().info() == Eigen::Success;
    return stats_.converged;
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& f) override {
    return finish(f, cg_.solve(f), false);
  }
  Eigen::VectorXd solveWithGuess(const Eigen::VectorXd& f, const Eigen::VectorXd& guess) override {
    if (guess.size() != f.size()) return solve(f);
    // Eigen reports 0 iterations both when the guess already met the tolerance and when one
    // step did: tell them apart by the guess's own residual.
    const bool guess_enough = relativeResidual(k_, guess, f) < cg_.tolerance();
    return finish(f, cg_.solveWithGuess(f, guess), guess_enough);
  }
  SolveStats stats() const override { return stats_; }
  std::string name() const override { return "pcg"; }

 private:
  /// Records the statistics of a solve that produced x.
  Eigen::VectorXd finish(const Eigen::VectorXd& f, Eigen::VectorXd x, bool guess_enough) {
    stats_.converged = cg_.info() == Eigen::Success;
    stats_.iterations = guess_enough ? 0 : conjugateGradientSteps(f);
    // The true residual, not CG's recurrence (which drifts from it by round-off).
    stats_.residual = relativeResidual(k_, x, f);
    return x;
  }
  /// CG steps taken (matrix-vector products). Eigen's count omits the step that converged:
  /// starting from d = 0, no step is needed only when F = 0 or the tolerance is >= 1.
  int conjugateGradientSteps(const Eigen::VectorXd& f) const {
    const int counted = static_cast<int>(cg_.iterations());
    const bool nothing_to_do = f.squaredNorm() == 0.0 || cg_.tolerance() >= 1.0;
    return stats_.converged && !nothing_to_do ? counted + 1 : counted;
  }

  Eigen::ConjugateGradient<SparseMatrix, Eigen::Lower | Eigen::Upper, BlockJacobiPreconditioner>
      cg_;
  SparseMatrix k_;  ///< the matrix cg_ refers to
  SolveStats stats_;
};

}  // namespace

std::unique_ptr<LinearSolver> makePcgSolver(const SolverOptions& options) {
  return std::make_unique<PcgSolver>(options);
}

}  // namespace rockmass::dda3d
