// The contact states of the open-close iteration: after each solve, every contact's normal
// gap and slip decide whether it is open, sliding or locked (docs/dda3d.md, "Open-close
// iteration"), with the round-off margins, chatter rules and joint strength that make the
// iteration settle.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include "dda3d/block_terms.h"
#include "dda3d/simulation.h"

namespace rockmass::dda3d {

using geometry::Vec3;

namespace {

/// Largest pull (in weights of the lighter block) of a contact held closed after it opened
/// and closed again in a step (updateContactStates).
constexpr double kHoldWeights = 12.0;
/// A contact that opened and closed again in a step (toggles >= 2) and pulls: held closed up
/// to one hold limit (holdLimit), made to slide first up to this many when locked
/// (updateClosedContact). At 4 and more, random piles gained 3.6-6.4 % of their energy
/// (seeds 86 and 422 of 500); at 2 the 1 000-cube pile took 9 steps below 1e-4 s.
constexpr double kSlideFirstHolds = 3.0;
/// The pull, in hold limits, of a contact that did not chatter: never held.
constexpr double kNeverHeld = std::numeric_limits<double>::infinity();
/// A contact that flipped open, closed and open again in a step closes past this many
/// allowed penetrations, or past kLateRestitution / 2 of its approach in the step, i.e. past
/// the gap it closed in the step (updateContactStates).
constexpr double kChatterClosingRatio = 0.1;
/// Largest ratio of the push-out speed of such a contact, found penetrating at the next step,
/// to its approach speed.
constexpr double kLateRestitution = 1.0;
/// A locked contact slides once its spring's force passes its shear strength by more than
/// the force of a round-off slip (open_threshold_ratio l0) and by more than this share of
/// the strength: the allowance lets a spring the predictor set at the limit stay stuck on a
/// resting block's round-off, but it is strength the joint does not have, so it must stay
/// small against the strength (updateContactStates). At 0.1 a base carried by sub-contact
/// points, whose strengths are small enough for the share to bind at every point, held 10 %
/// above its strength: eccentric dams came out 2-5 % above the shear-friction factor.
constexpr double kStickAllowance = 0.01;
/// Static mode: a contact that closed in the last open-close iteration no deeper than this
/// share of the allowed penetration counts in the iteration's allowance of state changes
/// (Simulation::openCloseIterate).
constexpr double kStaticClosingShare = 0.01;

}  // namespace

BlockVector Simulation::unknownsOf(const Eigen::VectorXd& solution, int block) const {
  const int m = movableIndex(block);
  return m < 0 ? BlockVector::Zero() : system_->unknowns(solution, m);
}

std::vector<BlockVector> Simulation::blockUnknowns(const Eigen::VectorXd& solution) const {
  std::vector<BlockVector> unknowns(blocks_.size(), BlockVector::Zero());
  if (solution.size() == 0) return unknowns;  // no solve (no movable block)
  tbb::parallel_for(std::size_t{0}, blocks_.size(), [&](std::size_t b) {
    unknowns[b] = unknownsOf(solution, static_cast<int>(b));
  });
  return unknowns;
}

Vec3 Simulation::relativeDisplacement(const Contact& c, const Eigen::VectorXd& solution,
                                      bool rigid_part) const {
  return relativeDisplacement(c, unknownsOf(solution, c.block_i), unknownsOf(solution, c.block_j),
                              rigid_part);
}

Vec3 Simulation::relativeDisplacement(const Contact& c, const std::vector<BlockVector>& unknowns,
                                      bool rigid_part) const {
  return relativeDisplacement(c, unknowns[static_cast<std::size_t>(c.block_i)],
                              unknowns[static_cast<std::size_t>(c.block_j)], rigid_part);
}

Vec3 Simulation::relativeDisplacement(const Contact& c, BlockVector di, BlockVector dj,
                                      bool rigid_part) const {
  const BlockState& bi = blocks_[static_cast<std::size_t>(c.block_i)];
  const BlockState& bj = blocks_[static_cast<std::size_t>(c.block_j)];
  if (dofs_ == 6) {
    // Rigid blocks: T(x) d = u0 + r x (x - c), without the zero strain columns.
    const Vec3 ui = di.head<3>() + di.segment<3>(3).cross(c.point - bi.centroid);
    const Vec3 uj = dj.head<3>() + dj.segment<3>(3).cross(c.foot - bj.centroid);
    return ui - uj;
  }
  if (rigid_part) {
    di.tail<kVoigtSize>().setZero();
    dj.tail<kVoigtSize>().setZero();
  }
  return displacementMatrix(c.point, bi.centroid) * di -
         displacementMatrix(c.foot, bj.centroid) * dj;
}

namespace {

/// The thresholds of the state changes in one update (Simulation::updateContactStates).
struct StateRules {
  double penalty = 0.0;            ///< k_n (N/m)
  double ks = 0.0;                 ///< k_s (N/m)
  double close_tolerance = 0.0;    ///< an open contact closes past this penetration (m)
  double open_tolerance = 0.0;     ///< a closed one opens past this gap (m), T A / k_n aside
  double reverse_tolerance = 0.0;  ///< a slip reversal below this is round-off (m)
  double allowed = 0.0;            ///< the allowed penetration g3 l0 (m)
  double friction_share = 0.0;     ///< DdaSettings::friction_tolerance
};

/// f N, plus c A while the contact keeps its cohesion.
double strengthOf(const Contact& c, const DdaJoint& joint) {
  return joint.friction * std::max(0.0, c.normal_force) +
         (c.bonded ? joint.cohesion * c.area : 0.0);
}

/// True when a contact that slid in the solve and still slides had its strength `used`
/// there and has `now` with the solve's normal force, and the two differ by more than the
/// friction tolerance's share of the larger. Whether it counts is its blocks' question
/// (Simulation::updateContactStates): between blocks that slide side by side, N wanders about
/// zero by round-off, and every such change is a large share of it.
bool frictionChanged(double used, double now, const StateRules& rules) {
  return std::abs(now - used) > rules.friction_share * std::max(now, used);
}

/// An open contact at gap `d` after the solve: closes (locked, no shear) past the threshold.
void updateOpenContact(Contact& c, double d, const StateRules& rules) {
  c.normal_force = 0.0;
  // A contact that closed, opened (its pull over the hold limit below) and is open again
  // in this step is met mid-step by a block arriving fast: solved closed it pulls,
  // solved open it penetrates (a cube landing at 2.5 m/s on a pile: 2.6 um and
  // 0.27 mm), and flipping it every iteration never settled; the steps of a landing pile
  // of 1 000 cubes were redone down to 2e-5 s (docs/dda3d.md). It stays open while its
  // penetration is at most half its approach in the step (gap0 - d), i.e. less than the
  // gap it closed, and a tenth of the allowed penetration: found penetrating at the next
  // step, its spring pushes it out at about 2 |d| / dt, at most its approach speed (a
  // restitution of 1 or less; the scheme's damping takes the rest). A resting contact (no
  // approach) closes as any other: left open whatever its approach, contacts sank and
  // were pushed out every step, and a settled pile boiled at 0.3 m/s.
  const double approach = c.gap0 - d;
  const double close_at = c.toggles >= 3 ? std::max(rules.close_tolerance,
                                                    std::min(kChatterClosingRatio * rules.allowed,
                                                             0.5 * kLateRestitution * approach))
                                         : rules.close_tolerance;
  if (d < -close_at) {
    c.state = ContactState::Locked;
    c.shear.setZero();
    ++c.toggles;
  }
}

/// A locked contact whose spring, with this iteration's `slip`, carries more than its
/// strength `limit` (beyond the allowance) starts to slide.
void updateLockedContact(Contact& c, const Vec3& slip, double limit, const DdaJoint& joint,
                         const StateRules& rules) {
  // Over the limit by more than a round-off slip: a contact whose spring the
  // predictor set at the limit must not slide on the round-off of a resting block.
  const Vec3 shear = tangential(c.shear, c.normal) + slip;
  // The allowance is a force: ks times the round-off slip, but never more than
  // kStickAllowance of the strength. Allowed ks times the round-off alone, a stiff
  // penalty (40 times E l0) gave a frictionless joint 250 N of shear strength per
  // contact: the joint between two cubes pushed down a slope carried 10 % of the
  // front cube's weight to the rear one, and the pair slid 17 % too fast
  // (kStickAllowance).
  const double allowance = std::min(rules.ks * rules.reverse_tolerance, kStickAllowance * limit);
  if (!c.held && rules.ks * (shear.norm() - allowance / rules.ks) > limit) {
    ++c.flips;
    c.state = ContactState::Sliding;
    // Shi's brittle joint loses its cohesion and tension as it starts to slide; the
    // plastic joint keeps them while it slides (docs/stability.md, "Joint models").
    if (joint.model == JointModel::Brittle) c.bonded = false;
    c.slide_direction = shear.normalized();
    c.slip_length = 0.0;  // not known yet: no transverse tangent
  }
}

/// A sliding contact: sticks where its friction would drive it back, else follows its slip.
void updateSlidingContact(Contact& c, const Vec3& slip, const Vec3& rigid_slip, double limit,
                          const StateRules& rules) {
  // A contact at its friction limit with no slip velocity can flip between locked
  // and sliding forever; after two flips in a step it stays sliding (the friction
  // force then holds it at the limit, which is what both states mean there), unless its
  // friction then drives it back (below).
  const bool frozen = c.flips >= 2;
  // Reversal is read on the whole slip of the point, strain included: a deformable block's
  // corner that the strain carries back against the friction would have the friction do work
  // on it (positive work); it sticks instead, as Coulomb's law has it.
  const double back = -slip.dot(c.slide_direction);
  if (limit > 0.0 && (frozen ? back > std::max(rules.reverse_tolerance, limit / rules.ks)
                             : back > rules.reverse_tolerance)) {
    // Friction alone would drive it back: it sticks, its spring carrying the friction.
    // A frozen contact (above) sticks too, for the rest of the step, once its friction
    // drove it back by more than its shear spring's stretch at the strength: its
    // friction, a load of f N along the direction of the last iteration's slip, did
    // work on the slip instead of resisting it. On a light block between heavy ones (a
    // 1 cm sliver, 106 kg, under 1e5 N corner contacts) the frozen friction forces of
    // its two faces lined up and threw it sideways at 1 m/s in one step (docs/dda3d.md,
    // "Known limits"). A smaller reversal is the creep of a contact at its limit: it
    // stays sliding, as the frozen rule means (a stuck spring would hold a wedge at
    // SRF 1.6 whose FS is 1.5).
    ++c.flips;
    c.state = ContactState::Locked;
    c.shear = (limit / rules.ks) * c.slide_direction;
    c.held = frozen;
    return;
  }
  // While the contact creeps (its slip in the step shorter than its shear spring's
  // stretch at the start of the step, the predictor's), the friction opposes the
  // trial shear, that stretch plus the slip (a return mapping). Along the slip alone,
  // a contact that creeps by 1e-7 m a step took its direction from the round-off of
  // that slip: its sideways part rolled a block on a plane, and the corners slid in
  // turn on either side. A contact that slides farther follows its slip.
  const Vec3 stretch = tangential(c.shear, c.normal);
  const Vec3 trial = rigid_slip.norm() < stretch.norm() ? Vec3(stretch + rigid_slip) : rigid_slip;
  if (trial.norm() > 0.0) {
    c.slide_direction = trial.normalized();
    c.slip_length = trial.norm();
  }
}

/// A closed (locked or sliding) contact at gap `d`: opens past its tension and the margin,
/// unless held (its pull `holds`, in hold limits, at most 1; infinite for a contact that did
/// not chatter) or, when locked, made to slide first; else its shear state is updated.
void updateClosedContact(Contact& c, double d, const Vec3& slip, const Vec3& rigid_slip,
                         double holds, const DdaJoint& joint, const StateRules& rules) {
  const bool stays_closed = holds <= 1.0;
  const double tension = c.bonded ? joint.tensile_strength * c.area : 0.0;
  c.normal_force = -rules.penalty * d;
  // The margin is a round-off distance: its force, penalty times it, sums over the
  // points of a face, so a sub-contact point takes its share (with the whole margin each,
  // the 512 points under a dam's lifting toe held 3e5 N of tension at 4.5e-10 m, and
  // the dam stood at 1.24 times its sliding factor).
  if (!stays_closed && d > tension / rules.penalty + c.share * rules.open_tolerance) {
    if (c.state == ContactState::Locked && holds <= kSlideFirstHolds) {
      // A locked contact that opened and closed again in this step, and pulls by up to
      // kSlideFirstHolds hold limits: its shear springs, not its normal spring, pull it open
      // (closing a contact that penetrates solved open gives it, alone, a compressive normal
      // spring), as they carry a shear that Coulomb's law gives no contact without a normal
      // force. It slides instead (its friction f N is nil while it pulls), counted as a flip,
      // and opens only if it still pulls so. Opened at once, it penetrated again solved
      // open: such contacts flipped open and closed until the step was redone, and a landing
      // pile of 1 000 cubes took steps down to 1.3e-5 s. A larger pull is a block really
      // lifting off (a box rocking on the slab under an impact pulled 60 hold limits): kept
      // closed for an iteration there, random piles gained up to 6 % of their energy
      // (docs/dda3d.md, "Open-close iteration").
      c.state = ContactState::Sliding;
      c.normal_force = 0.0;
      ++c.flips;
      c.slide_direction = rigid_slip.norm() > 0.0 ? Vec3(rigid_slip.normalized()) : Vec3::Zero();
      c.slip_length = 0.0;
      return;
    }
    ++c.toggles;
    // Opened: a crack, whatever the joint model (its cohesion and tension are gone).
    c.state = ContactState::Open;
    c.bonded = false;
    c.normal_force = 0.0;
    c.shear.setZero();
    return;
  }
  const double limit = strengthOf(c, joint);
  if (c.state == ContactState::Locked) {
    updateLockedContact(c, slip, limit, joint, rules);
  } else {
    updateSlidingContact(c, slip, rigid_slip, limit, rules);
  }
}

}  // namespace

Simulation::StateChanges Simulation::updateContactStates(const Eigen::VectorXd& solution) {
  StateRules rules;
  rules.penalty = penalty_;
  rules.ks = penalty_ / settings_.shear_penalty_ratio;
  rules.close_tolerance = settings_.close_threshold_ratio * half_domain_;
  rules.open_tolerance = settings_.open_threshold_ratio * half_domain_;
  // A sliding contact sticks only when its slip reverses by more than round-off: at a tiny
  // time step (or at rest) the rigid slip is ~1e-13 m in a random direction, and reading its
  // sign locked and released thousands of contacts of the Xiangjiaba model in turn, so that
  // the iteration never settled at any time step.
  rules.reverse_tolerance = settings_.open_threshold_ratio * half_domain_;
  rules.allowed = settings_.allowed_penetration_ratio * half_domain_;
  // Dynamic runs only: a static step starts from rest, so the friction of its path carries no
  // impulse to the next, and at rest N and so f N hold from one iteration to the next.
  rules.friction_share =
      settings_.mode == AnalysisMode::Dynamic ? settings_.friction_tolerance : 1.0;
  // Each contact's update reads the solution and changes that contact only: in parallel,
  // each recording how it changed (1 changed, 2 closed, 3 slid on with another strength),
  // then counted in order.
  // Every block's unknowns, read once (not twice per contact).
  const std::vector<BlockVector> unknowns = blockUnknowns(solution);
  std::vector<char> how(contacts_.size(), 0);
  // In a dynamic run, each closed contact's strength after the update and each sliding one's
  // change of strength, summed by block below.
  const bool checks_any_friction = rules.friction_share < 1.0;
  std::vector<double> strength(checks_any_friction ? contacts_.size() : 0, 0.0);
  std::vector<double> friction_change(strength.size(), 0.0);
  // The deepest penetration after the update, in the same pass (a largest value: the same in
  // any order), for the step's check.
  tbb::combinable<double> deepest([] { return 0.0; });
  tbb::parallel_for(std::size_t{0}, contacts_.size(), [&](std::size_t k) {
    Contact& c = contacts_[k];
    const Vec3 relative = relativeDisplacement(c, unknowns);
    const double d = c.gap0 + c.normal.dot(relative);
    const Vec3 slip = tangential(relative, c.normal);
    // The friction direction follows the rigid part of the motion: the strain part of a
    // deformable block's corner motion is elastic vibration, and letting it steer friction
    // tilts the friction forces sideways so that a block with phi > theta creeps.
    // (Rigid blocks have no strain unknowns: their rigid part is the whole motion.)
    const Vec3 rigid_slip =
        dofs_ == 6 ? slip : tangential(relativeDisplacement(c, unknowns, true), c.normal);
    c.gap = d;
    const ContactState before = c.state;
    const DdaJoint& joint = jointOf(c);
    // A sliding contact's friction is checked against its new N (a static run's never): the
    // strength the solve's friction load was (contactSprings), from the last N.
    const bool checks_friction = rules.friction_share < 1.0 && before == ContactState::Sliding;
    const double used = checks_friction ? strengthOf(c, joint) : 0.0;
    if (c.state == ContactState::Open) {
      updateOpenContact(c, d, rules);
    } else {
      // A contact that opened and closed again in this step stays closed while its pull is
      // below kHoldWeights times the lighter block's weight: it sits where neither state is
      // consistent (solved closed it pulls by ~1e-7 m, solved open it penetrates past the
      // closing threshold, its load shared with the contacts of the same faces), and
      // flipping it back and forth never settled (piles of cubes redid their landing steps
      // down to 3e-5 s). Held, it pulls for one step: at most kHoldWeights g dt of velocity
      // between its blocks. A larger pull is a contact really opening: held there, it fought
      // a neighbouring contact with forces of 100 weights, and their work created energy
      // (random piles, docs/dda3d.md "Robustness tests"; none at 12 weights in 200 piles).
      const double holds = c.toggles >= 2 ? penalty_ * d / holdLimit(c) : kNeverHeld;
      updateClosedContact(c, d, slip, rigid_slip, holds, joint, rules);
    }
    if (checks_any_friction && c.state != ContactState::Open) strength[k] = strengthOf(c, joint);
    if (c.state != before) {
      how[k] = before == ContactState::Open ? 2 : 1;
    } else if (checks_friction) {
      // Still sliding, so closed: its strength now is the one just stored.
      if (frictionChanged(used, strength[k], rules)) how[k] = 3;
      friction_change[k] = strength[k] - used;
    }
    double& local = deepest.local();
    local = std::max(local, -d);
  });
  StateChanges changes;
  changes.deepest = deepest.combine([](double x, double y) { return std::max(x, y); });
  // A sliding contact's change of friction counts where it changes its block's: a movable
  // block whose sliding contacts' strengths moved, in sum, by more than the friction
  // tolerance's share of the strength of all its closed contacts (summed in contact order:
  // the same sums with any number of threads). The friction a solve was off by is then at
  // most that share of what holds the block. The side contacts of cubes sliding in a train,
  // whose N wanders about zero by round-off, change by a large share of their own strength
  // but little of their blocks' (checked contact by contact, the accuracy bench's train took
  // 31 iterations a step; so, 1.10).
  std::vector<char> friction_moved;
  if (checks_any_friction) {
    std::vector<double> held(blocks_.size(), 0.0), moved(blocks_.size(), 0.0);
    for (std::size_t k = 0; k < contacts_.size(); ++k) {
      const Contact& c = contacts_[k];
      for (const int b : {c.block_i, c.block_j}) {
        held[static_cast<std::size_t>(b)] += strength[k];
        moved[static_cast<std::size_t>(b)] += std::abs(friction_change[k]);
      }
    }
    friction_moved.assign(blocks_.size(), 0);
    for (std::size_t b = 0; b < blocks_.size(); ++b) {
      friction_moved[b] = !blocks_[b].fixed && moved[b] > rules.friction_share * held[b] ? 1 : 0;
    }
  }
  const double shallow =
      settings_.mode == AnalysisMode::Static ? kStaticClosingShare * rules.allowed : -1.0;
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    if (how[k] == 0) continue;
    if (how[k] == 3) {
      const Contact& c = contacts_[k];
      changes.friction_changed += friction_moved[static_cast<std::size_t>(c.block_i)] != 0 ||
                                  friction_moved[static_cast<std::size_t>(c.block_j)] != 0;
      continue;
    }
    ++changes.changed;
    const bool closed = how[k] == 2;
    changes.closed += closed;
    changes.closed_deep += closed && -contacts_[k].gap > shallow;
    // The example names a contact that closed when any did (those always take another
    // iteration), else the first that changed.
    if (changes.example < 0 || (closed && changes.closed == 1)) {
      changes.example = static_cast<int>(k);
    }
  }
  return changes;
}

void Simulation::finishContacts(const Eigen::VectorXd& solution) {
  // One pass over the contacts (each changes only its own): the history, the locked
  // contacts' shear, each spring's energy after the step, summed by acceptStep, the friction
  // work of the last assembly's friction, summed by accountDissipation, and the counts by
  // state (integer sums: the same in any order).
  const std::vector<BlockVector> unknowns = blockUnknowns(solution);
  const bool solved = solution.size() > 0;
  springs_after_.resize(contacts_.size());
  springs_start_.resize(contacts_.size());
  const std::size_t applied = solved ? std::min(contacts_.size(), applied_friction_.size()) : 0;
  friction_terms_.assign(applied, FrictionTerms{});
  const std::function<void(std::size_t)> finish = [&](std::size_t k) {
    finishContact(k, unknowns, solved, k < applied);
  };
  finished_counts_ = countContacts(&finish);
}

void Simulation::finishContact(std::size_t k, const std::vector<BlockVector>& unknowns, bool solved,
                               bool friction) {
  Contact& c = contacts_[k];
  SpringEnergyTerms& t = springs_after_[k];
  SpringEnergyTerms& start = springs_start_[k];
  t = SpringEnergyTerms{};
  start = SpringEnergyTerms{};
  // The relative displacement of the step's solve, computed once for the friction work
  // and the contact's history.
  Vec3 relative = Vec3::Zero();
  if (solved) {
    const AppliedFriction* f = friction ? &applied_friction_[k] : nullptr;
    const bool works = f != nullptr && (!f->force.isZero(0.0) || f->transverse_stiffness != 0.0);
    if (works || c.state != ContactState::Open) relative = relativeDisplacement(c, unknowns);
    if (works) {
      // The friction of the last solve, -f N s on i and +f N s on j, did the work
      // -f N s . (u_i - u_j) (accountDissipation).
      FrictionTerms& w = friction_terms_[k];
      w.work = f->force.dot(relative);
      w.counts = kFrictionWork;
      if (f->transverse_stiffness > 0.0) {
        // (Rigid blocks have no strain unknowns: their rigid part is the whole motion.)
        const double x =
            f->across.dot(dofs_ == 6 ? relative : relativeDisplacement(c, unknowns, true));
        w.transverse = f->transverse_stiffness * x * x;
        w.counts |= kTransverseWork;
      }
    }
  }
  if (c.state == ContactState::Open) {
    c.shear.setZero();
    return;
  }
  // The springs at the start of the step, in the state it ended with: the gap and, locked,
  // the shear it started with (accountDissipation).
  start = springTerms(
      c.state, c.gap0,
      c.state == ContactState::Locked ? tangential(c.shear, c.normal) : Vec3(Vec3::Zero()));
  // Closed at the end of an accepted step; a sliding one adds its slip.
  c.was_closed = true;
  if (c.state == ContactState::Sliding) {
    if (solved) c.slipped += tangential(relative, c.normal).norm();
    c.shear.setZero();
  } else {
    // A locked contact's shear spring carries the step's relative motion.
    c.shear = tangential(c.shear + relative, c.normal);
  }
  // The springs after the step (springEnergy).
  t = springTerms(c.state, c.gap, c.shear);
}

Simulation::SpringEnergyTerms Simulation::springTerms(ContactState state, double gap,
                                                      const Vec3& shear) const {
  SpringEnergyTerms t;
  if (state == ContactState::Open) return t;
  t.closed = true;
  t.normal = 0.5 * penalty_ * gap * gap;
  t.apart = gap > 0.0;
  if (state == ContactState::Locked) {
    t.locked = true;
    t.shear = 0.5 * (penalty_ / settings_.shear_penalty_ratio) * shear.squaredNorm();
  }
  return t;
}

void Simulation::sumSprings(const std::vector<SpringEnergyTerms>& terms, double& stored,
                            double* pulling) {
  for (const SpringEnergyTerms& t : terms) {
    if (!t.closed) continue;
    (pulling && t.apart ? *pulling : stored) += t.normal;
    if (t.locked) stored += t.shear;
  }
}

double Simulation::holdLimit(const Contact& c) const {
  double lighter = std::numeric_limits<double>::infinity();
  for (int b : {c.block_i, c.block_j}) {
    const BlockState& block = blocks_[static_cast<std::size_t>(b)];
    if (!block.fixed) lighter = std::min(lighter, block.mass);
  }
  return kHoldWeights * model_.gravity.norm() * lighter;
}

double Simulation::shearStrength(const Contact& c, const DdaJoint& joint) const {
  return strengthOf(c, joint);
}

}  // namespace rockmass::dda3d
