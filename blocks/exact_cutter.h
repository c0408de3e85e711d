// The exact block cutter: exact-kernel convex splitting, region by region, with a CGAL Nef
// polyhedron referee.
//
// The domain's bounding box is split (kd-tree, longest axis first) into regions that each
// meet at most `max_discs_per_region` cutting discs; split planes never coincide with a disc
// or domain plane, so region faces are always fictitious. In every region a convex
// cell complex is built in exact arithmetic (CGAL Epeck; every vertex is the intersection of
// three planes with double coefficients, so numbers never grow): a cell is split by the full
// plane of every disc (an exactly planar polygon: its vertices are lifted onto the plane in
// rational arithmetic) and every domain-surface face (mesh domains) that meets it. Cells
// outside the rock are dropped. A face in a disc plane is a Disc face when the union of the
// discs in that plane covers it wholly (exact polygon clipping), else fictitious. Pieces
// glue into blocks across every shared face part that no disc covers - the fictitious-face
// rule of the fast cutter, decided exactly. Regions run in parallel (TBB). Structures stand
// on or beside the rock, as for the fast cutter: each is one block of its own material, not
// cut by discs and not cutting the rock.
//
// Why not CGAL's Nef differences and convex_decomposition_3 as the cutter: measured on this
// machine, one Nef difference costs about 10 ms even in a small region, so 100 discs of the
// benchmark cost 55-130 s however the regions are chosen, and convex_decomposition_3 of a
// cracked region took 28 s for 30 discs. The Nef polyhedron is kept as a referee
// (ExactCutOptions::nef_referee): it subtracts the discs from each region's rock, locates
// every piece in it, and checks that its volumes group the pieces exactly as the cutter did.
// CGAL stays inside blocks/exact/ (cut_parts.h names the parts).
#pragma once

#include <optional>
#include <string>

#include "blocks/block_model.h"
#include "blocks/cutter.h"
#include "blocks/piece_soundness.h"

namespace rockmass::blocks {

/// Settings of the exact cutter.
struct ExactCutOptions {
  /// Regions are split until each meets at most this many cutting discs (a region smaller
  /// than 1/64 of the domain's longest edge is not split further).
  int max_discs_per_region = 30;
  /// Worker threads for the regions; 0 = TBB's default (all cores).
  int threads = 0;
  /// Also sum the piece volumes in rational arithmetic and compare with the domain volume
  /// (forces the exact evaluation of every vertex; costs about as much as the cutting).
  bool check_exact_volume = false;
  /// Also build each region's rock minus its discs as a CGAL Nef polyhedron, locate every
  /// piece in it, and check that the Nef volumes give the same blocks (slow: about 10 ms per
  /// disc and region; for tests and audits).
  bool nef_referee = false;
};

/// What the exact cutter measured while it ran.
struct ExactCutReport {
  int regions = 0;            ///< regions of the kd split
  int disc_region_pairs = 0;  ///< Nef differences done (discs summed over regions)
  int pieces = 0;             ///< convex pieces in all blocks (slivers folded away)
  /// Slivers folded away and vertices merged (piece_soundness.h): the emitted pieces sum to
  /// the domain volume minus soundness.folded_volume, within soundness.volume_change.
  SoundnessReport soundness;
  double split_seconds = 0.0;    ///< exact splitting of cells, summed over regions (s)
  double nef_seconds = 0.0;      ///< Nef referee: construction and differences, summed (s)
  double extract_seconds = 0.0;  ///< classification, provenance, exact volumes, summed (s)
  double glue_seconds = 0.0;     ///< union of pieces into blocks, materials, adjacency (s)
  /// With check_exact_volume: the rational sum of the volumes of all exact rock cells (m3)
  /// as "p/q", slivers included (before soundPiece folds them away).
  std::string rock_volume_exact;
  /// With check_exact_volume: the domain volume as a rational "p/q" (m3).
  std::string domain_volume_exact;
  /// With check_exact_volume: whether the two rationals are equal.
  std::optional<bool> volume_conserved;
  /// With nef_referee: the number of blocks the Nef volumes give.
  std::optional<int> nef_blocks;
  /// With nef_referee: whether the Nef volumes group the pieces exactly as the cutter did.
  std::optional<bool> nef_agrees;
};

/// Cuts the rock of `input` into blocks with exact arithmetic (see the file comment).
/// The domain is input.domain_surface when it is not empty, else the union of
/// input.domain_pieces. Face provenance: Disc (disc id), Boundary (box face 0..5 for a box
/// domain, else the index of the first domain face in that plane), Structure (structure
/// index, on structure pieces only) or Fictitious (between pieces of one block). Block ids are 1..N
/// in blockOrder (block_assembly.h), the order the fast cutter uses too; materials by
/// SlabMaterials. Throws std::invalid_argument when the input has no domain or fewer than 3 disc
/// segments, or a structure overlaps the rock (checkStructuresOutsideRock).
BlockModel cutExact(const CutInput& input, const ExactCutOptions& options = {},
                    ExactCutReport* report = nullptr);

}  // namespace rockmass::blocks
