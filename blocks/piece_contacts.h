// Which convex pieces touch which: pairs of coplanar faces of opposite orientation that
// overlap. Both cutters glue pieces into blocks across fictitious contacts and derive the
// block adjacency from the real ones.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "blocks/block_model.h"
#include "geometry/box.h"
#include "geometry/vec.h"

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

/// A cutter's decision on one contact: its source; FaceKind::Fictitious glues the two pieces
/// into one block. The flag is true when the two faces are the same loop (bitwise equal
/// points, the two sides of one cut): their shared part is either face. Called concurrently
/// from several threads.
using ContactDecision = std::function<FaceSource(const PieceContact&, bool)>;

/// The same contacts when the plane of every face is known: `planes[i][f]` is the id of
/// the plane that face f of piece i lies in, equal for faces in one geometric plane (a
/// cutter knows it: the plane that made the face). Only faces with equal ids and opposite
/// normals and bounding boxes (grown by `tolerance`, m) that meet are compared, so the search costs
/// about the number of faces, not of piece pairs.
///
/// With `decide`, each contact found is decided at once (its source goes to `sources`, in
/// the order of the result), and pairs of pieces already glued by earlier Fictitious
/// decisions are not compared at all: first every pair of faces that are the two sides of
/// one cut (bitwise the same loop: cheap), then, per plane, the other candidate pairs
/// whose pieces are not yet in one cluster. The result then holds every contact between
/// pieces that end in different clusters and enough gluing contacts to form the clusters
/// (the same clusters as with all contacts); contacts inside a cluster may be missing.
std::vector<PieceContact> findContactsByPlane(std::span<const Piece> pieces,
                                              const std::vector<std::vector<int>>& planes,
                                              double tolerance, double min_area,
                                              const ContactDecision& decide = {},
                                              std::vector<FaceSource>* sources = nullptr);

/// The same with the plane ids flat: face_planes[k] for the k-th face counting the faces of
/// all pieces in piece and face order.
std::vector<PieceContact> findContactsByPlane(std::span<const Piece> pieces,
                                              std::span<const int> face_planes, double tolerance,
                                              double min_area, const ContactDecision& decide = {},
                                              std::vector<FaceSource>* sources = nullptr);

/// One face of one piece.
struct FaceRef {
  int piece = 0;  ///< index of the piece
  int face = 0;   ///< its face
};

/// Two faces that may touch.
using FacePair = std::pair<FaceRef, FaceRef>;

/// The contacts among explicitly given candidate face pairs (a cutter that tracked which
/// faces of its pieces may touch while splitting them), tested and decided as
/// findContactsByPlane with `decide` tests and decides its candidates: the mirrored pairs
/// first, then the others (in fixed batches of the given order) whose pieces are not glued
/// yet. Every real contact between two faces of a listed pair whose pieces end in different
/// clusters is in the result; pairs not listed are never looked at. Sorted as
/// findContactsByPlane; `sources` gets the decisions in the same order.
std::vector<PieceContact> decideCandidateContacts(std::span<const Piece> pieces,
                                                  std::span<const FacePair> candidates,
                                                  double tolerance, double min_area,
                                                  const ContactDecision& decide,
                                                  std::vector<FaceSource>* sources);

/// Faces prepared for the contact tests of decideCandidateContacts: per face its piece, its
/// corners, Newell unit normal, plane offset (through the corners' mean), bounding box and
/// every edge's inward unit normal. decideCandidateContacts builds it from the pieces; a
/// cutter that holds its pieces in flat arrays builds it with `add` (the same numbers) and
/// calls decideTableContacts.
struct ContactFaces {
  /// One face.
  struct Face {
    int piece = 0, face = 0;
    std::uint32_t begin = 0, end = 0;  ///< range in `points` and `inward`
    geometry::Vec3 normal;             ///< Newell unit normal (outward)
    double offset = 0.0;               ///< normal . x on the face's plane (m)
    geometry::Box box;                 ///< bounding box of the corners
  };
  std::vector<Face> faces;
  std::vector<geometry::Vec3> points;  ///< corners of all faces
  std::vector<geometry::Vec3> inward;  ///< per corner k: unit normal of edge k -> k+1 towards
                                       ///< the face's inside (zero for an edge of zero length)
  /// findContactsByPlane: [begin, end) of each plane with two faces or more.
  std::vector<std::pair<std::size_t, std::size_t>> groups;

  /// Appends face `face` of piece `piece`, whose corners are vertices[loop[k]]; returns its
  /// index in `faces`.
  std::uint32_t add(int piece, int face, std::span<const geometry::Vec3> vertices,
                    std::span<const int> loop);
  /// Fills entry k of a table sized beforehand (faces.size() > k, points and inward holding
  /// begin + loop.size() corners or more) as `add` would: face `face` of piece `piece`, whose
  /// corners are vertices[loop[j]], its corners at points[begin ..].
  void set(std::uint32_t k, int piece, int face, std::uint32_t begin,
           std::span<const geometry::Vec3> vertices, std::span<const int> loop);
  /// Appends the faces of `other`, their piece indices shifted by `piece_offset`.
  void append(const ContactFaces& other, int piece_offset);
};

/// decideCandidateContacts on a prepared table: `pairs` index table.faces, pieces are
/// 0 .. piece_count - 1. The same contacts, decisions and order as decideCandidateContacts
/// with the same candidates.
std::vector<PieceContact> decideTableContacts(
    const ContactFaces& table, std::size_t piece_count,
    std::span<const std::pair<std::uint32_t, std::uint32_t>> pairs, double tolerance,
    double min_area, const ContactDecision& decide, std::vector<FaceSource>* sources);

/// findContactsByPlane with `decide` on a prepared table: `table.groups` lists the [begin,
/// end) ranges of table.faces that lie in one plane (two faces or more), faces of a plane in
/// piece and face order; pieces are 0 .. piece_count - 1. The same contacts, decisions and
/// order as findContactsByPlane on the pieces the table was filled from (a cutter that holds
/// its pieces in flat arrays fills the table without reading them back).
std::vector<PieceContact> decidePlaneContacts(const ContactFaces& table, std::size_t piece_count,
                                              double tolerance, double min_area,
                                              const ContactDecision& decide,
                                              std::vector<FaceSource>* sources);

/// One of several contact tables decided together (a cutter's regions, each with its own
/// table, are not copied into one): its faces name pieces piece_offset + Face::piece, its
/// pairs index table->faces. `mirrored`: contacts the caller found itself between faces that
/// are the two sides of one cut (mirroredContactArea; pieces numbered as in the table, not in
/// `pairs`), decided with the mirrored pairs of `pairs`.
struct ContactTablePart {
  const ContactFaces* table = nullptr;
  int piece_offset = 0;
  std::span<const std::pair<std::uint32_t, std::uint32_t>> pairs;
  std::span<const PieceContact> mirrored;
};

/// For two faces of different pieces that are the two sides of one cut (`b` holds the corners
/// of `a` run backwards, bitwise), what decideTableContacts finds for them as a mirrored pair,
/// without a table: their area (of `a`) when they touch (opposite Newell normals, coplanar
/// within `tolerance`, a real contact), else nothing.
std::optional<double> mirroredContactArea(std::span<const geometry::Vec3> a,
                                          std::span<const geometry::Vec3> b, double tolerance,
                                          double min_area);

/// decideTableContacts over several tables (pieces 0 .. piece_count - 1 over all parts): the
/// candidates of each part in fixed batches of that part. Every real contact between two
/// faces of a listed pair whose pieces end in different clusters is in the result, and the
/// clusters are those of decideTableContacts on the parts' tables appended into one (only
/// contacts inside a cluster may differ: the batches differ). Sorted as findContactsByPlane;
/// `sources` gets the decisions in the same order.
std::vector<PieceContact> decideTableContacts(std::span<const ContactTablePart> parts,
                                              std::size_t piece_count, double tolerance,
                                              double min_area, const ContactDecision& decide,
                                              std::vector<FaceSource>* sources);

/// The overlap of two convex planar faces given counter-clockwise about `normal` (for `a`)
/// and about -normal (for `b`), assumed coplanar: `a` clipped by the edges of `b`, into
/// `out` (counter-clockwise about `normal`; fewer than 3 points when they do not overlap).
void faceOverlap(const std::vector<geometry::Vec3>& a, const std::vector<geometry::Vec3>& b,
                 const geometry::Vec3& normal, std::vector<geometry::Vec3>& out);

/// True when the convex planar polygon is thinner than `tolerance` (m): its area is at most
/// `tolerance` x its bounding-box diagonal (a convex polygon is at least area / diagonal
/// wide), or it is smaller than `tolerance` across. The area is summed about the first
/// vertex, so its round-off scales with the polygon's size, not with its distance from the
/// origin: a degenerate polygon 1e-15 m across never passes as a compact one.
bool thinnerThan(const std::vector<geometry::Vec3>& polygon, double tolerance);

/// True when an overlap is a real contact: an area above `min_area` (m2), or a compact
/// part, wider than `tolerance` (m). A small but compact contact (a 0.1 mm corner cut off a
/// piece by a crack) joins what it touches, as in the exact cutter; a sliver along an edge,
/// thinner than the tolerance, does not.
bool realContact(const std::vector<geometry::Vec3>& overlap, double area, double tolerance,
                 double min_area);

/// Overlap area (m2) of two convex planar faces given counter-clockwise about `normal` (for
/// `a`) and about -normal (for `b`), assumed coplanar.
double faceOverlapArea(const std::vector<geometry::Vec3>& a, const std::vector<geometry::Vec3>& b,
                       const geometry::Vec3& normal);

}  // namespace rockmass::blocks
