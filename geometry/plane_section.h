#pragma once
/// Sections through 3D geometry: a convex polyhedron cut by a plane gives a convex polygon, a
/// fracture (ellipse or planar polygon) gives trace segments. Used for the vertical section
/// through the block model (Figure 5 of the Xiangjiaba paper).
#include <optional>
#include <utility>
#include <vector>

#include "geometry/box.h"
#include "geometry/disc.h"
#include "geometry/polyhedron.h"
#include "geometry/vec.h"

namespace rockmass::geometry {

/// A section plane with an orthonormal in-plane frame (points in the plane are Vec2 (u, v)): a
/// point p maps to (u, v) = ((p - origin) . u_axis, (p - origin) . v_axis).
struct SectionPlane {
  Vec3 origin = Vec3::Zero();   ///< a point of the plane (m)
  Vec3 normal = Vec3::UnitY();  ///< unit normal
  Vec3 u_axis = Vec3::UnitX();  ///< unit, in the plane
  Vec3 v_axis = Vec3::UnitZ();  ///< unit, in the plane, normal to u_axis

  /// Signed distance of p from the plane along `normal` (m).
  double distance(const Vec3& p) const { return normal.dot(p - origin); }
  /// In-plane coordinates of p (its projection onto the plane).
  Vec2 project(const Vec3& p) const { return {u_axis.dot(p - origin), v_axis.dot(p - origin)}; }
  /// The 3D point of in-plane coordinates q.
  Vec3 lift(const Vec2& q) const { return origin + q.x() * u_axis + q.y() * v_axis; }
};

/// The plane where coordinate `axis` (0 = x, 1 = y, 2 = z) equals `offset`, with in-plane
/// coordinates that are plain world coordinates: (u, v) = (y, z) for x, (x, z) for y (a
/// vertical section looking North), (x, y) for z (a plan). Throws std::invalid_argument for
/// an axis outside 0..2.
SectionPlane axisPlane(int axis, double offset);

/// A convex polygon cut from a convex polyhedron, counter-clockwise in (u, v).
struct PolygonSection {
  std::vector<Vec2> points;  ///< corners, counter-clockwise, no repeats
  /// Per edge (points[k] -> points[k + 1], cyclically): the polyhedron face it lies in.
  std::vector<int> edge_faces;
};

/// What sectionPolyhedron gives for a polyhedron that has a face in the plane.
enum class FaceInPlane {
  Skip,   ///< nothing: the plane only touches it
  Above,  ///< the face, when the polyhedron lies on the plane's positive side: the section
          ///< just above the plane. The sections of a partition into polyhedra then tile the
          ///< plane even where it coincides with their faces (a cut or a region face).
};

/// The section of a convex polyhedron by `plane`, or nothing when the plane does not cross
/// its interior: a plane that only touches it (at a vertex, along an edge, or over a whole
/// face with FaceInPlane::Skip, within `tolerance` metres) gives nothing, so that a face
/// shared by two pieces is not drawn twice. With FaceInPlane::Above, a face in the plane of
/// a polyhedron on the positive side is its section (its edges lie in the neighbouring faces).
std::optional<PolygonSection> sectionPolyhedron(const Polyhedron& polyhedron,
                                                const SectionPlane& plane, double tolerance = 1e-9,
                                                FaceInPlane face_in_plane = FaceInPlane::Skip);

/// The trace of a fracture in `plane`, clipped to `box`: zero, one or (for a non-convex
/// polygon) several segments, as (u, v) end points. `segments` = 0 cuts the exact ellipse;
/// > 0 cuts disc.outline(segments), the polygon the block cutters use. A fracture parallel
/// to the plane has no trace.
std::vector<std::pair<Vec2, Vec2>> sectionTrace(const Disc& disc, const SectionPlane& plane,
                                                const Box& box, int segments = 0);

/// Signed area of a polygon in the plane (m2; > 0 when counter-clockwise).
double signedArea(const std::vector<Vec2>& polygon);

}  // namespace rockmass::geometry
