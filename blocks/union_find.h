// Union-find (disjoint sets) over dense integer ids, shared by the cutters and the block
// assembly.
#pragma once

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace rockmass::blocks {

/// Disjoint sets with path halving. The smallest id of a set is its root, so roots do not
/// depend on the order of unions (deterministic block numbering relies on this).
class UnionFind {
 public:
  /// `n` singleton sets 0..n-1.
  explicit UnionFind(std::size_t n = 0) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  /// Adds a singleton set; returns its id.
  int add() {
    parent_.push_back(static_cast<int>(parent_.size()));
    return parent_.back();
  }
  /// Number of ids (sets made so far, joined or not).
  std::size_t size() const { return parent_.size(); }
  /// The root (smallest id) of the set holding `i`.
  int find(int i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  /// Joins the sets of `a` and `b`.
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<int> parent_;
};

}  // namespace rockmass::blocks
