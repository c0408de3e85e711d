// Closed polyhedra made of planar polygonal faces, and their exact mass properties. Shared by
// the block cutters (blocks/), the DDA engine (dda3d/) and the writers (io/).
#pragma once

#include <vector>

#include "geometry/box.h"
#include "geometry/vec.h"

namespace rockmass::geometry {

/// A closed polyhedron: vertices and planar faces. Each face lists vertex indices
/// counter-clockwise seen from outside, so the right-hand normal points out. The cutters
/// give convex pieces; the type itself does not require convexity.
struct Polyhedron {
  std::vector<Vec3> vertices;           ///< m
  std::vector<std::vector<int>> faces;  ///< vertex indices, CCW seen from outside
};

/// Volume integrals of a solid: V = integral of 1, first = integral of x, and
/// second = integral of x x^T, all over the solid and about the global origin.
struct MassProperties {
  double volume = 0.0;                               ///< m3
  Vec3 first = Vec3::Zero();                         ///< m4
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  ///< m5

  /// Centroid first / volume (m); undefined for zero volume.
  Vec3 centroid() const { return first / volume; }
  /// Second moments about the centroid, integral of (x - c)(x - c)^T (m5).
  Eigen::Matrix3d centralSecond() const {
    const Vec3 c = centroid();
    return second - volume * c * c.transpose();
  }
  MassProperties& operator+=(const MassProperties& other) {
    volume += other.volume;
    first += other.first;
    second += other.second;
    return *this;
  }
};

/// Exact mass properties of a closed, outward-oriented polyhedron by the divergence theorem:
/// each face is fanned into triangles, each triangle with a reference point r forms a signed
/// tetrahedron, and for a tetrahedron p0..p3 of volume V the integral of x x^T is
/// V/20 (sum p_i p_i^T + (sum p_i)(sum p_i)^T) (Tonon 2004, J. Math. Stat. 1, 8-11).
/// The reference point is the first vertex, which keeps round-off relative to the piece's
/// size rather than its distance from the origin. Faces may be non-convex polygons as long
/// as they are planar.
MassProperties massProperties(const Polyhedron& polyhedron);

/// The same integrals taken about `reference` instead of the origin (of x - reference).
/// Summing the pieces of a block about a point of the block keeps the central second
/// moments accurate for a thin block far from the origin, where the shift to the origin
/// and back (second - V c c^T) would cancel all their digits.
MassProperties massProperties(const Polyhedron& polyhedron, const Vec3& reference);

/// Axis-aligned bounding box of the vertices.
Box bounds(const Polyhedron& polyhedron);

/// The box as a polyhedron: 8 vertices, 6 quadrilateral faces in the order
/// x_min, x_max, y_min, y_max, z_min, z_max.
Polyhedron boxPolyhedron(const Box& box);

/// Outward unit normal of face `face` (Newell's method, robust for any planar polygon).
Vec3 faceNormal(const Polyhedron& polyhedron, int face);

}  // namespace rockmass::geometry
