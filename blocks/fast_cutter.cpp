#include "blocks/fast_cutter.h"

#include <tbb/parallel_for.h>

#include <atomic>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include "blocks/cell_store.h"
#include "blocks/convex_partition.h"
#include "blocks/convex_split.h"
#include "blocks/fast_cut_parts.h"
#include "blocks/piece_contacts.h"
#include "blocks/region_split.h"
#include "blocks/union_find.h"
#include "geometry/disc.h"
#include "geometry/interrupt.h"

namespace rockmass::blocks {
namespace {

using namespace fastcut;

/// A kd region: its box, the plane id of each of its six faces (boxPolyhedron order; -1 on
/// the domain's bounding box) and the polygons that may meet it, ascending.
struct Region {
  Box box;
  std::array<int, 6> face_plane{-1, -1, -1, -1, -1, -1};
  std::vector<int> polygons;
};

/// Conservative: may the polygon meet the box?
bool polygonMayMeetBox(const CutPolygon& polygon, const Box& box, double tolerance) {
  const Box b = box.enlarged(tolerance);
  if ((polygon.box.max.array() < b.min.array()).any() ||
      (polygon.box.min.array() > b.max.array()).any()) {
    return false;
  }
  return !boxMissesPlane(box, polygon.plane, tolerance);
}

/// kd split of `region` (longest axis) until it meets at most `max_polygons` polygons or
/// its longest edge is below `min_size`. Split levels avoid every axis-aligned polygon
/// plane and domain-piece face plane (`avoid[axis]`: their levels), so a region face never
/// lies in a disc: region faces are fictitious.
void splitRegions(const std::vector<CutPolygon>& polygons,
                  const std::array<std::vector<double>, 3>& avoid, double min_size,
                  int max_polygons, double tolerance, UnionFind& plane_ids, Region region,
                  std::vector<Region>& out) {
  const int axis = longestAxis(region.box);
  if (static_cast<int>(region.polygons.size()) <= max_polygons ||
      region.box.size()[axis] < 2.0 * min_size) {
    out.push_back(std::move(region));
    return;
  }
  const double level = freeSplitLevel(
      region.box, axis,
      [&](double level) {
        return std::any_of(avoid[axis].begin(), avoid[axis].end(),
                           [&](double x) { return std::abs(x - level) <= 1e3 * tolerance; });
      },
      "fast cutter");
  const int plane = plane_ids.add();
  for (int side = 0; side < 2; ++side) {
    Region child;
    child.box = region.box;
    child.face_plane = region.face_plane;
    // boxPolyhedron faces: 2 axis = min side, 2 axis + 1 = max side.
    if (side == 0) {
      child.box.max[axis] = level;
      child.face_plane[2 * axis + 1] = plane;
    } else {
      child.box.min[axis] = level;
      child.face_plane[2 * axis] = plane;
    }
    for (int p : region.polygons) {
      if (polygonMayMeetBox(polygons[p], child.box, tolerance)) child.polygons.push_back(p);
    }
    splitRegions(polygons, avoid, min_size, max_polygons, tolerance, plane_ids, std::move(child),
                 out);
  }
}

/// What one region gives.
struct RegionCut {
  std::vector<Piece> pieces;
  std::vector<int> planes;  ///< plane id of every face of `pieces`, in piece and face order
  /// Tracked: the faces that may touch another (piece indices into `pieces`), for the
  /// contact tests, and the pairs of them (indices into faces.faces).
  ContactFaces faces;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  std::vector<std::pair<int, int>> coincident;  ///< plane ids found to be one plane
  /// Tracked: faces that are the two sides of one cut (the same loop, bitwise): (piece,
  /// face, other piece, other face), piece indices into `pieces`. Their coverage is one.
  std::vector<std::array<int, 4>> twins;
  /// Tracked: the contacts of the twins that touch (mirroredContactArea), not in `pairs`.
  std::vector<PieceContact> mirrored;
  /// Tracked: the faces of `pieces` in the region's kd faces (planes between regions), for
  /// the search across regions, with their plane ids (kd_planes, per entry of kd.faces).
  ContactFaces kd;
  std::vector<int> kd_planes;
  /// Per piece: what the assembly needs of it (computed here, while the piece is in cache).
  std::vector<PieceFacts> facts;
  long long piece_tests = 0;
  long long splits = 0;
};

/// The region's starting cells: the domain pieces clipped to the region box.
std::vector<Cell> regionCells(const Region& region, const std::vector<Piece>& domain,
                              const std::vector<std::vector<int>>& domain_planes, bool box_domain,
                              const CutTolerances& tol) {
  std::vector<Cell> cells;
  if (box_domain) {
    // The box itself: exact coordinates, faces on the domain keep its labels.
    WorkPiece work;
    work.piece.shape = geometry::boxPolyhedron(region.box);
    for (int f = 0; f < 6; ++f) {
      if (region.face_plane[f] < 0) {
        work.piece.face_sources.push_back(domain[0].face_sources[f]);
        work.planes.push_back(domain_planes[0][f]);
      } else {
        work.piece.face_sources.push_back({FaceKind::Fictitious, -1});
        work.planes.push_back(region.face_plane[f]);
      }
    }
    cells.push_back({std::move(work), region.box, {}});
    return cells;
  }
  const geometry::Polyhedron box_shape = geometry::boxPolyhedron(region.box);
  for (std::size_t i = 0; i < domain.size(); ++i) {
    const Box b = geometry::bounds(domain[i].shape);
    if ((b.max.array() < region.box.min.array()).any() ||
        (b.min.array() > region.box.max.array()).any()) {
      continue;
    }
    WorkPiece work{domain[i], domain_planes[i]};
    bool empty = false;
    for (int f = 0; f < 6 && !empty; ++f) {
      if (region.face_plane[f] < 0) continue;
      const Plane plane = Plane::through(box_shape.vertices[box_shape.faces[f][0]],
                                         geometry::faceNormal(box_shape, f));
      if (auto split = splitWork(work, plane, region.face_plane[f], tol.distance,
                                 {FaceKind::Fictitious, -1})) {
        work = std::move(split->below);
      } else {
        const Vec3 c = geometry::massProperties(work.piece.shape).centroid();
        empty = plane.distance(c) > 0.0;
      }
    }
    if (empty) continue;
    const Box box = geometry::bounds(work.piece.shape);
    cells.push_back({std::move(work), box, {}});
  }
  return cells;
}

/// Whether `polygon` cuts a cell whose section by the polygon's plane is `section`: the
/// polygon meets the section with area (more than a graze of the distance tolerance).
bool polygonCutsSection(const std::vector<Vec3>& section, const CutPolygon& polygon,
                        const Box& reach, const CutTolerances& tol, std::vector<Vec3>& covered,
                        std::vector<Vec3>& scratch) {
  // Does the polygon meet the section with area? A section whose box misses the
  // polygon's (grown by the tolerance) does not: no cut, as the tests below would find
  // (their clip would come out empty). Then vertex signs: an edge with the whole section
  // outside (within the tolerance) leaves at most a strip of that width; a section
  // inside every edge is covered whole; only the rest is clipped.
  if (!section.empty()) {
    Vec3 low = section.front(), high = section.front();
    for (const Vec3& x : section) {
      low = low.cwiseMin(x);
      high = high.cwiseMax(x);
    }
    if ((high.array() < reach.min.array()).any() || (low.array() > reach.max.array()).any()) {
      return false;
    }
  }
  bool apart = false, inside = true;
  for (const Plane& edge : polygon.edges) {
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (const Vec3& x : section) {
      const double d = edge.distance(x);
      low = std::min(low, d);
      high = std::max(high, d);
    }
    if (high <= tol.distance) {
      apart = true;
      break;
    }
    inside = inside && low >= 0.0;
  }
  // A covered part thinner than the distance tolerance is a graze: no cut. A small but
  // compact one (a corner poking 0.1 mm through a crack) is cut, as the exact cutter
  // cuts it (blocks-exact2's rule for EdgePlanes, thinnerThan).
  bool cut = false;
  if (!apart && inside) {
    cut = !thinnerThan(section, tol.distance);
  } else if (!apart) {
    overlapInto(section, polygon, covered, scratch);
    cut = covered.size() >= 3 && !thinnerThan(covered, tol.distance);
  }
  return cut;
}

/// The contact tables of a region's pieces: the pairs of faces that may touch (tracked
/// through the cuts), the two sides of each cut (twins, decided without a table entry), and
/// the faces in the region's kd faces. `local` maps a cell to its piece index.
void regionContactTables(const CellStore& store, const std::vector<int>& live,
                         const std::vector<int>& local, const Region& region,
                         const CutTolerances& tol, RegionCut& out) {
  // The contact table straight from the flat store (sequential, still in cache), faces in
  // first-use order of the pairs: slots and sizes first, then the table sized once and
  // filled.
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> slot(store.faceTotal(), kNone);
  struct Use {
    int cell, piece, face;
    std::uint32_t begin;
  };
  std::vector<Use> uses;
  std::uint32_t corners = 0;
  std::vector<Vec3> corners_a, corners_b;
  const auto slotOf = [&](int cell, int k, int face) {
    std::uint32_t& at = slot[store.faceIndex(cell, face)];
    if (at == kNone) {
      at = static_cast<std::uint32_t>(uses.size());
      uses.push_back({cell, k, face, corners});
      corners += static_cast<std::uint32_t>(store.view(cell).face_size[face]);
    }
    return at;
  };
  for (std::size_t k = 0; k < live.size(); ++k) {
    for (const Link& link : store.links(live[k])) {
      if (link.other_face < 0) continue;
      const int other = local[link.other];
      if (other <= static_cast<int>(k)) continue;
      if (store.planeOf(live[k], link.face) == store.planeOf(link.other, link.other_face) &&
          store.mirrored(live[k], link.face, link.other, link.other_face)) {
        // The two sides of one cut: their contact is decided without a table entry.
        out.twins.push_back({static_cast<int>(k), link.face, other, link.other_face});
        store.faceCorners(live[k], link.face, corners_a);
        store.faceCorners(link.other, link.other_face, corners_b);
        if (const std::optional<double> area =
                mirroredContactArea(corners_a, corners_b, tol.distance, tol.area)) {
          out.mirrored.push_back({static_cast<int>(k), link.face, other, link.other_face, *area});
        }
        continue;
      }
      const std::uint32_t a = slotOf(live[k], static_cast<int>(k), link.face);
      const std::uint32_t b = slotOf(link.other, other, link.other_face);
      out.pairs.emplace_back(a, b);
    }
  }
  // The faces in the region's kd faces, in piece and face order (counted, then the table
  // sized once and filled).
  std::vector<std::pair<int, int>> kd_faces;  // (k, face)
  std::uint32_t kd_corners = 0;
  for (std::size_t k = 0; k < live.size(); ++k) {
    for (int f = 0; f < store.faceCount(live[k]); ++f) {
      const int plane = store.planeOf(live[k], f);
      if (std::find(region.face_plane.begin(), region.face_plane.end(), plane) ==
          region.face_plane.end()) {
        continue;
      }
      kd_faces.emplace_back(static_cast<int>(k), f);
      kd_corners += static_cast<std::uint32_t>(store.view(live[k]).face_size[f]);
      out.kd_planes.push_back(plane);
    }
  }
  out.kd.faces.resize(kd_faces.size());
  out.kd.points.resize(kd_corners);
  out.kd.inward.resize(kd_corners);
  kd_corners = 0;
  for (std::size_t u = 0; u < kd_faces.size(); ++u) {
    const auto [k, f] = kd_faces[u];
    const FlatPieceView view = store.view(live[static_cast<std::size_t>(k)]);
    const auto loop = view.loops.subspan(static_cast<std::size_t>(view.face_begin[f]),
                                         static_cast<std::size_t>(view.face_size[f]));
    out.kd.set(static_cast<std::uint32_t>(u), k, f, kd_corners, view.vertices, loop);
    kd_corners += static_cast<std::uint32_t>(loop.size());
  }
  out.faces.faces.resize(uses.size());
  out.faces.points.resize(corners);
  out.faces.inward.resize(corners);
  for (std::size_t u = 0; u < uses.size(); ++u) {
    const FlatPieceView view = store.view(uses[u].cell);
    const auto f = static_cast<std::size_t>(uses[u].face);
    out.faces.set(static_cast<std::uint32_t>(u), uses[u].piece, uses[u].face, uses[u].begin,
                  view.vertices,
                  view.loops.subspan(static_cast<std::size_t>(view.face_begin[f]),
                                     static_cast<std::size_t>(view.face_size[f])));
  }
}

/// Splits the region's cells by the full plane of every polygon that meets them. With
/// `track`, follows which faces may touch through the splits (RegionCut::touching).
RegionCut cutRegion(const Region& region, const std::vector<CutPolygon>& polygons,
                    const std::vector<Piece>& domain,
                    const std::vector<std::vector<int>>& domain_planes, bool box_domain,
                    const CutTolerances& tol, const SoundnessTolerances& soundness, bool track) {
  RegionCut out;
  // Cells stay at their index in `store` (dead ones are dropped from `live`); `live` lists
  // the live ones in order, a split cell's halves taking its place.
  thread_local CellStore store;
  store.clear();
  {
    std::vector<Cell> start = regionCells(region, domain, domain_planes, box_domain, tol);
    if (track) initialTouching(start, tol.distance);
    for (Cell& cell : start) store.add(cell.work, cell.box, std::move(cell.links));
  }
  std::vector<int> live(store.size()), next;
  std::iota(live.begin(), live.end(), 0);
  std::vector<Vec3> section, covered, scratch;
  SectionScratch crossed;  // the section's work, reused by the split that follows it
  FlatSplit split;
  for (int p : region.polygons) {
    const CutPolygon& polygon = polygons[p];
    const Box reach = polygon.box.enlarged(tol.distance);
    next.clear();
    for (const int id : live) {
      const Box& box = store.box(id);
      const bool near = (box.min.array() <= reach.max.array()).all() &&
                        (reach.min.array() <= box.max.array()).all() &&
                        !boxMissesPlane(box, polygon.plane, tol.distance);
      if (!near) {
        next.push_back(id);
        continue;
      }
      ++out.piece_tests;
      int on_face = -1;
      const SectionKind kind =
          planeSectionFlat(store.view(id), polygon.plane, tol.distance, section, &on_face, crossed);
      if (kind == SectionKind::OnFace) {
        out.coincident.emplace_back(store.planeOf(id, on_face), polygon.plane_id);
      }
      if (kind != SectionKind::Crossing) {
        next.push_back(id);
        continue;
      }
      if (!polygonCutsSection(section, polygon, reach, tol, covered, scratch)) {
        next.push_back(id);
        continue;
      }
      if (!splitFlat(store.view(id), crossed, split)) {
        next.push_back(id);
        continue;
      }
      ++out.splits;
      const int below_id = store.addHalf(id, split.below_vertices, split.below_loops,
                                         split.below_size, split.below_origin, polygon.plane_id);
      const int above_id = store.addHalf(id, split.above_vertices, split.above_loops,
                                         split.above_size, split.above_origin, polygon.plane_id);
      if (track) relink(store, id, below_id, above_id, split, polygon.plane, tol.distance);
      store.kill(id);
      next.push_back(below_id);
      next.push_back(above_id);
    }
    std::swap(live, next);
  }
  std::vector<int> local(store.size(), -1);
  out.pieces.reserve(live.size());
  out.facts.reserve(live.size());
  for (std::size_t k = 0; k < live.size(); ++k) {
    local[live[k]] = static_cast<int>(k);
    out.pieces.push_back(store.piece(live[k], out.planes));
    const Piece& piece = out.pieces.back();
    out.facts.push_back({geometry::massProperties(piece.shape), geometry::bounds(piece.shape),
                         hasCloseVertices(piece, soundness)});
  }
  if (track) regionContactTables(store, live, local, region, tol, out);
  return out;
}

/// The vertices of face f of a piece.
void faceLoop(const Piece& piece, int f, std::vector<Vec3>& out) {
  out.clear();
  for (int v : piece.shape.faces[f]) out.push_back(piece.shape.vertices[v]);
}

/// Levels of the axis-aligned polygon planes and domain face planes along each axis: the
/// kd split avoids them (splitRegions).
std::array<std::vector<double>, 3> axisPlaneLevels(const std::vector<CutPolygon>& polygons,
                                                   const std::vector<Piece>& domain) {
  std::array<std::vector<double>, 3> avoid;
  for (const CutPolygon& polygon : polygons) {
    for (int a = 0; a < 3; ++a) {
      if (std::abs(polygon.plane.normal[a]) >= 1.0 - 1e-12) {
        avoid[a].push_back(polygon.plane.offset * (polygon.plane.normal[a] > 0 ? 1.0 : -1.0));
      }
    }
  }
  for (const Piece& piece : domain) {
    for (std::size_t f = 0; f < piece.shape.faces.size(); ++f) {
      const Vec3 n = geometry::faceNormal(piece.shape, static_cast<int>(f));
      for (int a = 0; a < 3; ++a) {
        if (std::abs(n[a]) >= 1.0 - 1e-12) {
          avoid[a].push_back(piece.shape.vertices[piece.shape.faces[f][0]][a]);
        }
      }
    }
  }
  return avoid;
}

/// The regions' kd faces in one table, in plane order (ties in piece and face order): the
/// table findContactsByPlane would build from the pieces.
ContactFaces kdFaceTable(const std::vector<RegionCut>& cuts, const std::vector<int>& piece_first,
                         UnionFind& plane_ids) {
  ContactFaces kd;
  std::vector<int> kd_root;
  for (std::size_t r = 0; r < cuts.size(); ++r) {
    kd.append(cuts[r].kd, piece_first[r]);
    for (int id : cuts[r].kd_planes) kd_root.push_back(plane_ids.find(id));
  }
  {
    std::vector<std::uint32_t> order(kd.faces.size());
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return kd_root[a] < kd_root[b]; });
    std::vector<ContactFaces::Face> sorted;
    sorted.reserve(order.size());
    for (std::uint32_t k : order) sorted.push_back(kd.faces[k]);
    kd.faces = std::move(sorted);
    for (std::size_t b = 0; b < order.size();) {
      std::size_t e = b + 1;
      while (e < order.size() && kd_root[order[e]] == kd_root[order[b]]) ++e;
      if (e - b >= 2) kd.groups.emplace_back(b, e);
      b = e;
    }
  }
  return kd;
}

/// Contacts inside regions and across them, with their sources, in one list in
/// (piece_a, piece_b, face_a, face_b) order.
void mergeContacts(const std::vector<PieceContact>& inside,
                   const std::vector<FaceSource>& inside_sources,
                   const std::vector<PieceContact>& across,
                   const std::vector<FaceSource>& across_sources,
                   std::vector<PieceContact>& contacts, std::vector<FaceSource>& sources) {
  // One list in (piece_a, piece_b, face_a, face_b) order, as findContactsByPlane sorts:
  // both lists are in that order already (and share no face pair: a contact inside a region
  // joins pieces of one region, one across regions pieces of two), so they are merged.
  const auto before = [](const PieceContact& x, const PieceContact& y) {
    return std::tie(x.piece_a, x.piece_b, x.face_a, x.face_b) <
           std::tie(y.piece_a, y.piece_b, y.face_a, y.face_b);
  };
  contacts.reserve(inside.size() + across.size());
  sources.reserve(inside.size() + across.size());
  std::size_t i = 0, j = 0;
  while (i < inside.size() || j < across.size()) {
    if (j == across.size() || (i < inside.size() && !before(across[j], inside[i]))) {
      contacts.push_back(inside[i]);
      sources.push_back(inside_sources[i++]);
    } else {
      contacts.push_back(across[j]);
      sources.push_back(across_sources[j++]);
    }
  }
}

/// The contacts of tracked regions: inside a region the pairs each region tracked; across
/// regions the faces in the kd planes only (two pieces of different regions can share area
/// only in the plane between them). `planes` is overwritten (kd plane ids, else -1).
std::vector<PieceContact> trackedContacts(
    const std::vector<ContactTablePart>& tracked, const std::vector<Region>& regions,
    const std::vector<RegionCut>& cuts, const std::vector<int>& piece_first,
    std::size_t piece_count, UnionFind& plane_ids, std::vector<int>& planes,
    const CutTolerances& tol, const ContactDecision& decide, std::vector<FaceSource>& sources) {
  std::vector<PieceContact> contacts;
  // Inside a region: the tracked pairs. Across regions: faces in the kd planes only (two
  // pieces of different regions can share area only in the plane between them).
  std::vector<FaceSource> inside_sources, across_sources;
  const std::vector<PieceContact> inside =
      decideTableContacts(tracked, piece_count, tol.distance, tol.area, decide, &inside_sources);
  std::vector<char> kd_plane(plane_ids.size(), 0);
  for (const Region& region : regions) {
    for (int id : region.face_plane) {
      if (id >= 0) kd_plane[plane_ids.find(id)] = 1;
    }
  }
  // In place (no copy): the contacts inside regions are decided already, and the faces
  // searched now keep their (kd plane) ids, which is all `decide` reads of them.
  for (int& id : planes) id = kd_plane[id] ? id : -1;
  const ContactFaces kd = kdFaceTable(cuts, piece_first, plane_ids);
  const std::vector<PieceContact> across =
      decidePlaneContacts(kd, piece_count, tol.distance, tol.area, decide, &across_sources);
  mergeContacts(inside, inside_sources, across, across_sources, contacts, sources);
  return contacts;
}

/// The kd regions of the cut (the split avoids the axis-aligned polygon and domain planes),
/// each with the polygons that may meet it.
std::vector<Region> kdRegions(const CutInput& input, const FastCutOptions& options,
                              const std::vector<CutPolygon>& polygons,
                              const std::vector<Piece>& domain, const CutTolerances& tol,
                              UnionFind& plane_ids) {
  const std::array<std::vector<double>, 3> avoid = axisPlaneLevels(polygons, domain);
  Region root;
  root.box = input.domain_box;
  for (std::size_t p = 0; p < polygons.size(); ++p) {
    if (polygonMayMeetBox(polygons[p], root.box, tol.distance)) {
      root.polygons.push_back(static_cast<int>(p));
    }
  }
  std::vector<Region> regions;
  splitRegions(polygons, avoid, input.domain_box.size().maxCoeff() / 64.0,
               std::max(1, options.max_discs_per_region), tol.distance, plane_ids, std::move(root),
               regions);
  return regions;
}

/// The regions' cuts in one list: pieces in region order, with their faces' plane ids, the
/// tracked contact tables (each region's table stays where the region built it; the contact
/// decisions read them in place), the twins (the two sides of one cut), and each piece's facts.
struct GatheredCut {
  std::vector<Piece> pieces;
  std::vector<int> planes;  ///< plane id of every face, in piece and face order
  std::vector<ContactTablePart> tracked;
  std::vector<std::array<int, 4>> twins;  ///< (piece, face, piece, face), global indices
  std::vector<int> piece_first;           ///< per region: the index of its first piece
  std::vector<PieceFacts> facts;          ///< per piece, for the assembly
};

GatheredCut gatherCuts(std::vector<RegionCut>& cuts, UnionFind& plane_ids,
                       FastCutReport& counters) {
  GatheredCut out;
  std::vector<Piece>& pieces = out.pieces;
  std::vector<int>& planes = out.planes;
  {
    std::size_t piece_total = 0, face_total = 0;
    for (const RegionCut& cut : cuts) {
      piece_total += cut.pieces.size();
      face_total += cut.planes.size();
    }
    pieces.reserve(piece_total);
    planes.reserve(face_total);
  }
  for (RegionCut& cut : cuts) {
    out.piece_first.push_back(static_cast<int>(pieces.size()));
    counters.piece_tests += cut.piece_tests;
    counters.splits += cut.splits;
    for (const auto& [a, b] : cut.coincident) plane_ids.unite(a, b);
    if (!cut.pairs.empty() || !cut.mirrored.empty()) {
      out.tracked.push_back({&cut.faces, static_cast<int>(pieces.size()), cut.pairs, cut.mirrored});
    }
    const int first = static_cast<int>(pieces.size());
    for (const auto& [i, f, j, g] : cut.twins) out.twins.push_back({first + i, f, first + j, g});
    for (Piece& piece : cut.pieces) pieces.push_back(std::move(piece));
    planes.insert(planes.end(), cut.planes.begin(), cut.planes.end());
    out.facts.insert(out.facts.end(), cut.facts.begin(), cut.facts.end());
  }
  return out;
}

/// The faces of all pieces in flat tables: face f of piece i is entry first_face[i] + f; its
/// plane (a root id) and, for a disc plane, the disc group of that plane.
struct FlatFaces {
  const std::vector<Piece>& pieces;
  const std::vector<int>& planes;  ///< per flat face: the root plane id
  std::vector<std::size_t> first_face;
  std::vector<int> group_of_root;  ///< per plane root id: its disc group (-1: none)

  FlatFaces(const std::vector<Piece>& pieces_in, const std::vector<int>& planes_in,
            const std::vector<DiscGroup>& groups, UnionFind& plane_ids)
      : pieces(pieces_in),
        planes(planes_in),
        first_face(pieces_in.size() + 1, 0),
        group_of_root(plane_ids.size(), -1) {
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      first_face[i + 1] = first_face[i] + pieces[i].shape.faces.size();
    }
    for (std::size_t g = 0; g < groups.size(); ++g) {
      int& slot = group_of_root[plane_ids.find(groups[g].plane_id)];
      if (slot < 0) slot = static_cast<int>(g);  // the first group of a root
    }
  }
  std::size_t index(int piece, int face) const {
    return first_face[piece] + static_cast<std::size_t>(face);
  }
  /// The disc group of the plane of face `face` of piece `piece` (-1: not a disc plane).
  int groupOf(int piece, int face) const {
    const int root = planes[index(piece, face)];
    return root < 0 ? -1 : group_of_root[root];
  }
};

/// Coverage of every face in a disc plane, with flat copies of the faces' coverage and
/// sources for the contact decisions (no cache miss per piece there).
struct FaceCover {
  std::vector<Cover> cover;
  std::vector<FaceSource> source;
};

/// Covers every fictitious face in a disc plane by its group's discs; a wholly covered face
/// becomes a Disc face. The second face of a pair of twins (the two sides of one cut) is not
/// covered itself: it takes the coverage of the first, the same loop run backwards (a pair
/// whose first face is itself a second, possible only for overlapping cells, is covered on
/// both sides).
FaceCover coverFaces(std::vector<Piece>& pieces, const FlatFaces& flat,
                     std::vector<std::array<int, 4>>& twins, const std::vector<DiscGroup>& groups,
                     const std::vector<CutPolygon>& polygons, const CutTolerances& tol) {
  FaceCover out{std::vector<Cover>(flat.first_face.back(), Cover::None),
                std::vector<FaceSource>(flat.first_face.back())};
  std::vector<char> second_twin(flat.first_face.back(), 0);
  std::erase_if(twins, [&](const std::array<int, 4>& t) {
    if (second_twin[flat.index(t[0], t[1])]) return true;
    second_twin[flat.index(t[2], t[3])] = 1;
    return false;
  });
  tbb::parallel_for(std::size_t{0}, pieces.size(), [&](std::size_t i) {
    Piece& piece = pieces[i];
    Cover* cover = &out.cover[flat.first_face[i]];
    const char* second = &second_twin[flat.first_face[i]];
    thread_local std::vector<Vec3> loop;
    for (std::size_t f = 0; f < piece.shape.faces.size(); ++f) {
      if (piece.face_sources[f].kind != FaceKind::Fictitious || second[f]) continue;
      const int g = flat.groupOf(static_cast<int>(i), static_cast<int>(f));
      if (g < 0) continue;
      faceLoop(piece, static_cast<int>(f), loop);
      int disc = -1;
      cover[f] = coverage(loop, groups[g], polygons, tol, &disc);
      if (cover[f] == Cover::Whole) piece.face_sources[f] = {FaceKind::Disc, disc};
    }
    std::copy(piece.face_sources.begin(), piece.face_sources.end(),
              out.source.begin() + static_cast<std::ptrdiff_t>(flat.first_face[i]));
  });
  for (const auto& [i, f, j, g] : twins) {
    const std::size_t from = flat.index(i, f);
    const std::size_t to = flat.index(j, g);
    if (pieces[j].face_sources[g].kind != FaceKind::Fictitious) continue;
    out.cover[to] = out.cover[from];
    if (out.cover[to] == Cover::Whole) {
      pieces[j].face_sources[g] = out.source[to] = out.source[from];
    }
  }
  return out;
}

/// The rule that decides a contact: it glues its pieces unless the discs wholly cover the
/// shared part (then it is a crack of that disc).
ContactDecision contactRule(const FlatFaces& flat, const FaceCover& covers,
                            const std::vector<DiscGroup>& groups,
                            const std::vector<CutPolygon>& polygons, const CutTolerances& tol) {
  return [&](const PieceContact& c, bool same_loop) -> FaceSource {
    const FaceSource& a = covers.source[flat.index(c.piece_a, c.face_a)];
    const FaceSource& b = covers.source[flat.index(c.piece_b, c.face_b)];
    const Cover ca = covers.cover[flat.index(c.piece_a, c.face_a)];
    const Cover cb = covers.cover[flat.index(c.piece_b, c.face_b)];
    const int g = flat.groupOf(c.piece_a, c.face_a);
    if (g < 0 || a.kind == FaceKind::Boundary || a.kind == FaceKind::Structure ||
        b.kind == FaceKind::Boundary || b.kind == FaceKind::Structure) {
      // Not a disc plane: the face labels decide.
      return a.kind == FaceKind::Fictitious ? b : a;
    }
    if (ca == Cover::Whole || cb == Cover::Whole) return ca == Cover::Whole ? a : b;
    if (ca == Cover::None || cb == Cover::None) return {FaceKind::Fictitious, -1};
    // Both partly covered, and the two sides of one cut: the shared part is the face itself,
    // partly covered, so the pieces glue.
    if (same_loop) return {FaceKind::Fictitious, -1};
    // Both partly covered: the coverage of their overlap decides.
    thread_local std::vector<Vec3> la, lb, shared;
    faceLoop(flat.pieces[c.piece_a], c.face_a, la);
    faceLoop(flat.pieces[c.piece_b], c.face_b, lb);
    const Vec3 normal = geometry::faceNormal(flat.pieces[c.piece_a].shape, c.face_a);
    faceOverlap(la, lb, normal, shared);
    int disc = -1;
    const bool whole =
        shared.size() >= 3 && coverage(shared, groups[g], polygons, tol, &disc) == Cover::Whole;
    return whole ? FaceSource{FaceKind::Disc, disc} : FaceSource{FaceKind::Fictitious, -1};
  };
}

/// True when the domain is its bounding box (one piece of 6 faces and 8 vertices spanning it).
bool isBoxDomain(const std::vector<Piece>& domain, const Box& box) {
  return domain.size() == 1 && domain[0].shape.faces.size() == 6 &&
         domain[0].shape.vertices.size() == 8 && geometry::bounds(domain[0].shape).min == box.min &&
         geometry::bounds(domain[0].shape).max == box.max;
}

BlockModel cutFullPlanes(const CutInput& input, const FastCutOptions& options,
                         const CutTolerances& tol, FastCutReport* report) {
  FastCutReport counters;
  const auto start = std::chrono::steady_clock::now();
  CutStart setup = startCut(input, tol);
  UnionFind& plane_ids = setup.plane_ids;
  const std::vector<CutPolygon>& polygons = setup.polygons;
  const bool box_domain = isBoxDomain(setup.domain, input.domain_box);
  const std::vector<DiscGroup> groups = groupPolygons(setup.polygons, tol.distance);
  counters.cutting_polygons = static_cast<int>(polygons.size());

  const std::vector<Region> regions =
      kdRegions(input, options, setup.polygons, setup.domain, tol, plane_ids);
  counters.regions = static_cast<int>(regions.size());

  const SoundnessTolerances soundness = soundnessTolerances(input.domain_box);
  std::vector<RegionCut> cuts(regions.size());
  std::atomic<std::size_t> finished{0};
  tbb::parallel_for(std::size_t{0}, regions.size(), [&](std::size_t r) {
    throwIfInterrupted("the block cut (fast cutter)");
    cuts[r] = cutRegion(regions[r], polygons, setup.domain, setup.domain_planes, box_domain, tol,
                        soundness, options.track_contacts);
    if (input.progress) input.progress(++finished, regions.size());
  });
  GatheredCut gathered = gatherCuts(cuts, plane_ids, counters);
  std::vector<Piece>& pieces = gathered.pieces;
  counters.pieces = static_cast<int>(pieces.size());
  for (int& id : gathered.planes) id = plane_ids.find(id);
  const FlatFaces flat(pieces, gathered.planes, groups, plane_ids);
  counters.cut_seconds = secondsSince(start);

  const auto assemble_start = std::chrono::steady_clock::now();
  const FaceCover covers = coverFaces(pieces, flat, gathered.twins, groups, polygons, tol);
  counters.coverage_seconds = secondsSince(assemble_start);

  const auto contact_start = std::chrono::steady_clock::now();
  // Pairs of pieces glued already are skipped (findContactsByPlane with a decision).
  const ContactDecision decide = contactRule(flat, covers, groups, polygons, tol);
  std::vector<FaceSource> sources;
  std::vector<PieceContact> contacts;
  if (!options.track_contacts) {
    contacts =
        findContactsByPlane(pieces, gathered.planes, tol.distance, tol.area, decide, &sources);
  } else {
    contacts = trackedContacts(gathered.tracked, regions, cuts, gathered.piece_first, pieces.size(),
                               plane_ids, gathered.planes, tol, decide, sources);
  }
  counters.contact_seconds = secondsSince(contact_start);
  gathered.tracked.clear();
  cuts.clear();
  return assembleCut(std::move(pieces), contacts, input, tol, counters, assemble_start, report,
                     &sources, &gathered.facts);
}

}  // namespace

BlockModel cutFast(const CutInput& input, const FastCutOptions& options, FastCutReport* report) {
  if (input.domain_pieces.empty()) throw std::invalid_argument("cutFast: no domain piece");
  if (input.network == nullptr) throw std::invalid_argument("cutFast: no fracture network");
  if (input.disc_segments < 3) throw std::invalid_argument("cutFast: disc_segments < 3");
  const CutTolerances tol = cutTolerances(input.domain_box);
  checkStructuresOutsideRock(input, tol);
  if (options.strategy == FastStrategy::EdgePlanes) return cutEdgePlanes(input, tol, report);
  return cutFullPlanes(input, options, tol, report);
}

BlockModel cutFast(const CutInput& input, FastCutReport* report) {
  return cutFast(input, FastCutOptions{}, report);
}

}  // namespace rockmass::blocks
