// Sub-contact points: each face of a piece cut into a grid of cells, a point at each cell's
// centroid carrying the cell's area (docs/stability.md, "Contact points").
#include <algorithm>
#include <cmath>
#include <limits>

#include "dda3d/contact_detection.h"
#include "dda3d/polygon2d.h"
#include "geometry/polyhedron.h"

namespace rockmass::dda3d {

using geometry::Polyhedron;
using geometry::Vec3;

namespace {

/// A face in its own 2D frame (u along its longest edge, w = n x u, from its first vertex)
/// and the grid of cells facePoints cuts it into (nu x nw; none when nu or nw < 2).
struct FaceGrid {
  Vec3 origin = Vec3::Zero(), u = Vec3::Zero(), w = Vec3::Zero();
  std::vector<Point2> polygon;
  Point2 low = Point2::Zero(), size = Point2::Zero();
  int nu = 0, nw = 0;
};

FaceGrid faceGrid(const geometry::Polyhedron& piece, std::size_t f, double spacing,
                  int max_per_face) {
  FaceGrid grid;
  const std::vector<int>& face = piece.faces[f];
  if (face.size() < 3 || !(spacing > 0.0)) return grid;
  const Vec3 n = geometry::faceNormal(piece, static_cast<int>(f));
  for (std::size_t k = 0; k < face.size(); ++k) {
    const Vec3 e = piece.vertices[static_cast<std::size_t>(face[(k + 1) % face.size()])] -
                   piece.vertices[static_cast<std::size_t>(face[k])];
    if (e.squaredNorm() > grid.u.squaredNorm()) grid.u = e;
  }
  if (!(grid.u.squaredNorm() > 0.0)) return grid;
  grid.u.normalize();
  grid.w = n.cross(grid.u).normalized();
  grid.origin = piece.vertices[static_cast<std::size_t>(face[0])];
  Point2 low = Point2::Constant(std::numeric_limits<double>::infinity());
  Point2 high = -low;
  for (int v : face) {
    const Vec3 x = piece.vertices[static_cast<std::size_t>(v)] - grid.origin;
    grid.polygon.emplace_back(x.dot(grid.u), x.dot(grid.w));
    low = low.cwiseMin(grid.polygon.back());
    high = high.cwiseMax(grid.polygon.back());
  }
  grid.low = low;
  grid.size = high - low;
  // Counted in doubles first: a spacing far below the face's size must not overflow.
  const double cu = std::ceil(grid.size.x() / spacing - 1e-9);
  const double cw = std::ceil(grid.size.y() / spacing - 1e-9);
  if (!(cu >= 2.0 && cw >= 2.0)) return grid;
  double nu = cu, nw = cw;
  while (nu * nw > max_per_face) {
    nu = std::max(2.0, std::ceil(nu / 2.0));
    nw = std::max(2.0, std::ceil(nw / 2.0));
  }
  grid.nu = static_cast<int>(nu);
  grid.nw = static_cast<int>(nw);
  return grid;
}

}  // namespace

std::size_t facePointBound(const Polyhedron& piece, double spacing, int max_per_face) {
  std::size_t count = 0;
  for (std::size_t f = 0; f < piece.faces.size(); ++f) {
    const FaceGrid grid = faceGrid(piece, f, spacing, max_per_face);
    count += static_cast<std::size_t>(grid.nu) * static_cast<std::size_t>(grid.nw);
  }
  return count;
}

FacePoints facePoints(const Polyhedron& piece, double spacing, int max_per_face) {
  FacePoints out;
  if (!(spacing > 0.0)) return out;
  out.first.push_back(0);
  for (std::size_t f = 0; f < piece.faces.size(); ++f) {
    const FaceGrid grid = faceGrid(piece, f, spacing, max_per_face);
    for (int i = 0; i < grid.nu && grid.nw >= 2; ++i) {
      for (int j = 0; j < grid.nw; ++j) {
        const Point2 c0 =
            grid.low + Point2(grid.size.x() * i / grid.nu, grid.size.y() * j / grid.nw);
        const Point2 c1 =
            grid.low + Point2(grid.size.x() * (i + 1) / grid.nu, grid.size.y() * (j + 1) / grid.nw);
        // The cell clipped to the face (convex, counter-clockwise about its normal).
        std::vector<Point2> cell{c0, {c1.x(), c0.y()}, c1, {c0.x(), c1.y()}};
        for (std::size_t k = 0; k < grid.polygon.size() && cell.size() >= 3; ++k) {
          const Point2& p = grid.polygon[k];
          const Point2 edge = grid.polygon[(k + 1) % grid.polygon.size()] - p;
          cell = clipped(cell, [&](const Point2& x) { return -cross2(edge, x - p); });
        }
        if (cell.size() < 3) continue;
        const double area = polygonArea(cell);
        if (!(area > 1e-12 * grid.size.x() * grid.size.y())) continue;
        const Point2 centroid = polygonCentroid(cell, area);
        out.points.push_back({grid.origin + centroid.x() * grid.u + centroid.y() * grid.w,
                              static_cast<int>(f), area});
      }
    }
    out.first.push_back(static_cast<int>(out.points.size()));
  }
  if (out.points.empty()) out.first.clear();
  return out;
}

}  // namespace rockmass::dda3d
