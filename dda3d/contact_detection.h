// Contact detection: a broad phase over piece bounding boxes grown by how far each block
// may move in the step (broad_phase.h), then a narrow phase between convex pieces of
// different blocks that writes vertex-to-face and edge-to-edge contacts as point-to-face
// entries (formulation doc, "Point-to-face contact" and "Edge-to-edge contact").
#pragma once

#include <functional>
#include <vector>

#include "dda3d/block_state.h"
#include "dda3d/broad_phase.h"
#include "dda3d/contact.h"

namespace rockmass::dda3d {

/// Two unit tangents completing the unit normal n to a right-handed orthonormal basis
/// (t1 x t2 = n): the shear directions of a contact, the 2D basis of a face.
void tangents(const geometry::Vec3& n, geometry::Vec3& t1, geometry::Vec3& t2);

/// The largest displacement of any vertex of `block` under the unknowns `d` (m), with the
/// first-order field |T(v) d|. Pieces are convex and |T(x) d| is convex in x, so this
/// bounds every point of the block; it is also >= the exact-rotation displacement
/// (chord <= arc), so a step checked against it never moves farther.
double largestVertexDisplacement(const BlockState& block, const BlockVector& d);

/// The first-order displacement field T(x) d of a block's unknowns `d`, affine in x:
/// u(x) = u(c) + J (x - c) (largestVertexDisplacement's, for a pass over the vertices that
/// computes other things too).
class LinearDisplacement {
 public:
  LinearDisplacement(const BlockState& block, const BlockVector& d);
  /// |u(x)|^2.
  double squaredAt(const geometry::Vec3& x) const {
    return (at_centroid_ + jacobian_ * (x - centroid_)).squaredNorm();
  }

 private:
  geometry::Vec3 centroid_;
  geometry::Vec3 at_centroid_;
  Eigen::Matrix3d jacobian_;
};

/// The sub-contact points of `piece`: each face cut into a grid of cells of about `spacing`
/// (m) along the face's longest edge and across it (cells clipped to the face), a point at
/// the centroid of each cell carrying the cell's area. A face narrower than two cells either
/// way gets none (its corners carry it). At most `max_per_face` points per face (the grid
/// is coarsened to fit).
FacePoints facePoints(const geometry::Polyhedron& piece, double spacing, int max_per_face = 1024);
/// How many points facePoints(piece, spacing, max_per_face) gives at most (the cells of each
/// face's grid before clipping), without making them.
std::size_t facePointBound(const geometry::Polyhedron& piece, double spacing,
                           int max_per_face = 1024);
/// Limits of a block's step reach (m), from the step control (formulation, "Step control":
/// a step moves no vertex farther than g2 l0).
struct ReachLimits {
  double floor = 0.0;         ///< reach of a block at rest (m)
  double cap = 0.0;           ///< the step control's own limit, 1.5 g2 l0 (m)
  double acceleration = 0.0;  ///< of the body force, |g| (m/s2)
};

/// How far any vertex of `block` may move in a step of `dt` (s): twice the larger of the
/// free flight over dt (its velocity times dt plus 1/2 |g| dt^2) and its last step's
/// displacement scaled from `last_dt` to dt (0: not scaled), clamped to [limits.floor,
/// limits.cap]; 0 for a fixed block. A step that moves a block farther is redone with a smaller dt,
/// so contacts between pieces farther apart than the sum of their blocks' reaches cannot form
/// within the step.
double stepReach(const BlockState& block, double dt, double last_dt, const ReachLimits& limits);
/// stepReach with the last step's largestVertexDisplacement(block, block.last_displacement)
/// already known (`last_largest`, from the geometry as it is now).
double stepReach(const BlockState& block, double dt, double last_dt, const ReachLimits& limits,
                 double last_largest);

/// Piece boxes grown by their block's `reach` (one per block, m), intersected by
/// overlappingPieces(): the candidate pairs (sorted, different blocks, not both fixed).
std::vector<PiecePair> broadPhase(const std::vector<BlockState>& blocks,
                                  const std::vector<double>& reach);

/// The broad phase's pairs kept between steps (a Verlet list): found once with every
/// block's piece boxes grown by its reach plus a margin, they hold every pair a broad phase
/// with a later reach finds for as long as no block has moved farther than its margin since
/// (how far each block moved is bounded by largestVertexDisplacement, summed over the steps).
/// findContacts then only filters them by the step's own reach.
class CandidatePairs {
 public:
  /// `margin`: how far (m) beyond its reach each block's boxes are grown.
  explicit CandidatePairs(double margin = 0.0) : margin_(margin) {}
  /// Adds `distance` (m, a bound on how far every point of `block` moved) after a step.
  void moved(std::size_t block, double distance) {
    if (block < moved_.size()) moved_[block] += distance;
  }
  /// Forgets the pairs (the blocks' geometry changed some other way).
  void clear() { pairs_.clear(), grown_.clear(), moved_.clear(); }
  /// The pairs for a step with `reach` (per block, m): the kept ones when they still cover
  /// it, else the broad phase again (grown by reach + margin).
  const std::vector<PiecePair>& pairs(const std::vector<BlockState>& blocks,
                                      const std::vector<double>& reach);
  /// How many times the broad phase ran.
  int builds() const { return builds_; }

 private:
  double margin_;
  std::vector<PiecePair> pairs_;
  std::vector<double> grown_;  ///< per block: its boxes' growth when the pairs were found
  std::vector<double> moved_;  ///< per block: how far it moved since (m)
  int builds_ = 0;
};

/// Index of each block's first piece when the pieces of all blocks are numbered in order,
/// then the total count (blocks.size() + 1 entries).
std::vector<std::size_t> firstPieces(const std::vector<BlockState>& blocks);

/// The face a vertex used last step against a piece: (face index, or -1 when none).
using PreviousFace =
    std::function<int(int block_i, int piece_i, int vertex, int block_j, int piece_j)>;

/// All contact entries for the coming step. Broad phase with the blocks' `reach` (m), then
/// for every candidate pair the narrow phase: open gaps up to reach_a + reach_b (the largest
/// gap that can close within the step) and penetrations up to `depth` (m, independent of
/// the motion: a vertex that sank in stays a contact however slowly it moves); vertices of
/// a against faces of b and the reverse, and the crossing edges. `previous_face` keeps the
/// reference face of a vertex that persists (the face it entered through). Per-piece world-space
/// data (face planes, boxes) is computed once per call. Geometry fields are set, states are not;
/// the order is that of the sorted pairs, so deterministic.
/// With `candidates`, the broad phase's pairs come from it (the same pairs, kept between
/// steps). With `only`, a flag per block, only the pairs of blocks of which at least one is
/// flagged are searched: every entry between those blocks, as a search of all would find it.
/// With `joint_of`, each entry's joint (Contact::joint) is set by it; with `hull_corners`, a
/// face lying on a face of the other block keeps only the corners of the convex hull of its
/// vertex entries (keepHullCorners, per joint), before the contact area is shared among the
/// entries.
std::vector<Contact> findContacts(const std::vector<BlockState>& blocks,
                                  const std::vector<double>& reach, double depth,
                                  const PreviousFace& previous_face,
                                  CandidatePairs* candidates = nullptr,
                                  const std::vector<char>* only = nullptr,
                                  const std::function<int(const Contact&)>& joint_of = {},
                                  bool hull_corners = false);

/// Sets the geometry of kept entries (point, foot, normal, gap0 without any overlap) from the
/// blocks' current geometry, each as the narrow phase computes it for the same vertex and
/// face, edges, or sub-contact point and face: the entries of an earlier detection moved with
/// their blocks (Simulation, DdaSettings::detection.search_margin). An edge crossing keeps its
/// normal's side; one without a face of b for its normal whose edges became parallel keeps
/// its normal. Returns the deepest penetration among them (m, >= 0; infinite when a gap is
/// not finite).
double refreshContacts(const std::vector<BlockState>& blocks, std::vector<Contact>& contacts);

}  // namespace rockmass::dda3d
