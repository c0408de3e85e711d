// Broad phase of the contact detection: which pieces of different blocks can touch within
// the coming step. Box intersection over piece bounding boxes (CGAL::box_intersection_d, a
// segment tree with streaming: O(n log^3 n + pairs) in the worst case, close to
// O(n log n + pairs) for a pile), never all pairs.
#pragma once

#include <vector>

#include "geometry/box.h"

namespace rockmass::dda3d {

/// A pair of pieces of two different blocks whose grown bounding boxes overlap;
/// (block_a, piece_a) < (block_b, piece_b).
struct PiecePair {
  int block_a, piece_a, block_b, piece_b;
  bool operator==(const PiecePair&) const = default;
};

/// The bounding box of one piece, already grown by how far its block may move in the step.
struct PieceBox {
  geometry::Box box;   ///< m
  int block = -1;      ///< block index
  int piece = -1;      ///< piece index in the block
  bool fixed = false;  ///< the block is fixed (pairs of two fixed blocks are skipped)
};

/// Every pair of boxes that overlap as closed sets (touching and zero-width boxes count),
/// except pairs within one block and pairs of two fixed blocks. Sorted by (block_a,
/// piece_a, block_b, piece_b), so the result does not depend on the order of `boxes`.
/// Movable boxes are intersected with each other (self intersection) and with the fixed
/// ones (bipartite), so pairs of fixed boxes are never generated.
std::vector<PiecePair> overlappingPieces(const std::vector<PieceBox>& boxes);

}  // namespace rockmass::dda3d
