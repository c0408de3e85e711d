#pragma once
/// DDA-shaped sparse SPD systems for the solver tests and bench/solver_bench.cpp: a grid of
/// unit cubes, each with the 12 unknowns of docs dda3d-formulation.md, the elastic term V E,
/// optionally the inertia term (2 / dt^2) M, contact springs (normal k_n, shear k_n / 2.5)
/// at four points of every shared face, and fixed-point springs under the bottom layer. A
/// soft layer (every other z layer) divides Young's modulus by `contrast`.
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "dda3d/displacement_field.h"
#include "dda3d/linear_solver.h"

namespace rockmass::test {

/// What the generated system looks like.
struct DdaSystemSpec {
  int nx = 3, ny = 3, nz = 3;     ///< blocks per axis (unit cubes)
  double young = 10e9;            ///< Pa, of the stiff blocks
  double contrast = 1e3;          ///< stiff / soft Young's modulus
  bool dynamic = true;            ///< add the inertia term (2 / dt^2) M
  double time_step = 1e-3;        ///< s
  double density = 2600.0;        ///< kg/m3
  double penalty_factor = 100.0;  ///< contact penalty k_n = factor * young * 1 m
};

/// Matrix order of the system (12 per block).
inline int ddaSystemSize(const DdaSystemSpec& spec) {
  return dda3d::kBlockDofs * spec.nx * spec.ny * spec.nz;
}

/// The assembled K (both triangles stored, compressed).
inline dda3d::SparseMatrix ddaSystemMatrix(const DdaSystemSpec& spec) {
  using dda3d::displacementMatrix;
  using dda3d::DisplacementMatrix;
  using geometry::Vec3;
  constexpr int kDofs = dda3d::kBlockDofs;
  using BlockMatrix = Eigen::Matrix<double, kDofs, kDofs>;
  using BlockVector = Eigen::Matrix<double, kDofs, 1>;

  const auto index = [&](int i, int j, int k) { return (k * spec.ny + j) * spec.nx + i; };
  const auto centroid = [](int i, int j, int k) { return Vec3(i + 0.5, j + 0.5, k + 0.5); };
  const double k_normal = spec.penalty_factor * spec.young;
  const double k_shear = k_normal / 2.5;

  std::vector<Eigen::Triplet<double>> triplets;
  const auto addBlock = [&](int row_block, int col_block, const BlockMatrix& m) {
    for (int c = 0; c < kDofs; ++c) {
      for (int r = 0; r < kDofs; ++r) {
        triplets.emplace_back(row_block * kDofs + r, col_block * kDofs + c, m(r, c));
      }
    }
  };

  // Inertia of a unit cube: M = rho * integral of T^T T, exact with 2 Gauss points per axis
  // (T is linear, T^T T quadratic).
  BlockMatrix mass = BlockMatrix::Zero();
  const double g = 0.5 / std::sqrt(3.0);
  for (double x : {-g, g}) {
    for (double y : {-g, g}) {
      for (double z : {-g, g}) {
        const DisplacementMatrix t = displacementMatrix(Vec3(x, y, z), Vec3::Zero());
        mass += spec.density * 0.125 * t.transpose() * t;
      }
    }
  }

  for (int k = 0; k < spec.nz; ++k) {
    for (int j = 0; j < spec.ny; ++j) {
      for (int i = 0; i < spec.nx; ++i) {
        const int b = index(i, j, k);
        const double young = (k % 2 == 1) ? spec.young / spec.contrast : spec.young;
        BlockMatrix diag = BlockMatrix::Zero();
        diag.bottomRightCorner<6, 6>() = dda3d::elasticMatrix(young, 0.25);  // V = 1 m3
        if (spec.dynamic) diag += 2.0 / (spec.time_step * spec.time_step) * mass;
        if (k == 0) {
          // Fixed points at the four bottom corners hold the pile.
          for (double x : {0.0, 1.0}) {
            for (double y : {0.0, 1.0}) {
              const DisplacementMatrix t =
                  displacementMatrix(Vec3(i + x, j + y, 0.0), centroid(i, j, k));
              diag += k_normal * t.transpose() * t;
            }
          }
        }
        addBlock(b, b, diag);
        // Contacts with the +x, +y, +z neighbours: 4 points inset 0.1 m on the shared face,
        // each with a normal and two shear springs.
        const std::array<std::array<int, 3>, 3> steps{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
        for (int axis = 0; axis < 3; ++axis) {
          const int ni = i + steps[axis][0], nj = j + steps[axis][1], nk = k + steps[axis][2];
          if (ni >= spec.nx || nj >= spec.ny || nk >= spec.nz) continue;
          const int nb = index(ni, nj, nk);
          const int u = (axis + 1) % 3, v = (axis + 2) % 3;
          BlockMatrix kii = BlockMatrix::Zero(), kij = BlockMatrix::Zero(),
                      kjj = BlockMatrix::Zero();
          for (double a : {0.1, 0.9}) {
            for (double c : {0.1, 0.9}) {
              Vec3 p = centroid(i, j, k) - Vec3::Constant(0.5);
              p[axis] += 1.0;
              p[u] += a;
              p[v] += c;
              const DisplacementMatrix ti = displacementMatrix(p, centroid(i, j, k));
              const DisplacementMatrix tj = displacementMatrix(p, centroid(ni, nj, nk));
              for (int d = 0; d < 3; ++d) {
                const double stiffness = d == axis ? k_normal : k_shear;
                const BlockVector e = ti.row(d).transpose();
                const BlockVector h = tj.row(d).transpose();
                kii += stiffness * e * e.transpose();
                kij -= stiffness * e * h.transpose();
                kjj += stiffness * h * h.transpose();
              }
            }
          }
          addBlock(b, b, kii);
          addBlock(nb, nb, kjj);
          addBlock(b, nb, kij);
          addBlock(nb, b, kij.transpose());
        }
      }
    }
  }
  const int n = ddaSystemSize(spec);
  dda3d::SparseMatrix matrix(n, n);
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  matrix.makeCompressed();
  return matrix;
}

/// A deterministic solution vector with the scales of DDA increments: translations and
/// rotations O(1e-3), strains O(1e-6), so that every unknown matters to the error norm
/// proportionally to its physical size.
inline Eigen::VectorXd ddaSolution(int size) {
  Eigen::VectorXd x(size);
  for (int r = 0; r < size; ++r) {
    const double wave = std::sin(0.7 * r + 0.3);
    x[r] = (r % dda3d::kBlockDofs < 6 ? 1e-3 : 1e-6) * wave;
  }
  return x;
}

}  // namespace rockmass::test
