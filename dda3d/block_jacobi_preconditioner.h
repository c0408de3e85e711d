// Block-Jacobi preconditioner for Eigen's iterative solvers: the inverse of each diagonal
// block (one DDA block's 6 or 12 unknowns), applied block by block. It captures what the
// scalar Jacobi preconditioner misses in a DDA matrix: the coupling between a block's
// translation, rotation and strain unknowns, whose scales differ by the block size squared.
#pragma once

#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace rockmass::dda3d {

/// Preconditioner M^-1 = blockdiag(K_00^-1, K_11^-1, ...) with blocks of block_size()
/// unknowns (the last block is smaller when the size does not divide the matrix order).
/// Meets Eigen's preconditioner interface (compute/analyzePattern/factorize/solve/info).
class BlockJacobiPreconditioner {
 public:
  BlockJacobiPreconditioner() = default;
  template <class Matrix>
  explicit BlockJacobiPreconditioner(const Matrix& k) {
    compute(k);
  }

  /// Unknowns per diagonal block (>= 1); set before compute().
  void setBlockSize(int size) { block_size_ = size; }
  /// Unknowns per diagonal block.
  int blockSize() const { return block_size_; }

  template <class Matrix>
  BlockJacobiPreconditioner& analyzePattern(const Matrix&) {
    return *this;
  }
  /// Factorizes every diagonal block (Cholesky); info() is NumericalIssue when one of them is
  /// not positive definite, which means the whole matrix is not either.
  template <class Matrix>
  BlockJacobiPreconditioner& factorize(const Matrix& k) {
    const Eigen::Index n = k.rows();
    factors_.clear();
    info_ = Eigen::Success;
    Eigen::MatrixXd block;
    for (Eigen::Index start = 0; start < n; start += block_size_) {
      const Eigen::Index size = std::min<Eigen::Index>(block_size_, n - start);
      block.setZero(size, size);
      for (Eigen::Index c = start; c < start + size; ++c) {
        for (typename Matrix::InnerIterator it(k, c); it; ++it) {
          if (it.row() >= start && it.row() < start + size) {
            block(it.row() - start, c - start) = it.value();
          }
        }
      }
      factors_.emplace_back(block);
      if (factors_.back().info() != Eigen::Success) info_ = Eigen::NumericalIssue;
    }
    return *this;
  }
  template <class Matrix>
  BlockJacobiPreconditioner& compute(const Matrix& k) {
    return factorize(k);
  }

  /// M^-1 b.
  template <class Rhs>
  Eigen::VectorXd solve(const Eigen::MatrixBase<Rhs>& b) const {
    Eigen::VectorXd x(b.size());
    Eigen::Index start = 0;
    for (const Eigen::LLT<Eigen::MatrixXd>& factor : factors_) {
      const Eigen::Index size = factor.rows();
      x.segment(start, size) = factor.solve(b.segment(start, size));
      start += size;
    }
    return x;
  }
  /// Success unless a diagonal block was not positive definite.
  Eigen::ComputationInfo info() const { return info_; }

 private:
  int block_size_ = 12;
  std::vector<Eigen::LLT<Eigen::MatrixXd>> factors_;
  Eigen::ComputationInfo info_ = Eigen::Success;
};

}  // namespace rockmass::dda3d
