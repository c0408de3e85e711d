#include "dda3d/linear_solver.h"

#include <stdexcept>

#include <Eigen/SparseCholesky>

namespace rockmass::dda3d {

namespace {

/// Eigen's simplicial LDL^T with the symbolic analysis kept while the pattern is unchanged.
class EigenLdltSolver final : public LinearSolver {
 public:
  bool factorize(const SparseMatrix& k) override {
    stats_ = {};
    if (!samePattern(k)) {
      ldlt_.analyzePattern(k);
      remember(k);
      stats_.analyzed = true;
    }
    ldlt_.factorize(k);
    return ldlt_.info() == Eigen::Success;
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& f) override { return ldlt_.solve(f); }
  SolveStats stats() const override { return stats_; }
  std::string name() const override { return "eigen-ldlt"; }

 private:
  bool samePattern(const SparseMatrix& k) const {
    if (k.rows() != rows_ || k.nonZeros() != static_cast<Eigen::Index>(inner_.size())) {
      return false;
    }
    for (Eigen::Index c = 0; c <= k.cols(); ++c) {
      if (k.outerIndexPtr()[c] != outer_[static_cast<std::size_t>(c)]) return false;
    }
    for (std::size_t i = 0; i < inner_.size(); ++i) {
      if (k.innerIndexPtr()[i] != inner_[i]) return false;
    }
    return true;
  }
  void remember(const SparseMatrix& k) {
    rows_ = k.rows();
    outer_.assign(k.outerIndexPtr(), k.outerIndexPtr() + k.cols() + 1);
    inner_.assign(k.innerIndexPtr(), k.innerIndexPtr() + k.nonZeros());
  }

  Eigen::SimplicialLDLT<SparseMatrix> ldlt_;
  Eigen::Index rows_ = -1;
  std::vector<int> outer_, inner_;
  SolveStats stats_;
};

}  // namespace

std::unique_ptr<LinearSolver> makeLinearSolver(const SolverOptions& options) {
  switch (options.kind) {
    case SolverKind::Eigen:
      return std::make_unique<EigenLdltSolver>();
    default:
      throw std::invalid_argument("makeLinearSolver: this backend is not built yet");
  }
}

}  // namespace rockmass::dda3d
