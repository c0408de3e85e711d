#include "blocks/cut_budget.h"

#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "geometry/disc.h"

namespace rockmass::blocks {
namespace {

using geometry::Box;
using geometry::Disc;
using geometry::Vec3;
using Vec2 = Eigen::Vector2d;
using BoxWithIndex = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

/// Points per ellipse of the estimate's outlines: the estimate needs the crossings, not the
/// exact ends of the segments.
constexpr int kOutlineSegments = 16;

/// A cutting disc as the estimate sees it: its plane, its in-plane frame, its outline.
struct PlanarDisc {
  int set = 0;
  Vec3 center;
  Vec3 normal;
  Vec3 u, v;                  ///< in-plane unit frame
  std::vector<Vec2> outline;  ///< in (u, v) about `center`
  double radius = 0.0;        ///< of the outline about `center`
  geometry::Box bounds;
};

Vec2 inPlane(const PlanarDisc& d, const Vec3& p) {
  const Vec3 r = p - d.center;
  return {r.dot(d.u), r.dot(d.v)};
}

double cross2(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// The interval of t on the line p + t dir (in the disc's plane) inside the disc's outline
/// (between its first and last crossing: exact for a convex outline).
std::optional<std::array<double, 2>> lineInside(const PlanarDisc& d, const Vec3& p,
                                                const Vec3& dir) {
  const Vec2 p2 = inPlane(d, p);
  const Vec2 d2(dir.dot(d.u), dir.dot(d.v));
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  const std::size_t n = d.outline.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = d.outline[i];
    const Vec2& b = d.outline[(i + 1) % n];
    const Vec2 e = b - a;
    const double denom = cross2(d2, e);
    if (denom == 0.0) continue;
    // p2 + t d2 = a + s e
    const double s = cross2(d2, p2 - a) / denom;
    if (s < 0.0 || s > 1.0) continue;
    const double t = cross2(e, p2 - a) / denom;
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  if (!(lo < hi)) return std::nullopt;
  return std::array<double, 2>{lo, hi};
}

/// A segment cut on a disc by another, in the disc's (u, v) frame.
struct Segment {
  Vec2 a, b;
  double min_u() const { return std::min(a.x(), b.x()); }
  double max_u() const { return std::max(a.x(), b.x()); }
};

bool crosses(const Segment& s, const Segment& t) {
  const Vec2 r = s.b - s.a;
  const Vec2 q = t.b - t.a;
  const double denom = cross2(r, q);
  if (denom == 0.0) return false;
  const double a = cross2(t.a - s.a, q) / denom;
  const double b = cross2(t.a - s.a, r) / denom;
  return a >= 0.0 && a <= 1.0 && b >= 0.0 && b <= 1.0;
}

struct Stop {};

/// The cutting discs of `input` that reach into its domain, in their own planes; sizes
/// `estimate.set_intersections` to the network's sets.
std::vector<PlanarDisc> planarDiscs(const CutInput& input, BlockEstimate& estimate) {
  const Box& domain = input.domain_box;
  std::vector<PlanarDisc> discs;
  if (!input.network) return discs;
  std::size_t sets = input.network->sets.size();
  for (const Disc& disc : input.network->discs) {
    sets = std::max(sets, static_cast<std::size_t>(std::max(disc.set, 0)) + 1);
  }
  estimate.set_intersections.assign(sets, 0);
  for (const Disc& disc : input.network->discs) {
    if (!disc.cuts) continue;
    const Box b = disc.bounds();
    if ((b.max.array() < domain.min.array()).any() || (b.min.array() > domain.max.array()).any()) {
      continue;
    }
    PlanarDisc d;
    d.set = std::max(disc.set, 0);
    d.center = disc.center;
    d.normal = disc.normal.normalized();
    d.u = disc.major.normalized();
    d.v = d.normal.cross(d.u).normalized();
    const std::vector<Vec3> outline =
        disc.polygon.empty() ? disc.outline(kOutlineSegments) : disc.polygon;
    for (const Vec3& p : outline) {
      d.outline.push_back(inPlane(d, p));
      d.radius = std::max(d.radius, d.outline.back().norm());
    }
    d.bounds = b;
    discs.push_back(std::move(d));
  }
  return discs;
}

/// Counts the points where segments cross on each disc into `estimate.vertices` (each point
/// where three discs meet is found on each of the three), by a sweep along u; stops (false)
/// once `total()` passes `limit`.
template <class Total>
bool countVertices(std::vector<std::vector<Segment>>& segments, BlockEstimate& estimate,
                   const Total& total, double limit) {
  std::int64_t crossings = 0;
  for (std::vector<Segment>& on_disc : segments) {
    std::sort(on_disc.begin(), on_disc.end(),
              [](const Segment& s, const Segment& t) { return s.min_u() < t.min_u(); });
    for (std::size_t i = 0; i < on_disc.size(); ++i) {
      const double end = on_disc[i].max_u();
      for (std::size_t j = i + 1; j < on_disc.size() && on_disc[j].min_u() <= end; ++j) {
        if (crosses(on_disc[i], on_disc[j])) ++crossings;
      }
      estimate.vertices = crossings / 3;
      if (total() > limit) return false;
    }
  }
  estimate.vertices = crossings / 3;
  return true;
}

}  // namespace

BlockEstimate estimateBlocks(const CutInput& input, double limit) {
  BlockEstimate estimate;
  const Box& domain = input.domain_box;
  const double scale = std::max(domain.diagonal(), 1e-300);
  const std::vector<PlanarDisc> discs = planarDiscs(input, estimate);
  estimate.discs = static_cast<std::int64_t>(discs.size());
  const auto total = [&] {
    return 1.0 + static_cast<double>(estimate.discs) + static_cast<double>(estimate.intersections) +
           static_cast<double>(estimate.vertices);
  };
  estimate.blocks = total();
  if (estimate.blocks > limit) {
    estimate.stopped = true;
    return estimate;
  }

  // Pairs: boxes clipped to the domain overlap, and the line of the two planes runs inside
  // both outlines and the domain over a common interval.
  std::vector<BoxWithIndex> boxes;
  boxes.reserve(discs.size());
  for (std::size_t i = 0; i < discs.size(); ++i) {
    const Vec3 lo = discs[i].bounds.min.cwiseMax(domain.min);
    const Vec3 hi = discs[i].bounds.max.cwiseMin(domain.max);
    boxes.emplace_back(CGAL::Bbox_3(lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z()),
                       static_cast<int>(i));
  }
  std::vector<std::vector<Segment>> segments(discs.size());
  const auto pair = [&](const BoxWithIndex& box_a, const BoxWithIndex& box_b) {
    const PlanarDisc& a = discs[static_cast<std::size_t>(box_a.info())];
    const PlanarDisc& b = discs[static_cast<std::size_t>(box_b.info())];
    Vec3 dir = a.normal.cross(b.normal);
    const double sine = dir.norm();
    if (sine < 1e-9) return;  // parallel planes do not cross
    // Each disc must reach the other's plane: its centre lies within radius x sine of it.
    const Vec3 between = b.center - a.center;
    if (std::abs(a.normal.dot(between)) > b.radius * sine ||
        std::abs(b.normal.dot(between)) > a.radius * sine) {
      return;
    }
    const double ha = a.normal.dot(a.center);
    const double hb = b.normal.dot(b.center);
    const Vec3 p = (ha * b.normal.cross(dir) + hb * dir.cross(a.normal)) / (sine * sine);
    dir /= sine;
    // The line misses a disc whose centre is farther from it than the disc's radius.
    if ((a.center - p).cross(dir).squaredNorm() > a.radius * a.radius ||
        (b.center - p).cross(dir).squaredNorm() > b.radius * b.radius) {
      return;
    }
    const double far = std::numeric_limits<double>::infinity();
    const auto in_box = geometry::lineInterval(domain, p, dir, -far, far);
    if (!in_box) return;
    const auto in_a = lineInside(a, p, dir);
    if (!in_a) return;
    const auto in_b = lineInside(b, p, dir);
    if (!in_b) return;
    const double lo = std::max({(*in_a)[0], (*in_b)[0], (*in_box)[0]});
    const double hi = std::min({(*in_a)[1], (*in_b)[1], (*in_box)[1]});
    if (!(hi - lo > 1e-9 * scale)) return;
    ++estimate.intersections;
    ++estimate.set_intersections[static_cast<std::size_t>(a.set)];
    ++estimate.set_intersections[static_cast<std::size_t>(b.set)];
    const Vec3 from = p + lo * dir;
    const Vec3 to = p + hi * dir;
    segments[static_cast<std::size_t>(box_a.info())].push_back({inPlane(a, from), inPlane(a, to)});
    segments[static_cast<std::size_t>(box_b.info())].push_back({inPlane(b, from), inPlane(b, to)});
    if (total() > limit) throw Stop{};
  };
  try {
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), pair);
  } catch (const Stop&) {
    estimate.blocks = total();
    estimate.stopped = true;
    return estimate;
  }

  // Vertices: the segments that cross on a disc.
  if (!countVertices(segments, estimate, total, limit)) {
    estimate.blocks = total();
    estimate.stopped = true;
    return estimate;
  }
  estimate.blocks = total();
  return estimate;
}

}  // namespace rockmass::blocks
