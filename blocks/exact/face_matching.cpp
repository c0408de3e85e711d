// The exact cutter's matching of faces across pieces in one plane (cut_parts.h): pieces glue
// across fictitious shared parts, covered shared parts become crack contacts.
#include "blocks/exact/cut_parts.h"

#include <algorithm>
#include <limits>
#include <map>

namespace rockmass::blocks::exactcut {

namespace {

/// What the double separating-axis filter says about two convex polygons.
enum class Overlap { No, Yes, Unsure };

/// Double separating-axis test of two counter-clockwise convex polygons: No or Yes when
/// every margin is clear of round-off, else Unsure (touching faces: shared edges).
Overlap overlapFilter(const std::vector<Eigen::Vector2d>& pd,
                      const std::vector<Eigen::Vector2d>& qd) {
  bool certain = true;
  const auto clearlySeparates = [&](const std::vector<Eigen::Vector2d>& a,
                                    const std::vector<Eigen::Vector2d>& b) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      const Eigen::Vector2d e = a[(i + 1) % a.size()] - a[i];
      const double eps = 1e-9 * (1.0 + e.norm() + a[i].norm());
      double best = -std::numeric_limits<double>::infinity();
      for (const Eigen::Vector2d& x : b) {
        const Eigen::Vector2d d = x - a[i];
        best = std::max(best, (e.x() * d.y() - e.y() * d.x()) / e.norm());
      }
      if (best < -eps) return true;
      if (best <= eps) certain = false;
    }
    return false;
  };
  if (clearlySeparates(pd, qd) || clearlySeparates(qd, pd)) return Overlap::No;
  return certain ? Overlap::Yes : Overlap::Unsure;
}

/// Whether two counter-clockwise convex polygons share an area > 0 (separating axis test on
/// the edges of both, exact).
bool overlapExact(const std::vector<Point2>& p, const std::vector<Point2>& q) {
  const auto separates = [](const std::vector<Point2>& a, const std::vector<Point2>& b) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      const Point2& s = a[i];
      const Point2& t = a[(i + 1) % a.size()];
      const bool all_outside = std::all_of(b.begin(), b.end(), [&](const Point2& x) {
        return CGAL::orientation(s, t, x) != CGAL::LEFT_TURN;
      });
      if (all_outside) return true;
    }
    return false;
  };
  return !separates(p, q) && !separates(q, p);
}

/// Area of the intersection of two convex counter-clockwise polygons (double; m2 in the
/// projection, scaled back to the plane by `scale`).
double overlapArea(const std::vector<Point2>& p, const std::vector<Point2>& q, double scale) {
  std::vector<Eigen::Vector2d> clipped = toDouble(p);
  const std::vector<Eigen::Vector2d> qd = toDouble(q);
  for (std::size_t i = 0; i < qd.size() && clipped.size() >= 3; ++i) {
    const Eigen::Vector2d s = qd[i];
    const Eigen::Vector2d e = qd[(i + 1) % qd.size()] - s;
    std::vector<Eigen::Vector2d> out;
    for (std::size_t k = 0; k < clipped.size(); ++k) {
      const Eigen::Vector2d& x = clipped[k];
      const Eigen::Vector2d& y = clipped[(k + 1) % clipped.size()];
      const double sx = e.x() * (x - s).y() - e.y() * (x - s).x();
      const double sy = e.x() * (y - s).y() - e.y() * (y - s).x();
      if (sx >= 0.0) out.push_back(x);
      if ((sx > 0.0 && sy < 0.0) || (sx < 0.0 && sy > 0.0))
        out.push_back(x + sx / (sx - sy) * (y - x));
    }
    clipped = std::move(out);
  }
  double twice = 0.0;
  for (std::size_t i = 0; clipped.size() >= 3 && i < clipped.size(); ++i) {
    const Eigen::Vector2d& a = clipped[i];
    const Eigen::Vector2d& b = clipped[(i + 1) % clipped.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * std::abs(twice) * scale;
}

}  // namespace

/// Matches faces in the same plane on opposite sides: pieces glue where the shared part is
/// not wholly covered by discs (region faces are never covered); covered shared parts
/// between pieces are crack contacts.
///
/// Candidate pairs come from a sweep over the faces' u-ranges in each plane. A pair whose
/// pieces are already glued is skipped: gluing them again changes nothing, and a crack
/// between two pieces of one block is no adjacency. So pairs the double filter decides run
/// first, and the pairs it cannot decide (faces that share an edge, where the exact test is
/// expensive) only afterwards, when most of them already lie in one block.
std::vector<CrackContact> matchFaces(const Context& context, const std::vector<FaceRecord>& records,
                                     UnionFind& sets, bool discs) {
  std::map<std::tuple<int, int, double>, std::vector<const FaceRecord*>> by_plane;
  for (const FaceRecord& r : records) {
    // The referee glues its Nef volumes across region faces only.
    if (!discs && std::get<0>(r.plane_key) != 0) continue;
    by_plane[r.plane_key].push_back(&r);
  }
  std::vector<CrackContact> cracks;
  // Decides one pair that overlaps with area: glue, or record the crack.
  const auto settle = [&](const FaceRecord* a, const FaceRecord* b) {
    if (std::get<0>(a->plane_key) != 1) {  // region faces, mesh planes inside the domain
      sets.unite(a->piece, b->piece);
      return;
    }
    const int group = std::get<1>(a->plane_key);
    const bool covered =
        a->source.kind == FaceKind::Disc || b->source.kind == FaceKind::Disc || [&] {
          std::vector<Point2> shared = a->polygon;
          for (std::size_t i = 0; i < b->polygon.size() && shared.size() >= 3; ++i) {
            shared = clipHalfPlane(shared, b->polygon[i], b->polygon[(i + 1) % b->polygon.size()],
                                   /*left=*/true);
          }
          return coveredByGroup(context, group, shared, a->drop_axis);
        }();
    if (!covered) {
      sets.unite(a->piece, b->piece);
    } else {
      const ExactDisc& disc =
          context.discs[static_cast<std::size_t>(context.groups[group].front())];
      const double scale = 1.0 / std::abs(disc.plane.normal[disc.drop_axis]);
      const FaceSource source = a->source.kind == FaceKind::Disc ? a->source : b->source;
      cracks.push_back({a->piece, b->piece, source, overlapArea(a->polygon, b->polygon, scale)});
    }
  };
  std::vector<std::pair<const FaceRecord*, const FaceRecord*>> unsure;
  for (auto& [key, faces] : by_plane) {
    std::vector<const FaceRecord*> below;
    std::vector<const FaceRecord*> above;
    for (const FaceRecord* r : faces) (r->above ? above : below).push_back(r);
    const auto by_u_min = [](const FaceRecord* x, const FaceRecord* y) {
      return x->bounds[0] < y->bounds[0];
    };
    std::sort(above.begin(), above.end(), by_u_min);
    std::vector<std::vector<Eigen::Vector2d>> above_double;
    for (const FaceRecord* b : above) above_double.push_back(toDouble(b->polygon));
    for (const FaceRecord* a : below) {
      const std::vector<Eigen::Vector2d> a_double = toDouble(a->polygon);
      for (std::size_t j = 0; j < above.size() && above[j]->bounds[0] <= a->bounds[1]; ++j) {
        const FaceRecord* b = above[j];
        if (b->bounds[1] < a->bounds[0] || a->bounds[3] < b->bounds[2] ||
            b->bounds[3] < a->bounds[2]) {
          continue;
        }
        if (sets.find(a->piece) == sets.find(b->piece)) continue;
        const Overlap overlap = overlapFilter(a_double, above_double[j]);
        if (overlap == Overlap::Yes) settle(a, b);
        if (overlap == Overlap::Unsure) unsure.emplace_back(a, b);
      }
    }
  }
  for (const auto& [a, b] : unsure) {
    if (sets.find(a->piece) == sets.find(b->piece)) continue;
    if (overlapExact(a->polygon, b->polygon)) settle(a, b);
  }
  return cracks;
}

}  // namespace rockmass::blocks::exactcut
