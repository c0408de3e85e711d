// Checks of a block model with CGAL's Polygon_mesh_processing: every piece is a closed,
// outward-oriented surface and the pieces' volumes add up to the block's volume.
#pragma once

#include <string>
#include <vector>

#include "blocks/block_model.h"
#include "blocks/piece_soundness.h"

namespace rockmass::blocks {

/// One problem found by validateBlocks.
struct BlockProblem {
  int block = 0;        ///< block id
  int piece = -1;       ///< piece index in the block (-1: the block as a whole)
  std::string message;  ///< what is wrong
};

/// Checks every piece of every block: closed (CGAL::is_closed), outward-oriented
/// (CGAL::Polygon_mesh_processing::is_outward_oriented), positive volume; and that the sum
/// of the pieces' volumes and block.folded_volume equals block.mass.volume within
/// `relative_tolerance`. Returns the
/// problems found (empty when the model is valid).
std::vector<BlockProblem> validateBlocks(const BlockModel& model,
                                         double relative_tolerance = 1e-12);

/// The smallest features of the pieces of a model: what decides whether the DDA's contact
/// detection and mass matrices can work with it. Each minimum comes with the block id and
/// piece index where it occurs (0 / -1 when the model has no piece).
struct PieceMeasures {
  int pieces = 0;                    ///< pieces of all blocks
  double min_volume = 0.0;           ///< smallest piece volume (m3)
  int min_volume_block = 0;          ///< its block id
  int min_volume_piece = -1;         ///< its piece index
  double min_edge = 0.0;             ///< shortest face edge of any piece (m)
  int min_edge_block = 0;            ///< its block id
  int min_edge_piece = -1;           ///< its piece index
  double min_vertex_distance = 0.0;  ///< closest two vertices of one piece (m)
  int min_vertex_distance_block = 0;
  int min_vertex_distance_piece = -1;
  double min_face_area = 0.0;  ///< smallest face area of any piece (m2)
  int min_face_area_block = 0;
  int min_face_area_piece = -1;
};

/// Measures every piece of every block (exhaustively: all vertex pairs of each piece).
PieceMeasures measurePieces(const BlockModel& model);

/// The degenerate pieces of a model: a piece with volume below tolerances.volume, two
/// vertices closer than tolerances.distance, or a face of area below tolerances.area. Each
/// gives one problem naming the measure and its value. Empty for a sound model (what
/// soundPiece makes of every piece the cutters emit).
std::vector<BlockProblem> findDegeneratePieces(const BlockModel& model,
                                               const SoundnessTolerances& tolerances);

}  // namespace rockmass::blocks
