// Splitting a convex piece by a plane, the one geometric step of the fast cutter.
//
// Robustness comes from classifying every vertex once against the plane, with a snapping
// tolerance: a vertex within `tolerance` of the plane is ON it and goes to both halves
// unchanged, so the split never makes a piece thinner than the tolerance out of round-off.
// Edges whose ends lie strictly on opposite sides are cut once, and the crossing point is
// shared by the two faces and the two halves. The topology of both halves follows from the
// signs alone, so each half is closed whatever the round-off in the crossing points.
#pragma once

#include <optional>
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

/// The part of a convex polygon where plane.distance >= 0 (Sutherland-Hodgman, one plane).
std::vector<Vec3> clipPolygon(const std::vector<Vec3>& polygon, const Plane& plane);
/// The same into `out` (cleared first; must not alias `polygon`), reusing its storage.
void clipPolygon(const std::vector<Vec3>& polygon, const Plane& plane, std::vector<Vec3>& out);

}  // namespace rockmass::blocks
