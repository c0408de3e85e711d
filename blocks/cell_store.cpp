#include "blocks/cell_store.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rockmass::blocks::fastcut {

namespace {

/// The lowest and highest signed distance (m) of the points of face f of `piece` from
/// `plane`.
std::pair<double, double> faceReach(const Piece& piece, int f, const Plane& plane) {
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (int v : piece.shape.faces[f]) {
    const double d = plane.distance(piece.shape.vertices[v]);
    low = std::min(low, d);
    high = std::max(high, d);
  }
  return {low, high};
}

}  // namespace

/// The starting cells' mutual neighbours (several domain pieces in the region): faces of
/// two cells with opposite normals, one lying in the plane of the other within twice the
/// tolerance, whose boxes meet. Conservative: the contact test decides later.
void initialTouching(std::vector<Cell>& cells, double tolerance) {
  const double margin = 2.0 * tolerance;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    for (std::size_t j = i + 1; j < cells.size(); ++j) {
      const Box near = cells[i].box.enlarged(margin);
      if ((near.max.array() < cells[j].box.min.array()).any() ||
          (cells[j].box.max.array() < near.min.array()).any()) {
        continue;
      }
      const Piece& a = cells[i].work.piece;
      const Piece& b = cells[j].work.piece;
      for (int fa = 0; fa < static_cast<int>(a.shape.faces.size()); ++fa) {
        const Vec3 na = geometry::faceNormal(a.shape, fa);
        const Plane pa = Plane::through(a.shape.vertices[a.shape.faces[fa][0]], na);
        for (int fb = 0; fb < static_cast<int>(b.shape.faces.size()); ++fb) {
          const Vec3 nb = geometry::faceNormal(b.shape, fb);
          if (na.dot(nb) > -0.999) continue;
          const Plane pb = Plane::through(b.shape.vertices[b.shape.faces[fb][0]], nb);
          const auto [low_b, high_b] = faceReach(b, fb, pa);
          const auto [low_a, high_a] = faceReach(a, fa, pb);
          const bool b_on_a = low_b >= -margin && high_b <= margin;
          const bool a_on_b = low_a >= -margin && high_a <= margin;
          if (!b_on_a && !a_on_b) continue;
          const int at_i = static_cast<int>(cells[i].links.size());
          const int at_j = static_cast<int>(cells[j].links.size());
          cells[i].links.push_back({fa, static_cast<int>(j), fb, at_j});
          cells[j].links.push_back({fb, static_cast<int>(i), fa, at_i});
        }
      }
    }
  }
}

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
            const Plane& plane, double tolerance) {
  thread_local std::vector<int> to_below, to_above;
  const std::size_t faces = static_cast<std::size_t>(store.faceCount(c));
  to_below.assign(faces, -1);
  to_above.assign(faces, -1);
  int new_below = -1, new_above = -1;
  for (std::size_t f = 0; f < split.below_origin.size(); ++f) {
    (split.below_origin[f] < 0 ? new_below : to_below[split.below_origin[f]]) = static_cast<int>(f);
  }
  for (std::size_t f = 0; f < split.above_origin.size(); ++f) {
    (split.above_origin[f] < 0 ? new_above : to_above[split.above_origin[f]]) = static_cast<int>(f);
  }
  std::vector<Link>& below = store.links(below_id);
  std::vector<Link>& above = store.links(above_id);
  below.clear();
  above.clear();
  below.push_back({new_below, above_id, new_above, 0});
  above.push_back({new_above, below_id, new_below, 0});
  // The new face's points: the ON vertices and crossing points, the part of the plane both
  // halves reach.
  double cap_low = std::numeric_limits<double>::infinity(), cap_high = -cap_low;
  {
    const std::size_t n = static_cast<std::size_t>(split.below_size.back());
    const std::size_t first = split.below_loops.size() - n;
    for (std::size_t k = first; k < split.below_loops.size(); ++k) {
      const double d = plane.distance(split.below_vertices[split.below_loops[k]]);
      cap_low = std::min(cap_low, d);
      cap_high = std::max(cap_high, d);
    }
  }
  const double margin = 2.0 * tolerance;  // beyond it on the other side: no contact
  // Per split face: half the tolerance times the sine of its angle with the plane (0: not
  // computed yet).
  thread_local std::vector<double> strip;
  strip.assign(faces, 0.0);
  for (const Link& link : store.links(c)) {
    if (link.other_face < 0) continue;  // a link whose face vanished in an earlier split
    const int fb = to_below[link.face], fa = to_above[link.face];
    bool keep_below = fb >= 0, keep_above = fa >= 0;
    if (keep_below && keep_above) {
      double& width = strip[static_cast<std::size_t>(link.face)];
      if (width == 0.0) {
        const Vec3 n = store.faceNormal(c, link.face);
        width = 0.5 * tolerance * n.cross(plane.normal).norm();
        // Parallel (degenerate): only the reach decides.
        if (width == 0.0) width = -std::numeric_limits<double>::infinity();
      }
      const auto [low, high] = store.faceReach(link.other, link.other_face, plane);
      keep_below = low <= margin && !(cap_high - low <= width);
      keep_above = high >= -margin && !(high - cap_low <= width);
    }
    // The linked cell's link back to (c, face) goes to the half kept, or one per half.
    std::vector<Link>& other = store.links(link.other);
    Link& back = other[static_cast<std::size_t>(link.back)];
    if (keep_below) {
      below.push_back({fb, link.other, link.other_face, link.back});
      back.other = below_id;
      back.other_face = fb;
      back.back = static_cast<int>(below.size()) - 1;
      if (keep_above) {
        above.push_back({fa, link.other, link.other_face, static_cast<int>(other.size())});
        other.push_back({link.other_face, above_id, fa, static_cast<int>(above.size()) - 1});
      }
    } else if (keep_above) {
      above.push_back({fa, link.other, link.other_face, link.back});
      back.other = above_id;
      back.other_face = fa;
      back.back = static_cast<int>(above.size()) - 1;
    } else {
      // The face lies in the splitting plane within the tolerance on both halves (a face
      // too small to keep): nothing of it is left to touch.
      back.other_face = -1;
    }
  }
}

}  // namespace rockmass::blocks::fastcut
