// The cells of a region of the fast cutter's FullPlanes strategy: a flat store of convex
// cells (vertices, face loops, plane ids, boxes) split in place, and, when contacts are
// tracked, the faces of other cells each face may touch (links). Internal to the blocks
// module (blocks/fast_cutter.cpp).
#pragma once

#include <span>
#include <vector>

#include "blocks/convex_split.h"
#include "blocks/fast_cut_parts.h"

namespace rockmass::blocks::fastcut {

/// Face `face` of a cell may touch face `other_face` of cell `other` of the same region.
struct Link {
  int face = 0;
  int other = 0;  ///< index in the region's cell store
  int other_face = 0;
  int back = 0;  ///< position of the reverse link in the other cell's list (lists of live
                 ///< cells only change in place or grow at the end, so positions hold)
};

/// A cell of a region: a work piece, its bounding box and, when contacts are tracked, the
/// faces of other cells of the region that may touch its faces.
struct Cell {
  WorkPiece work;
  Box box;
  std::vector<Link> links;
};

/// The starting cells' mutual neighbours (several domain pieces in the region): faces of
/// two cells with opposite normals, one lying in the plane of the other within twice the
/// tolerance, whose boxes meet. Conservative: the contact test decides later.
void initialTouching(std::vector<Cell>& cells, double tolerance);

/// The cells of one region in flat arrays, so that a split allocates nothing once the arrays
/// have grown: cell c's vertices are vertices[v_begin[c] ..], its faces are the global faces
/// f_begin[c] .. f_begin[c] + f_count[c] - 1, face g's loop is loops[face_begin[g] ..
/// + face_size[g]) (indices into the cell's vertices). A split appends its two halves; the
/// entries of a dead cell stay unused until the region is done.
class CellStore {
 public:
  /// Appends a cell; returns its index.
  int add(const WorkPiece& work, const Box& box, std::vector<Link> links) {
    const int id = beginCell(box, std::move(links));
    const geometry::Polyhedron& shape = work.piece.shape;
    vertices_.insert(vertices_.end(), shape.vertices.begin(), shape.vertices.end());
    v_count_.back() = static_cast<int>(shape.vertices.size());
    for (std::size_t f = 0; f < shape.faces.size(); ++f) {
      face_begin_.push_back(static_cast<int>(loops_.size()));
      face_size_.push_back(static_cast<int>(shape.faces[f].size()));
      loops_.insert(loops_.end(), shape.faces[f].begin(), shape.faces[f].end());
      source_.push_back(work.piece.face_sources[f]);
      plane_.push_back(work.planes[f]);
    }
    f_count_.back() = static_cast<int>(shape.faces.size());
    return id;
  }
  /// Appends one half of a split of cell `from` (FlatSplit below or above): new faces (origin
  /// -1) get `plane_id` and a Fictitious source, the others those of their origin face.
  int addHalf(int from, const std::vector<Vec3>& vertices, const std::vector<int>& loops,
              const std::vector<int>& sizes, const std::vector<int>& origin, int plane_id) {
    Box box;
    box.min = Vec3::Constant(std::numeric_limits<double>::infinity());
    box.max = -box.min;
    for (const Vec3& v : vertices) {
      box.min = box.min.cwiseMin(v);
      box.max = box.max.cwiseMax(v);
    }
    const int id = beginCell(box, {});
    vertices_.insert(vertices_.end(), vertices.begin(), vertices.end());
    v_count_.back() = static_cast<int>(vertices.size());
    int at = static_cast<int>(loops_.size());
    loops_.insert(loops_.end(), loops.begin(), loops.end());
    const int first = f_begin_[from];
    for (std::size_t f = 0; f < sizes.size(); ++f) {
      face_begin_.push_back(at);
      face_size_.push_back(sizes[f]);
      at += sizes[f];
      const FaceSource source =
          origin[f] < 0 ? FaceSource{FaceKind::Fictitious, -1} : source_[first + origin[f]];
      const int plane = origin[f] < 0 ? plane_id : plane_[first + origin[f]];
      source_.push_back(source);
      plane_.push_back(plane);
    }
    f_count_.back() = static_cast<int>(sizes.size());
    return id;
  }
  /// Cell c as a flat piece (valid until the next add).
  FlatPieceView view(int c) const {
    return {std::span<const Vec3>(vertices_).subspan(v_begin_[c], v_count_[c]), loops_,
            std::span<const int>(face_begin_).subspan(f_begin_[c], f_count_[c]),
            std::span<const int>(face_size_).subspan(f_begin_[c], f_count_[c])};
  }
  int faceCount(int c) const { return f_count_[c]; }
  /// Index of face f of cell c among all faces of the store (0 .. faceTotal() - 1).
  std::size_t faceIndex(int c, int f) const { return static_cast<std::size_t>(f_begin_[c] + f); }
  std::size_t faceTotal() const { return face_begin_.size(); }
  int planeOf(int c, int f) const { return plane_[f_begin_[c] + f]; }
  const Box& box(int c) const { return boxes_[c]; }
  std::size_t size() const { return v_begin_.size(); }
  std::vector<Link>& links(int c) { return links_[c]; }
  const std::vector<Link>& links(int c) const { return links_[c]; }
  /// Drops a dead cell's links.
  void kill(int c) {
    links_[c].clear();
    spare_links_.push_back(std::move(links_[c]));
  }
  /// Empties the store, keeping its storage (the store of a thread is reused by its
  /// regions: no allocation, no page faults once grown).
  void clear() {
    vertices_.clear();
    loops_.clear();
    face_begin_.clear();
    face_size_.clear();
    plane_.clear();
    source_.clear();
    v_begin_.clear();
    v_count_.clear();
    f_begin_.clear();
    f_count_.clear();
    boxes_.clear();
    for (std::vector<Link>& list : links_) {
      list.clear();
      spare_links_.push_back(std::move(list));
    }
    links_.clear();
  }
  /// The corners of face f of cell c, in loop order, into `out`.
  void faceCorners(int c, int f, std::vector<Vec3>& out) const {
    const int g = f_begin_[c] + f;
    out.clear();
    for (int k = face_begin_[g]; k < face_begin_[g] + face_size_[g]; ++k) {
      out.push_back(vertices_[v_begin_[c] + loops_[k]]);
    }
  }
  /// Newell unit normal of face f of cell c (zero for a degenerate face).
  Vec3 faceNormal(int c, int f) const {
    const int g = f_begin_[c] + f;
    const int n = face_size_[g];
    Vec3 sum = Vec3::Zero();
    for (int k = 0; k < n; ++k) {
      const Vec3& p = vertices_[v_begin_[c] + loops_[face_begin_[g] + k]];
      const Vec3& q = vertices_[v_begin_[c] + loops_[face_begin_[g] + (k + 1 == n ? 0 : k + 1)]];
      sum += p.cross(q);
    }
    const double length = sum.norm();
    return length > 0.0 ? Vec3(sum / length) : Vec3(Vec3::Zero());
  }
  /// The lowest and highest signed distance (m) of the points of face f of cell c from
  /// `plane`.
  std::pair<double, double> faceReach(int c, int f, const Plane& plane) const {
    double low = std::numeric_limits<double>::infinity(), high = -low;
    const int g = f_begin_[c] + f;
    for (int k = face_begin_[g]; k < face_begin_[g] + face_size_[g]; ++k) {
      const double d = plane.distance(vertices_[v_begin_[c] + loops_[k]]);
      low = std::min(low, d);
      high = std::max(high, d);
    }
    return {low, high};
  }
  /// True when face g of cell d is face f of cell c run backwards (the two sides of one cut,
  /// bitwise equal points), as sameLoop in piece_contacts.cpp decides it.
  bool mirrored(int c, int f, int d, int g) const {
    const int fc = f_begin_[c] + f, gd = f_begin_[d] + g;
    const int n = face_size_[fc];
    if (face_size_[gd] != n) return false;
    const auto a = [&](int k) -> const Vec3& {
      return vertices_[v_begin_[c] + loops_[face_begin_[fc] + k]];
    };
    const auto b = [&](int k) -> const Vec3& {
      return vertices_[v_begin_[d] + loops_[face_begin_[gd] + k]];
    };
    int start = n;
    for (int k = 0; k < n; ++k) {
      if (b(k) == a(0)) {
        start = k;
        break;
      }
    }
    if (start == n) return false;
    for (int k = 0; k < n; ++k) {
      if (a(k) != b((start + n - k) % n)) return false;
    }
    return true;
  }
  /// Cell c as a piece; the plane ids of its faces are appended to `planes`.
  Piece piece(int c, std::vector<int>& planes) const {
    Piece piece;
    const auto first = vertices_.begin() + v_begin_[c];
    piece.shape.vertices.assign(first, first + v_count_[c]);
    piece.shape.faces.resize(static_cast<std::size_t>(f_count_[c]));
    piece.face_sources.resize(static_cast<std::size_t>(f_count_[c]));
    for (int f = 0; f < f_count_[c]; ++f) {
      const int g = f_begin_[c] + f;
      const auto loop = loops_.begin() + face_begin_[g];
      piece.shape.faces[f].assign(loop, loop + face_size_[g]);
      piece.face_sources[f] = source_[g];
      planes.push_back(plane_[g]);
    }
    return piece;
  }

 private:
  int beginCell(const Box& box, std::vector<Link> links) {
    const int id = static_cast<int>(v_begin_.size());
    v_begin_.push_back(static_cast<int>(vertices_.size()));
    v_count_.push_back(0);
    f_begin_.push_back(static_cast<int>(face_begin_.size()));
    f_count_.push_back(0);
    boxes_.push_back(box);
    if (links.empty() && !spare_links_.empty()) {
      links = std::move(spare_links_.back());  // cleared, with its capacity
      spare_links_.pop_back();
    }
    links_.push_back(std::move(links));
    return id;
  }
  std::vector<Vec3> vertices_;
  std::vector<int> loops_;
  std::vector<int> face_begin_, face_size_, plane_;
  std::vector<FaceSource> source_;
  std::vector<int> v_begin_, v_count_, f_begin_, f_count_;
  std::vector<Box> boxes_;
  std::vector<std::vector<Link>> links_;
  std::vector<std::vector<Link>> spare_links_;  ///< emptied lists of dead cells, for reuse
};

/// Hands the links of cell c to its two halves `below` and `above` (the split `split`), and
/// updates the linked cells' own links. A face that goes to one half keeps its links; for a
/// face split between the halves, a linked face stays with a half unless the two can share
/// no more than a strip narrower than half the tolerance: the half's part of the face lies
/// on its side of the plane up to the new face's points (cap_low, cap_high: their lowest and
/// highest distance), the linked face on the other side from its lowest (highest) point on,
/// and a band of the plane's distances of height h is a strip of width h / sin(angle between
/// the face's plane and the splitting plane) in the face. Such a strip is never a real
/// contact (area at most half the tolerance times its extent, see realContact), nor is any
/// part of it after further splits, so the link is dropped; the contact tests would only
/// reject it (most such pairs are a face and the part of its former neighbour that the same
/// plane split off: they share the line where the plane crosses them). The two new faces are
/// linked.
void relink(CellStore& store, int c, int below_id, int above_id, const FlatSplit& split,
            const Plane& plane, double tolerance);

}  // namespace rockmass::blocks::fastcut
