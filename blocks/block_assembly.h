// From convex pieces to blocks: what both cutters share once the rock is cut. Face labels
// of the input solids, tolerances, gluing across fictitious faces, materials (slabs),
// deterministic block order and the adjacency between blocks.
#pragma once

#include <vector>

#include "blocks/block_model.h"
#include "blocks/cutter.h"
#include "blocks/piece_contacts.h"
#include "blocks/piece_soundness.h"

namespace rockmass::blocks {

/// Geometric tolerances of the cutters, relative to the domain size.
struct CutTolerances {
  double distance = 0.0;  ///< m: a point this close to a plane lies on it
  double area = 0.0;      ///< m2: an overlap or section this small is a mere touch
};

/// distance = 1e-11 x the domain diagonal (100x above the round-off of coordinates built by
/// a few hundred successive cuts, 1e-4x below the thinnest feature the tests resolve: two
/// discs 1e-9 m apart in a 10 m domain); area = distance x diagonal.
CutTolerances cutTolerances(const geometry::Box& domain);

/// The domain's convex pieces with face provenance: Boundary (id = running face index over
/// the pieces, so a box domain's faces are 0..5 in boxPolyhedron order), or Fictitious for a
/// face wholly covered by a face of another domain piece (an internal face of the convex
/// decomposition of a mesh domain).
std::vector<Piece> labelDomainPieces(const CutInput& input, const CutTolerances& tolerances);

/// The pieces of structure `structure` of `input` with face provenance: Structure (id =
/// the structure index), or Fictitious for a face wholly covered by a face of another piece
/// of the same structure (an internal face of its convex decomposition).
std::vector<Piece> labelStructurePieces(const CutInput& input, std::size_t structure,
                                        const CutTolerances& tolerances);

/// Throws std::invalid_argument when a structure piece overlaps a domain piece by more than
/// a sliver (1e-16 of the domain diagonal cubed): structures stand on or beside the rock,
/// both cutters leave them whole and the rock uncut by them.
void checkStructuresOutsideRock(const CutInput& input, const CutTolerances& tolerances);

/// Appends to `contacts` the contacts of the structure pieces (all[rock_count..]) with each
/// other and with the rock pieces (all[..rock_count]) whose bounding boxes come near a
/// structure (findPieceContacts). Rock-rock contacts are not searched.
void appendStructureContacts(const std::vector<Piece>& all, std::size_t rock_count,
                             const CutTolerances& tolerances, std::vector<PieceContact>& contacts);

/// The order in which both cutters number their blocks 1..N: by centroid x, then y, then z,
/// each rounded to 1e-9 of the domain diagonal, then by volume rounded to 1e-12 of the
/// domain volume (a ring block and the core it surrounds share a centroid), then by the
/// cutter's own order. Rounding makes the two cutters' round-off irrelevant: blocks whose
/// centroids differ by less than the rounding step are ordered by their volumes.
/// Returns the indices of `blocks` in id order.
std::vector<int> blockOrder(const std::vector<Block>& blocks, const geometry::Box& domain);

/// What the assembly computes of a rock piece as the cutter gives it.
struct PieceFacts {
  geometry::MassProperties mass;  ///< geometry::massProperties of its shape
  geometry::Box box;              ///< geometry::bounds of its shape
  bool close_vertices = false;    ///< hasCloseVertices with soundnessTolerances(domain box)
};

/// What the assembly noticed.
struct AssemblyReport {
  int inconsistent_contacts = 0;  ///< contacts fictitious on one side only (treated as real)
  SoundnessReport soundness;      ///< slivers folded, vertices merged (piece_soundness.h)
};

/// Glues the rock pieces into blocks across `rock_contacts` (their contacts among
/// themselves, as findPieceContacts gives them) that are fictitious on both sides (one
/// union-find), makes every rock piece sound (soundPiece: slivers folded away after the
/// gluing, near vertices merged; a block of slivers only disappears), adds each structure as
/// one block, assigns materials (structures: their own;
/// rock blocks: SlabMaterials::ofBlock), numbers the blocks 1..N in blockOrder, and lists the
/// adjacency: one entry per (block_a, block_b, source) with the summed contact area, sorted. Pieces
/// keep their face provenance. Contacts between structures and rock are found here.
///
/// `contact_sources`, when given (one per rock contact), is the cutter's own decision for
/// each rock contact instead of the face labels: Fictitious glues the two pieces, anything
/// else is a real contact with that source (a cutter that decides coverage per shared part,
/// where a face partly covered by a disc is labelled Fictitious but may touch a neighbour
/// only where the disc covers it). Inconsistent contacts are then those between a
/// Boundary or Structure face and a face of another kind.
///
/// `rock_facts`, when given (one per rock piece), holds what the assembly would compute of
/// each rock piece as given (a cutter that computes it while the piece is still in cache):
/// used instead, with the same results.
BlockModel assembleBlocks(std::vector<Piece> rock_pieces,
                          const std::vector<PieceContact>& rock_contacts, const CutInput& input,
                          const CutTolerances& tolerances, AssemblyReport* report = nullptr,
                          const std::vector<FaceSource>* contact_sources = nullptr,
                          const std::vector<PieceFacts>* rock_facts = nullptr);

}  // namespace rockmass::blocks
