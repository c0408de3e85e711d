#include "dda3d/linear_solver.h"

#include <vector>

#include <gtest/gtest.h>

namespace rockmass::dda3d {
namespace {

/// The 1D Laplacian with Dirichlet ends, scaled by `scale`: SPD with known solution for
/// F = K * ones.
SparseMatrix laplacian(int n, double scale) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 2.0 * scale);
    if (i > 0) t.emplace_back(i, i - 1, -scale);
    if (i + 1 < n) t.emplace_back(i, i + 1, -scale);
  }
  SparseMatrix k(n, n);
  k.setFromTriplets(t.begin(), t.end());
  return k;
}

TEST(LinearSolver, EigenLdltSolvesAndKeepsItsAnalysis) {
  const std::unique_ptr<LinearSolver> solver = makeLinearSolver({.kind = SolverKind::Eigen});
  const SparseMatrix k = laplacian(200, 1e9);
  const Eigen::VectorXd expected = Eigen::VectorXd::LinSpaced(200, -1.0, 1.0);
  ASSERT_TRUE(solver->factorize(k));
  EXPECT_TRUE(solver->stats().analyzed);
  // Condition number ~ 4 n^2 / pi^2 = 1.6e4: a direct solve loses ~4 digits at most.
  EXPECT_LT((solver->solve(k * expected) - expected).norm() / expected.norm(), 1e-11);
  // Same pattern, new values: no new symbolic analysis.
  ASSERT_TRUE(solver->factorize(laplacian(200, 3e9)));
  EXPECT_FALSE(solver->stats().analyzed);
  // A new pattern is analysed again.
  ASSERT_TRUE(solver->factorize(laplacian(100, 1.0)));
  EXPECT_TRUE(solver->stats().analyzed);
  EXPECT_EQ(solver->name(), "eigen-ldlt");
}

TEST(LinearSolver, ReportsASingularMatrix) {
  // A zero pivot breaks the factorization: factorize() must say so instead of returning
  // infinities from solve() later.
  const std::unique_ptr<LinearSolver> solver = makeLinearSolver({.kind = SolverKind::Eigen});
  SparseMatrix singular(2, 2);
  singular.insert(0, 0) = 1.0;  // the (1, 1) pivot is zero
  singular.makeCompressed();
  EXPECT_FALSE(solver->factorize(singular));
}

}  // namespace
}  // namespace rockmass::dda3d
