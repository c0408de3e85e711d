#include "dda3d/contact_hull.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <CGAL/Convex_hull_traits_adapter_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/property_map.h>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>
#include <tuple>

#include "dda3d/contact_detection.h"
#include "dda3d/piece_view.h"

namespace rockmass::dda3d {
namespace {

using geometry::Vec3;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = Kernel::Point_2;
using HullTraits =
    CGAL::Convex_hull_traits_adapter_2<Kernel, CGAL::Pointer_property_map<Point2>::const_type>;

/// Planes are the same when their normals agree within this (1 - cos, 1.4e-3 rad) and each
/// point lies within kCoplanarShare of the group's extent of the other's plane.
constexpr double kNormalSlack = 1e-6;
constexpr double kCoplanarShare = 1e-6;

/// True when plane `b` is plane `a` (normals within kNormalSlack, `x`, a point of b, within
/// `tolerance` of a).
bool samePlane(const detection::Plane& a, const detection::Plane& b, const Vec3& x,
               double tolerance) {
  return a.normal.dot(b.normal) > 1.0 - kNormalSlack &&
         std::abs(a.normal.dot(x) - a.offset) <= tolerance;
}

/// The corners of the convex hull of `points` (counter-clockwise), without those within
/// `tolerance` of the line through their neighbours (removed one at a time, in hull order,
/// until none is).
std::vector<std::size_t> hullCorners(const std::vector<Point2>& points, double tolerance) {
  std::vector<std::size_t> indices(points.size()), hull;
  std::iota(indices.begin(), indices.end(), std::size_t{0});
  CGAL::convex_hull_2(indices.begin(), indices.end(), std::back_inserter(hull),
                      HullTraits(CGAL::make_property_map(points)));
  bool removed = true;
  while (removed && hull.size() > 2) {
    removed = false;
    for (std::size_t k = 0; k < hull.size() && hull.size() > 2; ++k) {
      const Point2& a = points[hull[(k + hull.size() - 1) % hull.size()]];
      const Point2& p = points[hull[k]];
      const Point2& b = points[hull[(k + 1) % hull.size()]];
      const double bx = b.x() - a.x(), by = b.y() - a.y();
      const double length = std::hypot(bx, by);
      const double off_line = std::abs(bx * (p.y() - a.y()) - by * (p.x() - a.x()));
      if (off_line <= tolerance * length) {
        hull.erase(hull.begin() + static_cast<std::ptrdiff_t>(k));
        removed = true;
        --k;
      }
    }
  }
  return hull;
}

/// Marks in `keep` the entries of one group (same blocks and joint; `members`, in found
/// order) that are not corners of their planes' hull.
void reduceGroup(const std::vector<Contact>& contacts, const std::vector<BlockState>& blocks,
                 const std::size_t* members, std::size_t count, std::vector<char>& keep) {
  Vec3 low = contacts[members[0]].foot, high = low;
  for (std::size_t k = 1; k < count; ++k) {
    low = low.cwiseMin(contacts[members[k]].foot);
    high = high.cwiseMax(contacts[members[k]].foot);
  }
  const double tolerance = kCoplanarShare * (high - low).norm();
  if (!(tolerance > 0.0)) return;
  // Clusters of one plane of j and one plane of i, in found order: the first entry of a
  // cluster gives its planes.
  struct Cluster {
    detection::Plane j, i;
    std::vector<std::size_t> members;
  };
  std::vector<Cluster> clusters;
  for (std::size_t k = 0; k < count; ++k) {
    const Contact& c = contacts[members[k]];
    const detection::Plane j{c.normal, c.normal.dot(c.foot), 0.0};
    const detection::Plane i = detection::facePlane(
        blocks[static_cast<std::size_t>(c.block_i)].pieces[static_cast<std::size_t>(c.piece_i)],
        static_cast<std::size_t>(c.facing_face));
    auto found = std::find_if(clusters.begin(), clusters.end(), [&](const Cluster& cl) {
      return samePlane(cl.j, j, c.foot, tolerance) && samePlane(cl.i, i, c.point, tolerance);
    });
    if (found == clusters.end()) {
      clusters.push_back({j, i, {}});
      found = std::prev(clusters.end());
    }
    found->members.push_back(members[k]);
  }
  for (const Cluster& cluster : clusters) {
    if (cluster.members.size() < 3) continue;
    Vec3 t1, t2;
    tangents(cluster.j.normal, t1, t2);
    std::vector<Point2> points;
    points.reserve(cluster.members.size());
    for (std::size_t m : cluster.members) {
      points.emplace_back(t1.dot(contacts[m].foot), t2.dot(contacts[m].foot));
    }
    std::vector<char> corner(points.size(), 0);
    for (std::size_t h : hullCorners(points, tolerance)) corner[h] = 1;
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (!corner[k]) keep[cluster.members[k]] = 0;
    }
  }
}

}  // namespace

std::size_t keepHullCorners(std::vector<Contact>& contacts, const std::vector<BlockState>& blocks) {
  std::vector<std::size_t> facing;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    if (c.kind == ContactKind::VertexFace && c.facing_face >= 0) facing.push_back(k);
  }
  const auto key = [&](std::size_t k) {
    const Contact& c = contacts[k];
    return std::make_tuple(c.block_i, c.block_j, c.joint);
  };
  tbb::parallel_sort(facing.begin(), facing.end(), [&](std::size_t a, std::size_t b) {
    return std::make_tuple(key(a), a) < std::make_tuple(key(b), b);
  });
  std::vector<std::size_t> group_start;
  for (std::size_t k = 0; k < facing.size(); ++k) {
    if (k == 0 || key(facing[k]) != key(facing[k - 1])) group_start.push_back(k);
  }
  group_start.push_back(facing.size());
  std::vector<char> keep(contacts.size(), 1);
  // Each group marks its own entries only: in parallel, the same marks as one loop.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, group_start.size() - 1, 64),
                    [&](const tbb::blocked_range<std::size_t>& groups) {
                      for (std::size_t g = groups.begin(); g != groups.end(); ++g) {
                        const std::size_t count = group_start[g + 1] - group_start[g];
                        if (count < 3) continue;
                        reduceGroup(contacts, blocks, facing.data() + group_start[g], count, keep);
                      }
                    });
  std::size_t kept = 0;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    if (!keep[k]) continue;
    if (kept != k) contacts[kept] = std::move(contacts[k]);
    ++kept;
  }
  const std::size_t dropped = contacts.size() - kept;
  contacts.resize(kept);
  return dropped;
}

}  // namespace rockmass::dda3d
