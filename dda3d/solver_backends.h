// The backends behind makeLinearSolver(), one file each. Internal to dda3d.
#pragma once

#include <memory>

#include "dda3d/linear_solver.h"

namespace rockmass::dda3d {

/// Eigen::SimplicialLDLT (eigen_ldlt_solver.cpp).
std::unique_ptr<LinearSolver> makeEigenLdltSolver();
/// CHOLMOD supernodal LL^T (cholmod_solver.cpp); `report_residual`:
/// SolverOptions::report_residual.
std::unique_ptr<LinearSolver> makeCholmodSolver(bool report_residual = true);
/// Block-Jacobi preconditioned conjugate gradients (pcg_solver.cpp).
std::unique_ptr<LinearSolver> makePcgSolver(const SolverOptions& options);

/// A CHOLMOD backend whose symbolic analysis of K's pattern is done (its first factorize of
/// that pattern does not redo it); `flops` gets CHOLMOD's count of the factorization's flops.
std::unique_ptr<LinearSolver> makeAnalyzedCholmodSolver(const SparseMatrix& k, double& flops,
                                                        bool report_residual = true);
/// CHOLMOD's count of the flops of a supernodal factorization of K (its symbolic analysis,
/// with the ordering it would use), without factorizing.
double cholmodFactorFlops(const SparseMatrix& k);
/// SolverKind::Auto: Cholmod or Pcg, chosen at the first factorization (linear_solver.cpp).
std::unique_ptr<LinearSolver> makeAutoSolver(const SolverOptions& options);

/// |K x - f| / |f| (|K x| when f = 0): what a solve left over, relative to the load.
double relativeResidual(const SparseMatrix& k, const Eigen::VectorXd& x, const Eigen::VectorXd& f);

}  // namespace rockmass::dda3d
