#pragma once
/// A fracture: an elliptical disc, or a planar polygon given exactly (FAB files, interlayers).
#include <cstdint>
#include <optional>
#include <vector>

#include "geometry/box.h"
#include "geometry/vec.h"

namespace rockmass::geometry {

/// Where a disc came from.
enum class DiscOrigin { JointSet, Fault, Interlayer, FabFile };

/// A fracture surface. Ellipse form: centre, normal, major axis and semi-axes a >= b.
/// Polygon form (`polygon` not empty): the polygon is the fracture, exactly as given; the
/// ellipse fields then describe it approximately (centroid, Newell normal, a = largest
/// centroid-to-vertex distance along `major`, b = area / (pi a)).
struct Disc {
  std::int64_t id = 0;  ///< stable id, born at generation (1-based), kept by every stage
  int set = 0;          ///< index into FractureNetwork::sets
  int joint = 0;        ///< index of the joint (strength) properties in the scene
  DiscOrigin origin = DiscOrigin::JointSet;  ///< what made it
  Vec3 center = Vec3::Zero();                ///< centre (m)
  Vec3 normal = Vec3::UnitZ();               ///< unit normal (sign carries no meaning)
  Vec3 major = Vec3::UnitX();                ///< unit vector along the major axis, in the plane
  double a = 0.0;                            ///< semi-major axis (m)
  double b = 0.0;                            ///< semi-minor axis (m), b <= a
  bool cuts = true;                          ///< false: counts for RQD but does not cut blocks
  std::vector<Vec3> polygon;  ///< exact polygon (m) for polygon-form discs, else empty

  /// Unit vector along the minor axis: normal x major.
  Vec3 minor() const { return normal.cross(major); }
  /// Area of one face (m2): pi a b, or the polygon's area.
  double area() const;
  /// The fracture as a closed polygon: the exact polygon, or `segments` points on the
  /// ellipse (counter-clockwise about `normal`, first point at +a along `major`).
  std::vector<Vec3> outline(int segments) const;
  /// Distance t along `origin + t * dir` at which the line crosses the fracture, or nothing
  /// when it misses (or runs parallel to the plane). `dir` need not be unit length.
  std::optional<double> intersectLine(const Vec3& origin, const Vec3& dir) const;
  /// Area (m2) of the part of the fracture inside `box`: exact for polygons; for ellipses
  /// a 128-gon scaled to the ellipse's exact area is clipped (relative error below 1e-3).
  double areaInside(const Box& box) const;
  /// The polygon areaInside clips (m): the exact polygon, or a 128-gon scaled about the
  /// centre to exactly pi a b. Clipping it once per disc lets callers measure many boxes.
  std::vector<Vec3> areaOutline() const;
  /// Axis-aligned bounding box (m): exact for ellipses (from the semi-axes) and polygons.
  Box bounds() const;
};

/// Area of a planar polygon (m2), by Newell's method.
double polygonArea(const std::vector<Vec3>& polygon);
/// Newell normal of a planar polygon (unit; zero for a degenerate polygon).
Vec3 polygonNormal(const std::vector<Vec3>& polygon);
/// Area-weighted centroid of a planar polygon (m).
Vec3 polygonCentroid(const std::vector<Vec3>& polygon);
/// Clips a planar polygon to a box (Sutherland-Hodgman against the six faces).
std::vector<Vec3> clipPolygonToBox(const std::vector<Vec3>& polygon, const Box& box);
/// A polygon-form disc with the ellipse fields filled in as described for Disc.
/// Throws std::invalid_argument when the polygon has fewer than 3 points or no area.
Disc discFromPolygon(std::vector<Vec3> polygon);

}  // namespace rockmass::geometry
