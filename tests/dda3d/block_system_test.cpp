// The block-structured assembly of K D = F (dda3d/block_system.h): a contact point's springs
// added as one 3 x 3 stiffness (addPointSprings, addRigidPointSprings) against the same
// springs added one by one (addSpring), whose energy 1/2 k (d0 + a^T D_i + b^T D_j)^2 is the
// DDA's penalty spring (Shi 1988, ch. 4; docs dda3d-formulation.md).
#include "dda3d/block_system.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "dda3d/displacement_field.h"

namespace rockmass::dda3d {
namespace {

using geometry::Vec3;

/// One contact point's three springs: stiffness k_m along orthonormal e_m with offsets d_m.
struct PointSprings {
  Vec3 e[3];
  double k[3];
  double d[3];
  Eigen::Matrix3d stiffness() const {
    Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
    for (int m = 0; m < 3; ++m) s += k[m] * e[m] * e[m].transpose();
    return s;
  }
  Vec3 offsets() const {
    Vec3 s = Vec3::Zero();
    for (int m = 0; m < 3; ++m) s += k[m] * d[m] * e[m];
    return s;
  }
};

PointSprings testSprings() {
  // A tilted normal (a locked contact's normal spring and two shear springs at a tenth of it).
  const Vec3 n = Vec3(0.3, -0.5, 0.81).normalized();
  const Vec3 t0 = n.unitOrthogonal();
  const Vec3 t1 = n.cross(t0);
  return {{n, t0, t1}, {4.0e9, 4.0e8, 4.0e8}, {-2.0e-4, 3.0e-5, -1.5e-5}};
}

/// The system of blocks 0 and 1 (and fixed -1) from each way of adding the springs.
void expectSameSystems(int dofs, int i, int j) {
  const Vec3 ci(1.0, 2.0, -3.0), cj(2.5, 1.0, -2.0);
  const Vec3 point(1.7, 1.4, -2.4), foot(1.7, 1.4, -2.4002);
  const PointSprings springs = testSprings();
  BlockSystem one_by_one(2, dofs), combined(2, dofs);
  if (i >= 0 && j >= 0) {
    one_by_one.setPairs({{0, 1}});
    combined.setPairs({{0, 1}});
  }
  const DisplacementMatrix ti = displacementMatrix(point, ci);
  const DisplacementMatrix tj = displacementMatrix(foot, cj);
  for (int m = 0; m < 3; ++m) {
    const BlockVector a = ti.transpose() * springs.e[m];
    const BlockVector b = -(tj.transpose() * springs.e[m]);
    one_by_one.addSpring(i, a, j, b, springs.k[m], springs.d[m]);
  }
  if (dofs == 6) {
    combined.addRigidPointSprings(i, rotationColumns(point - ci), j, rotationColumns(foot - cj),
                                  springs.stiffness(), springs.offsets(), BlockSystem::Parts{});
  } else {
    combined.addPointSprings(i, ti, j, tj, springs.stiffness(), springs.offsets(),
                             BlockSystem::Parts{});
  }
  const Eigen::MatrixXd k1 = Eigen::MatrixXd(one_by_one.matrix());
  const Eigen::MatrixXd k2 = Eigen::MatrixXd(combined.matrix());
  ASSERT_EQ(k1.rows(), 2 * dofs);
  ASSERT_EQ(k2.rows(), 2 * dofs);
  // Both are sums of the same products in another order: equal to round-off of the largest
  // entry (k_n |arm|^2 ~ 1e10; 64 eps of it).
  const double scale = k1.cwiseAbs().maxCoeff();
  EXPECT_GT(scale, 1e9);  // the springs did land in K
  EXPECT_LE((k1 - k2).cwiseAbs().maxCoeff(), 64 * 2.2e-16 * scale);
  const Eigen::VectorXd f1 = one_by_one.rhs(), f2 = combined.rhs();
  const double f_scale = f1.cwiseAbs().maxCoeff();
  EXPECT_GT(f_scale, 1e4);
  EXPECT_LE((f1 - f2).cwiseAbs().maxCoeff(), 64 * 2.2e-16 * f_scale);
}

TEST(BlockSystem, DeformablePointSpringsEqualTheirSpringsOneByOne) {
  expectSameSystems(12, 0, 1);
}

TEST(BlockSystem, RigidPointSpringsEqualTheirSpringsOneByOne) {
  expectSameSystems(6, 0, 1);
}

TEST(BlockSystem, PointSpringsAgainstAFixedBodyLoadOnlyTheMovableBlock) {
  // j = -1 (a fixed block) and i = -1: only the movable side's K_ii and F_i, no coupling.
  expectSameSystems(12, 0, -1);
  expectSameSystems(6, -1, 1);
}

/// K and F of 40 contact points between blocks 0 and 1 (or a fixed body, -1), each a
/// different spring (a locked contact's three springs, a sliding contact's normal spring with
/// its friction force and transverse tangent), added point by point (addRigidPointSprings)
/// or as their sums (RigidSpringSums), the latter split into the parts two assembly threads
/// would add (K_ii and F_i, K_jj and F_j, K_ij).
void expectSumsEqualPointByPoint(int i, int j, bool transposed_pair) {
  const Vec3 ci(1.0, 2.0, -3.0), cj(2.5, 1.0, -2.0);
  BlockSystem point_by_point(2, 6), summed(2, 6);
  if (i >= 0 && j >= 0) {
    point_by_point.setPairs({{0, 1}});
    summed.setPairs({{0, 1}});
  }
  // Two threads' sums: one adds K_ii, F_i and K_ij; the other K_jj and F_j.
  BlockSystem::Parts first, second;
  first.j = false;
  second.i = second.pair = false;
  BlockSystem::RigidSpringSums sums_first, sums_second;
  sums_first.with_j = false;
  sums_second.with_i = sums_second.with_pair = false;
  for (int p = 0; p < 40; ++p) {
    const Vec3 point(1.0 + 0.037 * p, 1.1 + 0.071 * (p % 7), -2.9 + 0.013 * (p % 11));
    const Vec3 foot = point - Vec3(0.0, 0.0, 2e-4 * (1 + p % 3));
    const Vec3 n = Vec3(0.3 + 0.01 * p, -0.5, 0.81).normalized();
    Eigen::Matrix3d s = 4.0e9 * n * n.transpose();
    Vec3 offsets = 4.0e9 * (-2.0e-4 + 1e-6 * p) * n;
    const Vec3 t = n.unitOrthogonal();
    if (p % 3 == 0) {
      s += 4.0e8 * (Eigen::Matrix3d::Identity() - n * n.transpose());  // locked: shear springs
      offsets += 4.0e8 * 3.0e-5 * t;
    } else {
      s += 1.0e7 * t * t.transpose();  // sliding: the transverse tangent and the friction
      offsets += 2.0e5 * n.cross(t);
    }
    const Eigen::Matrix3d ri = rotationColumns(point - ci), rj = rotationColumns(foot - cj);
    point_by_point.addRigidPointSprings(i, ri, j, rj, s, offsets, BlockSystem::Parts{});
    sums_first.add(ri, rj, s, offsets);
    sums_second.add(ri, rj, s, offsets);
  }
  // The pair's block as the assembly finds it: stored as K_01, looked up through its slot
  // with the blocks in either order.
  bool transposed = false;
  const int slot = i >= 0 && j >= 0 ? summed.pairSlot(i, j, transposed) : -1;
  if (transposed_pair) {
    EXPECT_EQ(transposed, i > j);
  }
  summed.addRigidSpringSums(i, j, sums_first, summed.withSlot(slot, transposed, first));
  summed.addRigidSpringSums(i, j, sums_second, summed.withSlot(slot, transposed, second));
  const Eigen::MatrixXd k1 = Eigen::MatrixXd(point_by_point.matrix());
  const Eigen::MatrixXd k2 = Eigen::MatrixXd(summed.matrix());
  ASSERT_EQ(k1.rows(), 12);
  // The same products summed in another order: equal to round-off of the largest entry
  // (40 points of k_n |arm|^2 ~ 1e10; 64 eps of their sum).
  const double scale = k1.cwiseAbs().maxCoeff();
  EXPECT_GT(scale, 1e10);
  EXPECT_LE((k1 - k2).cwiseAbs().maxCoeff(), 64 * 2.2e-16 * scale);
  if (i >= 0 && j >= 0) {
    // The coupling landed (it is not zero) and in the right place.
    EXPECT_GT(k2.block(0, 6, 6, 6).cwiseAbs().maxCoeff(), 1e9);
  }
  const Eigen::VectorXd f1 = point_by_point.rhs(), f2 = summed.rhs();
  const double f_scale = f1.cwiseAbs().maxCoeff();
  EXPECT_GT(f_scale, 1e5);
  EXPECT_LE((f1 - f2).cwiseAbs().maxCoeff(), 64 * 2.2e-16 * f_scale);
}

TEST(BlockSystem, RigidSpringSumsEqualTheirPointsOneByOne) {
  expectSumsEqualPointByPoint(0, 1, false);
  // Block 1's point on block 0's face: the pair's block stores K_01 = K_10^T.
  expectSumsEqualPointByPoint(1, 0, true);
  // Against fixed bodies.
  expectSumsEqualPointByPoint(0, -1, false);
  expectSumsEqualPointByPoint(-1, 1, false);
}

TEST(BlockSystem, BothTrianglesOfKAreEqualToTheBit) {
  // The CHOLMOD backend factorizes K's upper triangle and the residuals and the energy
  // account read both: they must be the same matrix. A rigid block's T^T S T sums R^T S R,
  // whose two triangles differ in round-off; K's diagonal blocks take their lower one.
  for (const int dofs : {6, 12}) {
    BlockSystem system(2, dofs);
    system.setPairs({{0, 1}});
    const Vec3 ci(1.0, 2.0, -3.0), cj(2.5, 1.0, -2.0);
    const PointSprings springs = testSprings();
    bool asymmetric_sums = false;
    for (int p = 0; p < 40; ++p) {
      // Contact points spread over the joint between the blocks, with arms of every length.
      const Vec3 point(1.0 + 0.037 * p, 1.1 + 0.071 * (p % 7), -2.9 + 0.013 * (p % 11));
      const Vec3 foot = point - Vec3(0.0, 0.0, 2e-4);
      const Eigen::Matrix3d r = rotationColumns(point - ci);
      const Eigen::Matrix3d sr = springs.stiffness() * r;
      const Eigen::Matrix3d rsr = r.transpose() * sr;
      asymmetric_sums = asymmetric_sums || rsr != rsr.transpose();
      if (dofs == 6) {
        system.addRigidPointSprings(0, r, 1, rotationColumns(foot - cj), springs.stiffness(),
                                    springs.offsets(), BlockSystem::Parts{});
      } else {
        system.addPointSprings(0, displacementMatrix(point, ci), 1, displacementMatrix(foot, cj),
                               springs.stiffness(), springs.offsets(), BlockSystem::Parts{});
      }
    }
    EXPECT_TRUE(asymmetric_sums) << "no round-off to mirror: the test would not see it";
    const Eigen::MatrixXd k = Eigen::MatrixXd(system.matrix());
    ASSERT_EQ(k.rows(), 2 * dofs);
    EXPECT_GT(k.cwiseAbs().maxCoeff(), 1e9);  // the springs did land in K
    EXPECT_TRUE(k == k.transpose()) << "dofs " << dofs;
  }
}

}  // namespace
}  // namespace rockmass::dda3d
