// What the narrow phase of contact detection knows of a piece (its face planes, box,
// centroid, topology and sub-contact points) and the records it passes between its steps.
// Internal to dda3d (contact_detection.cpp, contact_areas.cpp).
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

#include "dda3d/block_state.h"
#include "dda3d/contact.h"
#include "dda3d/contact_detection.h"
#include "dda3d/polygon2d.h"
#include "geometry/box.h"
#include "geometry/polyhedron.h"

namespace rockmass::dda3d::detection {

using geometry::Box;
using geometry::Polyhedron;
using geometry::Vec3;

/// Two faces of different blocks share contact area when their outward normals are opposite
/// within 10 deg (blocks that rotate in a step tilt their faces by a fraction of that).
constexpr double kAreaCosine = 0.985;
/// Entries within this share of an area sample's distance (AreaSample::distance, the search's
/// range: 1e-4 of it is micrometres) of its nearest entry are as near, and the earliest of
/// them (in pair of pieces, then found order) takes the sample: the nearest alone flipped
/// between near-equidistant entries as the blocks moved by micrometres, and a search of the
/// Xiangjiaba region at rest moved 150-900 m2 of its 72 000 m2 of contact area between
/// entries (13 000-54 000 of them), changing their cohesion (assignAreas).
constexpr double kAreaTieShare = 1e-4;
/// A face's plane n . x = offset (unit n, out of the piece) and its area (m2).
struct Plane {
  Vec3 normal;
  double offset;  // n . x on the plane
  double area;
};

/// The plane of face f of `piece` (Newell's normal, through its first vertex).
inline Plane facePlane(const Polyhedron& piece, std::size_t f) {
  const std::vector<int>& face = piece.faces[f];
  Vec3 newell = Vec3::Zero();
  for (std::size_t k = 0; k < face.size(); ++k) {
    newell += piece.vertices[face[k]].cross(piece.vertices[face[(k + 1) % face.size()]]);
  }
  const double twice_area = newell.norm();
  const Vec3 n = twice_area > 0.0 ? Vec3(newell / twice_area) : Vec3(Vec3::Zero());
  return {n, n.dot(piece.vertices[face[0]]), 0.5 * twice_area};
}

inline std::vector<Plane> facePlanes(const Polyhedron& piece) {
  std::vector<Plane> planes;
  planes.reserve(piece.faces.size());
  for (std::size_t f = 0; f < piece.faces.size(); ++f) planes.push_back(facePlane(piece, f));
  return planes;
}

/// The 2D frame of a face with unit normal n: origin at its first vertex, axes t1, t2 of
/// tangents(n) (t1 x t2 = n, so the face, counter-clockwise seen from outside, stays so).
struct FaceFrame {
  Vec3 origin, t1, t2;
  FaceFrame(const Polyhedron& piece, const std::vector<int>& face, const Vec3& n)
      : origin(piece.vertices[static_cast<std::size_t>(face[0])]) {
    tangents(n, t1, t2);
  }
  Point2 flat(const Vec3& x) const { return Point2((x - origin).dot(t1), (x - origin).dot(t2)); }
  Vec3 at(const Point2& x) const { return origin + x.x() * t1 + x.y() * t2; }
};

/// Where face `face_a` of piece a, facing face `face_b` of piece b, overlaps it: a's face
/// projected along `frame`'s normal (b's face's frame) and clipped to b's face, in that frame,
/// counter-clockwise (a's face, seen from the other side, is reversed). Fewer than 3 points:
/// no overlap.
inline std::vector<Point2> facesOverlap(const Polyhedron& a, const std::vector<int>& face_a,
                                        const Polyhedron& b, const std::vector<int>& face_b,
                                        const FaceFrame& frame) {
  std::vector<Point2> polygon;
  for (auto v = face_a.rbegin(); v != face_a.rend(); ++v) {
    polygon.push_back(frame.flat(a.vertices[static_cast<std::size_t>(*v)]));
  }
  for (std::size_t k = 0; k < face_b.size() && polygon.size() >= 3; ++k) {
    const Point2 p = frame.flat(b.vertices[static_cast<std::size_t>(face_b[k])]);
    const Point2 q =
        frame.flat(b.vertices[static_cast<std::size_t>(face_b[(k + 1) % face_b.size()])]);
    const Point2 edge = q - p;
    polygon = clipped(polygon, [&](const Point2& x) { return -cross2(edge, x - p); });
  }
  return polygon;
}

/// True when q (on the face's plane) lies inside the convex face, within `tolerance` (m).
inline bool insideFace(const Polyhedron& piece, const std::vector<int>& face, const Vec3& normal,
                       const Vec3& q, double tolerance) {
  for (std::size_t k = 0; k < face.size(); ++k) {
    const Vec3& a = piece.vertices[face[k]];
    const Vec3& b = piece.vertices[face[(k + 1) % face.size()]];
    const Vec3 edge = b - a;
    if ((edge.cross(q - a)).dot(normal) < -tolerance * edge.norm()) return false;
  }
  return true;
}

/// World-space data of one piece for the narrow phase, built once per detection.
struct PieceView {
  int block = -1;
  int piece = -1;
  const Polyhedron* shape = nullptr;
  const PieceTopology* topology = nullptr;
  const FacePoints* points = nullptr;  ///< sub-contact points (none: nullptr)
  std::vector<Plane> planes;
  Box box;
  Vec3 centroid = Vec3::Zero();
};

inline PieceView view(const std::vector<BlockState>& blocks, int block, int piece) {
  const BlockState& b = blocks[static_cast<std::size_t>(block)];
  const Polyhedron& shape = b.pieces[static_cast<std::size_t>(piece)];
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& v : shape.vertices) centroid += v;
  centroid /= static_cast<double>(shape.vertices.size());
  const FacePoints* points =
      b.face_points.empty() ? nullptr : &b.face_points[static_cast<std::size_t>(piece)];
  return {block,
          piece,
          &shape,
          &b.topology[static_cast<std::size_t>(piece)],
          points,
          facePlanes(shape),
          geometry::bounds(shape),
          centroid};
}

/// A contact entry of `kind` between piece a (the point's) and piece b (the face's), its
/// geometry still to set.
inline Contact pairContact(ContactKind kind, const PieceView& a, const PieceView& b) {
  Contact c;
  c.kind = kind;
  c.block_i = a.block;
  c.piece_i = a.piece;
  c.block_j = b.block;
  c.piece_j = b.piece;
  return c;
}

/// How far from a piece the narrow phase looks (m).
struct Range {
  double gap;    ///< largest open gap recorded: the gap that can close within the step
  double depth;  ///< deepest penetration recorded
  /// How far outside its face a persisting vertex contact's foot may be (m).
  double keep_margin;
  double larger() const { return std::max(gap, depth); }
};

/// A share of the contact area between two blocks, at a corner of the overlap of two faces
/// that face each other; given to the nearest entry of the two blocks on that plane.
struct AreaSample {
  int block_a = -1;       ///< block of the first face
  int block_b = -1;       ///< block of the face whose plane holds `point`
  int piece_a = -1;       ///< piece of block_a
  int piece_b = -1;       ///< piece of block_b
  Vec3 point;             ///< corner of the overlap polygon, in b's face plane (m)
  Vec3 normal;            ///< of b's face, out of b
  double weight = 0.0;    ///< m2
  double distance = 0.0;  ///< farthest an entry may lie from b's plane to take it (m)
};

/// Contact area samples of every pair of facing faces of pieces a and b (corners of their
/// overlap with area weights), or sub-contact point entries where a face has points.
void overlapAreas(const PieceView& a, const PieceView& b, const Range& range, double tolerance,
                  std::vector<AreaSample>& out, std::vector<Contact>& contacts);

/// Gives every entry its share of the contact area (Contact::area), from the samples.
void assignAreas(std::vector<Contact>& contacts, const std::vector<AreaSample>& samples);

}  // namespace rockmass::dda3d::detection
