// The convex cell complex of one region of the exact cutter (cut_parts.h): exact splits of
// convex cells by disc and domain planes, the face provenance of every cell, and the
// optional Nef referee of the region.
#include "blocks/exact/cut_parts.h"

#include <algorithm>
#include <limits>
#include <map>
#include <stdexcept>
#include <unordered_map>

namespace rockmass::blocks::exactcut {

namespace {

/// Conservative double test: may the polygon meet the box?
bool mayMeetBox(const std::vector<Vec3>& polygon, const Box& box) {
  const double margin = 1e-9 * (1.0 + box.diagonal());
  for (int a = 0; a < 3; ++a) {
    double low = std::numeric_limits<double>::infinity();
    double high = -low;
    for (const Vec3& p : polygon) {
      low = std::min(low, p[a]);
      high = std::max(high, p[a]);
    }
    if (high < box.min[a] - margin || low > box.max[a] + margin) return false;
  }
  return true;
}

/// Splits a cell by plane `split` of the table: {negative part, positive part}; a part is
/// empty when the cell lies on one side (touching counts as one side).
std::array<std::optional<Cell>, 2> splitCell(const Cell& cell, int split, const PlaneTable& table) {
  const Plane3& plane = table.planes[static_cast<std::size_t>(split)];
  std::vector<CGAL::Oriented_side> side(cell.vertices.size());
  bool negative = false;
  bool positive = false;
  for (std::size_t i = 0; i < cell.vertices.size(); ++i) {
    side[i] = plane.oriented_side(cell.vertices[i]);
    negative = negative || side[i] == CGAL::ON_NEGATIVE_SIDE;
    positive = positive || side[i] == CGAL::ON_POSITIVE_SIDE;
  }
  if (!negative || !positive) {
    std::array<std::optional<Cell>, 2> out;
    out[positive ? 1 : 0] = cell;
    return out;
  }
  // The face on the other side of each directed edge.
  std::map<std::pair<int, int>, int> face_of_edge;
  for (std::size_t f = 0; f < cell.faces.size(); ++f) {
    const std::vector<int>& ring = cell.faces[f].ring;
    for (std::size_t k = 0; k < ring.size(); ++k) {
      face_of_edge[{ring[k], ring[(k + 1) % ring.size()]}] = static_cast<int>(f);
    }
  }
  std::vector<Point3> points = cell.vertices;
  std::map<std::pair<int, int>, int> crossing;  // edge (low, high) -> new vertex
  const auto crossingVertex = [&](int a, int b, int face) {
    const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
    if (const auto it = crossing.find(key); it != crossing.end()) return it->second;
    const int other = face_of_edge.at({b, a});
    const auto hit = CGAL::intersection(table.planes[cell.faces[face].plane],
                                        table.planes[cell.faces[other].plane], plane);
    const Point3* p = hit ? boost::get<Point3>(&*hit) : nullptr;
    if (p == nullptr) throw std::logic_error("exact cutter: degenerate edge split");
    points.push_back(*p);
    const int index = static_cast<int>(points.size()) - 1;
    crossing.emplace(key, index);
    return index;
  };
  std::array<std::optional<Cell>, 2> out;
  for (int part = 0; part < 2; ++part) {
    const CGAL::Oriented_side keep = part == 0 ? CGAL::ON_NEGATIVE_SIDE : CGAL::ON_POSITIVE_SIDE;
    const auto onPlane = [&](int v) {
      return v >= static_cast<int>(side.size()) || side[v] == CGAL::ON_ORIENTED_BOUNDARY;
    };
    std::vector<Cell::Face> faces;
    std::map<int, int> cap_next;  // cap edge v -> u (reversed face edges on the plane)
    for (std::size_t f = 0; f < cell.faces.size(); ++f) {
      const std::vector<int>& ring = cell.faces[f].ring;
      std::vector<int> kept;
      bool strictly = false;
      for (std::size_t k = 0; k < ring.size(); ++k) {
        const int a = ring[k];
        const int b = ring[(k + 1) % ring.size()];
        if (side[a] == keep || side[a] == CGAL::ON_ORIENTED_BOUNDARY) kept.push_back(a);
        strictly = strictly || side[a] == keep;
        if (side[a] != CGAL::ON_ORIENTED_BOUNDARY && side[b] != CGAL::ON_ORIENTED_BOUNDARY &&
            side[a] != side[b]) {
          kept.push_back(crossingVertex(a, b, static_cast<int>(f)));
        }
      }
      if (!strictly || kept.size() < 3) continue;
      for (std::size_t k = 0; k < kept.size(); ++k) {
        const int u = kept[k];
        const int v = kept[(k + 1) % kept.size()];
        if (onPlane(u) && onPlane(v)) cap_next[v] = u;
      }
      faces.push_back({std::move(kept), cell.faces[f].plane});
    }
    Cell::Face cap;
    cap.plane = split;
    if (!cap_next.empty()) {
      const int first = cap_next.begin()->first;
      int v = first;
      do {
        cap.ring.push_back(v);
        v = cap_next.at(v);
      } while (v != first && cap.ring.size() <= cap_next.size());
    }
    if (cap.ring.size() >= 3) faces.push_back(std::move(cap));
    // Compact the vertices.
    Cell result;
    std::map<int, int> renumber;
    for (Cell::Face& face : faces) {
      for (int& v : face.ring) {
        const auto [it, added] = renumber.try_emplace(v, static_cast<int>(result.vertices.size()));
        if (added) result.vertices.push_back(points[static_cast<std::size_t>(v)]);
        v = it->second;
      }
    }
    result.faces = std::move(faces);
    out[part] = std::move(result);
  }
  return out;
}

/// Conservative double test: may `polygon` meet the interior of the cell (rounded)?
bool polygonMayMeetCell(const std::vector<Vec3>& polygon, const Polyhedron& cell, double margin) {
  std::vector<Vec3> clipped = polygon;
  for (std::size_t f = 0; f < cell.faces.size() && !clipped.empty(); ++f) {
    const Vec3 n = geometry::faceNormal(cell, static_cast<int>(f));
    const double offset = n.dot(cell.vertices[cell.faces[f][0]]) + margin;
    std::vector<Vec3> out;
    for (std::size_t i = 0; i < clipped.size(); ++i) {
      const Vec3& p = clipped[i];
      const Vec3& q = clipped[(i + 1) % clipped.size()];
      const double sp = n.dot(p) - offset;
      const double sq = n.dot(q) - offset;
      if (sp <= 0.0) out.push_back(p);
      if ((sp < 0.0 && sq > 0.0) || (sp > 0.0 && sq < 0.0)) {
        out.push_back(p + (sp / (sp - sq)) * (q - p));
      }
    }
    clipped = std::move(out);
  }
  return !clipped.empty();
}

/// Clips a planar polygon to the box (Sutherland-Hodgman against its six planes, exact).
std::vector<Point3> clipToBox(std::vector<Point3> polygon, const Box& box) {
  for (int axis = 0; axis < 3 && !polygon.empty(); ++axis) {
    for (int side = 0; side < 2 && !polygon.empty(); ++side) {
      const FT bound(side == 0 ? box.min[axis] : box.max[axis]);
      const auto inside = [&](const Point3& p) {
        return side == 0 ? p.cartesian(axis) >= bound : p.cartesian(axis) <= bound;
      };
      std::vector<Point3> out;
      for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Point3& p = polygon[i];
        const Point3& q = polygon[(i + 1) % polygon.size()];
        const bool p_in = inside(p);
        if (p_in) out.push_back(p);
        if (p_in != inside(q)) {
          const FT t = (bound - p.cartesian(axis)) / (q.cartesian(axis) - p.cartesian(axis));
          out.push_back(p + t * (q - p));
        }
      }
      polygon = std::move(out);
    }
  }
  return polygon;
}

/// The rock of a region as a Nef polyhedron: the domain within the region (structures lie
/// outside the rock: checkStructuresOutsideRock).
Nef regionRock(const Context& context, const Box& region) {
  const Box& domain = context.input->domain_box;
  Box clipped{region.min.cwiseMax(domain.min), region.max.cwiseMin(domain.max)};
  Nef rock = nefFromPolyhedron(geometry::boxPolyhedron(clipped));
  if (!context.box_domain) {
    Nef solid;
    for (const Polyhedron& p : context.domain_solids) solid += nefFromPolyhedron(p);
    rock *= solid;
  }
  return rock;
}

/// Projection of a face ring, counter-clockwise, with its bounds.
void projectFace(const std::vector<Point3>& vertices, const std::vector<int>& ring, int drop_axis,
                 FaceRecord& record) {
  record.drop_axis = drop_axis;
  record.bounds = {
      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
      std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  for (const int v : ring) {
    const Point2 q = project(vertices[static_cast<std::size_t>(v)], drop_axis);
    record.polygon.push_back(q);
    const double u = CGAL::to_double(q.x());
    const double w = CGAL::to_double(q.y());
    record.bounds = {std::min(record.bounds[0], u), std::max(record.bounds[1], u),
                     std::min(record.bounds[2], w), std::max(record.bounds[3], w)};
  }
  record.polygon = counterClockwise(std::move(record.polygon));
}

/// Whether a cell face (its ring in `vertices`) lies inside the domain, not on its surface:
/// its interior point is in a marked volume of the domain's Nef polyhedron.
bool insideDomain(const Nef& domain, const std::vector<Point3>& vertices,
                  const std::vector<int>& ring) {
  std::vector<Point3> points;
  for (const int v : ring) points.push_back(vertices[static_cast<std::size_t>(v)]);
  Nef::Volume_const_handle volume;
  return CGAL::assign(volume, domain.locate(interiorPoint(points))) && volume->mark();
}

/// Whether the point is inside the rock: inside the domain (always, for a box domain).
bool insideRock(const Point3& p, const Nef* domain_nef) {
  if (domain_nef == nullptr) return true;
  Nef::Volume_const_handle volume;
  return CGAL::assign(volume, domain_nef->locate(p)) && volume->mark();
}

/// The region's starting cell: the region box with its six axis planes.
Cell startCell(const Context& context, const Box& box, PlaneTable& table) {
  const Polyhedron shape = geometry::boxPolyhedron(box);
  Cell cell;
  for (const Vec3& v : shape.vertices) cell.vertices.push_back(toPoint(v));
  const Box& domain = context.input->domain_box;
  for (int f = 0; f < 6; ++f) {
    const int axis = f / 2;
    const double level = f % 2 == 0 ? box.min[axis] : box.max[axis];
    std::array<double, 3> n{0.0, 0.0, 0.0};
    n[axis] = 1.0;
    const Plane3 plane(n[0], n[1], n[2], -level);
    PlaneTag tag{PlaneTag::RegionFace, -1, axis, level};
    if (level == domain.min[axis] || level == domain.max[axis]) {
      tag.kind = PlaneTag::DomainFace;
      for (std::size_t b = 0; b < context.boundary_planes.size(); ++b) {
        if (isAxisPlane(context.boundary_planes[b].exact, axis, level)) {
          tag.index = static_cast<int>(b);
          break;
        }
      }
    }
    cell.faces.push_back({shape.faces[static_cast<std::size_t>(f)], table.add(plane, tag)});
  }
  return cell;
}

/// The region's convex cells: its box split by every splitting surface (domain surface, the
/// region's discs) that meets a cell.
std::vector<Cell> regionCells(const Context& context, const Region& region, PlaneTable& table) {
  std::vector<Cell> cells{startCell(context, region.box, table)};
  const double margin = 1e-9 * (1.0 + context.input->domain_box.diagonal());
  const auto splitAll = [&](const std::vector<Vec3>& polygon, int plane) {
    std::vector<Cell> next;
    for (Cell& cell : cells) {
      Polyhedron rounded;
      for (const Point3& p : cell.vertices) rounded.vertices.push_back(toVec(p));
      for (const Cell::Face& f : cell.faces) rounded.faces.push_back(f.ring);
      if (!polygonMayMeetCell(polygon, rounded, margin)) {
        next.push_back(std::move(cell));
        continue;
      }
      for (std::optional<Cell>& part : splitCell(cell, plane, table)) {
        if (part) next.push_back(std::move(*part));
      }
    }
    cells = std::move(next);
  };
  for (const Splitter& s : context.surface_splitters) {
    if (!mayMeetBox(s.polygon, region.box)) continue;
    splitAll(s.polygon, table.add(s.plane.exact, s.tag));
  }
  for (const int d : region.discs) {
    const ExactDisc& disc = context.discs[static_cast<std::size_t>(d)];
    splitAll(disc.rounded,
             table.add(disc.plane.exact, {PlaneTag::DiscPlane, context.group_of_disc[d], 0, 0.0}));
  }
  return cells;
}

/// The Nef referee's rock of a region: the region's rock minus its discs.
Nef refereeRock(const Context& context, const Region& region) {
  Nef rock = regionRock(context, region.box);
  for (const int d : region.discs) {
    const std::vector<Point3> clipped =
        clipToBox(context.discs[static_cast<std::size_t>(d)].polygon, region.box);
    if (clipped.size() < 3 || !polygonPlane(clipped)) continue;
    rock -= Nef(clipped.begin(), clipped.end());
  }
  return rock;
}

/// Turns the rock cells of a region into pieces with the provenance of every face, and
/// records the faces to be matched across pieces (FaceRecord).
class PieceExtraction {
 public:
  PieceExtraction(const Context& context, const PlaneTable& table, const Nef* domain_nef,
                  RegionResult& result)
      : context_(context), table_(table), domain_nef_(domain_nef), result_(result) {}

  /// The piece of one cell, appended to result.pieces; its faces' records to result.records.
  Piece piece(const Cell& cell, const Point3& inside, int index) {
    Piece piece;
    for (const Point3& p : cell.vertices) piece.shape.vertices.push_back(toVec(p));
    for (const Cell::Face& face : cell.faces) {
      piece.shape.faces.push_back(face.ring);
      piece.face_sources.push_back(faceSource(cell, face, inside, index));
    }
    return piece;
  }

 private:
  /// A face in the plane of disc group `group`: a Disc face where the group's discs cover it
  /// wholly, else fictitious; recorded for the matching in that plane.
  FaceSource discFace(const Cell& cell, int group, const std::vector<int>& ring,
                      FaceRecord& record) {
    const int first = context_.groups[static_cast<std::size_t>(group)].front();
    const int drop = context_.discs[static_cast<std::size_t>(first)].drop_axis;
    FaceSource source{FaceKind::Fictitious, -1};
    record.plane_key = {1, group, 0.0};
    projectFace(cell.vertices, ring, drop, record);
    if (coveredByGroup(context_, group, record.polygon, drop)) {
      std::vector<Point3> points;
      for (const int v : ring) points.push_back(cell.vertices[static_cast<std::size_t>(v)]);
      const int d = discHolding(context_, group, interiorPoint(points));
      source = {FaceKind::Disc, static_cast<int>(context_.discs[static_cast<std::size_t>(d)].id)};
    }
    record.source = source;
    result_.records.push_back(std::move(record));
    return source;
  }

  /// A face on a plane of the domain surface. A mesh face's full plane also cuts the rock
  /// inside the domain: only the faces on the surface are Boundary; the others are matched in
  /// their plane. (A face on the domain's bounding box is never inside it, so tag.index >= 0.)
  FaceSource domainFace(const Cell& cell, const Cell::Face& face, const PlaneTag& tag,
                        const Point3& inside, FaceRecord& record) {
    if (domain_nef_ == nullptr || !insideDomain(*domain_nef_, cell.vertices, face.ring)) {
      return {FaceKind::Boundary, tag.index};
    }
    if (const int group = context_.boundary_group[tag.index]; group >= 0) {
      return discFace(cell, group, face.ring, record);
    }
    const int canonical = context_.boundary_canonical[tag.index];
    const KnownPlane& plane = context_.boundary_planes[canonical];
    int drop = 0;
    plane.normal.cwiseAbs().maxCoeff(&drop);
    record.plane_key = {2, canonical, 0.0};
    record.above = plane.exact.oriented_side(inside) == CGAL::ON_POSITIVE_SIDE;
    projectFace(cell.vertices, face.ring, drop, record);
    result_.records.push_back(std::move(record));
    return {FaceKind::Fictitious, -1};
  }

  FaceSource faceSource(const Cell& cell, const Cell::Face& face, const Point3& inside, int index) {
    const PlaneTag& tag = table_.tags[static_cast<std::size_t>(face.plane)];
    FaceRecord record;
    record.piece = index;
    record.above = table_.planes[static_cast<std::size_t>(face.plane)].oriented_side(inside) ==
                   CGAL::ON_POSITIVE_SIDE;
    switch (tag.kind) {
      case PlaneTag::RegionFace:
        record.plane_key = {0, tag.axis, tag.level};
        projectFace(cell.vertices, face.ring, tag.axis, record);
        result_.records.push_back(std::move(record));
        return {FaceKind::Fictitious, -1};
      case PlaneTag::DomainFace:
        return domainFace(cell, face, tag, inside, record);
      case PlaneTag::DiscPlane:
        return discFace(cell, tag.index, face.ring, record);
    }
    return {FaceKind::Fictitious, -1};
  }

  const Context& context_;
  const PlaneTable& table_;
  const Nef* domain_nef_;
  RegionResult& result_;
};

}  // namespace

Point3 interiorPoint(const std::vector<Point3>& vertices) {
  FT sx = 0, sy = 0, sz = 0;
  for (const Point3& p : vertices) {
    sx += p.x();
    sy += p.y();
    sz += p.z();
  }
  const FT n(static_cast<int>(vertices.size()));
  return Point3(sx / n, sy / n, sz / n);
}

RegionResult cutRegion(const Context& context, const Region& region, bool exact_volume,
                       bool nef_referee) {
  RegionResult result;
  auto start = Clock::now();
  PlaneTable table;
  const std::vector<Cell> cells = regionCells(context, region, table);
  result.decompose_seconds = secondsSince(start);

  std::optional<Nef> domain_nef;
  if (!context.box_domain) {
    domain_nef.emplace();
    for (const Polyhedron& solid : context.domain_solids) *domain_nef += nefFromPolyhedron(solid);
  }
  std::optional<Nef> rock;
  if (nef_referee) {
    start = Clock::now();
    rock = refereeRock(context, region);
    result.nef_seconds = secondsSince(start);
  }

  start = Clock::now();
  PieceExtraction extraction(context, table, domain_nef ? &*domain_nef : nullptr, result);
  std::unordered_map<const void*, int> piece_of_volume;
  for (const Cell& cell : cells) {
    const Point3 inside = interiorPoint(cell.vertices);
    if (!insideRock(inside, domain_nef ? &*domain_nef : nullptr)) continue;
    const int index = static_cast<int>(result.pieces.size());
    if (rock) {
      Nef::Volume_const_handle volume;
      if (CGAL::assign(volume, rock->locate(inside))) {
        const auto [it, added] = piece_of_volume.try_emplace(&*volume, index);
        if (!added) result.nef_links.emplace_back(it->second, index);
      }
    }
    Piece piece = extraction.piece(cell, inside, index);
    if (exact_volume) result.exact_volume += exactVolume(cell.vertices, piece.shape.faces);
    result.pieces.push_back(std::move(piece));
  }
  result.extract_seconds = secondsSince(start);
  return result;
}

}  // namespace rockmass::blocks::exactcut
