// The sparse symmetric positive definite solve of each DDA open-close iteration, behind one
// interface so that backends (CHOLMOD supernodal Cholesky, Eigen's simplicial LDLT, block-
// Jacobi preconditioned CG) can be swapped and compared.
#pragma once

#include <memory>
#include <string>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace rockmass::dda3d {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// Which backend solves K d = F.
enum class SolverKind {
  Cholmod,  ///< CHOLMOD supernodal Cholesky (SuiteSparse)
  Eigen,    ///< Eigen::SimplicialLDLT
  Pcg,      ///< conjugate gradients with a block-Jacobi (12x12 or 6x6) preconditioner
};

/// Settings of a backend.
struct SolverOptions {
  SolverKind kind = SolverKind::Cholmod;
  int block_size = 12;        ///< unknowns per block (6 rigid, 12 deformable), for Pcg's
                              ///< block-Jacobi preconditioner
  double tolerance = 1e-10;   ///< Pcg: relative residual |K d - F| / |F|
  int max_iterations = 5000;  ///< Pcg
};

/// One solve's account, for the step statistics.
struct SolveStats {
  bool analyzed = false;   ///< the symbolic analysis was redone (pattern changed)
  int iterations = 0;      ///< Pcg iterations (0 for direct solvers)
  double residual = 0.0;   ///< relative residual |K d - F| / |F| reached by the last solve
  bool converged = false;  ///< factorization succeeded (direct) / tolerance reached (Pcg)
};

/// Solves K d = F for a symmetric positive definite K, stored with both triangles.
/// Implementations keep their symbolic analysis while the sparsity pattern is unchanged.
class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  /// Factorizes (or prepares) K; returns false when K is not positive definite.
  virtual bool factorize(const SparseMatrix& k) = 0;
  /// Solves with the last factorized K.
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& f) = 0;
  /// Statistics of the last factorize + solve.
  virtual SolveStats stats() const = 0;
  /// "cholmod", "eigen-ldlt" or "pcg".
  virtual std::string name() const = 0;
};

/// A backend of the requested kind.
std::unique_ptr<LinearSolver> makeLinearSolver(const SolverOptions& options);

}  // namespace rockmass::dda3d
