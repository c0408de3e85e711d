// Remembers the sparsity pattern of the last matrix a direct solver analysed, so that the
// symbolic analysis (fill-reducing ordering, elimination tree, supernodes) is redone only
// when the pattern changes. Internal to the solver backends.
#pragma once

#include <vector>

#include "dda3d/linear_solver.h"

namespace rockmass::dda3d {

/// The (outer, inner) index arrays of a compressed column-major matrix.
class SparsityPattern {
 public:
  /// True when `k` has exactly the remembered pattern (same size, same nonzero positions).
  bool matches(const SparseMatrix& k) const;
  /// Remembers the pattern of `k` (which must be compressed).
  void remember(const SparseMatrix& k);
  /// Forgets the pattern, so that the next matches() is false.
  void forget();

 private:
  Eigen::Index rows_ = -1;
  std::vector<int> outer_, inner_;
};

}  // namespace rockmass::dda3d
