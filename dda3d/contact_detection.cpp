#include "dda3d/contact_detection.h"
#include "dda3d/contact_hull.h"

#include "dda3d/piece_view.h"
#include "dda3d/polygon2d.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

namespace rockmass::dda3d {

using namespace detection;

using geometry::Box;
using geometry::Polyhedron;
using geometry::Vec3;

namespace {

/// Edges nearly parallel within this angle give no edge-to-edge entry (sin 5 deg).
constexpr double kParallelSine = 0.087;
/// Edge parameters this close to an end are vertex contacts, handled as vertex-to-face.
constexpr double kEdgeEndMargin = 1e-6;
/// A vertex may touch face f when none of its edges dives into f's plane steeper than this
/// (cosine of the angle with the inward normal; 0.3 ~ 17 deg below the plane).
constexpr double kConeSlack = 0.3;
/// Two entries of one point of block i against block j are the same when their normals
/// agree to 1 - cos within this (coplanar faces of two pieces of j).
constexpr double kDuplicateNormalSlack = 1e-9;

/// Largest signed distance of p outside the planes of a convex piece (<= 0: inside). With
/// `surface`, only the planes of its faces on the block's surface count: for a point inside
/// the piece, minus how deep it lies below the block's surface there. The faces between the
/// piece and the block's other pieces are no surface: a point of another block sunk 1 mm into
/// the block's top beside such a face, 1e-5 m from it, read as 1e-5 m deep behind it, the top
/// face was then "far behind the nearest" and the point had no entry at all (the deformable
/// Xiangjiaba quick box crept on such points).
double outsideDistance(const std::vector<Plane>& planes, const Vec3& p,
                       const PieceTopology* surface = nullptr) {
  double outside = -std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < planes.size(); ++f) {
    if (surface != nullptr && !surface->faceExterior(f)) continue;
    outside = std::max(outside, planes[f].normal.dot(p) - planes[f].offset);
  }
  return outside;
}

/// Lowest and highest height n . (v - origin) of `vertices` (m).
std::pair<double, double> heightRange(const std::vector<Vec3>& vertices, const Vec3& n,
                                      const Vec3& origin) {
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (const Vec3& v : vertices) {
    const double h = n.dot(v - origin);
    low = std::min(low, h);
    high = std::max(high, h);
  }
  return {low, high};
}

/// True when a face plane of `b` has every vertex of `a` more than `distance` (m) on its
/// outer side: a and b are then farther apart than `distance` (b lies on the inner side).
bool separatedBeyond(const PieceView& a, const PieceView& b, double distance) {
  for (const Plane& plane : b.planes) {
    bool beyond = true;  // until a vertex of a lies within `distance` of the plane
    for (const Vec3& v : a.shape->vertices) {
      if (plane.normal.dot(v) - plane.offset <= distance) {
        beyond = false;
        break;
      }
    }
    if (beyond) return true;
  }
  return false;
}

/// Smallest overlap of the convex pieces a and b along the normals of their faces (m): for
/// each face plane, how deep the other piece's lowest vertex lies below it. Zero or less
/// means some face plane separates them.
double faceOverlap(const PieceView& a, const PieceView& b) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const auto& [inner, outer] : {std::pair{&a, &b}, std::pair{&b, &a}}) {
    for (const Plane& plane : outer->planes) {
      double lowest = std::numeric_limits<double>::infinity();
      for (const Vec3& v : inner->shape->vertices) {
        lowest = std::min(lowest, plane.normal.dot(v) - plane.offset);
      }
      smallest = std::min(smallest, -lowest);
    }
  }
  return smallest;
}

/// Two faces count as touching face to face when their outward normals are opposite within
/// this cosine: as for sharing contact area (10 deg). Blocks of a pile pressed side by side
/// tilt their faces by 1.1 deg against each other; with a 1 deg bound, the corner of one
/// such face beside the other's edge had no entry and sank 3 mm unseen into its neighbour.
constexpr double kFaceToFaceCosine = kAreaCosine;

/// Which vertices of the two pieces of a pair have a vertex-to-face entry against the other.
struct VertexEntries {
  std::vector<char> a, b;
};

/// Where edges of two pieces cross on faces that touch face to face.
struct FaceCrossing {
  bool touching = false;       ///< the edges lie in faces with opposite normals, planes near pc
  bool carried = false;        ///< the crossing is within the end margin of an end of either edge
  Vec3 normal = Vec3::Zero();  ///< of b's face, out of b
  int face = -1;               ///< that face of b
};

/// Looks for faces around edge `ea` of a and edge `eb` of b that touch face to face (opposite
/// normals, both planes within `distance` m of the crossing `pc`), and whether `pc` lies within
/// `end_margin` (in the faces' plane) of an end of either edge.
///
/// Such a crossing is a corner of the overlap polygon of the two faces. Near an edge end it
/// is the corner of stacked faces that coincide but for the blocks' strain (offsets of
/// ~1e-5 m), carried by the vertex-to-face entries of those corners (formulation doc,
/// "Point-to-face contact": face-face contact is its vertex entries); an edge-to-edge entry
/// would count the same support twice, and as the blocks strain its crossing slides in and
/// out of the edge ends, so it appears already penetrating by the faces' spring compression
/// (the deformable column, docs/dda3d.md). Farther from the ends it is a corner no vertex
/// carries (staggered blocks in a pile): edgeToEdge records it with b's face normal.
FaceCrossing faceCrossing(const PieceView& a, const PieceView& b, std::size_t ea, std::size_t eb,
                          const Vec3& pc, double distance, double end_margin,
                          const VertexEntries& entries) {
  const std::array<int, 2>& edge_a = a.topology->edges[ea];
  const std::array<int, 2>& edge_b = b.topology->edges[eb];
  FaceCrossing crossing;
  double best = -kFaceToFaceCosine;
  for (int fa : a.topology->edgeFaces(ea)) {
    const Plane& pa = a.planes[static_cast<std::size_t>(fa)];
    for (int fb : b.topology->edgeFaces(eb)) {
      const Plane& pb = b.planes[static_cast<std::size_t>(fb)];
      // Both planes pass within `distance` of the crossing. (Not |offset_a + offset_b|: for
      // faces tilted by 0.3 deg against each other, 11 m from the origin, that reads 6 cm.)
      const double alignment = pa.normal.dot(pb.normal);
      if (alignment < best && std::abs(pa.normal.dot(pc) - pa.offset) <= distance &&
          std::abs(pb.normal.dot(pc) - pb.offset) <= distance) {
        crossing.touching = true;
        crossing.normal = pb.normal;
        crossing.face = fb;
        best = alignment;
      }
    }
  }
  if (!crossing.touching) return crossing;
  // Distance in the faces' plane: how far the faces are pressed into each other (or apart)
  // says nothing of whether the crossing is a corner; a corner of one block on an edge of the
  // other seen 1.4 mm deep was kept as a crossing, its gap read across the nearly coplanar
  // edges of a tilted block (a pile of cubes, docs/dda3d.md).
  // Only an end that has its vertex entry carries the crossing: the vertex tests and this one
  // measure the corner's offset differently (its foot beyond the face's boundary, its depth),
  // and a corner coming down onto a neighbour's edge 0.35 mm a step sat on the margins of
  // both, had neither entry and sank 2 mm unseen (a pile of cubes, docs/dda3d.md).
  const Vec3& n = crossing.normal;
  for (const Polyhedron* shape : {a.shape, b.shape}) {
    const bool of_a = shape == a.shape;
    const std::array<int, 2>& edge = of_a ? edge_a : edge_b;
    const std::vector<char>& has_entry = of_a ? entries.a : entries.b;
    for (int v : edge) {
      const Vec3 offset = shape->vertices[static_cast<std::size_t>(v)] - pc;
      if (has_entry[static_cast<std::size_t>(v)] &&
          (offset - n * n.dot(offset)).norm() <= end_margin) {
        crossing.carried = true;
      }
    }
  }
  return crossing;
}

/// Box of the segment p q.
Box segmentBox(const Vec3& p, const Vec3& q) {
  return {p.cwiseMin(q), p.cwiseMax(q)};
}

/// True when the closed boxes x and y share a point.
bool overlaps(const Box& x, const Box& y) {
  return (x.min.array() <= y.max.array()).all() && (y.min.array() <= x.max.array()).all();
}

/// The face of `a` around vertex v that faces the direction -normal (face to face), the most
/// opposite of them (the first among equals); -1 when none does.
int facingFace(const PieceView& a, std::size_t v, const Vec3& normal) {
  int facing = -1;
  double most = -kFaceToFaceCosine;
  for (int f : a.topology->vertex_faces[v]) {
    const double cosine = a.planes[static_cast<std::size_t>(f)].normal.dot(normal);
    if (cosine < most) {
      most = cosine;
      facing = f;
    }
  }
  return facing;
}

/// True when a face of `a` around vertex v faces the direction -normal (face to face).
bool facesAt(const PieceView& a, std::size_t v, const Vec3& normal) {
  return facingFace(a, v, normal) >= 0;
}

/// Vertices of `a` against faces of `b`.
void vertexToFace(const PieceView& a, const PieceView& b, const Range& range, double tolerance,
                  const PreviousFace& previous_face, std::vector<Contact>& out) {
  const Box reach = b.box.enlarged(range.gap);
  for (std::size_t v = 0; v < a.shape->vertices.size(); ++v) {
    const Vec3& p = a.shape->vertices[v];
    if (!a.topology->vertexExterior(v) || !reach.contains(p)) continue;
    const double piece_outside = outsideDistance(b.planes, p);
    if (piece_outside > range.gap) continue;
    const bool is_outside = piece_outside > tolerance;
    // Outside b: how far (across any of its faces); inside: how deep below the block's
    // surface faces of b.
    const double outside = is_outside ? piece_outside : outsideDistance(b.planes, p, b.topology);
    const int previous = previous_face(a.block, a.piece, static_cast<int>(v), b.block, b.piece);
    int best = -1;
    double best_gap = 0.0, best_alignment = 0.0;
    bool best_on_face = false;
    for (std::size_t f = 0; f < b.planes.size(); ++f) {
      // Interior faces of b's block are no contact faces: a vertex near one is near (or in)
      // the neighbouring piece, whose exterior faces carry it.
      if (!b.topology->faceExterior(f)) continue;
      const Plane& plane = b.planes[f];
      const double gap = plane.normal.dot(p) - plane.offset;
      // The face a vertex used last step keeps it while the vertex stays within a margin of
      // the face (outside a side plane or beyond the face's boundary): strain moves the
      // coincident corners of stacked faces apart by ~1e-5 m, and dropping the entry there
      // would hand the corner to an edge crossing (seen already penetrating) or to nothing.
      const bool kept = static_cast<int>(f) == previous && outside <= range.keep_margin;
      // A vertex of a face of a that faces f (opposite normals), not deeper than the keep
      // margin behind f's plane, and within that margin of f's boundary (tested below), is
      // f's corner contact from the start, as a kept one is: edgeToEdge leaves the crossings
      // within that margin of a corner of two touching faces to the vertex entries
      // (faceCrossing). Without this, a corner just beyond the boundary of a face it rests on
      // (stacked blocks flush along one side, their strain or a 1e-5 rad tilt moving it in and
      // out) had no entry at all, penetrated unresisted and was found again 0.1-0.5 mm deep;
      // the penalty spring then threw the blocks apart (a pile of cubes, docs/dda3d.md).
      const bool on_face = gap >= -range.keep_margin && facesAt(a, v, plane.normal);
      if (gap < -range.depth || (is_outside && gap <= tolerance && !kept && !on_face)) continue;
      // Without a face from the last step, a vertex in b is taken to have entered through a
      // face about as near as the nearest one (outside = minus its depth). A face far behind
      // the nearest would be a guess: at a vertex resting on b's edge or corner (nearest
      // faces rejected by the foot or cone tests) it read as a penetration of up to the
      // piece's thickness, and the penalty then threw the blocks apart.
      if (static_cast<int>(f) != previous && gap < outside - range.keep_margin) continue;
      const Vec3 foot = p - gap * plane.normal;
      // A vertex barely inside b, behind this face by about the least depth, entered through it:
      // its foot may sit a round-off motion beyond the face's edge (a vertex on the line
      // where two pieces of b meet), and rejecting the face there handed the vertex to a
      // steeper face of b at a false depth of 0.7 mm on the Xiangjiaba model.
      // "Least depth" within 1 % of the keep margin (7 um on 1 m pieces): a vertex near an
      // edge of b is about as deep behind both faces there, and either may be the one.
      const bool least_deep =
          !is_outside && gap >= outside - std::max(tolerance, 0.01 * range.keep_margin);
      if (!insideFace(*b.shape, b.shape->faces[f], plane.normal, foot,
                      kept || least_deep || on_face ? range.keep_margin : tolerance)) {
        continue;
      }
      bool cone_ok = true;  // i's body near the vertex stays on the outer side of f
      for (int w : a.topology->neighbours[v]) {
        const Vec3 edge = a.shape->vertices[static_cast<std::size_t>(w)] - p;
        if (plane.normal.dot(edge) < -kConeSlack * edge.norm()) cone_ok = false;
      }
      if (!cone_ok) continue;
      if (static_cast<int>(f) == previous) {
        best = previous;
        break;
      }
      // A face that a face of a around the vertex lies on (on_face) first: the vertex came
      // through it, however little deeper it sits behind it than behind a steeper face of
      // b's edge. A vertex of the flat rock surface at a dam's toe edge sat 1 um behind the
      // dam's base and 0.5 um behind its sloping downstream face: taken by the slope, it
      // became a buttress of 6e8 N against the dam's sliding (the Xiangjiaba dam held at a
      // strength reduction of 6, twice its limit-equilibrium factor). Then the least
      // penetration (the face it most likely entered through); among equal gaps (a vertex on
      // an edge or corner of b) the face that looks most towards the vertex.
      const double alignment = plane.normal.dot((p - b.centroid).normalized());
      const bool better = on_face != best_on_face
                              ? on_face
                              : gap > best_gap + tolerance ||
                                    (gap > best_gap - tolerance && alignment > best_alignment);
      if (best < 0 || better) {
        best = static_cast<int>(f);
        best_gap = gap;
        best_alignment = alignment;
        best_on_face = on_face;
      }
    }
    if (best < 0) continue;
    const Plane& plane = b.planes[static_cast<std::size_t>(best)];
    Contact c = pairContact(ContactKind::VertexFace, a, b);
    c.vertex = static_cast<int>(v);
    c.face = best;
    c.facing_face = facingFace(a, v, plane.normal);
    c.point = p;
    c.normal = plane.normal;
    c.gap0 = plane.normal.dot(p) - plane.offset;
    c.foot = p - c.gap0 * plane.normal;
    out.push_back(c);
  }
}

/// An edge of b within reach of a's box: its index, box, start, direction and length (the
/// inner loop of edgeToEdge reads them for every edge of a).
struct NearEdge {
  std::size_t index;
  Box box;
  Vec3 start, direction;
  double length;
};

/// Crossing edges of `a` and `b`.
void edgeToEdge(const PieceView& a, const PieceView& b, const Range& range, double tolerance,
                const VertexEntries& entries, std::vector<NearEdge>& near_b,
                std::vector<Contact>& out) {
  const Box reach_b = b.box.enlarged(range.larger());
  // The edges of b within reach of a's box, with their boxes: the only ones any edge of a
  // can cross (computed once per pair, not once per edge of a).
  const Box reach_a = a.box.enlarged(range.larger());
  near_b.clear();
  for (std::size_t eb = 0; eb < b.topology->edges.size(); ++eb) {
    if (!b.topology->edgeExterior(eb)) continue;
    const Vec3& b0 = b.shape->vertices[static_cast<std::size_t>(b.topology->edges[eb][0])];
    const Vec3& b1 = b.shape->vertices[static_cast<std::size_t>(b.topology->edges[eb][1])];
    const Box box = segmentBox(b0, b1);
    if (overlaps(box, reach_a)) {
      const Vec3 w = b1 - b0;
      near_b.push_back({eb, box, b0, w, w.norm()});
    }
  }
  if (near_b.empty()) return;
  std::optional<double> overlap;  // faceOverlap(a, b)
  for (std::size_t ea = 0; ea < a.topology->edges.size(); ++ea) {
    if (!a.topology->edgeExterior(ea)) continue;
    const Vec3& a0 = a.shape->vertices[static_cast<std::size_t>(a.topology->edges[ea][0])];
    const Vec3& a1 = a.shape->vertices[static_cast<std::size_t>(a.topology->edges[ea][1])];
    const Box edge_box = segmentBox(a0, a1);
    if (!overlaps(edge_box, reach_b)) continue;
    const Box edge_reach = edge_box.enlarged(range.larger());
    const Vec3 u = a1 - a0;
    const double parallel_u = kParallelSine * u.norm();
    for (const NearEdge& near : near_b) {
      if (!overlaps(near.box, edge_reach)) continue;
      const std::size_t eb = near.index;
      const Vec3& b0 = near.start;
      const Vec3& w = near.direction;
      const Vec3 cross = u.cross(w);
      const double cross_norm = cross.norm();
      if (cross_norm <= parallel_u * near.length) continue;
      const Vec3 r = a0 - b0;
      const double uu = u.dot(u), uw = u.dot(w), ww = w.dot(w), ur = u.dot(r), wr = w.dot(r);
      const double den = cross_norm * cross_norm;
      const double s = (uw * wr - ww * ur) / den;
      const double t = (uu * wr - uw * ur) / den;
      if (s <= kEdgeEndMargin || s >= 1.0 - kEdgeEndMargin || t <= kEdgeEndMargin ||
          t >= 1.0 - kEdgeEndMargin) {
        continue;
      }
      const Vec3 pc = a0 + s * u;
      const Vec3 qc = b0 + t * w;
      if ((pc - qc).norm() > range.larger()) continue;
      const FaceCrossing on_faces =
          faceCrossing(a, b, ea, eb, pc, range.larger(), range.keep_margin, entries);
      if (on_faces.carried) continue;
      Vec3 n = cross / cross_norm;
      if (on_faces.touching) {
        // A corner of the overlap of two touching faces: it acts across b's face. The plane
        // of the two edges is tilted against the faces by their relative rotation (1e-3 rad
        // in a landing pile), and the support tests below then found b's far vertices on
        // both sides of it: the corner had no entry until it penetrated, then came in deep
        // and threw the blocks apart.
        n = on_faces.normal;
      } else {
        // Orient n out of b: the plane through qc must support b (n in b's edge normal
        // cone), and -n must support a at pc. Never from the sign of pc - qc, which flips
        // once the edges penetrate.
        const auto [low, high] = heightRange(b.shape->vertices, n, qc);
        if (high > tolerance) {
          if (low < -tolerance) continue;
          n = -n;
        }
        if (heightRange(a.shape->vertices, n, pc).first < -tolerance) continue;
      }
      Contact c = pairContact(ContactKind::EdgeEdge, a, b);
      c.edge_i = static_cast<int>(ea);
      c.edge_j = static_cast<int>(eb);
      c.normal_face = on_faces.touching ? on_faces.face : -1;
      c.point = pc;
      c.normal = n;
      c.gap0 = n.dot(pc - qc);
      c.foot = pc - c.gap0 * n;
      if (c.gap0 < -range.depth || c.gap0 > range.gap) continue;
      // A negative gap is a penetration only if the edges really pass through each other:
      // then each closest point lies inside the other piece. Skew edges of two pieces kept
      // apart by some other plane (small pieces, a reach as large as they are) can satisfy
      // both support tests above with the slabs overlapping; without this check they were
      // recorded as penetrations as deep as the search depth.
      // (The closest points of edges on touching faces sit off the other's side planes by
      // the gap times the faces' relative tilt: the keep margin is the slack there.)
      const double slack = on_faces.touching ? range.keep_margin : tolerance;
      if (c.gap0 < -tolerance &&
          (outsideDistance(b.planes, pc) > slack || outsideDistance(a.planes, qc) > slack)) {
        continue;
      }
      // An edge crossing is the contact only along the axis of least penetration (the
      // separating-axis view of two convex pieces). Where a face plane of either piece shows
      // a far smaller overlap, the pieces press through that face, and its vertex-to-face
      // entries carry the contact: two pieces stacked face to face on a 1e-7 m spring
      // compression have skew edges (one lying in the shared face, one ending on it) whose
      // crossing read as a 0.25 m horizontal penetration on the Xiangjiaba model, and its
      // penalty force, 10^4 times the model's weight, threw the blocks apart.
      if (c.gap0 < -tolerance) {
        if (!overlap) overlap = faceOverlap(a, b);  // once per pair, when first needed
        if (*overlap + tolerance < 0.5 * -c.gap0) continue;
      }
      out.push_back(c);
    }
  }
}

}  // namespace

void tangents(const Vec3& n, Vec3& t1, Vec3& t2) {
  const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  t1 = n.cross(helper).normalized();
  t2 = n.cross(t1);
}

const std::vector<PiecePair>& CandidatePairs::pairs(const std::vector<BlockState>& blocks,
                                                    const std::vector<double>& reach) {
  bool covered = grown_.size() == blocks.size();
  for (std::size_t b = 0; covered && b < blocks.size(); ++b) {
    if (moved_[b] + reach[b] > grown_[b]) covered = false;
  }
  if (covered) return pairs_;
  grown_.resize(blocks.size());
  for (std::size_t b = 0; b < blocks.size(); ++b)
    grown_[b] = blocks[b].fixed ? 0.0 : reach[b] + margin_;
  moved_.assign(blocks.size(), 0.0);
  pairs_ = broadPhase(blocks, grown_);
  ++builds_;
  return pairs_;
}

std::vector<PiecePair> broadPhase(const std::vector<BlockState>& blocks,
                                  const std::vector<double>& reach) {
  std::vector<PieceBox> boxes;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    for (std::size_t p = 0; p < blocks[b].pieces.size(); ++p) {
      // A piece inside its block (every face against another piece of it) meets no other
      // block but through the pieces around it.
      if (!blocks[b].topology[p].exterior) continue;
      boxes.push_back({geometry::bounds(blocks[b].pieces[p]).enlarged(reach[b]),
                       static_cast<int>(b), static_cast<int>(p), blocks[b].fixed});
    }
  }
  return overlappingPieces(boxes);
}

namespace {

/// The diagonal of the box of piece `piece` of block `block` (m): the size the narrow phase's
/// tolerances of a pair of pieces scale with (findContacts).
double pieceDiagonal(const std::vector<BlockState>& blocks, int block, int piece) {
  return geometry::bounds(
             blocks[static_cast<std::size_t>(block)].pieces[static_cast<std::size_t>(piece)])
      .diagonal();
}

/// One point of block i pressed into block j has one entry per piece of j it was found
/// against, each with that piece's least deep face. The block's surface is the union of
/// its pieces' surface faces: a point sunk into piece q beside the face where q meets
/// another piece p of j (no surface) is deep behind q's surface faces but shallow behind
/// p's, the face it came through. As within one piece (vertexToFace: a face far behind the
/// nearest is a guess), a penetrating vertex entry deeper than the least deep one of the
/// point by more than the keep margin is dropped. On the Xiangjiaba quick box such an entry
/// read a corner resting on a slope as 3.7 mm deep behind the region's side plane: its
/// spring pushed the block against its roller and the foundation never came to rest.
/// Open entries and entries as deep as the least deep (a point in a re-entrant corner of j,
/// pressed into both faces) are kept. `group` (positions order[first, end)) is one point of
/// block i against block j; `keep` marks what is kept.
template <class Entry>
void dropDeeperEntries(const std::vector<std::size_t>& order, std::size_t first, std::size_t end,
                       std::vector<char>& keep, const Entry& entry,
                       const std::vector<BlockState>& blocks) {
  double least_deep = -std::numeric_limits<double>::infinity();
  int penetrating = 0;
  for (std::size_t k = first; k < end; ++k) {
    const Contact& c = entry(order[k]);
    if (!keep[order[k]] || c.kind != ContactKind::VertexFace || !(c.gap0 < 0.0)) continue;
    least_deep = std::max(least_deep, c.gap0);
    ++penetrating;
  }
  if (penetrating < 2) return;
  for (std::size_t k = first; k < end; ++k) {
    const Contact& c = entry(order[k]);
    if (!keep[order[k]] || c.kind != ContactKind::VertexFace || !(c.gap0 < 0.0)) continue;
    // The keep margin of the entry's pair of pieces (findContacts' Range::keep_margin).
    const double size =
        pieceDiagonal(blocks, c.block_i, c.piece_i) + pieceDiagonal(blocks, c.block_j, c.piece_j);
    if (c.gap0 < least_deep - std::max(1e-9 * size, 1e-4 * size)) keep[order[k]] = 0;
  }
}

/// Drops the copies of an edge crossing. A crossing of block i's edge with block j's lies on
/// the edges of every piece of i (and of j) that meets along them, so it is found once per
/// such pair of pieces, at points equal only within the round-off of the pieces' copies of
/// their shared corners. Grouped by exact coordinates (withoutDuplicates), the copies were one
/// entry when their points came out bit for bit equal and two springs when not, and which it
/// was changed from search to search: 7 700 of the Xiangjiaba region's 24 000 crossing
/// entries were second copies, about 450 of them appeared or vanished at every search of the
/// foundation at rest, moving 1e8 N between springs, and the searched steps read unbalanced
/// ratios of 1e-3 to 4e-3 where the steps between them read 1e-5 to 1e-4. Copies within the pair of
/// pieces' detection tolerance (findContacts: 1e-9 of their sizes) with the same normal are one
/// crossing; the first found is kept, as in an exact group. `keys` are sorted by (block i, block j,
/// vertex, x, y, z, found order); edge entries have vertex -1. Serial: a few comparisons per
/// crossing.
template <class Key, class Entry>
void dropEdgeCopies(const std::vector<Key>& keys, std::vector<char>& keep, const Entry& entry,
                    const std::vector<BlockState>& blocks) {
  const auto isCrossing = [&](const Key& key) {
    return keep[key.index] && key.vertex < 0 && entry(key.index).kind == ContactKind::EdgeEdge;
  };
  for (std::size_t k = 0; k < keys.size(); ++k) {
    if (!isCrossing(keys[k])) continue;
    const Contact& c = entry(keys[k].index);
    double tolerance = -1.0;  // computed when a candidate copy follows
    for (std::size_t m = k + 1; m < keys.size(); ++m) {
      if (keys[m].block_i != keys[k].block_i || keys[m].block_j != keys[k].block_j ||
          keys[m].vertex != keys[k].vertex) {
        break;
      }
      if (tolerance < 0.0) {
        tolerance = 1e-9 * (pieceDiagonal(blocks, c.block_i, c.piece_i) +
                            pieceDiagonal(blocks, c.block_j, c.piece_j));
      }
      if (keys[m].x - keys[k].x > tolerance) break;
      if (!isCrossing(keys[m])) continue;
      const Contact& d = entry(keys[m].index);
      if ((d.point - c.point).norm() > tolerance ||
          d.normal.dot(c.normal) <= 1.0 - kDuplicateNormalSlack) {
        continue;
      }
      if (keys[m].index > keys[k].index) {
        keep[keys[m].index] = 0;
      } else {
        keep[keys[k].index] = 0;
        break;
      }
    }
  }
}

/// The entries of `chunks` (in chunk order) without the duplicates, in one vector.
std::vector<Contact> withoutDuplicates(std::vector<std::vector<Contact>> chunks,
                                       const std::vector<BlockState>& blocks) {
  // A vertex of a block made of several pieces belongs to each piece that meets there, and a
  // face of the other block may be split between its pieces: the same point of block i
  // against the same plane of block j is then found once per piece pair. Each copy is a
  // full penalty spring, so the copies would make that corner several times stiffer than
  // the others (6 copies at a corner of a multi-piece Xiangjiaba block). The first copy
  // found is kept (a deterministic order, so that contacts carry over between steps).
  // Runs every step: entries are grouped by a stable sort on (block i, block j, point)
  // rather than a map of per-point lists.
  // The keys are sorted as compact copies, the found order last (a stable order, in
  // parallel): reading them through the contacts cost a cache miss per comparison.
  // A vertex entry's point is its block's vertex (PieceTopology::block_vertex: the pieces'
  // copies of one corner, equal within round-off); other entries' points are their
  // coordinates (vertex -1).
  struct Key {
    int block_i, block_j, vertex;
    double x, y, z;
    std::size_t index;
    auto tied() const { return std::tie(block_i, block_j, vertex, x, y, z); }
    bool operator<(const Key& o) const {
      return std::tie(block_i, block_j, vertex, x, y, z, index) <
             std::tie(o.block_i, o.block_j, o.vertex, o.x, o.y, o.z, o.index);
    }
  };
  // Entry k of the joined list is chunk_of[k]'s entry k - start[chunk_of[k]]: the chunks
  // are read in place (through a table of pointers), and the kept entries moved once, into
  // the result.
  std::vector<std::size_t> start(chunks.size() + 1, 0);
  for (std::size_t ch = 0; ch < chunks.size(); ++ch) start[ch + 1] = start[ch] + chunks[ch].size();
  const std::size_t total = start.back();
  std::vector<Contact*> at(total);
  const auto entry = [&](std::size_t k) -> Contact& { return *at[k]; };
  std::vector<Key> keys(total);
  // A NaN coordinate would break the sort's strict order (undefined behaviour): a step whose
  // geometry went non-finite fails here, by name (the first such entry in the found order).
  std::vector<std::size_t> first_bad(chunks.size(), total);
  tbb::parallel_for(std::size_t{0}, chunks.size(), [&](std::size_t ch) {
    for (std::size_t i = 0; i < chunks[ch].size(); ++i) {
      Contact& c = chunks[ch][i];
      at[start[ch] + i] = &c;
      if (first_bad[ch] == total && !c.point.allFinite()) first_bad[ch] = start[ch] + i;
      const PieceTopology& t =
          blocks[static_cast<std::size_t>(c.block_i)].topology[static_cast<std::size_t>(c.piece_i)];
      const bool corner = c.kind == ContactKind::VertexFace && !t.block_vertex.empty();
      keys[start[ch] + i] = {c.block_i,
                             c.block_j,
                             corner ? t.block_vertex[static_cast<std::size_t>(c.vertex)] : -1,
                             corner ? 0.0 : c.point.x(),
                             corner ? 0.0 : c.point.y(),
                             corner ? 0.0 : c.point.z(),
                             start[ch] + i};
    }
  });
  for (const std::size_t bad : first_bad) {
    if (bad == total) continue;
    const Contact& c = entry(bad);
    throw std::runtime_error("contact detection: a contact point of blocks " +
                             std::to_string(c.block_i) + " and " + std::to_string(c.block_j) +
                             " is not finite");
  }
  tbb::parallel_sort(keys.begin(), keys.end());
  // Groups of one point of block i against block j: their starts (in sorted order), then each
  // group on its own (groups touch their own entries only, so in parallel).
  std::vector<std::size_t> group_start;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    if (k == 0 || keys[k].tied() != keys[k - 1].tied()) group_start.push_back(k);
  }
  group_start.push_back(keys.size());
  std::vector<std::size_t> order(keys.size());
  tbb::parallel_for(std::size_t{0}, keys.size(), [&](std::size_t k) { order[k] = keys[k].index; });
  std::vector<char> keep(total, 1);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, group_start.size() - 1, 512),
      [&](const tbb::blocked_range<std::size_t>& groups) {
        for (std::size_t g = groups.begin(); g != groups.end(); ++g) {
          const std::size_t first = group_start[g], end = group_start[g + 1];
          if (end - first < 2) continue;
          // Within a group (found order), drop an entry whose normal matches a kept one's.
          for (std::size_t k = first + 1; k < end; ++k) {
            const Vec3& n = entry(order[k]).normal;
            for (std::size_t m = first; m < k; ++m) {
              if (keep[order[m]] && entry(order[m]).normal.dot(n) > 1.0 - kDuplicateNormalSlack) {
                keep[order[k]] = 0;
                break;
              }
            }
          }
          dropDeeperEntries(order, first, end, keep, entry, blocks);
        }
      });
  dropEdgeCopies(keys, keep, entry, blocks);
  std::vector<Contact> kept;
  kept.reserve(static_cast<std::size_t>(std::count(keep.begin(), keep.end(), 1)));
  for (std::size_t ch = 0; ch < chunks.size(); ++ch) {
    for (std::size_t i = 0; i < chunks[ch].size(); ++i) {
      if (keep[start[ch] + i]) kept.push_back(std::move(chunks[ch][i]));
    }
    std::vector<Contact>().swap(chunks[ch]);
  }
  return kept;
}

/// The chunks' results one after the other, in chunk order.
template <class T>
std::vector<T> joined(std::vector<std::vector<T>> chunks) {
  std::size_t total = 0;
  for (const std::vector<T>& chunk : chunks) total += chunk.size();
  std::vector<T> out;
  out.reserve(total);
  for (std::vector<T>& chunk : chunks) {
    out.insert(out.end(), std::make_move_iterator(chunk.begin()),
               std::make_move_iterator(chunk.end()));
  }
  return out;
}

}  // namespace

std::vector<std::size_t> firstPieces(const std::vector<BlockState>& blocks) {
  std::vector<std::size_t> first(blocks.size() + 1, 0);
  for (std::size_t b = 0; b < blocks.size(); ++b) first[b + 1] = first[b] + blocks[b].pieces.size();
  return first;
}

std::vector<Contact> findContacts(const std::vector<BlockState>& blocks,
                                  const std::vector<double>& reach, double depth,
                                  const PreviousFace& previous_face, CandidatePairs* candidates,
                                  const std::vector<char>* only,
                                  const std::function<int(const Contact&)>& joint_of,
                                  bool hull_corners) {
  // Per-piece data, built once for the pieces that take part in some pair.
  const std::vector<std::size_t> first_piece = firstPieces(blocks);
  std::vector<PiecePair> pairs;
  if (candidates == nullptr) {
    pairs = broadPhase(blocks, reach);
  } else {
    // The kept pairs whose boxes, grown by this step's reach, overlap: the broad phase's own.
    const std::vector<PiecePair>& kept = candidates->pairs(blocks, reach);
    std::vector<Box> boxes(first_piece.back());
    tbb::parallel_for(std::size_t{0}, blocks.size(), [&](std::size_t b) {
      for (std::size_t p = 0; p < blocks[b].pieces.size(); ++p) {
        if (blocks[b].topology[p].exterior) {
          boxes[first_piece[b] + p] = geometry::bounds(blocks[b].pieces[p]).enlarged(reach[b]);
        }
      }
    });
    std::vector<char> keep(kept.size());
    tbb::parallel_for(std::size_t{0}, kept.size(), [&](std::size_t k) {
      const PiecePair& pair = kept[k];
      keep[k] = overlaps(boxes[first_piece[static_cast<std::size_t>(pair.block_a)] +
                               static_cast<std::size_t>(pair.piece_a)],
                         boxes[first_piece[static_cast<std::size_t>(pair.block_b)] +
                               static_cast<std::size_t>(pair.piece_b)]);
    });
    pairs.reserve(kept.size());
    for (std::size_t k = 0; k < kept.size(); ++k) {
      if (keep[k]) pairs.push_back(kept[k]);
    }
  }
  if (only != nullptr) {
    const auto flagged = [&](int block) { return (*only)[static_cast<std::size_t>(block)] != 0; };
    pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                               [&](const PiecePair& pair) {
                                 return !flagged(pair.block_a) && !flagged(pair.block_b);
                               }),
                pairs.end());
  }
  // Views of the pieces in some pair, built first so that the narrow phase only reads them.
  std::vector<PieceView> views(first_piece.back());
  std::vector<std::pair<int, int>> needed(first_piece.back(), {-1, -1});
  const auto indexOf = [&](int block, int piece) {
    return first_piece[static_cast<std::size_t>(block)] + static_cast<std::size_t>(piece);
  };
  for (const PiecePair& pair : pairs) {
    needed[indexOf(pair.block_a, pair.piece_a)] = {pair.block_a, pair.piece_a};
    needed[indexOf(pair.block_b, pair.piece_b)] = {pair.block_b, pair.piece_b};
  }
  tbb::parallel_for(std::size_t{0}, views.size(), [&](std::size_t k) {
    if (needed[k].first >= 0) views[k] = view(blocks, needed[k].first, needed[k].second);
  });
  // The narrow phase in chunks of pairs, in parallel; the chunks' entries are joined in pair
  // order, so the result is the same as a serial loop's (deterministic).
  constexpr std::size_t kChunk = 128;
  std::vector<std::vector<Contact>> found((pairs.size() + kChunk - 1) / kChunk);
  std::vector<std::vector<AreaSample>> areas(found.size());
  tbb::parallel_for(std::size_t{0}, found.size(), [&](std::size_t chunk) {
    const std::size_t end = std::min(pairs.size(), (chunk + 1) * kChunk);
    VertexEntries entries;  // scratch, reused by the chunk's pairs
    std::vector<NearEdge> near_b;
    for (std::size_t k = chunk * kChunk; k < end; ++k) {
      const PiecePair& pair = pairs[k];
      const PieceView& a = views[indexOf(pair.block_a, pair.piece_a)];
      const PieceView& b = views[indexOf(pair.block_b, pair.piece_b)];
      const double gap = reach[static_cast<std::size_t>(pair.block_a)] +
                         reach[static_cast<std::size_t>(pair.block_b)];
      const double tolerance = 1e-9 * (a.box.diagonal() + b.box.diagonal());
      // Farther apart than the range: nothing below can be recorded (a vertex's foot may sit
      // a round-off margin outside its face, which the doubled range covers).
      const double apart = 2.0 * gap + tolerance;
      if (separatedBeyond(a, b, apart) || separatedBeyond(b, a, apart)) continue;
      // A persisting vertex contact is kept up to 1e-4 of the pieces' size outside its face:
      // far above the strain offsets of coincident corners, far below a step's motion.
      const Range range{gap, depth,
                        std::max(tolerance, 1e-4 * (a.box.diagonal() + b.box.diagonal()))};
      std::vector<Contact>& out = found[chunk];
      const std::size_t first = out.size();
      vertexToFace(a, b, range, tolerance, previous_face, out);
      vertexToFace(b, a, range, tolerance, previous_face, out);
      entries.a.assign(a.shape->vertices.size(), 0);
      entries.b.assign(b.shape->vertices.size(), 0);
      for (std::size_t e = first; e < out.size(); ++e) {
        const bool of_a = out[e].block_i == a.block && out[e].piece_i == a.piece;
        (of_a ? entries.a : entries.b)[static_cast<std::size_t>(out[e].vertex)] = 1;
      }
      edgeToEdge(a, b, range, tolerance, entries, near_b, out);
      overlapAreas(a, b, range, tolerance, areas[chunk], out);
    }
  });
  std::vector<Contact> contacts = withoutDuplicates(std::move(found), blocks);
  if (joint_of) {
    tbb::parallel_for(std::size_t{0}, contacts.size(),
                      [&](std::size_t k) { contacts[k].joint = joint_of(contacts[k]); });
  }
  if (hull_corners) keepHullCorners(contacts, blocks);
  assignAreas(contacts, joined(std::move(areas)));
  return contacts;
}

double refreshContacts(const std::vector<BlockState>& blocks, std::vector<Contact>& contacts) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  const auto pieceOf = [&](int block, int piece) -> const Polyhedron& {
    return blocks[static_cast<std::size_t>(block)].pieces[static_cast<std::size_t>(piece)];
  };
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, contacts.size(), 1024), 0.0,
      [&](const tbb::blocked_range<std::size_t>& range, double deepest) {
        for (std::size_t k = range.begin(); k != range.end(); ++k) {
          Contact& c = contacts[k];
          const Polyhedron& a = pieceOf(c.block_i, c.piece_i);
          const Polyhedron& b = pieceOf(c.block_j, c.piece_j);
          if (c.kind == ContactKind::EdgeEdge) {
            const PieceTopology& ta = blocks[static_cast<std::size_t>(c.block_i)]
                                          .topology[static_cast<std::size_t>(c.piece_i)];
            const PieceTopology& tb = blocks[static_cast<std::size_t>(c.block_j)]
                                          .topology[static_cast<std::size_t>(c.piece_j)];
            const std::array<int, 2>& ea = ta.edges[static_cast<std::size_t>(c.edge_i)];
            const std::array<int, 2>& eb = tb.edges[static_cast<std::size_t>(c.edge_j)];
            const Vec3& a0 = a.vertices[static_cast<std::size_t>(ea[0])];
            const Vec3& b0 = b.vertices[static_cast<std::size_t>(eb[0])];
            const Vec3 u = a.vertices[static_cast<std::size_t>(ea[1])] - a0;
            const Vec3 w = b.vertices[static_cast<std::size_t>(eb[1])] - b0;
            const Vec3 cross = u.cross(w);
            const double cross_norm = cross.norm();
            const double den = cross_norm * cross_norm;
            if (!(den > 0.0)) {
              // Parallel edges: the entry keeps its point and normal; gap0 (the last step's,
              // its overlap added) goes back to the geometric gap. Non-finite: a search.
              c.gap0 -= c.overlap;
              deepest = std::isfinite(den) ? std::max(deepest, -c.gap0) : kInfinity;
              continue;
            }
            // The closest points of the two lines, as edgeToEdge finds the crossing.
            const Vec3 r = a0 - b0;
            const double uu = u.dot(u), uw = u.dot(w), ww = w.dot(w), ur = u.dot(r), wr = w.dot(r);
            const Vec3 pc = a0 + ((uw * wr - ww * ur) / den) * u;
            const Vec3 qc = b0 + ((uu * wr - uw * ur) / den) * w;
            Vec3 n = cross / cross_norm;
            if (c.normal_face >= 0) {
              n = facePlane(b, static_cast<std::size_t>(c.normal_face)).normal;
            } else if (n.dot(c.normal) < 0.0) {
              n = -n;
            }
            c.point = pc;
            c.normal = n;
            c.gap0 = n.dot(pc - qc);
          } else {
            const Plane plane = facePlane(b, static_cast<std::size_t>(c.face));
            c.point = c.kind == ContactKind::VertexFace
                          ? a.vertices[static_cast<std::size_t>(c.vertex)]
                          : blocks[static_cast<std::size_t>(c.block_i)]
                                .face_points[static_cast<std::size_t>(c.piece_i)]
                                .points[static_cast<std::size_t>(c.vertex)]
                                .position;
            c.normal = plane.normal;
            c.gap0 = plane.normal.dot(c.point) - plane.offset;
          }
          c.foot = c.point - c.gap0 * c.normal;
          // A non-finite gap reads as infinitely deep: the step searches, and the search
          // reports the geometry (findContacts' non-finite check).
          deepest = std::isfinite(c.gap0) ? std::max(deepest, -c.gap0) : kInfinity;
        }
        return deepest;
      },
      [](double x, double y) { return std::max(x, y); });
}

}  // namespace rockmass::dda3d
