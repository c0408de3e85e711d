// Contact detection: a sort-and-sweep broad phase over piece bounding boxes, then a narrow
// phase between convex pieces of different blocks that writes vertex-to-face and
// edge-to-edge contacts as point-to-face entries (formulation doc, "Point-to-face contact"
// and "Edge-to-edge contact").
#pragma once

#include <functional>
#include <utility>
#include <vector>

#include "dda3d/block_state.h"
#include "dda3d/contact.h"

namespace rockmass::dda3d {

/// A pair of pieces whose bounding boxes, grown by the detection range, overlap.
struct PiecePair {
  int block_a, piece_a, block_b, piece_b;
};

/// Sort-and-sweep over piece bounding boxes grown by `range` / 2 on every side, along the
/// axis where the box centres spread most. Pairs within one block and pairs of two fixed
/// blocks are skipped. O(n log n + pairs); the result is sorted, so deterministic.
std::vector<PiecePair> broadPhase(const std::vector<BlockState>& blocks, double range);

/// The face a vertex used last step against a piece: (face index, or -1 when none).
using PreviousFace =
    std::function<int(int block_i, int piece_i, int vertex, int block_j, int piece_j)>;

/// Narrow phase between two convex pieces of different blocks, both directions (vertices
/// of a against faces of b and the reverse) and the crossing edges. `range` (m) is the
/// largest gap still recorded; `previous_face` keeps the reference face of a vertex that
/// persists (the face it entered through). Appends to `out`; geometry fields are set,
/// states are not.
void narrowPhase(const std::vector<BlockState>& blocks, const PiecePair& pair, double range,
                 const PreviousFace& previous_face, std::vector<Contact>& out);

}  // namespace rockmass::dda3d
