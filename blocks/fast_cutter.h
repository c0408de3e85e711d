// The fast cutter: convex splitting in floating point (see docs/blocks.md).
//
// Every piece stays convex. A disc polygon that crosses a piece first peels off, by the
// planes through its edges perpendicular to the disc, the parts of the piece whose section
// lies outside the polygon (new faces Fictitious); the remaining core, whose section lies
// wholly inside the polygon, is split by the disc's plane (new faces Disc). Pieces glued
// across fictitious faces form one block, so cracks that end inside the rock leave it whole
// and non-convex blocks come out as clusters of convex pieces.
#pragma once

#include "blocks/block_assembly.h"
#include "blocks/block_model.h"
#include "blocks/cutter.h"

namespace rockmass::blocks {

/// Counters of one fast cut.
struct FastCutReport {
  int cutting_polygons = 0;       ///< convex polygons cut (a non-convex disc gives several)
  long long piece_tests = 0;      ///< (polygon, piece) pairs whose bounding boxes met
  long long splits = 0;           ///< plane splits made
  int pieces = 0;                 ///< convex rock pieces at the end
  int inconsistent_contacts = 0;  ///< see AssemblyReport (0 in a sound cut)
  double cut_seconds = 0.0;       ///< wall time of the splitting
  double assemble_seconds = 0.0;  ///< wall time of contacts, gluing, materials, adjacency
};

/// Cuts the domain pieces of `input` by every disc of input.network with cuts == true, in
/// id order, each as its disc_segments-gon (Disc::outline; FAB polygons projected onto
/// their plane, non-convex ones split into convex parts), and assembles the blocks
/// (assembleBlocks). Deterministic. Throws std::invalid_argument for an input it cannot cut
/// (no domain piece, a null network, disc_segments < 3, a structure that overlaps the rock).
BlockModel cutFast(const CutInput& input, FastCutReport* report = nullptr);

}  // namespace rockmass::blocks
