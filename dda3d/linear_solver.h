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
  /// Cholmod up to SolverOptions::auto_cholmod_unknowns unknowns of the movable blocks
  /// (resolvedSolverOptions); above, chosen at the first factorization from the matrix: Cholmod
  /// when its factorization costs at most auto_cholmod_flop_ratio times the flops of a PCG
  /// solve (auto_pcg_iterations products with K), else warm-started Pcg.
  Auto,
};

/// Settings of a backend.
struct SolverOptions {
  SolverKind kind = SolverKind::Cholmod;
  int block_size = 12;        ///< unknowns per block (6 rigid, 12 deformable), for Pcg's
                              ///< block-Jacobi preconditioner
  double tolerance = 1e-10;   ///< Pcg: relative residual |K d - F| / |F|
  int max_iterations = 5000;  ///< Pcg
  /// Auto: the most unknowns (of the movable blocks) Cholmod solves, Pcg above: 1000 rigid
  /// or 500 deformable blocks. Measured: at 12 000 unknowns (1000 deformable cubes) a PCG
  /// solve is the faster one and CHOLMOD's fill-in grows superlinearly with a 3D pile's size
  /// (bench/solver_bench.cpp); at 6 000 (1000 rigid cubes settling, 13 open-close iterations
  /// a step) CHOLMOD runs 5.3x PCG's steps per second, and at 5 598 (the Xiangjiaba model,
  /// 933 rigid blocks) it factorizes in 43 ms, as fast as a warm-started PCG solve of a
  /// resting step, its overload steps taking 0.7 of PCG's time (docs/performance.md, "DDA
  /// linear solvers").
  int auto_cholmod_unknowns = 6000;
  /// Auto above auto_cholmod_unknowns: CHOLMOD's factorization flops (its symbolic analysis'
  /// count) over those of one PCG solve, 2 nnz(K) auto_pcg_iterations, up to which CHOLMOD is
  /// kept. The fill of a factor is the model's: a 3D pile of 1000 deformable cubes fills in
  /// so much that PCG solves it faster, the 20 m slice of the Xiangjiaba foundation (933
  /// deformable blocks, nearly plane) so little that CHOLMOD factorizes it 4 times faster than
  /// PCG solves it (docs/performance.md, "DDA linear solvers").
  double auto_cholmod_flop_ratio = 1.0;
  int auto_pcg_iterations = 400;  ///< PCG iterations a solve is reckoned at (Auto's choice)
  /// Direct backends: each solve's relative residual in SolveStats (a copy of K kept at each
  /// factorization and a product with it at each solve). The DDA engine does not read it, and
  /// turns it off.
  bool report_residual = true;
};

/// One solve's account, for the step statistics.
struct SolveStats {
  bool analyzed = false;  ///< the symbolic analysis was redone (pattern changed)
  int iterations = 0;     ///< Pcg iterations (0 for direct solvers)
  /// Relative residual |K d - F| / |F| reached by the last solve (0 when a direct backend
  /// does not report it: SolverOptions::report_residual).
  double residual = 0.0;
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
  /// Solves with the last factorized K, starting from `guess` (same size as f). Iterative
  /// backends start there (fewer iterations when the guess is close); direct backends
  /// ignore it, so the result is that of solve(f).
  virtual Eigen::VectorXd solveWithGuess(const Eigen::VectorXd& f, const Eigen::VectorXd& guess) {
    (void)guess;
    return solve(f);
  }
  /// Statistics of the last factorize + solve.
  virtual SolveStats stats() const = 0;
  /// "cholmod", "eigen-ldlt" or "pcg".
  virtual std::string name() const = 0;
};

/// A backend of the requested kind (Auto: the backend that chooses at its first
/// factorization, with `options.tolerance` for PCG).
std::unique_ptr<LinearSolver> makeLinearSolver(const SolverOptions& options);

/// The file this process loaded for the shared library `soname` (e.g. "libblas.so.3", the
/// BLAS CHOLMOD's supernodes run on, or "liblapack.so.3"), resolved through symbolic links,
/// or "" when none is loaded. The BLAS's round-off is the factorization's (docs/dda3d.md,
/// "BLAS").
std::string loadedLibrary(const std::string& soname);

}  // namespace rockmass::dda3d
