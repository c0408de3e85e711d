#include "dda3d/block_state.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include <Eigen/Geometry>

namespace rockmass::dda3d {

using geometry::Vec3;

PieceTopology pieceTopology(const geometry::Polyhedron& piece) {
  PieceTopology topology;
  const std::size_t n = piece.vertices.size();
  topology.neighbours.resize(n);
  topology.vertex_faces.resize(n);
  std::map<std::pair<int, int>, int> seen;
  for (std::size_t f = 0; f < piece.faces.size(); ++f) {
    const std::vector<int>& face = piece.faces[f];
    for (std::size_t k = 0; k < face.size(); ++k) {
      const int a = face[k];
      const int b = face[(k + 1) % face.size()];
      topology.vertex_faces[static_cast<std::size_t>(a)].push_back(static_cast<int>(f));
      const std::pair<int, int> key(std::min(a, b), std::max(a, b));
      if (seen.emplace(key, static_cast<int>(topology.edges.size())).second) {
        topology.edges.push_back({key.first, key.second});
        topology.neighbours[static_cast<std::size_t>(a)].push_back(b);
        topology.neighbours[static_cast<std::size_t>(b)].push_back(a);
      }
    }
  }
  return topology;
}

void BlockState::updateMassProperties() {
  // Moments about a vertex of the block, not the origin: a sliver 1 mm thick 300 m from the
  // origin would otherwise lose every digit of its central second moments (and its mass
  // matrix would not be positive definite).
  geometry::MassProperties total;
  const Vec3 reference = pieces.empty() || pieces.front().vertices.empty()
                             ? Vec3::Zero()
                             : pieces.front().vertices.front();
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 high = -low;
  for (const geometry::Polyhedron& piece : pieces) {
    total += geometry::massProperties(piece, reference);
    const geometry::Box box = geometry::bounds(piece);
    low = low.cwiseMin(box.min);
    high = high.cwiseMax(box.max);
  }
  volume = total.volume;
  centroid = reference + total.centroid();
  second = total.centralSecond();
  size = (high - low).norm();
}

BlockMatrix massMatrix(const BlockState& block) {
  // T(X) = [I | A(X)], A linear in X: A(X) = sum_k X_k A_k. Then
  // integral T^T T = [[V I, 0], [0, sum_kl S_kl A_k^T A_l]] with S the central second moments.
  std::array<Eigen::Matrix<double, 3, 9>, 3> a;
  for (int k = 0; k < 3; ++k) {
    a[static_cast<std::size_t>(k)] = displacementMatrix(Vec3::Unit(k), Vec3::Zero()).rightCols<9>();
  }
  BlockMatrix m = BlockMatrix::Zero();
  m.topLeftCorner<3, 3>() = block.volume * Eigen::Matrix3d::Identity();
  for (int k = 0; k < 3; ++k) {
    for (int l = 0; l < 3; ++l) {
      m.bottomRightCorner<9, 9>() += block.second(k, l) *
                                     a[static_cast<std::size_t>(k)].transpose() *
                                     a[static_cast<std::size_t>(l)];
    }
  }
  const double density = block.volume > 0.0 ? block.mass / block.volume : 0.0;
  return density * m;
}

Eigen::Matrix3d rotationMatrix(const Vec3& rotation) {
  const double angle = rotation.norm();
  if (angle == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, rotation / angle).toRotationMatrix();
}

Vec3 movedPoint(const Vec3& x, const Vec3& centroid, const BlockVector& d) {
  const Vec3 arm = x - centroid;
  Eigen::Matrix3d strain;
  // clang-format off
  strain << d[6],       0.5 * d[11], 0.5 * d[10],
            0.5 * d[11], d[7],       0.5 * d[9],
            0.5 * d[10], 0.5 * d[9], d[8];
  // clang-format on
  return centroid + d.head<3>() + rotationMatrix(d.segment<3>(3)) * arm + strain * arm;
}

namespace {

/// A face in its own 2D frame (u along its longest edge, w = n x u, from its first vertex)
/// and the grid of cells facePoints cuts it into (nu x nw; none when nu or nw < 2).
struct FaceGrid {
  Vec3 origin = Vec3::Zero(), u = Vec3::Zero(), w = Vec3::Zero();
  std::vector<Eigen::Vector2d> polygon;
  Eigen::Vector2d low = Eigen::Vector2d::Zero(), size = Eigen::Vector2d::Zero();
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
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d high = -low;
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

std::size_t facePointBound(const geometry::Polyhedron& piece, double spacing, int max_per_face) {
  std::size_t count = 0;
  for (std::size_t f = 0; f < piece.faces.size(); ++f) {
    const FaceGrid grid = faceGrid(piece, f, spacing, max_per_face);
    count += static_cast<std::size_t>(grid.nu) * static_cast<std::size_t>(grid.nw);
  }
  return count;
}

std::vector<FacePoint> facePoints(const geometry::Polyhedron& piece, double spacing,
                                  int max_per_face) {
  std::vector<FacePoint> out;
  if (!(spacing > 0.0)) return out;
  for (std::size_t f = 0; f < piece.faces.size(); ++f) {
    const FaceGrid grid = faceGrid(piece, f, spacing, max_per_face);
    const int nu = grid.nu, nw = grid.nw;
    if (nu < 2 || nw < 2) continue;
    const std::vector<Eigen::Vector2d>& polygon = grid.polygon;
    const Eigen::Vector2d& low = grid.low;
    const Eigen::Vector2d& size = grid.size;
    const Vec3 &origin = grid.origin, &u = grid.u, &w = grid.w;
    // Each cell clipped to the face (convex: Sutherland-Hodgman against its edges, taken
    // counter-clockwise about n).
    for (int i = 0; i < nu; ++i) {
      for (int j = 0; j < nw; ++j) {
        const Eigen::Vector2d c0 = low + Eigen::Vector2d(size.x() * i / nu, size.y() * j / nw);
        const Eigen::Vector2d c1 =
            low + Eigen::Vector2d(size.x() * (i + 1) / nu, size.y() * (j + 1) / nw);
        std::vector<Eigen::Vector2d> cell{c0, {c1.x(), c0.y()}, c1, {c0.x(), c1.y()}};
        for (std::size_t k = 0; k < polygon.size() && cell.size() >= 3; ++k) {
          const Eigen::Vector2d& p = polygon[k];
          const Eigen::Vector2d edge = polygon[(k + 1) % polygon.size()] - p;
          const auto inside = [&](const Eigen::Vector2d& x) {
            const Eigen::Vector2d r = x - p;
            return edge.x() * r.y() - edge.y() * r.x();  // >= 0: left of the edge
          };
          std::vector<Eigen::Vector2d> next;
          for (std::size_t m = 0; m < cell.size(); ++m) {
            const Eigen::Vector2d& a = cell[m];
            const Eigen::Vector2d& b = cell[(m + 1) % cell.size()];
            const double da = inside(a), db = inside(b);
            if (da >= 0.0) next.push_back(a);
            if ((da >= 0.0) != (db >= 0.0)) next.push_back(a + (b - a) * (da / (da - db)));
          }
          cell = std::move(next);
        }
        if (cell.size() < 3) continue;
        double area = 0.0;
        Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
        for (std::size_t m = 0; m < cell.size(); ++m) {
          const Eigen::Vector2d& a = cell[m];
          const Eigen::Vector2d& b = cell[(m + 1) % cell.size()];
          const double cross = a.x() * b.y() - a.y() * b.x();
          area += 0.5 * cross;
          centroid += cross * (a + b);
        }
        if (!(area > 1e-12 * size.x() * size.y())) continue;
        centroid /= 6.0 * area;
        out.push_back({origin + centroid.x() * u + centroid.y() * w, static_cast<int>(f), area});
      }
    }
  }
  return out;
}

}  // namespace rockmass::dda3d
