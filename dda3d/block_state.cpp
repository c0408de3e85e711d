#include "dda3d/block_state.h"

#include <algorithm>
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
  // The faces around both ends of each edge.
  topology.edge_face_start.push_back(0);
  for (const std::array<int, 2>& edge : topology.edges) {
    const std::vector<int>& second = topology.vertex_faces[static_cast<std::size_t>(edge[1])];
    for (int f : topology.vertex_faces[static_cast<std::size_t>(edge[0])]) {
      if (std::find(second.begin(), second.end(), f) != second.end()) {
        topology.edge_face_list.push_back(f);
      }
    }
    topology.edge_face_start.push_back(static_cast<int>(topology.edge_face_list.size()));
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

BlockMotion::BlockMotion(const Vec3& centroid, const BlockVector& d)
    : centroid_(centroid), translation_(d.head<3>()), rotation_(rotationMatrix(d.segment<3>(3))) {
  // clang-format off
  strain_ << d[6],       0.5 * d[11], 0.5 * d[10],
             0.5 * d[11], d[7],       0.5 * d[9],
             0.5 * d[10], 0.5 * d[9], d[8];
  // clang-format on
}

Vec3 movedPoint(const Vec3& x, const Vec3& centroid, const BlockVector& d) {
  return BlockMotion(centroid, d)(x);
}

}  // namespace rockmass::dda3d
