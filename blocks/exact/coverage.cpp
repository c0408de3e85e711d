// Whether a face in a disc plane is covered by the union of the discs in that plane, exactly
// (cut_parts.h), with a double filter for the clear cases.
#include "blocks/exact/cut_parts.h"

#include <algorithm>
#include <limits>

namespace rockmass::blocks::exactcut {

namespace {

/// True when the polygon has no area.
bool flat(const std::vector<Point2>& polygon) {
  if (polygon.size() < 3) return true;
  FT twice = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Point2& p = polygon[i];
    const Point2& q = polygon[(i + 1) % polygon.size()];
    twice += p.x() * q.y() - q.x() * p.y();
  }
  return twice == 0;
}

/// Smallest signed distance of q to the edges of a counter-clockwise convex polygon:
/// positive inside, negative outside (double).
double insideDistance(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& q) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d e = polygon[(i + 1) % polygon.size()] - polygon[i];
    const Eigen::Vector2d d = q - polygon[i];
    best = std::min(best, (e.x() * d.y() - e.y() * d.x()) / e.norm());
  }
  return best;
}

/// Quick double answer to coveredByGroup for a one-disc group: covered when every vertex is
/// clearly inside the disc, not covered when one is clearly outside, else unknown.
std::optional<bool> quickCovered(const Context& context, int group,
                                 const std::vector<Eigen::Vector2d>& polygon, int drop_axis) {
  const std::vector<int>& members = context.groups[static_cast<std::size_t>(group)];
  if (members.size() != 1) return std::nullopt;
  const ExactDisc& disc = context.discs[static_cast<std::size_t>(members.front())];
  if (disc.drop_axis != drop_axis) return std::nullopt;
  const double eps = 1e-9 * (1.0 + disc.bounds.diagonal());
  bool all_inside = true;
  for (const Eigen::Vector2d& q : polygon) {
    const double d = insideDistance(disc.ccw2d, q);
    if (d < -eps) return false;
    all_inside = all_inside && d > eps;
  }
  if (all_inside) return true;
  return std::nullopt;
}

}  // namespace

/// Keeps the part of a convex polygon on the left of s->t (or on the right when `left` is
/// false), exact.
std::vector<Point2> clipHalfPlane(const std::vector<Point2>& polygon, const Point2& s,
                                  const Point2& t, bool left) {
  const K::Line_2 line(s, t);
  const CGAL::Oriented_side keep = left ? CGAL::ON_POSITIVE_SIDE : CGAL::ON_NEGATIVE_SIDE;
  std::vector<Point2> out;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Point2& p = polygon[i];
    const Point2& q = polygon[(i + 1) % polygon.size()];
    const CGAL::Oriented_side sp = line.oriented_side(p);
    const CGAL::Oriented_side sq = line.oriented_side(q);
    if (sp == keep || sp == CGAL::ON_ORIENTED_BOUNDARY) out.push_back(p);
    if (sp != CGAL::ON_ORIENTED_BOUNDARY && sq != CGAL::ON_ORIENTED_BOUNDARY && sp != sq) {
      const auto hit = CGAL::intersection(K::Segment_2(p, q), line);
      if (const Point2* x = hit ? boost::get<Point2>(&*hit) : nullptr) out.push_back(*x);
    }
  }
  return out;
}

/// Counter-clockwise copy of a polygon.
std::vector<Point2> counterClockwise(std::vector<Point2> polygon) {
  FT twice = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Point2& p = polygon[i];
    const Point2& q = polygon[(i + 1) % polygon.size()];
    twice += p.x() * q.y() - q.x() * p.y();
  }
  if (twice < 0) std::reverse(polygon.begin(), polygon.end());
  return polygon;
}

/// Double version of a projected polygon.
std::vector<Eigen::Vector2d> toDouble(const std::vector<Point2>& polygon) {
  std::vector<Eigen::Vector2d> out;
  for (const Point2& p : polygon) out.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()));
  return out;
}

/// Whether the convex polygon (projected by dropping `drop_axis`) lies wholly inside the
/// union of the discs of `group`: the polygon minus each (convex) disc polygon in turn,
/// exactly, leaves nothing with area.
bool coveredByGroup(const Context& context, int group, const std::vector<Point2>& polygon,
                    int drop_axis) {
  if (const auto quick = quickCovered(context, group, toDouble(polygon), drop_axis)) return *quick;
  std::vector<std::vector<Point2>> rest{polygon};
  for (const int d : context.groups[static_cast<std::size_t>(group)]) {
    std::vector<Point2> disc;
    for (const Point3& p : context.discs[static_cast<std::size_t>(d)].polygon) {
      disc.push_back(project(p, drop_axis));
    }
    disc = counterClockwise(std::move(disc));
    std::vector<std::vector<Point2>> next;
    for (std::vector<Point2> piece : rest) {
      for (std::size_t i = 0; i < disc.size() && !flat(piece); ++i) {
        const Point2& s = disc[i];
        const Point2& t = disc[(i + 1) % disc.size()];
        std::vector<Point2> outside = clipHalfPlane(piece, s, t, /*left=*/false);
        if (!flat(outside)) next.push_back(std::move(outside));
        piece = clipHalfPlane(piece, s, t, /*left=*/true);
      }
    }
    rest = std::move(next);
    if (rest.empty()) return true;
  }
  return rest.empty();
}

/// The disc of `group` whose polygon holds point q (projected), else the group's first.
int discHolding(const Context& context, int group, const Point3& q) {
  const std::vector<int>& members = context.groups[static_cast<std::size_t>(group)];
  for (const int d : members) {
    const ExactDisc& disc = context.discs[static_cast<std::size_t>(d)];
    if (CGAL::bounded_side_2(disc.polygon2d.begin(), disc.polygon2d.end(),
                             project(q, disc.drop_axis), K()) != CGAL::ON_UNBOUNDED_SIDE) {
      return d;
    }
  }
  return members.front();
}

}  // namespace rockmass::blocks::exactcut
