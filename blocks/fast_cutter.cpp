#include "blocks/fast_cutter.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "blocks/convex_partition.h"
#include "blocks/convex_split.h"
#include "blocks/piece_contacts.h"
#include "blocks/union_find.h"
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
  int plane_id = 0;          ///< id of `plane` (a UnionFind id: coincident planes share a root)
  int first_edge_id = 0;     ///< id of edges[0]; edges[k] has first_edge_id + k
};

/// A piece being cut, with the id of the plane each face lies in. Faces made by one cutting
/// plane share its id; coincident planes are merged when a polygon meets a face in its
/// plane. Contacts are then searched among faces of one plane only.
struct WorkPiece {
  Piece piece;
  std::vector<int> planes;  ///< per face
};

/// The convex cutting polygons of one disc.
void addCutPolygons(const geometry::Disc& disc, int segments, double tolerance, UnionFind& ids,
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
    polygon.plane_id =
        out.empty() || out.back().disc_id != polygon.disc_id ? ids.add() : out.back().plane_id;
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
    polygon.first_edge_id = ids.add();
    for (std::size_t k = 1; k < polygon.edges.size(); ++k) ids.add();
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

  int add(WorkPiece piece) {
    const int id = static_cast<int>(pieces_.size());
    boxes_.push_back(geometry::bounds(piece.piece.shape));
    pieces_.push_back(std::move(piece));
    alive_.push_back(1);
    seen_.push_back(-1);
    forCells(boxes_.back(), [&](std::vector<int>& cell) { cell.push_back(id); });
    return id;
  }
  void kill(int id) {
    alive_[id] = 0;
    pieces_[id] = WorkPiece{};
  }
  const WorkPiece& piece(int id) const { return pieces_[id]; }
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
  std::vector<WorkPiece> takeAlive() {
    std::vector<WorkPiece> out;
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
  std::vector<WorkPiece> pieces_;
  std::vector<Box> boxes_;
  std::vector<char> alive_;
  std::vector<int> seen_;
  int stamp_ = 0;
};

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// True when the box lies more than `tolerance` on one side of the plane.
bool boxMissesPlane(const Box& box, const Plane& plane, double tolerance) {
  const Vec3 c = box.center();
  const Vec3 h = 0.5 * box.size();
  const double reach = h.dot(plane.normal.cwiseAbs());
  return std::abs(plane.distance(c)) > reach + tolerance;
}

/// Splits a work piece by a plane with id `plane_id`; faces keep their plane ids.
std::optional<std::pair<WorkPiece, WorkPiece>> splitWork(const WorkPiece& work, const Plane& plane,
                                                         int plane_id, double tolerance,
                                                         FaceSource cap) {
  std::optional<SplitPieces> split = splitPiece(work.piece, plane, tolerance, cap);
  if (!split) return std::nullopt;
  const auto planes = [&](const std::vector<int>& origin) {
    std::vector<int> out;
    out.reserve(origin.size());
    for (int f : origin) out.push_back(f < 0 ? plane_id : work.planes[f]);
    return out;
  };
  return std::pair{WorkPiece{std::move(split->below), planes(split->below_origin)},
                   WorkPiece{std::move(split->above), planes(split->above_origin)}};
}

/// What cutting one piece by one polygon gives.
struct CutResult {
  std::optional<std::vector<WorkPiece>> pieces;  ///< replacements, or nothing: unchanged
  std::vector<std::pair<int, int>> coincident;   ///< plane ids found to be one plane
  long long splits = 0;                          ///< plane splits made
};

/// Cuts one piece by one polygon.
CutResult cutPiece(const WorkPiece& work, const CutPolygon& polygon, const CutTolerances& tol) {
  CutResult result;
  const Piece& piece = work.piece;
  const Section section = planeSection(piece, polygon.plane, tol.distance);
  if (section.kind == SectionKind::None) return result;
  if (section.kind == SectionKind::OnFace) {
    result.coincident.emplace_back(work.planes[section.face], polygon.plane_id);
    // A disc on a face that is already real (boundary, structure, another crack) adds nothing.
    if (piece.face_sources[section.face].kind != FaceKind::Fictitious) return result;
  }
  // Does the polygon cover any of the section?
  std::vector<Vec3> covered = section.polygon;
  for (const Plane& edge : polygon.edges) {
    covered = clipPolygon(covered, edge);
    if (covered.size() < 3) return result;
  }
  // A covered part thinner than the distance tolerance is a graze along a polygon edge:
  // nothing to cut. A small but compact one is a real crossing (a piece corner poking
  // 0.1 mm through a crack): it is cut, as the exact cutter cuts it.
  if (thinnerThan(covered, tol.distance)) return result;

  std::vector<WorkPiece> out;
  WorkPiece core = work;
  std::vector<Vec3> core_section = section.polygon;
  for (std::size_t k = 0; k < polygon.edges.size(); ++k) {
    const Plane& edge = polygon.edges[k];
    double lowest = 0.0;
    for (const Vec3& p : core_section) lowest = std::min(lowest, edge.distance(p));
    if (lowest >= -tol.distance) continue;  // the section is inside this edge's half-plane
    if (auto split = splitWork(core, edge, polygon.first_edge_id + static_cast<int>(k),
                               tol.distance, {FaceKind::Fictitious, -1})) {
      ++result.splits;
      out.push_back(std::move(split->first));  // outside the polygon: not cut by the disc
      core = std::move(split->second);
    }
    core_section = clipPolygon(core_section, edge);
  }
  const FaceSource disc{FaceKind::Disc, polygon.disc_id};
  if (section.kind == SectionKind::Crossing) {
    if (auto split = splitWork(core, polygon.plane, polygon.plane_id, tol.distance, disc)) {
      ++result.splits;
      out.push_back(std::move(split->first));
      out.push_back(std::move(split->second));
    } else {
      out.push_back(std::move(core));
    }
  } else {
    // The disc lies on a fictitious face: its part inside the polygon becomes a crack.
    bool relabelled = false;
    Piece& c = core.piece;
    for (std::size_t f = 0; f < c.shape.faces.size(); ++f) {
      if (c.face_sources[f].kind != FaceKind::Fictitious) continue;
      const std::vector<int>& face = c.shape.faces[f];
      const bool on = std::all_of(face.begin(), face.end(), [&](int v) {
        return std::abs(polygon.plane.distance(c.shape.vertices[v])) <= tol.distance;
      });
      if (on) {
        c.face_sources[f] = disc;
        relabelled = true;
      }
    }
    if (out.empty() && !relabelled) return result;
    out.push_back(std::move(core));
  }
  result.pieces = std::move(out);
  return result;
}

}  // namespace

BlockModel cutFast(const CutInput& input, FastCutReport* report) {
  if (input.domain_pieces.empty()) throw std::invalid_argument("cutFast: no domain piece");
  if (input.network == nullptr) throw std::invalid_argument("cutFast: no fracture network");
  if (input.disc_segments < 3) throw std::invalid_argument("cutFast: disc_segments < 3");
  const CutTolerances tol = cutTolerances(input.domain_box);
  checkStructuresOutsideRock(input, tol);
  FastCutReport counters;
  const auto start = std::chrono::steady_clock::now();

  // Plane ids: one per domain face, then per cutting polygon its plane and its edges.
  UnionFind plane_ids;  // coincident planes end up with one root
  std::vector<Piece> domain = labelDomainPieces(input, tol);
  std::vector<std::vector<int>> domain_planes(domain.size());
  for (std::size_t i = 0; i < domain.size(); ++i) {
    for (std::size_t f = 0; f < domain[i].shape.faces.size(); ++f) {
      domain_planes[i].push_back(plane_ids.add());
    }
  }
  if (domain.size() > 1) {
    for (const PieceContact& c : findPieceContacts(domain, tol.distance, tol.area)) {
      plane_ids.unite(domain_planes[c.piece_a][c.face_a], domain_planes[c.piece_b][c.face_b]);
    }
  }
  std::vector<CutPolygon> polygons;
  for (const geometry::Disc& disc : input.network->discs) {
    if (disc.cuts) addCutPolygons(disc, input.disc_segments, tol.distance, plane_ids, polygons);
  }
  counters.cutting_polygons = static_cast<int>(polygons.size());

  PieceStore store(input.domain_box, polygons.size());
  for (std::size_t i = 0; i < domain.size(); ++i) {
    store.add({std::move(domain[i]), std::move(domain_planes[i])});
  }
  std::vector<int> ids;
  std::vector<CutResult> results;
  for (const CutPolygon& polygon : polygons) {
    ids = store.query(polygon.box.enlarged(tol.distance));
    std::erase_if(
        ids, [&](int id) { return boxMissesPlane(store.box(id), polygon.plane, tol.distance); });
    counters.piece_tests += static_cast<long long>(ids.size());
    // The pieces a polygon meets are cut independently (in parallel), then replaced in
    // ascending order, so the result does not depend on the thread count.
    results.assign(ids.size(), CutResult{});
    const auto cut_one = [&](std::size_t k) {
      results[k] = cutPiece(store.piece(ids[k]), polygon, tol);
    };
    if (ids.size() >= 32) {
      tbb::parallel_for(std::size_t{0}, ids.size(), cut_one);
    } else {
      for (std::size_t k = 0; k < ids.size(); ++k) cut_one(k);
    }
    for (std::size_t k = 0; k < ids.size(); ++k) {
      counters.splits += results[k].splits;
      for (const auto& [a, b] : results[k].coincident) plane_ids.unite(a, b);
      if (!results[k].pieces) continue;
      store.kill(ids[k]);
      for (WorkPiece& p : *results[k].pieces) store.add(std::move(p));
    }
  }
  std::vector<WorkPiece> work = store.takeAlive();
  counters.pieces = static_cast<int>(work.size());
  counters.cut_seconds = secondsSince(start);

  const auto assemble_start = std::chrono::steady_clock::now();
  std::vector<Piece> pieces;
  std::vector<std::vector<int>> planes;
  pieces.reserve(work.size());
  planes.reserve(work.size());
  for (WorkPiece& w : work) {
    for (int& id : w.planes) id = plane_ids.find(id);
    pieces.push_back(std::move(w.piece));
    planes.push_back(std::move(w.planes));
  }
  const std::vector<PieceContact> contacts =
      findContactsByPlane(pieces, planes, tol.distance, tol.area);
  AssemblyReport assembly;
  BlockModel model = assembleBlocks(std::move(pieces), contacts, input, tol, &assembly);
  counters.inconsistent_contacts = assembly.inconsistent_contacts;
  counters.assemble_seconds = secondsSince(assemble_start);
  if (report) *report = counters;
  return model;
}

}  // namespace rockmass::blocks
