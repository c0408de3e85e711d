// The sparse SPD solve of DDA: three backends (CHOLMOD supernodal, Eigen LDLT, block-Jacobi
// PCG) checked against each other and against the perturbation bounds of numerical linear
// algebra (Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., ch. 7 and 10):
// for a backward-stable Cholesky solve |x - x*| / |x*| <= c(n) kappa(K) eps, and for any
// approximate solution |x - x*| / |x*| <= kappa(K) |K x - F| / |F|.
#include "dda3d/linear_solver.h"

#include <cmath>
#include <limits>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/CholmodSupport>
#include <Eigen/Eigenvalues>

#if defined(__linux__)
#include <pthread.h>
#include <sched.h>
#endif

#include "dda3d/block_jacobi_preconditioner.h"
#include "dda3d/solver_backends.h"
#include "scenarios/dda_matrices.h"

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

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// 2-norm condition number of a (small) symmetric positive definite matrix.
double conditionNumber(const SparseMatrix& k) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(Eigen::MatrixXd(k),
                                                             Eigen::EigenvaluesOnly);
  return eigen.eigenvalues().maxCoeff() / eigen.eigenvalues().minCoeff();
}

double relativeError(const Eigen::VectorXd& x, const Eigen::VectorXd& expected) {
  return (x - expected).norm() / expected.norm();
}

struct AgreementCase {
  double contrast;
  bool dynamic;
};

/// Contrast and dynamic/static, for test listings.
void PrintTo(const AgreementCase& c, std::ostream* out) {
  *out << "contrast " << c.contrast << (c.dynamic ? ", dynamic" : ", static");
}

class BackendsAgree : public ::testing::TestWithParam<AgreementCase> {};

TEST_P(BackendsAgree, OnDdaShapedSystems) {
  // 27 unit-cube blocks (324 unknowns) coupled by contact springs, a soft layer softer by
  // `contrast`; static systems (no inertia) are the badly conditioned ones.
  const test::DdaSystemSpec spec{.contrast = GetParam().contrast, .dynamic = GetParam().dynamic};
  const SparseMatrix k = test::ddaSystemMatrix(spec);
  const Eigen::VectorXd expected = test::ddaSolution(static_cast<int>(k.rows()));
  const Eigen::VectorXd f = k * expected;
  const double kappa = conditionNumber(k);
  ASSERT_GT(kappa, GetParam().dynamic ? 10.0 : 1e6) << "the case is not the hard one it claims";

  // Backward-stable direct solves: forward error <= c(n) kappa eps. c(n) = 10 is generous
  // for these sparse factors (a few hundred flops per entry); the measured errors sit well
  // below it.
  const double direct_bound = 10.0 * kappa * kEps;
  Eigen::VectorXd cholmod_x, eigen_x;
  for (SolverKind kind : {SolverKind::Cholmod, SolverKind::Eigen}) {
    const std::unique_ptr<LinearSolver> solver = makeLinearSolver({.kind = kind});
    ASSERT_TRUE(solver->factorize(k)) << solver->name();
    const Eigen::VectorXd x = solver->solve(f);
    EXPECT_LT(relativeError(x, expected), direct_bound) << solver->name();
    // The residual a backward-stable solve leaves is a few eps relative to |K| |x|.
    EXPECT_LT(solver->stats().residual, 100.0 * kEps * kappa) << solver->name();
    EXPECT_TRUE(solver->stats().converged);
    (kind == SolverKind::Cholmod ? cholmod_x : eigen_x) = x;
  }
  // The two direct solutions agree within the sum of their error bounds.
  EXPECT_LT(relativeError(cholmod_x, eigen_x), 2.0 * direct_bound);

  // PCG stopped at relative residual tol: its error is bounded by kappa * residual.
  const double tolerance = 1e-12;
  const std::unique_ptr<LinearSolver> pcg =
      makeLinearSolver({.kind = SolverKind::Pcg, .tolerance = tolerance, .max_iterations = 20000});
  ASSERT_TRUE(pcg->factorize(k));
  const Eigen::VectorXd x = pcg->solve(f);
  ASSERT_TRUE(pcg->stats().converged);
  // True residual: the recurrence one CG stops on drifts by round-off ~ kappa eps.
  EXPECT_LE(pcg->stats().residual, tolerance + kappa * kEps);
  EXPECT_LT(relativeError(x, cholmod_x), kappa * tolerance + direct_bound);
  EXPECT_GT(pcg->stats().iterations, 0);
}

INSTANTIATE_TEST_SUITE_P(StiffnessContrasts, BackendsAgree,
                         ::testing::Values(AgreementCase{1e3, true}, AgreementCase{1e6, true},
                                           AgreementCase{1e3, false}, AgreementCase{1e6, false}),
                         [](const ::testing::TestParamInfo<AgreementCase>& info) {
                           // e.g. "Contrast1e3Dynamic", "Contrast1e6Static"
                           return "Contrast1e" +
                                  std::to_string(static_cast<int>(
                                      std::lround(std::log10(info.param.contrast)))) +
                                  (info.param.dynamic ? "Dynamic" : "Static");
                         });

TEST(LinearSolver, PcgStartsFromAGuessDirectSolversIgnoreIt) {
  const test::DdaSystemSpec spec{.contrast = 1e3};
  const SparseMatrix k = test::ddaSystemMatrix(spec);
  const Eigen::VectorXd expected = test::ddaSolution(static_cast<int>(k.rows()));
  const Eigen::VectorXd f = k * expected;
  const double tolerance = 1e-8;
  const std::unique_ptr<LinearSolver> pcg =
      makeLinearSolver({.kind = SolverKind::Pcg, .tolerance = tolerance});
  ASSERT_TRUE(pcg->factorize(k));
  pcg->solve(f);
  const int cold = pcg->stats().iterations;
  // The exact solution already meets the tolerance: no CG step.
  Eigen::VectorXd x = pcg->solveWithGuess(f, expected);
  EXPECT_EQ(pcg->stats().iterations, 0);
  EXPECT_LT(relativeError(x, expected), 1e-14);  // returned unchanged (round-off only)
  // A guess 1% off (what the previous step's solution typically is) needs fewer steps than
  // a start from zero, and still ends within the tolerance.
  x = pcg->solveWithGuess(f, 1.01 * expected);
  EXPECT_LT(pcg->stats().iterations, cold);
  EXPECT_LE(pcg->stats().residual, tolerance);
  // Direct backends: the guess changes nothing, the result is solve(f) bit for bit.
  const std::unique_ptr<LinearSolver> cholmod = makeLinearSolver({.kind = SolverKind::Cholmod});
  ASSERT_TRUE(cholmod->factorize(k));
  EXPECT_EQ(cholmod->solveWithGuess(f, 2.0 * expected), cholmod->solve(f));
}

TEST(LinearSolver, CholmodKeepsItsAnalysisWhileThePatternHolds) {
  const std::unique_ptr<LinearSolver> solver = makeLinearSolver({.kind = SolverKind::Cholmod});
  EXPECT_EQ(solver->name(), "cholmod");
  const test::DdaSystemSpec spec;
  const SparseMatrix k = test::ddaSystemMatrix(spec);
  const Eigen::VectorXd expected = test::ddaSolution(static_cast<int>(k.rows()));
  ASSERT_TRUE(solver->factorize(k));
  EXPECT_TRUE(solver->stats().analyzed);
  // New values, same pattern (the next open-close iteration): numeric factorization only,
  // and the reused analysis still gives the right answer (kappa ~ 1e4 here: 1e-10 is loose).
  const SparseMatrix stiffer = 3.0 * k;
  ASSERT_TRUE(solver->factorize(stiffer));
  EXPECT_FALSE(solver->stats().analyzed);
  EXPECT_LT(relativeError(solver->solve(stiffer * expected), expected), 1e-10);
  // A new contact (one more coupling entry pair) changes the pattern: analysed again.
  SparseMatrix coupled = k;
  const int last = static_cast<int>(k.rows()) - 1;
  coupled.coeffRef(0, last) += 1.0;
  coupled.coeffRef(last, 0) += 1.0;
  coupled.makeCompressed();
  ASSERT_TRUE(solver->factorize(coupled));
  EXPECT_TRUE(solver->stats().analyzed);
  EXPECT_LT(relativeError(solver->solve(coupled * expected), expected), 1e-10);
}

TEST(LinearSolver, CholmodFactorizesTheUpperTriangleToTheLowerOnesBits) {
  // The backend hands CHOLMOD K's upper triangle (one transpose into the permuted lower
  // triangle it factorizes, against two from the lower one: cholmod_factorize_p). With both
  // triangles equal (BlockSystem::matrix) the factor is the one of the lower triangle: the
  // same solution to the bit as CHOLMOD on the lower triangle, with or without the residual.
  const SparseMatrix k = test::ddaSystemMatrix(test::DdaSystemSpec{});
  ASSERT_TRUE(SparseMatrix(k.transpose()).isApprox(k, 0.0));
  const Eigen::VectorXd f = k * test::ddaSolution(static_cast<int>(k.rows()));
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> lower;
  lower.compute(k);
  ASSERT_EQ(lower.info(), Eigen::Success);
  const Eigen::VectorXd expected = lower.solve(f);
  for (const bool report : {true, false}) {
    const std::unique_ptr<LinearSolver> solver =
        makeLinearSolver({.kind = SolverKind::Cholmod, .report_residual = report});
    ASSERT_TRUE(solver->factorize(k));
    const Eigen::VectorXd x = solver->solve(f);
    EXPECT_TRUE(x == expected) << "report_residual " << report;
    // The residual when reported: a backward-stable solve's few eps of |K| |x| / |F|
    // (kappa ~ 1e4 here); 0 when not.
    if (report) {
      EXPECT_GT(solver->stats().residual, 0.0);
      EXPECT_LT(solver->stats().residual, 1e-10);
    } else {
      EXPECT_EQ(solver->stats().residual, 0.0);
    }
  }
}

#if defined(__linux__)
// CHOLMOD's factorization holds its thread on the CPU it runs on while it works
// (cholmod_solver.cpp: a thread the scheduler moved between cores factorized 2x slower); the
// thread's own CPU set must be given back afterwards, whole, on success and on failure.
TEST(LinearSolver, CholmodGivesItsThreadsCpuSetBack) {
  cpu_set_t before, after;
  ASSERT_EQ(pthread_getaffinity_np(pthread_self(), sizeof(before), &before), 0);
  const std::unique_ptr<LinearSolver> solver = makeLinearSolver({.kind = SolverKind::Cholmod});
  const SparseMatrix k = test::ddaSystemMatrix(test::DdaSystemSpec{});
  ASSERT_TRUE(solver->factorize(k));
  ASSERT_EQ(pthread_getaffinity_np(pthread_self(), sizeof(after), &after), 0);
  EXPECT_TRUE(CPU_EQUAL(&before, &after));
  EXPECT_FALSE(solver->factorize(SparseMatrix(-1.0 * k)));  // not positive definite
  ASSERT_EQ(pthread_getaffinity_np(pthread_self(), sizeof(after), &after), 0);
  EXPECT_TRUE(CPU_EQUAL(&before, &after));
}
#endif

TEST(LinearSolver, NonPositiveDefiniteMatrixIsAFailureForEveryBackend) {
  // K - 2 lambda_min I has a negative eigenvalue: no Cholesky factor exists. The shift moves
  // only the diagonal, so the pattern (and CHOLMOD's analysis) is that of a real DDA matrix.
  const SparseMatrix k = test::ddaSystemMatrix({.nx = 2, .ny = 2, .nz = 2});
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(Eigen::MatrixXd(k),
                                                             Eigen::EigenvaluesOnly);
  SparseMatrix identity(k.rows(), k.cols());
  identity.setIdentity();
  const SparseMatrix indefinite = k - 2.0 * eigen.eigenvalues().minCoeff() * identity;
  for (SolverKind kind : {SolverKind::Cholmod, SolverKind::Eigen}) {
    const std::unique_ptr<LinearSolver> solver = makeLinearSolver({.kind = kind});
    EXPECT_FALSE(solver->factorize(indefinite)) << solver->name();
    EXPECT_FALSE(solver->stats().converged) << solver->name();
    // The solver recovers: the SPD matrix with the same pattern factorizes afterwards.
    EXPECT_TRUE(solver->factorize(k)) << solver->name();
    const Eigen::VectorXd expected = test::ddaSolution(static_cast<int>(k.rows()));
    EXPECT_LT(relativeError(solver->solve(k * expected), expected), 1e-10) << solver->name();
  }
  // A negative diagonal entry makes a diagonal block indefinite: PCG's preconditioner sees it.
  SparseMatrix negative = k;
  negative.coeffRef(5, 5) = -1.0;
  const std::unique_ptr<LinearSolver> pcg = makeLinearSolver({.kind = SolverKind::Pcg});
  EXPECT_FALSE(pcg->factorize(negative));
  // A 2 x 2 indefinite matrix (eigenvalues 3 and -1) for CHOLMOD, the smallest case.
  SparseMatrix small(2, 2);
  small.insert(0, 0) = 1.0;
  small.insert(1, 0) = 2.0;
  small.insert(0, 1) = 2.0;
  small.insert(1, 1) = 1.0;
  small.makeCompressed();
  EXPECT_FALSE(makeLinearSolver({.kind = SolverKind::Cholmod})->factorize(small));
}

TEST(LinearSolver, PcgAccuracyFollowsItsTolerance) {
  const test::DdaSystemSpec spec{.contrast = 1e3, .dynamic = false};
  const SparseMatrix k = test::ddaSystemMatrix(spec);
  const Eigen::VectorXd expected = test::ddaSolution(static_cast<int>(k.rows()));
  const Eigen::VectorXd f = k * expected;
  const double kappa = conditionNumber(k);
  int previous_iterations = 0;
  for (double tolerance : {1e-4, 1e-6, 1e-8, 1e-10, 1e-12}) {
    const std::unique_ptr<LinearSolver> pcg = makeLinearSolver(
        {.kind = SolverKind::Pcg, .tolerance = tolerance, .max_iterations = 20000});
    ASSERT_TRUE(pcg->factorize(k));
    const Eigen::VectorXd x = pcg->solve(f);
    const SolveStats stats = pcg->stats();
    EXPECT_TRUE(stats.converged) << tolerance;
    // The reported residual is the true one; CG stopped on its recurrence residual, which
    // drifts from the true one by round-off of order kappa eps (Higham, section 17.5).
    EXPECT_LE(stats.residual, tolerance + kappa * kEps);
    EXPECT_DOUBLE_EQ(stats.residual, (k * x - f).norm() / f.norm());
    // Error bound kappa * residual (Higham, Lemma 7.1 restated for relative residuals).
    EXPECT_LE(relativeError(x, expected), kappa * stats.residual);
    // A tighter tolerance costs more iterations.
    EXPECT_GT(stats.iterations, previous_iterations) << tolerance;
    previous_iterations = stats.iterations;
  }
}

TEST(LinearSolver, AutoTakesCholmodWhereItsFactorIsCheapAndPcgWhereItFillsIn) {
  // 1 000 deformable unit cubes either way (12 000 unknowns, above auto_cholmod_unknowns): a
  // 10 x 10 x 10 pile, whose factor fills in (CHOLMOD's count 2.9e9 flops, 3.9 times a PCG
  // solve of 400 iterations; bench/solver_bench.cpp: PCG 0.44 of CHOLMOD's time), and a
  // 50 x 20 x 1 layer, nearly plane as the Xiangjiaba foundation's 20 m slice is (its 933
  // deformable blocks: 0.19 times; CHOLMOD factorizes it in 0.3 s where a PCG solve took
  // 1.3 s). The choice is made once, from the first matrix, and the solve is right either way.
  const SolverOptions options{.kind = SolverKind::Auto, .tolerance = 1e-10};
  const test::DdaSystemSpec pile{.nx = 10, .ny = 10, .nz = 10};
  const test::DdaSystemSpec layer{.nx = 50, .ny = 20, .nz = 1};
  for (const auto& [spec, expected] : {std::pair{pile, "pcg"}, std::pair{layer, "cholmod"}}) {
    const SparseMatrix k = test::ddaSystemMatrix(spec);
    ASSERT_EQ(k.rows(), 12000);
    const Eigen::VectorXd x_star = test::ddaSolution(static_cast<int>(k.rows()));
    const Eigen::VectorXd f = k * x_star;
    const std::unique_ptr<LinearSolver> solver = makeLinearSolver(options);
    EXPECT_EQ(solver->name(), "auto");  // not chosen before it has seen a matrix
    ASSERT_TRUE(solver->factorize(k));
    EXPECT_EQ(solver->name(), expected);
    const double direct = cholmodFactorFlops(k);
    const double iterative = 2.0 * static_cast<double>(k.nonZeros()) * 400.0;
    EXPECT_EQ(direct <= iterative, std::string(expected) == "cholmod") << direct / iterative;
    // PCG at 1e-10 and CHOLMOD at round-off: both well within 1e-6 of x* (the layer's and the
    // pile's condition numbers are below 1e4, so PCG's error bound kappa 1e-10 holds it).
    EXPECT_LT(relativeError(solver->solve(f), x_star), 1e-6) << expected;
  }
}

TEST(LinearSolver, PcgStopsAtItsIterationLimit) {
  const SparseMatrix k = test::ddaSystemMatrix({.contrast = 1e6, .dynamic = false});
  const Eigen::VectorXd f = k * test::ddaSolution(static_cast<int>(k.rows()));
  const std::unique_ptr<LinearSolver> pcg =
      makeLinearSolver({.kind = SolverKind::Pcg, .tolerance = 1e-14, .max_iterations = 3});
  ASSERT_TRUE(pcg->factorize(k));
  pcg->solve(f);
  EXPECT_EQ(pcg->stats().iterations, 3);
  EXPECT_FALSE(pcg->stats().converged);
  EXPECT_GT(pcg->stats().residual, 1e-14);
}

TEST(BlockJacobiPreconditioner, IsTheExactInverseOfABlockDiagonalMatrix) {
  // Blocks that do not touch: K is block diagonal, M^-1 = K^-1 and CG converges in one step
  // (the preconditioned operator is the identity).
  const SparseMatrix k = test::ddaSystemMatrix({.nx = 1, .ny = 1, .nz = 1});
  SparseMatrix two_blocks(24, 24);
  std::vector<Eigen::Triplet<double>> t;
  for (int offset : {0, 12}) {
    for (int c = 0; c < 12; ++c) {
      for (SparseMatrix::InnerIterator it(k, c); it; ++it) {
        t.emplace_back(offset + it.row(), offset + c, (offset == 0 ? 1.0 : 7.0) * it.value());
      }
    }
  }
  two_blocks.setFromTriplets(t.begin(), t.end());
  const Eigen::VectorXd expected = test::ddaSolution(24);
  const std::unique_ptr<LinearSolver> pcg =
      makeLinearSolver({.kind = SolverKind::Pcg, .block_size = 12, .tolerance = 1e-12});
  ASSERT_TRUE(pcg->factorize(two_blocks));
  const Eigen::VectorXd x = pcg->solve(two_blocks * expected);
  EXPECT_EQ(pcg->stats().iterations, 1);
  // One block solve: error of a dense Cholesky solve of a 12 x 12 block (kappa ~ 1e4).
  EXPECT_LT(relativeError(x, expected), 1e-10);

  // A matrix order that the block size does not divide: the last block is smaller.
  BlockJacobiPreconditioner preconditioner;
  preconditioner.setBlockSize(5);
  preconditioner.compute(two_blocks);
  ASSERT_EQ(preconditioner.info(), Eigen::Success);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(24);
  const Eigen::VectorXd z = preconditioner.solve(ones);
  // The last block covers unknowns 20..23: z there solves K[20:24, 20:24] z = 1.
  const Eigen::MatrixXd last = Eigen::MatrixXd(two_blocks).bottomRightCorner(4, 4);
  EXPECT_LT((last * z.tail(4) - ones.tail(4)).norm(), 1e-9 * last.norm() * z.tail(4).norm());
}

}  // namespace
}  // namespace rockmass::dda3d
