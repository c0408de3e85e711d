// Fewer, larger convex pieces per block for the DDA. Both cutters give a block as a
// cluster of convex pieces, and a block glued from small blocks (block_merge.h) is the
// union of all their pieces: a Xiangjiaba quick-box block has 160 pieces on average. The
// DDA looks for contacts between pieces, so every piece boundary that reaches the block's
// surface adds vertices (contact points) and pieces (narrow-phase pairs) that carry nothing
// a larger piece would not. Two pieces of a block whose union is convex are replaced by the
// union: same volume, same surface, fewer pieces and fewer surface vertices.
#pragma once

#include <optional>

#include "blocks/block_model.h"

namespace rockmass::blocks {

/// What coarsenPieces did to one block or a model.
struct CoarseningReport {
  int pieces_before = 0;
  int pieces_after = 0;
  int vertices_before = 0;  ///< sum over the pieces
  int vertices_after = 0;
};

/// The union of two convex pieces when it is convex, else nothing. They must lie on the two
/// sides of a common face plane (faces with opposite normals and the same offset, within
/// `tolerance` m); the union is then convex exactly when every vertex of each lies on the
/// inner side of every other face plane of the other (within `tolerance`), and it is the
/// intersection of those planes. The result's vertices are vertices of the inputs, copied
/// bit for bit (so it stays conforming with its neighbours); each face keeps the provenance
/// of the input face it lies in, and the shared face disappears. Its volume equals the sum
/// of the two within 1e-9 relative, or no union is returned.
std::optional<Piece> convexUnion(const Piece& a, const Piece& b, double tolerance);

/// Merges pieces of `block` greedily (in piece order, deterministic) while some pair has a
/// convex union; mass properties, bounds and the block's surface do not change.
/// `tolerance` (m) is the distance below which a vertex counts as on a plane.
CoarseningReport coarsenPieces(Block& block, double tolerance);

/// coarsenPieces on every block of the model, in parallel (TBB); the same result as in
/// sequence. The tolerance is 1e-9 of the domain's diagonal.
CoarseningReport coarsenPieces(BlockModel& model);

}  // namespace rockmass::blocks
