// The global DDA system K D = F in 12 x 12 (or 6 x 6) blocks: one diagonal block per movable
// block and one off-diagonal block per pair of blocks coupled by contacts or bolts. The
// sparse pattern depends only on the set of coupled pairs, so the solver's symbolic
// analysis is reused while contacts keep touching the same blocks.
#pragma once

#include <unordered_map>
#include <utility>
#include <vector>

#include "dda3d/block_state.h"
#include "dda3d/linear_solver.h"

namespace rockmass::dda3d {

/// Block-structured assembly of K (both triangles) and F.
class BlockSystem {
 public:
  /// `block_count` movable blocks of `dofs` unknowns each (6 or 12).
  BlockSystem(int block_count, int dofs);

  /// Sets the coupled pairs (movable indices, a < b, any order, duplicates allowed).
  /// Rebuilds the sparse pattern only when the set changed; returns true if it did.
  bool setPairs(std::vector<std::pair<int, int>> pairs);
  /// Zeroes all values, keeps the pattern.
  void clear();

  /// Adds the energy 1/2 k (d0 + a^T D_i + b^T D_j)^2; i or j = -1 is a fixed body.
  void addSpring(int i, const BlockVector& a, int j, const BlockVector& b, double k, double d0);
  /// Which of a spring's terms addSpring(..., Parts) adds: K_ii and F_i, K_jj and F_j, the
  /// coupling K_ij. Threads that own disjoint sets of blocks and pairs may then add the terms
  /// of one spring each its own, in parallel, every sum in the serial order.
  struct Parts {
    bool i = true, j = true, pair = true;
    /// K_ij's stored block when already found (withPair), else looked up per spring.
    BlockMatrix* pair_block = nullptr;
    bool transposed = false;  ///< pair_block stores K_ji
  };
  /// `parts` with K_ij's block found once, for several springs between blocks i and j.
  Parts withPair(int i, int j, Parts parts) {
    if (parts.pair && i >= 0 && j >= 0 && i != j) {
      parts.pair_block = &pairBlock(i, j, parts.transposed);
    }
    return parts;
  }
  /// addSpring's terms that `parts` names, each added exactly as addSpring adds it.
  void addSpring(int i, const BlockVector& a, int j, const BlockVector& b, double k, double d0,
                 const Parts& parts);
  /// K_ii += m.
  void addDiagonal(int i, const BlockMatrix& m) { diagonal_[static_cast<std::size_t>(i)] += m; }
  /// F_i += f (no-op for i = -1).
  void addForce(int i, const BlockVector& f) {
    if (i >= 0) rhs_[static_cast<std::size_t>(i)] += f;
  }

  /// K as a sparse matrix (values refreshed from the blocks, pattern kept).
  const SparseMatrix& matrix();
  /// F stacked.
  Eigen::VectorXd rhs() const;
  /// Unknowns of movable block i from a stacked solution (zero-padded to 12).
  BlockVector unknowns(const Eigen::VectorXd& x, int i) const;
  /// Index of the first movable block whose diagonal block K_ii is not positive definite,
  /// or -1 (a diagnostic for a failed factorization).
  int firstIndefiniteDiagonal() const;
  /// K_ii of movable block i.
  const BlockMatrix& diagonalBlock(int i) const { return diagonal_[static_cast<std::size_t>(i)]; }
  /// Number of coupled pairs (off-diagonal blocks).
  std::size_t pairCount() const { return pairs_.size(); }

 private:
  BlockMatrix& pairBlock(int i, int j, bool& transposed);

  int block_count_;
  int dofs_;
  std::vector<BlockMatrix> diagonal_;
  std::vector<BlockVector> rhs_;
  std::vector<std::pair<int, int>> pairs_;  // sorted, unique, first < second
  std::vector<BlockMatrix> off_diagonal_;   // K_{first, second}
  std::unordered_map<long long, int> pair_index_;
  /// Per block column: row blocks in ascending order, each with its source (-1: diagonal,
  /// else pair index) and whether that source is stored transposed.
  struct Source {
    int row_block;
    int pair;
    bool transposed;
  };
  std::vector<std::vector<Source>> columns_;
  SparseMatrix matrix_;
};

}  // namespace rockmass::dda3d
