// The fast cutter: convex splitting in floating point (see docs/blocks.md).
//
// Default (FastStrategy::FullPlanes): the exact cutter's strategy in double precision (kd
// regions, full-plane splits of the cells a disc meets, coverage of each face and each
// shared face part by the discs of its plane decides crack or glue). The original
// design stays selectable (FastStrategy::EdgePlanes):
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

/// How the fast cutter makes every face decidable.
enum class FastStrategy {
  /// The exact cutter's strategy in floating point: the domain is split into kd regions of
  /// at most FastCutOptions::max_discs_per_region discs; in each region every convex cell a
  /// disc polygon meets is split by the disc's full plane; afterwards each face in a disc
  /// plane is classified by how the discs of that plane cover it (wholly: Disc; partly or
  /// not: Fictitious), and two touching pieces glue unless the discs wholly cover the part
  /// of the plane they share. About 4x fewer pieces than EdgePlanes.
  FullPlanes,
  /// Issue 3's design: the parts of a piece whose section lies outside the polygon are
  /// peeled off by the planes through the polygon's edges, perpendicular to the disc, so
  /// that every face is wholly inside or wholly outside its disc.
  EdgePlanes,
};

/// Settings of the fast cutter.
struct FastCutOptions {
  FastStrategy strategy = FastStrategy::FullPlanes;  ///< see FastStrategy
  /// FullPlanes: regions are split (longest axis) until each meets at most this many
  /// cutting polygons (a region smaller than 1/64 of the domain's longest edge is not
  /// split further).
  int max_discs_per_region = 30;
  /// FullPlanes: follow, through every split, which faces of a region's cells may touch
  /// (the two new faces touch each other; a split face's neighbours go to the half or halves
  /// they reach), and test only those pairs for contacts, plus a geometric search among the
  /// faces in the planes between regions. False: search every plane geometrically
  /// (findContactsByPlane over all faces; the method before tracking, kept for comparison).
  /// Both give the same blocks and adjacency (tested).
  bool track_contacts = true;
};

/// Counters of one fast cut.
struct FastCutReport {
  int cutting_polygons = 0;       ///< convex polygons cut (a non-convex disc gives several)
  long long piece_tests = 0;      ///< (polygon, piece) pairs whose bounding boxes met
  long long splits = 0;           ///< plane splits made
  int pieces = 0;                 ///< convex rock pieces at the end (slivers folded away)
  SoundnessReport soundness;      ///< slivers folded, vertices merged (piece_soundness.h)
  int regions = 0;                ///< kd regions (FullPlanes; 1 for EdgePlanes)
  int inconsistent_contacts = 0;  ///< see AssemblyReport (0 in a sound cut)
  double cut_seconds = 0.0;       ///< wall time of the splitting
  double assemble_seconds = 0.0;  ///< wall time of contacts, gluing, materials, adjacency
  double coverage_seconds = 0.0;  ///< FullPlanes: part of assemble_seconds spent classifying
                                  ///< faces in disc planes (Cover)
  double contact_seconds = 0.0;   ///< part of assemble_seconds spent finding and deciding
                                  ///< contacts (the rest: assembleBlocks)
};

/// Cuts the domain pieces of `input` by every disc of input.network with cuts == true, in
/// id order, each as its disc_segments-gon (Disc::outline; FAB polygons projected onto
/// their plane, non-convex ones split into convex parts; discs in one plane, within the
/// tolerance, are cut in the plane of the first), by `options.strategy`, and assembles the blocks
/// (assembleBlocks). Deterministic. Throws std::invalid_argument for an input it cannot cut
/// (no domain piece, a null network, disc_segments < 3, a structure that overlaps the rock).
BlockModel cutFast(const CutInput& input, const FastCutOptions& options,
                   FastCutReport* report = nullptr);

/// cutFast with the default options (FastStrategy::FullPlanes).
BlockModel cutFast(const CutInput& input, FastCutReport* report = nullptr);

}  // namespace rockmass::blocks
