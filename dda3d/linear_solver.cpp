#include "dda3d/linear_solver.h"

#include <stdexcept>

#include "dda3d/solver_backends.h"

namespace rockmass::dda3d {

double relativeResidual(const SparseMatrix& k, const Eigen::VectorXd& x, const Eigen::VectorXd& f) {
  const double residual = (k * x - f).norm();
  const double scale = f.norm();
  return scale > 0.0 ? residual / scale : residual;
}

std::unique_ptr<LinearSolver> makeLinearSolver(const SolverOptions& options) {
  switch (options.kind) {
    case SolverKind::Cholmod:
      return makeCholmodSolver();
    case SolverKind::Eigen:
      return makeEigenLdltSolver();
    case SolverKind::Pcg:
      return makePcgSolver(options);
    case SolverKind::Auto:
      throw std::invalid_argument("makeLinearSolver: resolve SolverKind::Auto first");
  }
  throw std::invalid_argument("makeLinearSolver: unknown solver kind");
}

}  // namespace rockmass::dda3d
