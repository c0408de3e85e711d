// The kd split both cutters share: regions of the domain halved across their longest axis,
// near the middle, at a level no disc or domain plane lies in, until each region meets few
// enough discs (docs/blocks.md, "Regions").
#pragma once

#include <functional>
#include <string>

#include "geometry/box.h"

namespace rockmass::blocks {

/// Candidate levels tried along an axis: the middle, then 1/67 of the extent below and above
/// it, 2/67 below and above, ... (kSplitAttempts in all).
inline constexpr int kSplitAttempts = 33;

/// The longest axis of `box` (0, 1, 2; the first of equal ones).
int longestAxis(const geometry::Box& box);

/// The first candidate level along `axis` of `box` for which `clashes(level)` is false: a
/// region face never lies in a disc or on the domain surface, so it is a fictitious face.
/// Throws std::runtime_error naming `cutter` when every candidate clashes.
double freeSplitLevel(const geometry::Box& box, int axis,
                      const std::function<bool(double)>& clashes, const std::string& cutter);

}  // namespace rockmass::blocks
