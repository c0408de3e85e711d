// The energy account of a DDA run: the work of the loads against what is stored (kinetic,
// strain, springs) and dissipated (friction, the scheme's numerical damping, contact state
// changes), for checking that nothing grows beyond the work of the loads (docs/dda3d.md,
// "Energy account").
#include <tbb/parallel_for.h>

#include <cstdint>
#include <vector>

#include "dda3d/block_terms.h"
#include "dda3d/simulation.h"

namespace rockmass::dda3d {

using geometry::Vec3;

void Simulation::accountDissipation(const Eigen::VectorXd& solution, double dt) {
  // Friction: the forces applied in the last solve, -f N s on i and +f N s on j, did the work
  // -f N s . (u_i - u_j); the blocks lost that much.
  // The transverse tangent springs of sliding contacts are friction too: the work against
  // them, k x^2 (x the rigid slip across the direction), is dissipated, not stored; the
  // numerical term below dots the whole matrix, so their 1/2 k x^2 is taken out of it.
  // Each contact's terms from finishContacts' pass (in parallel, before this), summed in
  // contact order as one loop would.
  double transverse = 0.0;
  for (const FrictionTerms& t : friction_terms_) {
    if (!(t.counts & kFrictionWork)) continue;
    friction_work_ -= t.work;
    if (t.counts & kTransverseWork) {
      friction_work_ += t.transverse;
      transverse += 0.5 * t.transverse;
    }
  }
  // Springs at the start of the step, in the states the step ended with: the energy
  // 1/2 k (d0 + e^T D)^2 of every spring at D = 0. Where it differs from the springs' energy
  // at the end of the last step, contact changes between the steps added (or removed) it:
  // contacts detected already penetrating, closed or opened, shear springs restarted,
  // penalty changes. A contact still apart (d0 > 0) that closes during the step is the
  // exception: the solve counts 1/2 k d0^2 as if its spring pulled from the start and takes
  // it back in 1/2 d^T K d (an implicit, inelastic impact), so that share is moved from the
  // numerical dissipation instead of being counted as a change.
  // (Each contact's terms from finishContacts' pass, which ran before this one.)
  double springs_start = pointSpringEnergy();
  double pulling = 0.0;
  sumSprings(springs_start_, springs_start, &pulling);
  contact_changes_ += springs_start - springs_after_step_;
  numerical_dissipation_ -= pulling;
  if (solution.size() == 0) return;
  // The step solved (K + c0 M) d = F + M (c1 v0 + c2 a0). Dotted with d, and with every
  // spring and the strain energy quadratic, the work of the loads less the friction work
  // equals dU + 1/2 d^T K d (forces taken at the end of the step) + d^T M a_b, a_b =
  // (1 - alpha_m) a1 + alpha_m a0 the Bossak-weighted acceleration. The scheme removed what
  // of that did not become kinetic energy: 1/2 d^T K d + d^T M a_b - (T1 - T0).
  const double ratio = settings_.mode == AnalysisMode::Static ? 0.0 : settings_.dynamic_ratio;
  const double c0 = inertiaCoefficient(scheme_, dt);
  // K as the last open-close iteration factorized it (its values are not filled again).
  double removed = 0.5 * solution.dot(system_->filledMatrix() * solution);
  for (const BlockState& block : blocks_) {
    if (block.fixed) continue;
    const BlockVector d = system_->unknowns(solution, block.dof_offset);
    const BlockMatrix m = inertiaMatrix(block);
    const BlockVector a1 = endAcceleration(d, block.velocity, block.acceleration, dt, scheme_);
    const BlockVector v1 = endVelocity(block.velocity, block.acceleration, a1, dt, scheme_);
    const BlockVector weighted =
        (1.0 - scheme_.alpha_m) * a1 + scheme_.alpha_m * block.acceleration;
    const double end_kinetic = 0.5 * v1.dot(m * v1);
    removed += -0.5 * c0 * d.dot(m * d) + d.dot(m * weighted) - end_kinetic +
               0.5 * block.velocity.dot(m * block.velocity);
    // A dynamic ratio below 1 (or static mode) takes a share of the kinetic energy away.
    removed += (1.0 - ratio * ratio) * end_kinetic;
  }
  numerical_dissipation_ += removed - transverse;
}

EnergyAccount Simulation::energy() const {
  EnergyAccount e;
  for (const BlockState& block : blocks_) {
    if (block.fixed) continue;
    e.kinetic += 0.5 * block.velocity.dot(massMatrix(block) * block.velocity);
    if (settings_.kinematics == Kinematics::Deformable) {
      e.strain +=
          0.5 * block.volume *
          block.strain.dot(elastic_[static_cast<std::size_t>(block.material)] * block.strain);
    }
  }
  e.springs = springEnergy();
  e.work_of_loads = work_of_loads_;
  e.friction = friction_work_;
  e.numerical = numerical_dissipation_;
  e.contact_changes = contact_changes_;
  return e;
}

double Simulation::springEnergy() const {
  double energy = pointSpringEnergy();
  std::vector<SpringEnergyTerms> springs(contacts_.size());
  tbb::parallel_for(std::size_t{0}, contacts_.size(), [&](std::size_t k) {
    const Contact& c = contacts_[k];
    springs[k] = springTerms(c.state, c.gap, c.shear);
  });
  sumSprings(springs, energy);
  return energy;
}

double Simulation::pointSpringEnergy() const {
  double energy = 0.0;
  for (const MaterialPoint& fp : fixed_points_) {
    const Vec3 u = fp.current - fp.initial;
    const double held =
        fp.direction.isZero(0.0) ? u.squaredNorm() : fp.direction.dot(u) * fp.direction.dot(u);
    energy += 0.5 * settings_.fixed_point_penalty_ratio * penalty_ * held;
  }
  for (std::size_t k = 0; k < bolt_a_.size(); ++k) {
    if (bolt_state_[k].broken) continue;
    const double stretch =
        (bolt_b_[k].current - bolt_a_[k].current).norm() - bolt_state_[k].free_length;
    energy += 0.5 * model_.bolts[k].stiffness * stretch * stretch;
  }
  return energy;
}

}  // namespace rockmass::dda3d
