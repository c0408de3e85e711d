#include "dda3d/linear_solver.h"

#include <stdexcept>
#include <utility>

#include "dda3d/solver_backends.h"

namespace rockmass::dda3d {

double relativeResidual(const SparseMatrix& k, const Eigen::VectorXd& x, const Eigen::VectorXd& f) {
  const double residual = (k * x - f).norm();
  const double scale = f.norm();
  return scale > 0.0 ? residual / scale : residual;
}

namespace {

/// SolverKind::Auto above auto_cholmod_unknowns: the backend is chosen from the first matrix it
/// factorizes and kept for the run (a run's solver, and so its answers, depend on the model
/// only, not on timings).
class AutoSolver final : public LinearSolver {
 public:
  explicit AutoSolver(const SolverOptions& options) : options_(options) {}

  bool factorize(const SparseMatrix& k) override {
    if (!chosen_) {
      // The analysis that counts CHOLMOD's flops is the one it keeps when it is chosen.
      double direct = 0.0;
      std::unique_ptr<LinearSolver> cholmod =
          makeAnalyzedCholmodSolver(k, direct, options_.report_residual);
      const double iterative = 2.0 * static_cast<double>(k.nonZeros()) *
                               static_cast<double>(options_.auto_pcg_iterations);
      SolverOptions pcg = options_;
      pcg.kind = SolverKind::Pcg;
      chosen_ = direct <= options_.auto_cholmod_flop_ratio * iterative ? std::move(cholmod)
                                                                       : makePcgSolver(pcg);
    }
    return chosen_->factorize(k);
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& f) override { return chosen_->solve(f); }
  Eigen::VectorXd solveWithGuess(const Eigen::VectorXd& f, const Eigen::VectorXd& guess) override {
    return chosen_->solveWithGuess(f, guess);
  }
  SolveStats stats() const override { return chosen_ ? chosen_->stats() : SolveStats{}; }
  std::string name() const override { return chosen_ ? chosen_->name() : "auto"; }

 private:
  SolverOptions options_;
  std::unique_ptr<LinearSolver> chosen_;
};

}  // namespace

std::unique_ptr<LinearSolver> makeAutoSolver(const SolverOptions& options) {
  return std::make_unique<AutoSolver>(options);
}

std::unique_ptr<LinearSolver> makeLinearSolver(const SolverOptions& options) {
  switch (options.kind) {
    case SolverKind::Cholmod:
      return makeCholmodSolver(options.report_residual);
    case SolverKind::Eigen:
      return makeEigenLdltSolver();
    case SolverKind::Pcg:
      return makePcgSolver(options);
    case SolverKind::Auto:
      return makeAutoSolver(options);
  }
  throw std::invalid_argument("makeLinearSolver: unknown solver kind");
}

}  // namespace rockmass::dda3d
