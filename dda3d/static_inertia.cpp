// The inertia of a static run's blocks (docs/stability.md, "Static runs of massive
// blocks"; docs/dda3d.md, "Deformable blocks at scale"): a static step starts from rest, and
// its inertia term only sets how much of the out-of-balance force one step relieves, so the
// masses of massive and large deformable blocks are scaled to their stiffness.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "dda3d/block_terms.h"
#include "dda3d/simulation.h"

namespace rockmass::dda3d {

namespace {

/// Static mode: a block's inertia term (1 - alpha_m) M / (beta dt^2) is held to at most this
/// many contact penalties (its mass scaled down, as in dynamic relaxation). The term only
/// regularises a static step (every step starts from rest), but it also sets how much of the
/// out-of-balance force one step relieves: K / (K + c0 M). For a 5e8 kg dam at dt = 2 ms, c0 M
/// was 5.7 penalties; each step relieved 15 %, the heel corners crept at their limit for
/// tens of steps until the round-off of their slip turned the friction sideways, the dam
/// walked across its base, and the strength reduction found 2.20 where f W / H = 2.42 (2.45
/// with dt = 10 ms). Held to one penalty: 2.45 at dt = 2 ms.
constexpr double kStaticInertiaRatio = 1.0;
/// Static mode: a deformable block's rotation and strain inertia is held to at most this many
/// times the shear stiffness of its strain (Simulation::inertiaMatrix).
constexpr double kStaticStrainInertiaRatio = 1.0;

/// G of an isotropic elastic matrix (Voigt, engineering shear strains).
double shearModulus(const ElasticMatrix& d) {
  return d.diagonal().tail<3>().minCoeff();
}

}  // namespace

BlockMatrix Simulation::inertiaMatrix(const BlockState& block) const {
  BlockMatrix m = massMatrix(block);
  if (settings_.mode != AnalysisMode::Static) return m;
  m *= staticMassScale(block);
  if (dofs_ != kBlockDofs) return m;
  // The linear part of the field, rotation and strain (unknowns 3..11): their inertia c0 M
  // grows with the block's size squared (rho V L^2) and the strain's stiffness with its
  // volume (V D). A rotation with the shear strain that leaves the base corners where they
  // are is held by the elastic stiffness alone, and its inertia (the rotation's, scaled only
  // with the mass) was 60 times that stiffness for the Xiangjiaba dam at dt = 2 ms: each
  // static step relieved 1.3 % of its out-of-balance force, and the dam on one rock block
  // settled in 400 steps instead of 40 at dt = 20 ms. Those rows and columns are scaled by
  // sqrt(t) (S M S, S = diag(1, sqrt(t)), which keeps M positive definite) so that their
  // largest inertia c0 t M is at most kStaticStrainInertiaRatio times the shear stiffness of
  // the strain, V G (the density scaling of dynamic relaxation: the masses set the path to
  // rest, not the state of rest).
  const double c0 = inertiaCoefficient(scheme_, settings_.time_step);
  const double stiffness =
      block.volume * shearModulus(elastic_[static_cast<std::size_t>(block.material)]);
  constexpr int kLinear = kBlockDofs - 3;
  const Eigen::Matrix<double, kLinear, kLinear> linear = m.bottomRightCorner<kLinear, kLinear>();
  const double inertia = c0 * linear.selfadjointView<Eigen::Lower>().eigenvalues().maxCoeff();
  const double cap = kStaticStrainInertiaRatio * stiffness;
  if (!(inertia > cap)) return m;
  const double root = std::sqrt(cap / inertia);
  m.bottomRows<kLinear>() *= root;
  m.rightCols<kLinear>() *= root;
  return m;
}

double Simulation::staticMassScale(const BlockState& block) const {
  if (settings_.mode != AnalysisMode::Static) return 1.0;
  // At the run's time step: a step redone at a smaller one still gets more inertia, which is
  // what lets a step whose open-close iteration did not settle settle.
  const double inertia = inertiaCoefficient(scheme_, settings_.time_step) * block.mass;
  double cap = kStaticInertiaRatio * penalty_;
  if (settings_.kinematics == Kinematics::Deformable && block.volume > 0.0) {
    // A deformable block's translation also moves in modes held by its elasticity alone: the
    // dam's shear with the translation that keeps its base where it is (u = 2 g (z - z_c),
    // the base held). Their inertia c0 s m (z_b - z_c)^2 is held to the stiffness of that
    // strain, G V, as inertiaMatrix holds the rotation and strain: at one penalty it was 85
    // times that stiffness for the Xiangjiaba dam, and the dam took 500 static steps to rest.
    const double shear = shearModulus(elastic_[static_cast<std::size_t>(block.material)]);
    const double spread = block.second.trace() / block.volume;  // mean |X - X_c|^2 (m2)
    if (spread > 0.0) {
      cap = std::min(cap, kStaticStrainInertiaRatio * shear * block.volume / spread);
    }
  }
  return inertia > cap ? cap / inertia : 1.0;
}

}  // namespace rockmass::dda3d
