#include "blocks/convex_partition.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Partition_traits_2.h>
#include <CGAL/partition_2.h>

#include <algorithm>
#include <iterator>
#include <list>
#include <numeric>
#include <stdexcept>

namespace rockmass::blocks {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Traits = CGAL::Partition_traits_2<Kernel>;
using Point = Traits::Point_2;

/// Twice the signed area (positive for counter-clockwise).
double signedArea2(const std::vector<geometry::Vec2>& p) {
  double sum = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const geometry::Vec2& a = p[i];
    const geometry::Vec2& b = p[(i + 1) % p.size()];
    sum += a.x() * b.y() - a.y() * b.x();
  }
  return sum;
}

}  // namespace

bool isConvex(const std::vector<geometry::Vec2>& polygon) {
  const double sign = signedArea2(polygon) >= 0.0 ? 1.0 : -1.0;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point a(polygon[i].x(), polygon[i].y());
    const Point b(polygon[(i + 1) % n].x(), polygon[(i + 1) % n].y());
    const Point c(polygon[(i + 2) % n].x(), polygon[(i + 2) % n].y());
    // Exact orientation predicate: a right turn in a counter-clockwise polygon is reflex.
    const CGAL::Orientation o = CGAL::orientation(a, b, c);
    if ((sign > 0 && o == CGAL::RIGHT_TURN) || (sign < 0 && o == CGAL::LEFT_TURN)) return false;
  }
  return true;
}

std::vector<std::vector<int>> convexPartition(const std::vector<geometry::Vec2>& polygon) {
  std::vector<int> order(polygon.size());
  std::iota(order.begin(), order.end(), 0);
  if (signedArea2(polygon) < 0.0) std::reverse(order.begin(), order.end());
  if (isConvex(polygon)) return {order};
  Traits::Polygon_2 input;
  for (int i : order) input.push_back(Point(polygon[i].x(), polygon[i].y()));
  if (!input.is_simple()) throw std::invalid_argument("the polygon is not simple");
  std::list<Traits::Polygon_2> parts;
  CGAL::approx_convex_partition_2(input.vertices_begin(), input.vertices_end(),
                                  std::back_inserter(parts));
  std::vector<std::vector<int>> out;
  for (const Traits::Polygon_2& part : parts) {
    std::vector<int> indices;
    for (auto v = part.vertices_begin(); v != part.vertices_end(); ++v) {
      // Partition vertices are input vertices: find which one (n is small).
      for (int i : order) {
        if (polygon[i].x() == v->x() && polygon[i].y() == v->y()) {
          indices.push_back(i);
          break;
        }
      }
    }
    out.push_back(std::move(indices));
  }
  return out;
}

}  // namespace rockmass::blocks
