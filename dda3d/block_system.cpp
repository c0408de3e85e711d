#include "dda3d/block_system.h"

#include <Eigen/Cholesky>

#include <algorithm>

#include <tbb/parallel_for.h>

namespace rockmass::dda3d {

namespace {
long long pairKey(int i, int j) {
  return (static_cast<long long>(i) << 32) | static_cast<unsigned>(j);
}
}  // namespace

BlockSystem::BlockSystem(int block_count, int dofs)
    : block_count_(block_count),
      dofs_(dofs),
      diagonal_(static_cast<std::size_t>(block_count), BlockMatrix::Zero()),
      rhs_(static_cast<std::size_t>(block_count), BlockVector::Zero()) {
  setPairs({});
}

bool BlockSystem::setPairs(std::vector<std::pair<int, int>> pairs) {
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  if (pairs == pairs_ && matrix_.rows() == static_cast<Eigen::Index>(block_count_) * dofs_) {
    return false;
  }
  pairs_ = std::move(pairs);
  ++pairs_version_;
  off_diagonal_.assign(pairs_.size(), BlockMatrix::Zero());
  pair_index_.clear();
  columns_.assign(static_cast<std::size_t>(block_count_), {});
  for (int b = 0; b < block_count_; ++b)
    columns_[static_cast<std::size_t>(b)].push_back({b, -1, false});
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const auto [i, j] = pairs_[p];
    pair_index_[pairKey(i, j)] = static_cast<int>(p);
    // Column j holds K_ij (stored); column i holds K_ji = K_ij^T.
    columns_[static_cast<std::size_t>(j)].push_back({i, static_cast<int>(p), false});
    columns_[static_cast<std::size_t>(i)].push_back({j, static_cast<int>(p), true});
  }
  std::size_t nonzeros = 0;
  for (auto& column : columns_) {
    std::sort(column.begin(), column.end(),
              [](const Source& x, const Source& y) { return x.row_block < y.row_block; });
    nonzeros += column.size();
  }
  const Eigen::Index n = static_cast<Eigen::Index>(block_count_) * dofs_;
  matrix_ = SparseMatrix(n, n);
  matrix_.resizeNonZeros(static_cast<Eigen::Index>(nonzeros) * dofs_ * dofs_);
  int* outer = matrix_.outerIndexPtr();
  int* inner = matrix_.innerIndexPtr();
  int at = 0;
  for (int b = 0; b < block_count_; ++b) {
    for (int c = 0; c < dofs_; ++c) {
      outer[b * dofs_ + c] = at;
      for (const Source& s : columns_[static_cast<std::size_t>(b)]) {
        for (int r = 0; r < dofs_; ++r) inner[at++] = s.row_block * dofs_ + r;
      }
    }
  }
  outer[n] = at;
  return true;
}

void BlockSystem::clear() {
  tbb::parallel_for(std::size_t{0}, diagonal_.size(), [&](std::size_t b) {
    diagonal_[b].setZero();
    rhs_[b].setZero();
  });
  tbb::parallel_for(std::size_t{0}, off_diagonal_.size(),
                    [&](std::size_t p) { off_diagonal_[p].setZero(); });
}

BlockMatrix& BlockSystem::pairBlock(int i, int j, bool& transposed) {
  transposed = i > j;
  const auto found = pair_index_.find(transposed ? pairKey(j, i) : pairKey(i, j));
  return off_diagonal_[static_cast<std::size_t>(found->second)];
}

int BlockSystem::pairSlot(int i, int j, bool& transposed) const {
  transposed = i > j;
  if (i < 0 || j < 0 || i == j) return -1;
  const auto found = pair_index_.find(transposed ? pairKey(j, i) : pairKey(i, j));
  return found == pair_index_.end() ? -1 : found->second;
}

namespace {

/// m += k x y^T over the first `dofs` rows and columns (6: rigid blocks, whose strain rows and
/// columns the matrix never reads; 12: all). The same products entry by entry, so the used
/// entries are bitwise those of the full update.
void addOuter(BlockMatrix& m, double k, const BlockVector& x, const BlockVector& y, int dofs) {
  if (dofs == 6) {
    m.topLeftCorner<6, 6>().noalias() += k * x.head<6>() * y.head<6>().transpose();
  } else {
    m.noalias() += k * x * y.transpose();
  }
}

}  // namespace

void BlockSystem::addSpring(int i, const BlockVector& a, int j, const BlockVector& b, double k,
                            double d0) {
  addSpring(i, a, j, b, k, d0, Parts{});
}

void BlockSystem::addSpring(int i, const BlockVector& a, int j, const BlockVector& b, double k,
                            double d0, const Parts& parts) {
  // Both ends on one block (i == j): its owner's parts i and j are the same thread's.
  if (i >= 0 && parts.i) {
    addOuter(diagonal_[static_cast<std::size_t>(i)], k, a, a, dofs_);
    rhs_[static_cast<std::size_t>(i)] -= k * d0 * a;
  }
  if (j >= 0 && parts.j) {
    addOuter(diagonal_[static_cast<std::size_t>(j)], k, b, b, dofs_);
    rhs_[static_cast<std::size_t>(j)] -= k * d0 * b;
  }
  if (i >= 0 && j >= 0 && i != j && parts.pair) {
    bool transposed = parts.transposed;
    BlockMatrix& m = parts.pair_block ? *parts.pair_block : pairBlock(i, j, transposed);
    if (transposed) {
      addOuter(m, k, b, a, dofs_);  // stored K_ji
    } else {
      addOuter(m, k, a, b, dofs_);
    }
  } else if (i >= 0 && i == j && parts.i) {
    BlockMatrix& m = diagonal_[static_cast<std::size_t>(i)];
    if (dofs_ == 6) {
      m.topLeftCorner<6, 6>().noalias() +=
          k * (a.head<6>() * b.head<6>().transpose() + b.head<6>() * a.head<6>().transpose());
    } else {
      m.noalias() += k * (a * b.transpose() + b * a.transpose());
    }
  }
}

namespace {

/// T_l^T S T_r of rigid blocks' T = [I | R] (their first six columns), S symmetric, by its
/// 3 x 3 parts: [[S, S R_r], [R_l^T S, R_l^T S R_r]], given S R_l, S R_r and R_l^T S R_r.
void addRigidBlock(BlockMatrix& m, double sign, const Eigen::Matrix3d& s,
                   const Eigen::Matrix3d& sr_left, const Eigen::Matrix3d& sr_right,
                   const Eigen::Matrix3d& rsr) {
  m.topLeftCorner<3, 3>() += sign * s;
  m.block<3, 3>(0, 3) += sign * sr_right;
  m.block<3, 3>(3, 0) += sign * sr_left.transpose();
  m.block<3, 3>(3, 3) += sign * rsr;
}

}  // namespace

void BlockSystem::addPointSprings(int i, const DisplacementMatrix& ti, int j,
                                  const DisplacementMatrix& tj, const Eigen::Matrix3d& s,
                                  const geometry::Vec3& offsets, const Parts& parts) {
  const bool pair = i >= 0 && j >= 0 && parts.pair;
  const auto pairTarget = [&](bool& transposed) -> BlockMatrix& {
    transposed = parts.transposed;
    return parts.pair_block ? *parts.pair_block : pairBlock(i, j, transposed);
  };
  const DisplacementMatrix wi = s * ti, wj = s * tj;
  if (i >= 0 && parts.i) {
    diagonal_[static_cast<std::size_t>(i)].noalias() += ti.transpose() * wi;
    rhs_[static_cast<std::size_t>(i)].noalias() -= ti.transpose() * offsets;
  }
  if (j >= 0 && parts.j) {
    diagonal_[static_cast<std::size_t>(j)].noalias() += tj.transpose() * wj;
    rhs_[static_cast<std::size_t>(j)].noalias() += tj.transpose() * offsets;
  }
  if (pair) {
    bool transposed = false;
    BlockMatrix& m = pairTarget(transposed);
    if (transposed) {
      m.noalias() -= tj.transpose() * wi;
    } else {
      m.noalias() -= ti.transpose() * wj;
    }
  }
}

void BlockSystem::addRigidPointSprings(int i, const Eigen::Matrix3d& ri, int j,
                                       const Eigen::Matrix3d& rj, const Eigen::Matrix3d& s,
                                       const geometry::Vec3& offsets, const Parts& parts) {
  const Eigen::Matrix3d sri = s * ri, srj = s * rj;
  if (i >= 0 && parts.i) {
    addRigidBlock(diagonal_[static_cast<std::size_t>(i)], 1.0, s, sri, sri, ri.transpose() * sri);
    BlockVector& f = rhs_[static_cast<std::size_t>(i)];
    f.head<3>() -= offsets;
    f.segment<3>(3) -= ri.transpose() * offsets;
  }
  if (j >= 0 && parts.j) {
    addRigidBlock(diagonal_[static_cast<std::size_t>(j)], 1.0, s, srj, srj, rj.transpose() * srj);
    BlockVector& f = rhs_[static_cast<std::size_t>(j)];
    f.head<3>() += offsets;
    f.segment<3>(3) += rj.transpose() * offsets;
  }
  if (i >= 0 && j >= 0 && parts.pair) {
    bool transposed = parts.transposed;
    BlockMatrix& m = parts.pair_block ? *parts.pair_block : pairBlock(i, j, transposed);
    if (transposed) {
      addRigidBlock(m, -1.0, s, srj, sri, rj.transpose() * sri);  // stored K_ji = -T_j^T S T_i
    } else {
      addRigidBlock(m, -1.0, s, sri, srj, ri.transpose() * srj);
    }
  }
}

void BlockSystem::addRigidSpringSums(int i, int j, const RigidSpringSums& sums,
                                     const Parts& parts) {
  if (i >= 0 && parts.i) {
    addRigidBlock(diagonal_[static_cast<std::size_t>(i)], 1.0, sums.s, sums.sr_i, sums.sr_i,
                  sums.rsr_ii);
    BlockVector& f = rhs_[static_cast<std::size_t>(i)];
    f.head<3>() -= sums.offsets;
    f.segment<3>(3) -= sums.moment_i;
  }
  if (j >= 0 && parts.j) {
    addRigidBlock(diagonal_[static_cast<std::size_t>(j)], 1.0, sums.s, sums.sr_j, sums.sr_j,
                  sums.rsr_jj);
    BlockVector& f = rhs_[static_cast<std::size_t>(j)];
    f.head<3>() += sums.offsets;
    f.segment<3>(3) += sums.moment_j;
  }
  if (i >= 0 && j >= 0 && parts.pair) {
    bool transposed = parts.transposed;
    BlockMatrix& m = parts.pair_block ? *parts.pair_block : pairBlock(i, j, transposed);
    if (transposed) {
      // stored K_ji = -sum T_j^T S T_i: [[S, S R_i], [R_j^T S, R_j^T S R_i]]
      addRigidBlock(m, -1.0, sums.s, sums.sr_j, sums.sr_i, sums.rsr_ij.transpose());
    } else {
      addRigidBlock(m, -1.0, sums.s, sums.sr_i, sums.sr_j, sums.rsr_ij);
    }
  }
}

const SparseMatrix& BlockSystem::matrix() {
  double* values = matrix_.valuePtr();
  const int* outer = matrix_.outerIndexPtr();
  // Each block's columns in parallel: they start where the pattern says (setPairs).
  tbb::parallel_for(0, block_count_, [&](int b) {
    int at = outer[b * dofs_];
    for (int c = 0; c < dofs_; ++c) {
      for (const Source& s : columns_[static_cast<std::size_t>(b)]) {
        if (s.pair < 0) {
          // The lower triangle mirrored: K_ii's sums of T^T S T are symmetric but for their
          // round-off, and both triangles of K must be equal (the solvers read either).
          const BlockMatrix& m = diagonal_[static_cast<std::size_t>(b)];
          for (int r = 0; r < dofs_; ++r) values[at++] = r >= c ? m(r, c) : m(c, r);
        } else {
          const BlockMatrix& m = off_diagonal_[static_cast<std::size_t>(s.pair)];
          if (s.transposed) {
            for (int r = 0; r < dofs_; ++r) values[at++] = m(c, r);
          } else {
            for (int r = 0; r < dofs_; ++r) values[at++] = m(r, c);
          }
        }
      }
    }
  });
  return matrix_;
}

int BlockSystem::firstIndefiniteDiagonal() const {
  for (int b = 0; b < block_count_; ++b) {
    const Eigen::MatrixXd m = diagonal_[static_cast<std::size_t>(b)].topLeftCorner(dofs_, dofs_);
    const Eigen::LLT<Eigen::MatrixXd> llt(m);
    if (llt.info() != Eigen::Success) return b;
  }
  return -1;
}

Eigen::VectorXd BlockSystem::rhs() const {
  Eigen::VectorXd f(static_cast<Eigen::Index>(block_count_) * dofs_);
  for (int b = 0; b < block_count_; ++b) {
    f.segment(static_cast<Eigen::Index>(b) * dofs_, dofs_) =
        rhs_[static_cast<std::size_t>(b)].head(dofs_);
  }
  return f;
}

BlockVector BlockSystem::unknowns(const Eigen::VectorXd& x, int i) const {
  BlockVector d = BlockVector::Zero();
  d.head(dofs_) = x.segment(static_cast<Eigen::Index>(i) * dofs_, dofs_);
  return d;
}

}  // namespace rockmass::dda3d
