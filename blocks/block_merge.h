// Gluing small blocks to their neighbours before a DDA. A DFN with dense short joints cuts
// a foundation into many blocks far smaller than the structure above them (the Xiangjiaba
// quick box: median 0.05 m3 under a 5e8 kg dam). They carry no load path of their own, yet
// they set the DDA's time step and contact count. Gluing each one to the neighbour it shares
// the most face area with keeps the mass, the volume and the geometry (the glued block is
// the union of the pieces, a non-convex block like any other), only the joint between them
// no longer opens.
#pragma once

#include "blocks/block_model.h"

namespace rockmass::blocks {

/// What mergeSmallBlocks did.
struct MergeReport {
  double min_volume = 0.0;  ///< m3, the threshold
  int blocks_before = 0;
  int blocks_after = 0;
  int merged = 0;              ///< cut blocks glued into another
  double merged_volume = 0.0;  ///< m3, their volume
  /// Blocks (or glued groups) still below min_volume: structures, and rock blocks with no
  /// rock neighbour of their material (with across_materials: no rock neighbour at all).
  int left_small = 0;
  /// Of `merged`, the cut blocks whose glued block is of another material (across_materials).
  int merged_across = 0;
  double merged_across_volume = 0.0;  ///< m3, their volume
};

/// Glues every rock block of `model` smaller than `min_volume` (m3) to the rock neighbour of
/// the same material with which it shares the largest face area (ties: the lower id),
/// smallest block first, and again while the glued block stays below the threshold. Without
/// `across_materials`, blocks of different materials are never glued (a rock block is not
/// glued to a fault slab); structures never are, nor is anything glued to them (a rock block
/// is not glued to the dam, even of the same material).
/// The result has the blocks renumbered 1..N in the order of their lowest original id, each
/// with the pieces of the blocks glued into it, the summed mass properties and the union of
/// the bounds; adjacency areas between glued groups are summed, adjacency inside a group
/// dropped. Volumes are conserved exactly (the pieces are kept as they are).
///
/// With `across_materials`, a small rock block with no neighbour of its own material (a
/// sliver of an interlayer slab between two joints, a rock chip wedged in a slab) is glued
/// to the rock neighbour of any material it shares the most face area with, and takes that
/// neighbour's material; structures are still never glued, nor glued to. Its faces keep
/// their joints; its mass changes by (density difference) x its volume.
MergeReport mergeSmallBlocks(BlockModel& model, double min_volume, bool across_materials = false);

}  // namespace rockmass::blocks
