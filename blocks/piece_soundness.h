// Sound convex pieces: what both cutters do to every rock piece once the pieces are glued
// into blocks, so that the DDA's contact detection and mass matrices never see a degenerate
// piece.
//
// Planes of a random fracture network that pass nearly through a common point or line make,
// in exact arithmetic as in floating point, cells whose vertices nearly coincide: slivers of
// 1e-16 m3 with edges of a few micrometres in a 100 m domain, and, next to them, pieces with
// one very short edge or one tiny face. soundPiece merges the vertices of a piece that lie
// closer than a distance tolerance (an edge collapse: faces that shrink to fewer than three
// corners disappear, spikes and pinches are removed), and folds away a piece whose volume
// falls below a volume tolerance. A merge that would flatten a thin piece (lose more than 1%
// of its volume) is refused: a slab between two discs 1e-9 m apart stays a block (issue 3).
// Neighbouring pieces are not changed: a folded sliver leaves a gap of its own volume (at
// most the volume tolerance each), and a collapsed edge moves a vertex by at most the
// distance tolerance. The gluing is decided before, on the unchanged pieces, so a block
// stays whole when a sliver inside it is folded; a block made of slivers only disappears.
#pragma once

#include <optional>
#include <vector>

#include "blocks/block_model.h"
#include "geometry/box.h"

namespace rockmass::blocks {

/// Tolerances of a sound piece, relative to the domain.
struct SoundnessTolerances {
  double distance = 0.0;  ///< m: two vertices of one piece closer than this are merged
  double area = 0.0;      ///< m2: a face below this area is degenerate (distance^2)
  double volume = 0.0;    ///< m3: a piece below this volume is folded away
};

/// distance = 1e-7 x the domain diagonal (12 um in the 122 m Xiangjiaba quick box: four
/// orders below any feature the DDA resolves, four above the cutters' own tolerance
/// cutTolerances().distance), area = distance^2, volume = 1e-15 x the domain's box volume
/// (2.4e-11 m3 there: a 0.3 mm cube; the degenerate pieces are 1e-16 m3). A folded piece
/// leaves a hole in the geometry (not in its block's mass): 1e-15 keeps the holes far below
/// the 1e-9 relative at which sections tile the domain and volumes are conserved, which a
/// 1e-12 tolerance (1 mm pieces) did not.
SoundnessTolerances soundnessTolerances(const geometry::Box& domain);

/// A piece made sound, with the face of the input each of its faces comes from.
struct SoundPiece {
  Piece piece;                   ///< vertices merged, degenerate faces removed
  std::vector<int> face_origin;  ///< per face of piece: the index of the input face
};

/// What soundPiece found in one piece.
struct SoundPieceReport {
  int merged_vertices = 0;  ///< vertices merged into a neighbour
  int removed_faces = 0;    ///< faces that collapsed (fewer than 3 corners or no area)
  /// Vertices closer than the tolerance were left alone: the edge collapse would not give a
  /// closed surface, or would change the volume by more than 1% (a thin piece, not a tiny
  /// feature: flattening it would lose it). The piece is kept as it is.
  bool unrepaired = false;
};

/// The piece with every cluster of vertices closer than tolerances.distance (single linkage)
/// merged into the centre of the cluster's bounding box (a point both cutters find alike),
/// faces that collapse to fewer than three corners removed,
/// spikes (a -> b -> a) cut off and pinched rings split; or nothing when the piece's volume
/// (after merging) is below tolerances.volume: the piece is folded away. When the merged
/// surface would not be a closed 2-manifold (every directed edge once, its reverse once), or
/// its volume would differ from the piece's by more than 1% (the piece is thin, like the slab
/// between two discs 1e-9 m apart, rather than a piece with a tiny feature), the piece is
/// kept unchanged (report->unrepaired). Deterministic.
std::optional<SoundPiece> soundPiece(const Piece& piece, const SoundnessTolerances& tolerances,
                                     SoundPieceReport* report = nullptr);

/// True when two vertices of the piece lie closer than tolerances.distance: only then may
/// soundPiece change its shape. Otherwise soundPiece gives the piece unchanged, or nothing
/// when its volume is below tolerances.volume (callers use this to skip the copy).
bool hasCloseVertices(const Piece& piece, const SoundnessTolerances& tolerances);

/// What soundPiece did to the pieces of a cut (summed by addToReport).
struct SoundnessReport {
  int folded_pieces = 0;       ///< pieces folded away (volume below the tolerance)
  double folded_volume = 0.0;  ///< their volume (m3), at most folded_pieces x volume tolerance
  int merged_vertices = 0;     ///< vertices merged into a neighbour
  int removed_faces = 0;       ///< degenerate faces removed
  int unrepaired = 0;          ///< pieces kept unchanged (see SoundPieceReport::unrepaired)
  double volume_change = 0.0;  ///< sum over kept pieces of |volume after - volume before| (m3)
  SoundnessReport& operator+=(const SoundnessReport& other);
};

/// Adds what soundPiece did to `piece` (`sound`: its result, nothing when folded away) to
/// `report`.
void addToReport(const Piece& piece, const std::optional<SoundPiece>& sound,
                 const SoundPieceReport& piece_report, SoundnessReport& report);

}  // namespace rockmass::blocks
