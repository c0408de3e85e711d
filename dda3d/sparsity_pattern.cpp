#include "dda3d/sparsity_pattern.h"

#include <algorithm>

namespace rockmass::dda3d {

bool SparsityPattern::matches(const SparseMatrix& k) const {
  if (k.rows() != rows_ || k.cols() != rows_ ||
      k.nonZeros() != static_cast<Eigen::Index>(inner_.size())) {
    return false;
  }
  return std::equal(outer_.begin(), outer_.end(), k.outerIndexPtr()) &&
         std::equal(inner_.begin(), inner_.end(), k.innerIndexPtr());
}

void SparsityPattern::remember(const SparseMatrix& k) {
  rows_ = k.rows();
  outer_.assign(k.outerIndexPtr(), k.outerIndexPtr() + k.cols() + 1);
  inner_.assign(k.innerIndexPtr(), k.innerIndexPtr() + k.nonZeros());
}

void SparsityPattern::forget() {
  rows_ = -1;
  outer_.clear();
  inner_.clear();
}

}  // namespace rockmass::dda3d
