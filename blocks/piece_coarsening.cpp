#include "blocks/piece_coarsening.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <tbb/parallel_for.h>

#include "blocks/convex_split.h"

namespace rockmass::blocks {

using geometry::Box;
using geometry::Polyhedron;

namespace {

/// Provenance given to the faces of the start box of a union: none may survive the clipping.
constexpr FaceSource kStartBox{FaceKind::Fictitious, -2};
/// Two faces lie in one plane with opposite sides when their outward normals are opposite
/// within this cosine (and every vertex of one lies within the tolerance of the other).
constexpr double kOppositeCosine = -0.999;
/// Volumes must add up to this relative error for a union to be accepted.
constexpr double kVolumeSlack = 1e-9;

/// The plane of every face of a convex piece, normal pointing out.
std::vector<Plane> facePlanes(const Polyhedron& shape) {
  std::vector<Plane> planes;
  planes.reserve(shape.faces.size());
  for (std::size_t f = 0; f < shape.faces.size(); ++f) {
    const Vec3 n = geometry::faceNormal(shape, static_cast<int>(f));
    double offset = 0.0;
    for (int v : shape.faces[f]) offset += n.dot(shape.vertices[static_cast<std::size_t>(v)]);
    planes.push_back({n, offset / static_cast<double>(shape.faces[f].size())});
  }
  return planes;
}

/// True when every vertex of `shape` lies within `tolerance` of `plane`'s inner side.
bool inside(const Polyhedron& shape, const Plane& plane, double tolerance) {
  return std::all_of(shape.vertices.begin(), shape.vertices.end(),
                     [&](const Vec3& v) { return plane.distance(v) <= tolerance; });
}

/// The face of `b` in the plane of face `fa` of `a`, on its other side, or -1.
int opposedFace(const std::vector<Plane>& planes_a, int fa, const Piece& b,
                const std::vector<Plane>& planes_b, double tolerance) {
  const Plane& plane = planes_a[static_cast<std::size_t>(fa)];
  for (std::size_t fb = 0; fb < planes_b.size(); ++fb) {
    if (planes_b[fb].normal.dot(plane.normal) > kOppositeCosine) continue;
    const std::vector<int>& face = b.shape.faces[fb];
    if (std::all_of(face.begin(), face.end(), [&](int v) {
          return std::abs(plane.distance(b.shape.vertices[static_cast<std::size_t>(v)])) <=
                 tolerance;
        })) {
      return static_cast<int>(fb);
    }
  }
  return -1;
}

std::optional<Piece> unionOf(const Piece& a, const std::vector<Plane>& planes_a, const Piece& b,
                             const std::vector<Plane>& planes_b, double tolerance) {
  // The common plane: a face of a and a face of b in one plane, facing each other.
  int fa = -1, fb = -1;
  for (std::size_t f = 0; f < planes_a.size() && fb < 0; ++f) {
    fb = opposedFace(planes_a, static_cast<int>(f), b, planes_b, tolerance);
    if (fb >= 0) fa = static_cast<int>(f);
  }
  if (fb < 0) return std::nullopt;
  // Convex union <=> each lies inside the other's remaining planes; it is then their
  // intersection (see the header).
  for (std::size_t f = 0; f < planes_a.size(); ++f) {
    if (static_cast<int>(f) != fa && !inside(b.shape, planes_a[f], tolerance)) return std::nullopt;
  }
  for (std::size_t f = 0; f < planes_b.size(); ++f) {
    if (static_cast<int>(f) != fb && !inside(a.shape, planes_b[f], tolerance)) return std::nullopt;
  }
  // Build the intersection by clipping a box that holds both with each remaining plane.
  Box box = geometry::bounds(a.shape);
  const Box box_b = geometry::bounds(b.shape);
  box.min = box.min.cwiseMin(box_b.min);
  box.max = box.max.cwiseMax(box_b.max);
  const double size = box.diagonal();
  Piece work{geometry::boxPolyhedron(box.enlarged(0.1 * size)),
             std::vector<FaceSource>(6, kStartBox)};
  const auto clip = [&](const Plane& plane, const FaceSource& source) {
    std::optional<SplitPieces> split = splitPiece(work, plane, tolerance, source);
    if (split) {
      work = std::move(split->below);
      return true;
    }
    // Not crossed: a plane already covered by a coplanar one, so nothing lies above it.
    return inside(work.shape, plane, tolerance);
  };
  for (std::size_t f = 0; f < planes_a.size(); ++f) {
    if (static_cast<int>(f) != fa && !clip(planes_a[f], a.face_sources[f])) return std::nullopt;
  }
  for (std::size_t f = 0; f < planes_b.size(); ++f) {
    if (static_cast<int>(f) != fb && !clip(planes_b[f], b.face_sources[f])) return std::nullopt;
  }
  if (std::find(work.face_sources.begin(), work.face_sources.end(), kStartBox) !=
      work.face_sources.end()) {
    return std::nullopt;
  }
  // Every vertex of the union is a vertex of a or of b: put the original back, bit for bit,
  // so that the union stays conforming with the pieces around it.
  const double snap = std::max(1e3 * tolerance, 1e-7 * size);
  std::vector<const Vec3*> originals;
  for (const Vec3& v : a.shape.vertices) originals.push_back(&v);
  for (const Vec3& v : b.shape.vertices) originals.push_back(&v);
  std::vector<const Vec3*> used;
  for (Vec3& v : work.shape.vertices) {
    const Vec3* nearest = nullptr;
    double best = std::numeric_limits<double>::infinity();
    for (const Vec3* o : originals) {
      const double d = (*o - v).squaredNorm();
      if (d < best) {
        best = d;
        nearest = o;
      }
    }
    if (std::sqrt(best) > snap) return std::nullopt;
    if (std::find(used.begin(), used.end(), nearest) != used.end()) return std::nullopt;
    used.push_back(nearest);
    v = *nearest;
  }
  const double volume_a = geometry::massProperties(a.shape).volume;
  const double volume_b = geometry::massProperties(b.shape).volume;
  const double volume = geometry::massProperties(work.shape).volume;
  if (std::abs(volume - volume_a - volume_b) > kVolumeSlack * (volume_a + volume_b)) {
    return std::nullopt;
  }
  return work;
}

bool touches(const Box& x, const Box& y, double tolerance) {
  return (x.min.array() <= y.max.array() + tolerance).all() &&
         (y.min.array() <= x.max.array() + tolerance).all();
}

int vertexCount(const std::vector<Piece>& pieces) {
  int count = 0;
  for (const Piece& p : pieces) count += static_cast<int>(p.shape.vertices.size());
  return count;
}

}  // namespace

std::optional<Piece> convexUnion(const Piece& a, const Piece& b, double tolerance) {
  return unionOf(a, facePlanes(a.shape), b, facePlanes(b.shape), tolerance);
}

CoarseningReport coarsenPieces(Block& block, double tolerance) {
  CoarseningReport report;
  report.pieces_before = static_cast<int>(block.pieces.size());
  report.vertices_before = vertexCount(block.pieces);
  struct Item {
    Piece piece;
    std::vector<Plane> planes;
    Box box;
    bool alive = true;
  };
  std::vector<Item> items;
  items.reserve(block.pieces.size());
  for (Piece& p : block.pieces) {
    std::vector<Plane> planes = facePlanes(p.shape);
    const Box box = geometry::bounds(p.shape);
    items.push_back({std::move(p), std::move(planes), box, true});
  }
  // Passes until no pair merges. Within a pass the pieces are swept in the order of their
  // boxes' lower x, so only pairs whose boxes overlap in x are tried.
  for (bool merged = true; merged;) {
    merged = false;
    std::vector<std::size_t> order;
    for (std::size_t k = 0; k < items.size(); ++k) {
      if (items[k].alive) order.push_back(k);
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
      return items[x].box.min.x() < items[y].box.min.x();
    });
    for (std::size_t oi = 0; oi < order.size(); ++oi) {
      Item& a = items[order[oi]];
      if (!a.alive) continue;
      for (std::size_t oj = oi + 1; oj < order.size(); ++oj) {
        Item& b = items[order[oj]];
        if (b.box.min.x() > a.box.max.x() + tolerance) break;
        if (!b.alive || !touches(a.box, b.box, tolerance)) continue;
        std::optional<Piece> u = unionOf(a.piece, a.planes, b.piece, b.planes, tolerance);
        if (!u) continue;
        a.piece = std::move(*u);
        a.planes = facePlanes(a.piece.shape);
        a.box = geometry::bounds(a.piece.shape);
        b.alive = false;
        merged = true;
      }
    }
  }
  block.pieces.clear();
  for (Item& item : items) {
    if (item.alive) block.pieces.push_back(std::move(item.piece));
  }
  report.pieces_after = static_cast<int>(block.pieces.size());
  report.vertices_after = vertexCount(block.pieces);
  return report;
}

CoarseningReport coarsenPieces(BlockModel& model) {
  const double tolerance = 1e-9 * model.domain.diagonal();
  std::vector<CoarseningReport> reports(model.blocks.size());
  tbb::parallel_for(std::size_t{0}, model.blocks.size(),
                    [&](std::size_t k) { reports[k] = coarsenPieces(model.blocks[k], tolerance); });
  CoarseningReport total;
  for (const CoarseningReport& r : reports) {
    total.pieces_before += r.pieces_before;
    total.pieces_after += r.pieces_after;
    total.vertices_before += r.vertices_before;
    total.vertices_after += r.vertices_after;
  }
  return total;
}

}  // namespace rockmass::blocks
