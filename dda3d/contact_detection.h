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

/// Piece boxes grown by their block's `reach` (one per block, m), intersected by
/// overlappingPieces(): the candidate pairs (sorted, different blocks, not both fixed).
std::vector<PiecePair> broadPhase(const std::vector<BlockState>& blocks,
                                  const std::vector<double>& reach);

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
std::vector<Contact> findContacts(const std::vector<BlockState>& blocks,
                                  const std::vector<double>& reach, double depth,
                                  const PreviousFace& previous_face);

}  // namespace rockmass::dda3d
