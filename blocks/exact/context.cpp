// The exact cutter's context (cut_parts.h): exact planes, discs lifted exactly onto their
// planes, disc groups by plane, and the planes of the domain surface.
#include "blocks/exact/cut_parts.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace rockmass::blocks::exactcut {

namespace {

/// True when every point lies exactly on `plane`; a quick double test rejects most planes.
bool allOnPlane(const KnownPlane& plane, const Vec3& approx_normal, double approx_offset,
                const std::vector<Point3>& points, double tolerance) {
  const double cosine = plane.normal.dot(approx_normal);
  if (std::abs(cosine) < 1.0 - 1e-9) return false;
  if (std::abs(approx_offset - (cosine > 0 ? plane.offset : -plane.offset)) > tolerance) {
    return false;
  }
  return std::all_of(points.begin(), points.end(),
                     [&](const Point3& p) { return plane.exact.has_on(p); });
}

/// The disc's outline as an exactly planar polygon. An interlayer segment (a rectangle swept
/// along x or y: its vertices are exactly coplanar in double) is kept as given, on the plane
/// through its vertices: the segments of an interlayer surface share their knee edges exactly,
/// and lifting each onto its own plane would open round-off windows (1e-13 m2) between them
/// through which the slab would glue to the rock. Any other outline is lifted exactly onto
/// the plane through the centre: each vertex keeps two coordinates and gets the third (along
/// the normal's largest component) solved from the plane equation in rational arithmetic.
ExactDisc makeExactDisc(const geometry::Disc& disc, int segments) {
  ExactDisc out;
  out.id = disc.id;
  out.bounds.min = Vec3::Constant(std::numeric_limits<double>::infinity());
  out.bounds.max = -out.bounds.min;
  const std::vector<Vec3> outline = disc.outline(segments);
  const auto add = [&](const Point3& p, const Vec3& v) {
    if (!out.polygon.empty() && (out.polygon.back() == p || out.polygon.front() == p)) return;
    out.polygon.push_back(p);
    out.rounded.push_back(v);
    out.bounds.min = out.bounds.min.cwiseMin(v);
    out.bounds.max = out.bounds.max.cwiseMax(v);
  };
  std::optional<Plane3> given;
  if (!disc.polygon.empty() && disc.origin == geometry::DiscOrigin::Interlayer) {
    std::vector<Point3> points;
    for (const Vec3& v : outline) points.push_back(toPoint(v));
    given = polygonPlane(points);
    if (given && !std::all_of(points.begin(), points.end(),
                              [&](const Point3& p) { return given->has_on(p); })) {
      given.reset();
    }
  }
  if (given) {
    out.plane = knownPlane(*given);
    if (out.plane.normal.dot(disc.normal) < 0.0) out.plane = knownPlane(given->opposite());
    out.plane.normal.cwiseAbs().maxCoeff(&out.drop_axis);
    for (const Vec3& v : outline) add(toPoint(v), v);
  } else {
    const Vec3 n = disc.normal;
    const double w = -n.dot(disc.center);
    const Plane3 plane(n.x(), n.y(), n.z(), w);
    int k = 0;
    n.cwiseAbs().maxCoeff(&k);
    out.drop_axis = k;
    out.plane = knownPlane(plane);
    for (const Vec3& v : outline) {
      std::array<FT, 3> c{FT(v.x()), FT(v.y()), FT(v.z())};
      FT rest = FT(w);
      for (int j = 0; j < 3; ++j) {
        if (j != k) rest += FT(n[j]) * c[j];
      }
      c[k] = -rest / FT(n[k]);
      add(Point3(c[0], c[1], c[2]), v);
    }
  }
  for (const Point3& p : out.polygon) out.polygon2d.push_back(project(p, out.drop_axis));
  for (const Point2& p : out.polygon2d) {
    out.ccw2d.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()));
  }
  double twice = 0.0;
  for (std::size_t i = 0; i < out.ccw2d.size(); ++i) {
    const Eigen::Vector2d& a = out.ccw2d[i];
    const Eigen::Vector2d& b = out.ccw2d[(i + 1) % out.ccw2d.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  if (twice < 0.0) std::reverse(out.ccw2d.begin(), out.ccw2d.end());
  return out;
}

/// Planes of every face of `solid` (a plane that matches nothing for a degenerate face).
std::vector<KnownPlane> facePlanes(const Polyhedron& solid) {
  std::vector<KnownPlane> planes;
  for (const std::vector<int>& face : solid.faces) {
    std::vector<Point3> points;
    for (const int v : face) points.push_back(toPoint(solid.vertices[v]));
    const auto plane = polygonPlane(points);
    planes.push_back(knownPlane(plane ? *plane : Plane3(0, 0, 1, -1e300)));
  }
  return planes;
}

/// The vertices of one face (m).
std::vector<Vec3> facePolygon(const Polyhedron& solid, std::size_t face) {
  std::vector<Vec3> polygon;
  for (const int v : solid.faces[face]) polygon.push_back(solid.vertices[v]);
  return polygon;
}

/// Fills context.boundary_canonical and boundary_group (mesh domains): the full plane of a
/// surface face also splits the rock inside the domain, and the cell faces it makes there are
/// matched by plane (a mesh's coplanar faces are one plane) like region faces, or like disc
/// faces when a disc group lies in that plane.
void linkBoundaryPlanes(Context& context) {
  std::vector<std::vector<Point3>> points;
  for (const Polyhedron& solid : context.domain_solids) {
    for (std::size_t f = 0; f < solid.faces.size(); ++f) {
      std::vector<Point3> face;
      for (const int v : solid.faces[f]) face.push_back(toPoint(solid.vertices[v]));
      points.push_back(std::move(face));
    }
  }
  const std::size_t count = context.boundary_planes.size();
  context.boundary_canonical.assign(count, -1);
  context.boundary_group.assign(count, -1);
  for (std::size_t b = 0; b < count; ++b) {
    const KnownPlane& plane = context.boundary_planes[b];
    for (std::size_t c = 0; c < b && context.boundary_canonical[b] < 0; ++c) {
      if (context.boundary_canonical[c] == static_cast<int>(c) &&
          allOnPlane(context.boundary_planes[c], plane.normal, plane.offset, points[b],
                     context.tolerance)) {
        context.boundary_canonical[b] = static_cast<int>(c);
      }
    }
    if (context.boundary_canonical[b] >= 0) {
      context.boundary_group[b] =
          context.boundary_group[static_cast<std::size_t>(context.boundary_canonical[b])];
      continue;
    }
    context.boundary_canonical[b] = static_cast<int>(b);
    for (std::size_t g = 0; g < context.groups.size(); ++g) {
      const ExactDisc& first = context.discs[static_cast<std::size_t>(context.groups[g].front())];
      if (allOnPlane(first.plane, plane.normal, plane.offset, points[b], context.tolerance)) {
        context.boundary_group[b] = static_cast<int>(g);
        break;
      }
    }
  }
}

}  // namespace

KnownPlane knownPlane(const Plane3& plane) {
  const Vec3 n(CGAL::to_double(plane.a()), CGAL::to_double(plane.b()), CGAL::to_double(plane.c()));
  const double length = n.norm();
  return {plane, n / length, -CGAL::to_double(plane.d()) / length};
}

/// Plane of a planar polygon through its first non-collinear vertex triple.
std::optional<Plane3> polygonPlane(const std::vector<Point3>& polygon) {
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
    if (!CGAL::collinear(polygon[0], polygon[i], polygon[i + 1])) {
      return Plane3(polygon[0], polygon[i], polygon[i + 1]);
    }
  }
  return std::nullopt;
}

/// Drops coordinate `axis` of p.
Point2 project(const Point3& p, int axis) {
  switch (axis) {
    case 0:
      return Point2(p.y(), p.z());
    case 1:
      return Point2(p.z(), p.x());
    default:
      return Point2(p.x(), p.y());
  }
}

/// Conservative double test: may the disc's polygon meet the box?
bool mayMeet(const ExactDisc& disc, const Box& box) {
  const double margin = 1e-9 * (1.0 + box.diagonal());
  for (int a = 0; a < 3; ++a) {
    if (disc.bounds.max[a] < box.min[a] - margin || disc.bounds.min[a] > box.max[a] + margin) {
      return false;
    }
  }
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner((i & 1) ? box.max.x() : box.min.x(), (i & 2) ? box.max.y() : box.min.y(),
                      (i & 4) ? box.max.z() : box.min.z());
    const double s = disc.plane.normal.dot(corner) - disc.plane.offset;
    low = std::min(low, s);
    high = std::max(high, s);
  }
  return low <= margin && high >= -margin;
}

/// True when an axis-aligned plane coordinate[axis] == level coincides with the plane.
bool isAxisPlane(const Plane3& plane, int axis, double level) {
  const std::array<FT, 3> n{plane.a(), plane.b(), plane.c()};
  for (int j = 0; j < 3; ++j) {
    if (j != axis && n[j] != 0) return false;
  }
  return n[axis] * FT(level) + plane.d() == 0;
}

Context makeContext(const CutInput& input) {
  Context context;
  context.input = &input;
  context.tolerance = 1e-7 * (1.0 + input.domain_box.diagonal());
  if (!input.domain_surface.faces.empty()) {
    context.domain_solids.push_back(input.domain_surface);
  } else {
    context.domain_solids = input.domain_pieces;
  }
  if (context.domain_solids.empty()) {
    throw std::invalid_argument("exact cutter: the input has no domain");
  }
  if (input.disc_segments < 3) {
    throw std::invalid_argument("exact cutter: disc_segments must be at least 3, got " +
                                std::to_string(input.disc_segments));
  }
  const Box first = geometry::bounds(context.domain_solids.front());
  context.box_domain = input.domain_surface.faces.empty() && context.domain_solids.size() == 1 &&
                       context.domain_solids.front().faces.size() == 6 &&
                       first.min == input.domain_box.min && first.max == input.domain_box.max;
  for (const Polyhedron& solid : context.domain_solids) {
    const std::vector<KnownPlane> planes = facePlanes(solid);
    for (std::size_t f = 0; f < planes.size(); ++f) {
      if (!context.box_domain) {
        const int id = static_cast<int>(context.boundary_planes.size());
        context.surface_splitters.push_back(
            {facePolygon(solid, f), planes[f], {PlaneTag::DomainFace, id, 0, 0.0}});
      }
      context.boundary_planes.push_back(planes[f]);
    }
  }
  if (input.network != nullptr) {
    for (const geometry::Disc& disc : input.network->discs) {
      if (!disc.cuts) continue;
      ExactDisc exact = makeExactDisc(disc, input.disc_segments);
      if (exact.polygon.size() >= 3 && mayMeet(exact, input.domain_box)) {
        context.discs.push_back(std::move(exact));
      }
    }
  }
  // Discs in one plane form a group: their union is what covers a face.
  for (std::size_t d = 0; d < context.discs.size(); ++d) {
    const ExactDisc& disc = context.discs[d];
    int group = -1;
    for (std::size_t g = 0; g < context.groups.size() && group < 0; ++g) {
      const ExactDisc& first = context.discs[static_cast<std::size_t>(context.groups[g].front())];
      if (allOnPlane(first.plane, disc.plane.normal, disc.plane.offset, disc.polygon,
                     context.tolerance)) {
        group = static_cast<int>(g);
      }
    }
    if (group < 0) {
      group = static_cast<int>(context.groups.size());
      context.groups.emplace_back();
    }
    context.groups[static_cast<std::size_t>(group)].push_back(static_cast<int>(d));
    context.group_of_disc.push_back(group);
  }
  if (!context.box_domain) linkBoundaryPlanes(context);
  return context;
}

}  // namespace rockmass::blocks::exactcut
