// What a cut will make, estimated before the cut: a budget checked by the commands, so that a
// network that would cut into 1e8 blocks is refused at once instead of eating the machine.
#pragma once
#include <cstdint>
#include <vector>

#include "blocks/cutter.h"

namespace rockmass::blocks {

/// The arrangement of the cutting discs inside the domain, counted (or counted until the
/// estimate passed the limit).
struct BlockEstimate {
  std::int64_t discs = 0;          ///< cutting discs that reach into the domain
  std::int64_t intersections = 0;  ///< pairs of them that cross inside the domain
  std::int64_t vertices = 0;       ///< points where three of them meet inside the domain
  /// The cells of an arrangement of planes with these counts, 1 + discs + intersections +
  /// vertices (each k-flat inside a convex region adds one cell; Zaslavsky's count for
  /// planes in general position). Finite discs make fewer blocks: an upper estimate (the
  /// Xiangjiaba scene: 1.56e5 for 42 786 blocks, cut into 457 305 convex pieces).
  double blocks = 0.0;
  bool stopped = false;  ///< counting stopped once `blocks` passed the limit (a lower bound)
  /// Per set of the network: intersections its discs take part in (the set that drives
  /// the count is the one with the most).
  std::vector<std::int64_t> set_intersections;
};

/// Counts the arrangement of `input`'s cutting discs inside its domain box, stopping as soon
/// as the estimate of blocks exceeds `limit`. Cost: a box-intersection pass over the discs
/// and, per disc, a sweep over the segments other discs cut on it.
BlockEstimate estimateBlocks(const CutInput& input, double limit);

}  // namespace rockmass::blocks
