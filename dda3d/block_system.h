// The global DDA system K D = F in 12 x 12 (or 6 x 6) blocks: one diagonal block per movable
// block and one off-diagonal block per pair of blocks coupled by contacts or bolts. The
// sparse pattern depends only on the set of coupled pairs, so the solver's symbolic
// analysis is reused while contacts keep touching the same blocks.
#pragma once

#include <unordered_map>
#include <utility>
#include <vector>

#include "dda3d/block_state.h"
#include "dda3d/displacement_field.h"
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
    /// K_ij's stored block when already found (withSlot), else looked up per spring.
    BlockMatrix* pair_block = nullptr;
    bool transposed = false;  ///< pair_block stores K_ji
  };
  /// Where K_ij is stored: the index of its block among the coupled pairs, negative when i or j
  /// is fixed, i == j, or the pair is not coupled; `transposed` when the block stores K_ji.
  /// Valid until the pairs change (pairsVersion()).
  int pairSlot(int i, int j, bool& transposed) const;
  /// `parts` with K_ij's block taken from its slot (pairSlot).
  Parts withSlot(int slot, bool transposed, Parts parts) {
    if (parts.pair && slot >= 0) {
      parts.pair_block = &off_diagonal_[static_cast<std::size_t>(slot)];
      parts.transposed = transposed;
    }
    return parts;
  }
  /// Bumped each time setPairs changes the coupled pairs.
  int pairsVersion() const { return pairs_version_; }
  /// addSpring's terms that `parts` names, each added exactly as addSpring adds it.
  void addSpring(int i, const BlockVector& a, int j, const BlockVector& b, double k, double d0,
                 const Parts& parts);
  /// The springs of one contact point at once: k_m along orthonormal directions e_m with
  /// offsets d_m, passed as S = sum k_m e_m e_m^T and s = sum k_m d_m e_m. The energy
  /// 1/2 sum k_m (d_m + e_m^T (T_i D_i - T_j D_j))^2 adds K_ii += T_i^T S T_i, F_i -= T_i^T s,
  /// K_jj += T_j^T S T_j, F_j += T_j^T s, K_ij -= T_i^T S T_j: the sum of addSpring over the
  /// springs in one product (a locked contact's three springs in a third of the arithmetic).
  /// i or j = -1 is a fixed body; i == j (both ends on one block) is not taken here.
  /// Deformable blocks (12 unknowns); rigid ones take addRigidPointSprings.
  void addPointSprings(int i, const DisplacementMatrix& ti, int j, const DisplacementMatrix& tj,
                       const Eigen::Matrix3d& s, const geometry::Vec3& offsets, const Parts& parts);
  /// addPointSprings of rigid blocks (6 unknowns each), from the rotation columns of T_i and
  /// T_j (rotationColumns; their translation columns are the identity).
  void addRigidPointSprings(int i, const Eigen::Matrix3d& ri, int j, const Eigen::Matrix3d& rj,
                            const Eigen::Matrix3d& s, const geometry::Vec3& offsets,
                            const Parts& parts);
  /// The springs of several points between one pair of rigid blocks, summed before they are
  /// added to K and F (addRigidSpringSums): for each point, S and s as addPointSprings takes
  /// them and the rotation columns R_i, R_j of its arms (rotationColumns). The blocks' terms
  /// are linear in S, so their sums are the sums of the points' terms (addRigidPointSprings of
  /// each), in another order of the additions.
  struct RigidSpringSums {
    Eigen::Matrix3d s = Eigen::Matrix3d::Zero();       ///< sum of S
    Eigen::Matrix3d sr_i = Eigen::Matrix3d::Zero();    ///< sum of S R_i
    Eigen::Matrix3d sr_j = Eigen::Matrix3d::Zero();    ///< sum of S R_j
    Eigen::Matrix3d rsr_ii = Eigen::Matrix3d::Zero();  ///< sum of R_i^T S R_i
    Eigen::Matrix3d rsr_jj = Eigen::Matrix3d::Zero();  ///< sum of R_j^T S R_j
    Eigen::Matrix3d rsr_ij = Eigen::Matrix3d::Zero();  ///< sum of R_i^T S R_j
    geometry::Vec3 offsets = geometry::Vec3::Zero();   ///< sum of s
    geometry::Vec3 moment_i = geometry::Vec3::Zero();  ///< sum of R_i^T s
    geometry::Vec3 moment_j = geometry::Vec3::Zero();  ///< sum of R_j^T s
    /// Which sums are kept: K_ii and F_i's, K_jj and F_j's, K_ij's (the others stay zero).
    bool with_i = true, with_j = true, with_pair = true;

    void add(const Eigen::Matrix3d& ri, const Eigen::Matrix3d& rj, const Eigen::Matrix3d& springs,
             const geometry::Vec3& spring_offsets) {
      s += springs;
      offsets += spring_offsets;
      if (with_i || with_pair) {
        const Eigen::Matrix3d sri = springs * ri;
        sr_i += sri;
        if (with_i) {
          rsr_ii.noalias() += ri.transpose() * sri;
          moment_i.noalias() += ri.transpose() * spring_offsets;
        }
      }
      if (with_j || with_pair) {
        const Eigen::Matrix3d srj = springs * rj;
        sr_j += srj;
        if (with_j) {
          rsr_jj.noalias() += rj.transpose() * srj;
          moment_j.noalias() += rj.transpose() * spring_offsets;
        }
        if (with_pair) rsr_ij.noalias() += ri.transpose() * srj;
      }
    }
  };
  /// Adds the sums' terms that `parts` names, as addRigidPointSprings adds one point's; the
  /// sums must have been kept for them (RigidSpringSums::with_i, with_j, with_pair).
  void addRigidSpringSums(int i, int j, const RigidSpringSums& sums, const Parts& parts);
  /// K_ii += m.
  void addDiagonal(int i, const BlockMatrix& m) { diagonal_[static_cast<std::size_t>(i)] += m; }
  /// F_i += f (no-op for i = -1).
  void addForce(int i, const BlockVector& f) {
    if (i >= 0) rhs_[static_cast<std::size_t>(i)] += f;
  }

  /// K as a sparse matrix (values refreshed from the blocks, pattern kept), its two
  /// triangles equal: each diagonal block's upper triangle is its lower one.
  const SparseMatrix& matrix();
  /// K as the last matrix() filled it (the blocks' terms added since are not in it).
  const SparseMatrix& filledMatrix() const { return matrix_; }
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
  int pairs_version_ = 0;
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
