// The only translation unit of dda3d that instantiates CGAL (box_intersection_d).
#include "dda3d/broad_phase.h"

#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cstddef>
#include <tuple>

namespace rockmass::dda3d {

namespace {

/// A box handed to CGAL: an index into the caller's boxes.
struct IndexedBox {
  const PieceBox* box;
  std::size_t index;
};

/// CGAL's BoxIntersectionTraits_d for IndexedBox; the id (unique per box, shared by the
/// copies CGAL makes) is the index.
struct IndexedBoxTraits {
  using Box_parameter = const IndexedBox&;
  using NT = double;
  using ID = std::size_t;
  static double min_coord(Box_parameter b, int dim) { return b.box->box.min[dim]; }
  static double max_coord(Box_parameter b, int dim) { return b.box->box.max[dim]; }
  static std::size_t id(Box_parameter b) { return b.index; }
  static int dimension() { return 3; }
};

/// Below this many boxes CGAL scans all pairs of a sub-range (its default).
constexpr std::ptrdiff_t kCutoff = 10;

}  // namespace

std::vector<PiecePair> overlappingPieces(const std::vector<PieceBox>& boxes) {
  std::vector<IndexedBox> movable, fixed;
  for (std::size_t k = 0; k < boxes.size(); ++k) {
    (boxes[k].fixed ? fixed : movable).push_back({&boxes[k], k});
  }
  std::vector<PiecePair> pairs;
  const auto report = [&pairs](const IndexedBox& x, const IndexedBox& y) {
    if (x.box->block == y.box->block) return;
    PiecePair pair{x.box->block, x.box->piece, y.box->block, y.box->piece};
    if (std::tie(pair.block_b, pair.piece_b) < std::tie(pair.block_a, pair.piece_a)) {
      pair = {y.box->block, y.box->piece, x.box->block, x.box->piece};
    }
    pairs.push_back(pair);
  };
  CGAL::box_self_intersection_d(movable.begin(), movable.end(), report, IndexedBoxTraits(), kCutoff,
                                CGAL::Box_intersection_d::CLOSED);
  if (!movable.empty() && !fixed.empty()) {
    CGAL::box_intersection_d(movable.begin(), movable.end(), fixed.begin(), fixed.end(), report,
                             IndexedBoxTraits(), kCutoff, CGAL::Box_intersection_d::CLOSED,
                             CGAL::Box_intersection_d::BIPARTITE);
  }
  std::sort(pairs.begin(), pairs.end(), [](const PiecePair& x, const PiecePair& y) {
    return std::tie(x.block_a, x.piece_a, x.block_b, x.piece_b) <
           std::tie(y.block_a, y.piece_a, y.block_b, y.piece_b);
  });
  return pairs;
}

}  // namespace rockmass::dda3d
