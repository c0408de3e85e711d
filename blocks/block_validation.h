// Checks of a block model with CGAL's Polygon_mesh_processing: every piece is a closed,
// outward-oriented surface and the pieces' volumes add up to the block's volume.
#pragma once

#include <string>
#include <vector>

#include "blocks/block_model.h"

namespace rockmass::blocks {

/// One problem found by validateBlocks.
struct BlockProblem {
  int block = 0;        ///< block id
  int piece = -1;       ///< piece index in the block (-1: the block as a whole)
  std::string message;  ///< what is wrong
};

/// Checks every piece of every block: closed (CGAL::is_closed), outward-oriented
/// (CGAL::Polygon_mesh_processing::is_outward_oriented), positive volume; and that the sum
/// of the pieces' volumes equals block.mass.volume within `relative_tolerance`. Returns the
/// problems found (empty when the model is valid).
std::vector<BlockProblem> validateBlocks(const BlockModel& model,
                                         double relative_tolerance = 1e-12);

}  // namespace rockmass::blocks
