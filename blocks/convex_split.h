// Splitting a convex piece by a plane, the one geometric step of the fast cutter.
//
// Robustness comes from classifying every vertex once against the plane, with a snapping
// tolerance: a vertex within `tolerance` of the plane is ON it and goes to both halves
// unchanged, so the split never makes a piece thinner than the tolerance out of round-off.
// Edges whose ends lie strictly on opposite sides are cut once, and the crossing point is
// shared by the two faces and the two halves. The topology of both halves follows from the
// signs alone, so each half is closed whatever the round-off in the crossing points.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "blocks/block_model.h"
#include "geometry/vec.h"

namespace rockmass::blocks {

using geometry::Vec3;

/// An oriented plane n . x = offset with a unit normal n.
struct Plane {
  Vec3 normal = Vec3::UnitZ();  ///< unit normal
  double offset = 0.0;          ///< n . x on the plane (m)

  /// Signed distance of `point` (m): positive on the side the normal points to.
  double distance(const Vec3& point) const { return normal.dot(point) - offset; }
  /// The plane through `point` with unit normal `normal`.
  static Plane through(const Vec3& point, const Vec3& normal) {
    return {normal, normal.dot(point)};
  }
};

/// The two halves of a split piece.
struct SplitPieces {
  Piece below;  ///< the half where distance <= 0; its new face has outward normal +n
  Piece above;  ///< the half where distance >= 0; its new face has outward normal -n
  std::vector<int> below_origin;  ///< per face of `below`: the face of the input it is part of
                                  ///< (-1 for the new face, which comes last)
  std::vector<int> above_origin;  ///< the same for `above`
};

/// Splits a closed convex piece by `plane`. Returns nothing when the plane does not cross
/// it: no vertex lies more than `tolerance` (m) on one of the two sides. The new face of
/// both halves gets the provenance `cap`; every other face keeps its own.
std::optional<SplitPieces> splitPiece(const Piece& piece, const Plane& plane, double tolerance,
                                      FaceSource cap);

/// How a plane meets a convex piece.
enum class SectionKind {
  None,      ///< the plane misses it or only touches a vertex or an edge
  Crossing,  ///< the plane cuts through it
  OnFace,    ///< a face of the piece lies in the plane (within the tolerance)
};

/// The intersection of a plane and a convex piece.
struct Section {
  SectionKind kind = SectionKind::None;
  std::vector<Vec3> polygon;  ///< convex polygon, counter-clockwise about the plane's normal
  int face = -1;              ///< for OnFace: the face of the piece that lies in the plane
};

/// The section of a convex piece by `plane` (same classification as splitPiece).
Section planeSection(const Piece& piece, const Plane& plane, double tolerance);

/// A convex piece in flat form (blocks/fast_cutter's cell store): its vertices, and face f's
/// loop as loops[face_begin[f] .. face_begin[f] + face_size[f]) (vertex indices into
/// `vertices`, counter-clockwise seen from outside).
struct FlatPieceView {
  std::span<const Vec3> vertices;
  std::span<const int> loops;
  std::span<const int> face_begin;  ///< per face: first entry of its loop in `loops`
  std::span<const int> face_size;   ///< per face: number of corners
};

/// The two halves of a flat split, in scratch storage reused by the caller.
struct FlatSplit {
  std::vector<Vec3> below_vertices, above_vertices;
  std::vector<int> below_loops, above_loops;    ///< face loops, concatenated
  std::vector<int> below_size, above_size;      ///< per face: corners
  std::vector<int> below_origin, above_origin;  ///< per face: input face, -1 for the new one
};

/// splitPiece on a flat piece: the very same halves (vertices, faces, loops and origins in
/// the same order, bitwise the same points), into `out`. False when the plane does not cross.
bool splitFlat(const FlatPieceView& piece, const Plane& plane, double tolerance, FlatSplit& out);

/// planeSection on a flat piece: the same kind, face and polygon (into `polygon`, cleared).
SectionKind planeSectionFlat(const FlatPieceView& piece, const Plane& plane, double tolerance,
                             std::vector<Vec3>& polygon, int* face);

/// What a section found, kept for a split of the same piece by the same plane (scratch
/// storage reused by the caller): the split then classifies no vertex, computes no crossing
/// point and sorts nothing again.
struct SectionScratch {
  std::vector<double> distance;            ///< per vertex: signed distance from the plane (m)
  std::vector<std::int8_t> side;           ///< per vertex: -1, 0 (within the tolerance) or +1
  std::vector<Vec3> points;                ///< section points: ON vertices, then crossing points
  int on_count = 0;                        ///< how many of `points` are ON vertices
  std::vector<std::pair<int, int>> edges;  ///< per crossing point: its edge (lower, higher)
  std::vector<int> order;                  ///< `points` counter-clockwise about the plane's normal
};

/// planeSectionFlat keeping its work in `scratch`, for splitFlat(piece, scratch, out).
SectionKind planeSectionFlat(const FlatPieceView& piece, const Plane& plane, double tolerance,
                             std::vector<Vec3>& polygon, int* face, SectionScratch& scratch);

/// splitFlat by the plane of the planeSectionFlat that filled `scratch` for this very piece
/// and returned SectionKind::Crossing: the very same halves as splitFlat(piece, plane, ...).
bool splitFlat(const FlatPieceView& piece, const SectionScratch& scratch, FlatSplit& out);

/// The part of a convex polygon where plane.distance >= 0 (Sutherland-Hodgman, one plane).
std::vector<Vec3> clipPolygon(const std::vector<Vec3>& polygon, const Plane& plane);
/// The same into `out` (cleared first; must not alias `polygon`), reusing its storage.
void clipPolygon(const std::vector<Vec3>& polygon, const Plane& plane, std::vector<Vec3>& out);

}  // namespace rockmass::blocks
