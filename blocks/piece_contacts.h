// Which convex pieces touch which: pairs of coplanar faces of opposite orientation that
// overlap. Both cutters glue pieces into blocks across fictitious contacts and derive the
// block adjacency from the real ones.
#pragma once

#include <span>
#include <vector>

#include "blocks/block_model.h"

namespace rockmass::blocks {

/// Two pieces touching across one face each.
struct PieceContact {
  int piece_a = 0;    ///< index of the first piece (piece_a < piece_b)
  int face_a = 0;     ///< its face
  int piece_b = 0;    ///< index of the second piece
  int face_b = 0;     ///< its face
  double area = 0.0;  ///< overlap area of the two faces (m2)
};

/// All contacts among `pieces` (closed convex polyhedra with outward faces): faces of two
/// different pieces in one plane (the smaller face's vertices within `tolerance` (m) of the
/// larger face's plane), whose normals are opposite, and whose overlap is a real contact: an
/// area above `min_area` (m2), or a compact one, wider than `tolerance` (area > tolerance x
/// the overlap's bounding-box diagonal); thinner overlaps are mere touches. Candidate pairs come
/// from CGAL's box intersection (bounding boxes grown by `tolerance`). Sorted by
/// (piece_a, piece_b, face_a, face_b).
std::vector<PieceContact> findPieceContacts(std::span<const Piece> pieces, double tolerance,
                                            double min_area);

/// The same contacts when the plane of every face is known: `planes[i][f]` is the id of
/// the plane that face f of piece i lies in, equal for faces in one geometric plane (a
/// cutter knows it: the plane that made the face). Only faces with equal ids and opposite
/// normals and bounding boxes (grown by `tolerance`, m) that meet are compared, so the search costs
/// about the number of faces, not of piece pairs.
std::vector<PieceContact> findContactsByPlane(std::span<const Piece> pieces,
                                              const std::vector<std::vector<int>>& planes,
                                              double tolerance, double min_area);

/// True when the convex planar polygon is thinner than `tolerance` (m): its area is at most
/// `tolerance` x its bounding-box diagonal (a convex polygon is at least area / diagonal
/// wide), or it is smaller than `tolerance` across. The area is summed about the first
/// vertex, so its round-off scales with the polygon's size, not with its distance from the
/// origin: a degenerate polygon 1e-15 m across never passes as a compact one.
bool thinnerThan(const std::vector<geometry::Vec3>& polygon, double tolerance);

/// Overlap area (m2) of two convex planar faces given counter-clockwise about `normal` (for
/// `a`) and about -normal (for `b`), assumed coplanar.
double faceOverlapArea(const std::vector<geometry::Vec3>& a, const std::vector<geometry::Vec3>& b,
                       const geometry::Vec3& normal);

}  // namespace rockmass::blocks
