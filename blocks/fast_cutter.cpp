#include "blocks/fast_cutter.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "blocks/convex_partition.h"
#include "blocks/convex_split.h"
#include "geometry/disc.h"

namespace rockmass::blocks {
namespace {

using geometry::Box;
using geometry::Vec2;

/// A convex cutting polygon: (part of) one disc.
struct CutPolygon {
  int disc_id = 0;
  Plane plane;               ///< the disc's plane
  std::vector<Vec3> points;  ///< counter-clockwise about plane.normal
  std::vector<Plane> edges;  ///< per edge: perpendicular to the disc, normal pointing inside
  Box box;                   ///< bounding box of the points
};

/// The convex cutting polygons of one disc.
void addCutPolygons(const geometry::Disc& disc, int segments, double tolerance,
                    std::vector<CutPolygon>& out) {
  std::vector<Vec3> outline = disc.outline(segments);
  const Vec3 n = disc.normal.normalized();
  const Plane plane = Plane::through(disc.center, n);
  // FAB polygons are used as given, up to their tiny departures from planarity.
  for (Vec3& p : outline) p -= plane.distance(p) * n;
  if (geometry::polygonNormal(outline).dot(n) < 0.0) std::reverse(outline.begin(), outline.end());
  const Vec3 u = n.unitOrthogonal();
  const Vec3 w = n.cross(u);
  std::vector<Vec2> flat;
  for (const Vec3& p : outline)
    flat.emplace_back((p - disc.center).dot(u), (p - disc.center).dot(w));
  for (const std::vector<int>& part : convexPartition(flat)) {
    CutPolygon polygon;
    polygon.disc_id = static_cast<int>(disc.id);
    polygon.plane = plane;
    for (int i : part) polygon.points.push_back(outline[i]);
    const std::size_t m = polygon.points.size();
    polygon.box = {Vec3::Constant(std::numeric_limits<double>::infinity()),
                   Vec3::Constant(-std::numeric_limits<double>::infinity())};
    for (std::size_t k = 0; k < m; ++k) {
      const Vec3& p = polygon.points[k];
      const Vec3& q = polygon.points[(k + 1) % m];
      polygon.box.min = polygon.box.min.cwiseMin(p);
      polygon.box.max = polygon.box.max.cwiseMax(p);
      const Vec3 inward = n.cross(q - p);
      if (inward.norm() <= tolerance) continue;  // a degenerate edge cuts nothing
      polygon.edges.push_back(Plane::through(p, inward.normalized()));
    }
    out.push_back(std::move(polygon));
  }
}

/// The live pieces and a uniform grid over their bounding boxes, for the query "which pieces
/// may meet this polygon". Dead pieces are dropped from the cells lazily.
class PieceStore {
 public:
  PieceStore(const Box& domain, std::size_t polygons) : domain_(domain) {
    const Vec3 size = domain.size().cwiseMax(1e-300);
    const double target = std::clamp(2.0 * static_cast<double>(polygons), 1.0, 262144.0);
    const double cell = std::cbrt(size.prod() / target);
    for (int a = 0; a < 3; ++a) {
      dims_[a] = std::clamp(static_cast<int>(std::ceil(size[a] / cell)), 1, 256);
      cell_size_[a] = size[a] / dims_[a];
    }
    cells_.resize(static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2]);
  }

  int add(Piece piece) {
    const int id = static_cast<int>(pieces_.size());
    boxes_.push_back(geometry::bounds(piece.shape));
    pieces_.push_back(std::move(piece));
    alive_.push_back(1);
    seen_.push_back(-1);
    forCells(boxes_.back(), [&](std::vector<int>& cell) { cell.push_back(id); });
    return id;
  }
  void kill(int id) {
    alive_[id] = 0;
    pieces_[id] = Piece{};
  }
  const Piece& piece(int id) const { return pieces_[id]; }
  const Box& box(int id) const { return boxes_[id]; }

  /// Live pieces whose boxes meet `box`, ascending.
  std::vector<int> query(const Box& box) {
    ++stamp_;
    std::vector<int> found;
    forCells(box, [&](std::vector<int>& cell) {
      std::erase_if(cell, [&](int id) { return !alive_[id]; });
      for (int id : cell) {
        if (seen_[id] == stamp_) continue;
        seen_[id] = stamp_;
        const Box& b = boxes_[id];
        if ((b.min.array() <= box.max.array()).all() && (box.min.array() <= b.max.array()).all()) {
          found.push_back(id);
        }
      }
    });
    std::sort(found.begin(), found.end());
    return found;
  }

  /// The live pieces in creation order.
  std::vector<Piece> takeAlive() {
    std::vector<Piece> out;
    for (std::size_t i = 0; i < pieces_.size(); ++i) {
      if (alive_[i]) out.push_back(std::move(pieces_[i]));
    }
    return out;
  }

 private:
  template <class F>
  void forCells(const Box& box, F&& f) {
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] =
          std::clamp(static_cast<int>(std::floor((box.min[a] - domain_.min[a]) / cell_size_[a])), 0,
                     dims_[a] - 1);
      hi[a] =
          std::clamp(static_cast<int>(std::floor((box.max[a] - domain_.min[a]) / cell_size_[a])), 0,
                     dims_[a] - 1);
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x)
          f(cells_[(static_cast<std::size_t>(z) * dims_[1] + y) * dims_[0] + x]);
  }

  Box domain_;
  int dims_[3] = {1, 1, 1};
  double cell_size_[3] = {1, 1, 1};
  std::vector<std::vector<int>> cells_;
  std::vector<Piece> pieces_;
  std::vector<Box> boxes_;
  std::vector<char> alive_;
  std::vector<int> seen_;
  int stamp_ = 0;
};

/// True when the box lies more than `tolerance` on one side of the plane.
bool boxMissesPlane(const Box& box, const Plane& plane, double tolerance) {
  const Vec3 c = box.center();
  const Vec3 h = 0.5 * box.size();
  const double reach = h.dot(plane.normal.cwiseAbs());
  return std::abs(plane.distance(c)) > reach + tolerance;
}

/// Cuts one piece by one polygon. Returns the pieces that replace it, or nothing when the
/// polygon leaves it unchanged.
std::optional<std::vector<Piece>> cutPiece(const Piece& piece, const CutPolygon& polygon,
                                           const CutTolerances& tol, FastCutReport& report) {
  const Section section = planeSection(piece, polygon.plane, tol.distance);
  if (section.kind == SectionKind::None) return std::nullopt;
  // A disc on a face that is already real (boundary, structure, another crack) adds nothing.
  if (section.kind == SectionKind::OnFace &&
      piece.face_sources[section.face].kind != FaceKind::Fictitious) {
    return std::nullopt;
  }
  // Does the polygon cover any of the section?
  std::vector<Vec3> covered = section.polygon;
  for (const Plane& edge : polygon.edges) {
    covered = clipPolygon(covered, edge);
    if (covered.size() < 3) return std::nullopt;
  }
  if (geometry::polygonArea(covered) <= tol.area) return std::nullopt;

  std::vector<Piece> out;
  Piece core = piece;
  std::vector<Vec3> core_section = section.polygon;
  for (const Plane& edge : polygon.edges) {
    double lowest = 0.0;
    for (const Vec3& p : core_section) lowest = std::min(lowest, edge.distance(p));
    if (lowest >= -tol.distance) continue;  // the section is inside this edge's half-plane
    if (std::optional<SplitPieces> split =
            splitPiece(core, edge, tol.distance, {FaceKind::Fictitious, -1})) {
      ++report.splits;
      out.push_back(std::move(split->below));  // outside the polygon: not cut by the disc
      core = std::move(split->above);
    }
    core_section = clipPolygon(core_section, edge);
  }
  const FaceSource disc{FaceKind::Disc, polygon.disc_id};
  if (section.kind == SectionKind::Crossing) {
    if (std::optional<SplitPieces> split = splitPiece(core, polygon.plane, tol.distance, disc)) {
      ++report.splits;
      out.push_back(std::move(split->below));
      out.push_back(std::move(split->above));
    } else {
      out.push_back(std::move(core));
    }
  } else {
    // The disc lies on a face: its part inside the polygon becomes a crack, unless it is
    // already one or lies on the domain boundary or a structure.
    bool relabelled = false;
    for (std::size_t f = 0; f < core.shape.faces.size(); ++f) {
      if (core.face_sources[f].kind != FaceKind::Fictitious) continue;
      const std::vector<int>& face = core.shape.faces[f];
      const bool on = std::all_of(face.begin(), face.end(), [&](int v) {
        return std::abs(polygon.plane.distance(core.shape.vertices[v])) <= tol.distance;
      });
      if (on) {
        core.face_sources[f] = disc;
        relabelled = true;
      }
    }
    if (out.empty() && !relabelled) return std::nullopt;
    out.push_back(std::move(core));
  }
  return out;
}

/// Throws when a structure piece overlaps the rock domain by more than a sliver.
void checkStructuresOutsideRock(const CutInput& input, const CutTolerances& tol) {
  for (std::size_t s = 0; s < input.structures.size(); ++s) {
    for (const geometry::Polyhedron& shape : input.structures[s].pieces) {
      for (const geometry::Polyhedron& domain : input.domain_pieces) {
        // Clip the structure piece by the domain piece's face planes.
        Piece inside{shape, std::vector<FaceSource>(shape.faces.size())};
        bool empty = false;
        for (std::size_t f = 0; f < domain.faces.size() && !empty; ++f) {
          const Plane plane = Plane::through(domain.vertices[domain.faces[f][0]],
                                             geometry::faceNormal(domain, static_cast<int>(f)));
          const Section section = planeSection(inside, plane, tol.distance);
          if (section.kind == SectionKind::Crossing) {
            inside = splitPiece(inside, plane, tol.distance, {})->below;
          } else {
            // Not crossed: wholly inside or wholly outside this face's half-space.
            const Vec3 c = geometry::massProperties(inside.shape).centroid();
            empty = plane.distance(c) > 0.0;
          }
        }
        if (!empty &&
            geometry::massProperties(inside.shape).volume > tol.area * tol.distance * 1e6) {
          throw std::invalid_argument("structure " + std::to_string(s + 1) +
                                      " overlaps the rock domain; the cutters need structures "
                                      "that stand on or beside the rock, not in it");
        }
      }
    }
  }
}

}  // namespace

BlockModel cutFast(const CutInput& input, FastCutReport* report) {
  if (input.domain_pieces.empty()) throw std::invalid_argument("cutFast: no domain piece");
  if (input.network == nullptr) throw std::invalid_argument("cutFast: no fracture network");
  if (input.disc_segments < 3) throw std::invalid_argument("cutFast: disc_segments < 3");
  const CutTolerances tol = cutTolerances(input.domain_box);
  checkStructuresOutsideRock(input, tol);
  FastCutReport counters;

  std::vector<CutPolygon> polygons;
  for (const geometry::Disc& disc : input.network->discs) {
    if (disc.cuts) addCutPolygons(disc, input.disc_segments, tol.distance, polygons);
  }
  counters.cutting_polygons = static_cast<int>(polygons.size());

  PieceStore store(input.domain_box, polygons.size());
  for (Piece& piece : labelDomainPieces(input, tol)) store.add(std::move(piece));
  for (const CutPolygon& polygon : polygons) {
    for (int id : store.query(polygon.box.enlarged(tol.distance))) {
      if (boxMissesPlane(store.box(id), polygon.plane, tol.distance)) continue;
      ++counters.piece_tests;
      std::optional<std::vector<Piece>> replaced =
          cutPiece(store.piece(id), polygon, tol, counters);
      if (!replaced) continue;
      store.kill(id);
      for (Piece& p : *replaced) store.add(std::move(p));
    }
  }
  std::vector<Piece> pieces = store.takeAlive();
  counters.pieces = static_cast<int>(pieces.size());
  AssemblyReport assembly;
  BlockModel model = assembleBlocks(std::move(pieces), input, tol, &assembly);
  counters.inconsistent_contacts = assembly.inconsistent_contacts;
  if (report) *report = counters;
  return model;
}

}  // namespace rockmass::blocks
