#include "dda3d/simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "dda3d/block_terms.h"
#include "dda3d/contact_detection.h"
#include "dda3d/contact_joint.h"
#include "dda3d/contact_persistence.h"
#include "dda3d/model_validation.h"
#include "geometry/interrupt.h"

namespace rockmass::dda3d {

using geometry::Vec3;

namespace {

// What an assembly thread adds of a contact (Simulation::listAssembly): K_ii and F_i, K_jj
// and F_j, K_ij, and whether it records the contact's friction.
constexpr std::uint8_t kAddsI = 1;
constexpr std::uint8_t kAddsJ = 2;
constexpr std::uint8_t kAddsPair = 4;
constexpr std::uint8_t kRecords = 8;

/// The terms an assembly thread adds of a contact (kAdds* bits) as BlockSystem::Parts.
BlockSystem::Parts partsOf(std::uint8_t adds) {
  BlockSystem::Parts parts;
  parts.i = (adds & kAddsI) != 0;
  parts.j = (adds & kAddsJ) != 0;
  parts.pair = (adds & kAddsPair) != 0;
  return parts;
}

/// A locked contact's springs as one point's (BlockSystem::addPointSprings): the normal spring
/// (k_n along n, offset gap0) and the two shear springs (k_s along the tangents t_1, t_2,
/// offsets the shear's components). t_1 t_1^T + t_2 t_2^T = I - n n^T, so S = k_s I +
/// (k_n - k_s) n n^T, and the shear's offsets are k_s times its part across n.
inline void lockedSprings(const Contact& c, double kn, double ks, Eigen::Matrix3d& s,
                          Vec3& offsets) {
  const Vec3& n = c.normal;
  s.noalias() = (kn - ks) * (n * n.transpose());
  s.diagonal().array() += ks;
  offsets = (kn * c.gap0 - ks * c.shear.dot(n)) * n + ks * c.shear;
}

/// A contact's pair of blocks, the lower first (either may hold its point).
inline std::pair<int, int> blockPair(const Contact& c) {
  return std::minmax(c.block_i, c.block_j);
}

/// The frame of a contact's pair in the assembly: its lower and upper block and what the
/// thread adds of them (kAddsI for the lower block's terms, kAddsJ for the upper's, kAddsPair),
/// and whether the pair's block of K stores K_upper,lower.
struct PairFrame {
  int lower = -1, upper = -1;
  std::uint8_t adds = 0;
  bool transposed = false;
};

template <class Entry>
PairFrame pairFrame(const Contact& c, const Entry& e) {
  PairFrame f;
  const bool swapped = c.block_i > c.block_j;
  std::tie(f.lower, f.upper) = blockPair(c);
  f.adds = e.adds & kAddsPair;
  if (e.adds & kAddsI) f.adds |= swapped ? kAddsJ : kAddsI;
  if (e.adds & kAddsJ) f.adds |= swapped ? kAddsI : kAddsJ;
  f.transposed = e.transposed != swapped;
  return f;
}

Eigen::Matrix3d voigtToTensor(const VoigtVector& v, double shear_scale) {
  Eigen::Matrix3d t;
  // clang-format off
  t << v[0],               shear_scale * v[5], shear_scale * v[4],
       shear_scale * v[5], v[1],               shear_scale * v[3],
       shear_scale * v[4], shear_scale * v[3], v[2];
  // clang-format on
  return t;
}
VoigtVector tensorToVoigt(const Eigen::Matrix3d& t, double shear_scale) {
  VoigtVector v;
  v << t(0, 0), t(1, 1), t(2, 2), t(1, 2) / shear_scale, t(2, 0) / shear_scale,
      t(0, 1) / shear_scale;
  return v;
}
/// R s R^T for a stress (shear scale 1) or a strain with engineering shears (scale 1/2).
VoigtVector rotateVoigt(const VoigtVector& v, const Eigen::Matrix3d& r, double shear_scale) {
  return tensorToVoigt(r * voigtToTensor(v, shear_scale) * r.transpose(), shear_scale);
}

/// A step is accepted while no vertex moved farther than this many g2 l0 (step control).
constexpr double kAcceptedDisplacementRatio = 1.5;
/// Reach of a block at rest, in g2 l0: room for the step that starts it moving.
constexpr double kRestingReachRatio = 0.1;

}  // namespace

Simulation::Simulation(DdaModel model, DdaSettings settings)
    : model_(std::move(model)), settings_(settings) {
  if (model_.joints.empty()) model_.joints.push_back(DdaJoint{});
  validateModel(model_, settings_);
  scheme_ = settings_.integration == TimeIntegration::Shi
                ? shiCoefficients()
                : bossakCoefficients(settings_.spectral_radius);
  dofs_ = settings_.kinematics == Kinematics::Rigid ? 6 : kBlockDofs;
  for (const DdaMaterial& m : model_.materials) {
    elastic_.push_back(elasticMatrix(m.young, m.poisson));
  }

  geometry::Box all{Vec3::Constant(std::numeric_limits<double>::infinity()),
                    Vec3::Constant(-std::numeric_limits<double>::infinity())};
  int movable = 0;
  double total_volume = 0.0;
  for (std::size_t b = 0; b < model_.blocks.size(); ++b) {
    const DdaBlock& in = model_.blocks[b];
    BlockState s;
    s.pieces = in.pieces;
    for (const geometry::Polyhedron& p : s.pieces) {
      s.topology.push_back(pieceTopology(p));
      s.face_points.push_back(
          facePoints(p, in.contact_point_spacing.value_or(settings_.contact_point_spacing)));
      const geometry::Box box = geometry::bounds(p);
      all.min = all.min.cwiseMin(box.min);
      all.max = all.max.cwiseMax(box.max);
    }
    if (settings_.detection.surface_only) markExterior(s.pieces, s.topology);
    s.material = in.material;
    s.fixed = in.fixed;
    s.updateMassProperties();
    if (!(s.volume > 0.0)) {
      throw std::invalid_argument("block " + std::to_string(b) +
                                  " has a non-positive volume (faces must be CCW from outside)");
    }
    s.mass = model_.materials[static_cast<std::size_t>(in.material)].density * s.volume;
    s.stress = in.initial_stress;
    if (!s.fixed) {
      s.dof_offset = movable++;
      s.velocity.head<3>() = in.initial_velocity;
      s.velocity.segment<3>(3) = in.initial_angular_velocity;
    }
    total_volume += s.volume;
    blocks_.push_back(std::move(s));
    initial_centroids_.push_back(blocks_.back().centroid);
    active_.fixed_blocks |= in.fixed;
  }
  half_domain_ = settings_.half_domain_size > 0.0 ? settings_.half_domain_size
                                                  : 0.5 * (all.max - all.min).maxCoeff();
  // The kept broad-phase pairs reach one step control limit beyond the blocks' reach.
  candidates_ =
      CandidatePairs(kAcceptedDisplacementRatio * settings_.max_displacement_ratio * half_domain_);
  // The stiffest material of the blocks in the model (a material no block uses, e.g. one the
  // scene declares for a structure elsewhere, does not stiffen the contacts).
  double young_max = 0.0;
  for (const BlockState& block : blocks_) {
    young_max =
        std::max(young_max, model_.materials.at(static_cast<std::size_t>(block.material)).young);
  }
  const double block_length =
      blocks_.empty() ? 1.0 : std::cbrt(total_volume / static_cast<double>(blocks_.size()));
  penalty_ = settings_.penalty > 0.0 ? settings_.penalty
                                     : settings_.penalty_factor * young_max * block_length;
  initial_penalty_ = penalty_;
  dt_ = settings_.time_step;

  const auto attach = [](int block, const Vec3& p) {
    return MaterialPoint{block, p, p, Vec3::Zero()};
  };
  for (const DdaMonitor& m : model_.monitors) monitor_points_.push_back(attach(m.block, m.point));
  for (const DdaPointLoad& l : model_.point_loads) {
    load_points_.push_back(attach(l.block, l.point));
  }
  for (const DdaFixedPoint& f : model_.fixed_points) {
    fixed_points_.push_back(attach(f.block, f.point));
    if (f.current) fixed_points_.back().current = *f.current;
    fixed_points_.back().direction = f.direction;
  }
  for (const DdaBolt& bolt : model_.bolts) {
    bolt_a_.push_back(attach(bolt.block_a, bolt.point_a));
    bolt_b_.push_back(bolt.block_b >= 0 ? attach(bolt.block_b, bolt.point_b)
                                        : MaterialPoint{-1, bolt.point_b, bolt.point_b});
    BoltState state;
    state.free_length = (bolt.point_b - bolt.point_a).norm() - bolt.pretension / bolt.stiffness;
    state.force = bolt.broken ? 0.0 : bolt.pretension;
    state.broken = bolt.broken;
    bolt_state_.push_back(state);
  }

  system_ = std::make_unique<BlockSystem>(movable, dofs_);
  SolverOptions solver = resolvedSolverOptions(settings_, movable);
  solver.report_residual = false;  // no step reads it
  solver_ = makeLinearSolver(solver);
  base_k_.assign(static_cast<std::size_t>(movable), BlockMatrix::Zero());
  base_f_.assign(static_cast<std::size_t>(movable), BlockVector::Zero());
  load_f_.assign(static_cast<std::size_t>(movable), BlockVector::Zero());
  initialAccelerations();
}

void Simulation::initialAccelerations() {
  // assembleBlockTerms leaves the loads at t = 0 in load_f_; dt is irrelevant here.
  assembleBlockTerms(settings_.time_step);
  const bool fixed_blocks = active_.fixed_blocks;
  active_ = ActiveTerms{};  // nothing was assembled into a system yet
  active_.fixed_blocks = fixed_blocks;
  std::vector<BlockVector> force = load_f_;
  for (const BlockState& block : blocks_) {
    if (block.fixed || settings_.kinematics != Kinematics::Deformable) continue;
    force[static_cast<std::size_t>(block.dof_offset)] += initialStressLoad(block);
  }
  for (std::size_t k = 0; k < bolt_a_.size(); ++k) {
    const DdaBolt& bolt = model_.bolts[k];
    const Vec3 axis = bolt.point_b - bolt.point_a;
    if (axis.norm() <= 0.0 || bolt.broken) continue;
    // The pretension pulls point a towards b and b towards a.
    const Vec3 pull = bolt.pretension * axis.normalized();
    const BlockState& a = blocks_[static_cast<std::size_t>(bolt.block_a)];
    if (!a.fixed) force[static_cast<std::size_t>(a.dof_offset)] += pointLoad(a, bolt.point_a, pull);
    if (bolt.block_b >= 0) {
      const BlockState& b = blocks_[static_cast<std::size_t>(bolt.block_b)];
      if (!b.fixed) {
        force[static_cast<std::size_t>(b.dof_offset)] += pointLoad(b, bolt.point_b, -pull);
      }
    }
  }
  for (BlockState& block : blocks_) {
    if (block.fixed) continue;
    if (settings_.mode == AnalysisMode::Static) {
      // Static mode (Shi's dynamic ratio 0): every step starts from rest, so v0 = a0 = 0 at
      // t = 0 as after every step (updateBlocks). The inertia term (1 - alpha_m) M /
      // (beta dt^2) then only regularises the step (held to kStaticInertiaRatio penalties,
      // staticMassScale); a stored a0 = g would add the load
      // M (c2 g) to the first step for any rho_inf > 0 (c2 vanishes only at rho_inf = 0).
      block.velocity.setZero();
      block.acceleration.setZero();
      continue;
    }
    const BlockMatrix m = massMatrix(block);
    const BlockVector& f = force[static_cast<std::size_t>(block.dof_offset)];
    block.acceleration.setZero();
    if (dofs_ == kBlockDofs) {
      block.acceleration = m.ldlt().solve(f);
    } else {
      block.acceleration.head<6>() = m.topLeftCorner<6, 6>().ldlt().solve(f.head<6>());
    }
  }
}

Simulation::~Simulation() = default;

std::string Simulation::solverName() const {
  return solver_->name();
}

const DdaJoint& Simulation::jointOf(const Contact& c) const {
  return model_.joints.at(static_cast<std::size_t>(c.joint >= 0 ? c.joint : model_.default_joint));
}

namespace {

/// Carries the state of `old` (the same entry in the last step) over to `c`, whose geometry
/// is this step's: shear spring and sliding direction turned into c's tangent plane, the
/// late-found overlap no deeper than c's penetration. `old` may be `c` itself (a kept entry):
/// each field is read before it is written.
void carryOver(Contact& c, const Contact& old) {
  c.state = old.state;
  c.bonded = old.bonded;
  c.shear = tangential(old.shear, c.normal);
  const Vec3 slide = tangential(old.slide_direction, c.normal);
  c.slide_direction = slide.norm() > 0.0 ? Vec3(slide.normalized()) : Vec3(Vec3::Zero());
  c.normal_force = old.normal_force;
  c.slip_length = old.slip_length;
  c.was_closed = old.was_closed;
  c.slipped = old.slipped;
  c.overlap = std::min(old.overlap, std::max(0.0, -c.gap0));
}

/// Resets an entry's per-step counters at the start of a step; gap0 takes its overlap.
void startStep(Contact& c) {
  c.gap0 += c.overlap;
  c.gap = c.gap0;
  c.flips = 0;
  c.toggles = 0;
  c.held = false;
}

/// The step's start of each contact's fields that an attempt changes (`save`), in parallel, in
/// `to`'s buffer when it is large enough.
void saveStepStart(const std::vector<Contact>& from, std::vector<ContactStepState>& to) {
  to.resize(from.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, from.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        to[k] = ContactStepState(from[k]);
                      }
                    });
}

/// Each contact back to its step's start (saveStepStart), for a redone attempt.
void restoreStepStart(const std::vector<ContactStepState>& from, std::vector<Contact>& to) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, from.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k) {
                        from[k].restore(to[k]);
                      }
                    });
}

}  // namespace

double Simulation::keptEntriesMargin() const {
  return settings_.detection.search_margin * settings_.max_displacement_ratio * half_domain_;
}

std::vector<char> Simulation::blocksToSearch() const {
  // moved_since_search_ is empty until this run's first search (and after adoptContacts).
  if (!(settings_.detection.search_margin > 0.0) || moved_since_search_.empty() ||
      search_requested_) {
    return {};
  }
  const double margin = keptEntriesMargin();
  std::vector<char> only(blocks_.size(), 0);
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    only[b] = moved_since_search_[b] > margin || reach_[b] > searched_reach_[b];
  }
  return only;
}

bool Simulation::keepEntries(std::vector<Contact>& entries, const std::vector<char>& searched,
                             double depth, bool creep, std::vector<ContactStepState>* start) {
  // In place: a search that follows (an entry deeper than `depth`) only reads the entries'
  // keys and states (PreviousContacts), which the refresh leaves as they were.
  if (refreshContacts(blocks_, entries) > depth) return false;
  if (start != nullptr) start->resize(entries.size());
  tbb::parallel_for(std::size_t{0}, entries.size(), [&](std::size_t k) {
    Contact& c = entries[k];
    carryOver(c, c);
    startStep(c);
    if (creep) startFromCreep(c);
    if (start != nullptr) (*start)[k] = ContactStepState(c);
  });
  // A gap the search left out was wider than the two blocks' reaches then, and has narrowed
  // by at most how far they moved since: a step that moves no block farther than its reach
  // then less that motion cannot close it (checkStep redoes a step that moves one farther).
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    if (searched[b] == 0) {
      reach_[b] = std::min(reach_[b], searched_reach_[b] - moved_since_search_[b]);
    }
  }
  return true;
}

int Simulation::detectContacts() {
  // Each block's reach: how far its vertices may move in this step, from its motion and
  // the step control's limit 1.5 g2 l0; step() redoes a step that moves a block farther, so
  // a gap wider than the two blocks' reaches cannot close within it.
  const double g2_l0 = settings_.max_displacement_ratio * half_domain_;
  const ReachLimits limits{kRestingReachRatio * g2_l0, kAcceptedDisplacementRatio * g2_l0,
                           model_.gravity.norm()};
  reach_.resize(blocks_.size());
  const bool known = last_largest_.size() == blocks_.size();
  tbb::parallel_for(std::size_t{0}, blocks_.size(), [&](std::size_t b) {
    reach_[b] = known ? stepReach(blocks_[b], dt_, last_dt_, limits, last_largest_[b])
                      : stepReach(blocks_[b], dt_, last_dt_, limits);
  });
  // Penetrations are kept down to 3 g2 l0 (the former search distance), whatever the reach.
  const double depth = 2.0 * kAcceptedDisplacementRatio * g2_l0;
  // Entries kept while no block moved beyond the margin; only the pairs of the blocks that
  // did searched while they are at most half of them (a search of all beyond).
  const std::vector<char> only = blocksToSearch();
  const auto to_search = static_cast<std::size_t>(std::count(only.begin(), only.end(), 1));
  // The same contacts, each started from its creep (startFromCreep) and its step's start
  // saved (the state the step's attempts start from: nothing changes it before the first
  // solve) in the same pass: the search's split of the assembly holds.
  if (!only.empty() && to_search == 0 && keepEntries(contacts_, only, depth, true, &step_start_)) {
    step_start_pending_ = false;
    return 0;
  }
  if (to_search > 0 && 2 * to_search <= blocks_.size()) {
    int late = 0;
    if (searchPartly(only, depth, late)) return late;
  }
  int late = 0;
  std::vector<Contact> detected = searchContacts(contacts_, nullptr, depth, late);
  ++searches_;
  search_requested_ = false;
  searched_reach_ = reach_;
  moved_since_search_.assign(blocks_.size(), 0.0);
  useContacts(std::move(detected));
  return late;
}

bool Simulation::searchPartly(const std::vector<char>& only, double depth, int& late) {
  const auto searched = [&](const Contact& c) {
    return only[static_cast<std::size_t>(c.block_i)] != 0 ||
           only[static_cast<std::size_t>(c.block_j)] != 0;
  };
  std::vector<Contact> kept, before;
  kept.reserve(contacts_.size());
  for (const Contact& c : contacts_) (searched(c) ? before : kept).push_back(c);
  // Nothing to keep (every entry has a searched block), or a kept entry deeper than a search
  // keeps: a search of all. The searched blocks' pairs are searched with the kept blocks'
  // reach cut as in a kept step, and their own reach.
  if (kept.empty() || !keepEntries(kept, only, depth)) return false;
  std::vector<Contact> detected = searchContacts(before, &only, depth, late);
  ++partial_searches_;
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    if (only[b] == 0) continue;
    searched_reach_[b] = reach_[b];
    moved_since_search_[b] = 0.0;
  }
  // The kept entries first (in their order), then the searched ones (in the search's).
  kept.insert(kept.end(), std::make_move_iterator(detected.begin()),
              std::make_move_iterator(detected.end()));
  useContacts(std::move(kept));
  return true;
}

std::vector<Contact> Simulation::searchContacts(const std::vector<Contact>& before,
                                                const std::vector<char>* only, double depth,
                                                int& late) {
  const PreviousContacts previous(blocks_, before);
  const PreviousFace previous_face = [&](int bi, int pi, int v, int bj, int pj) {
    return previous.face(bi, pi, v, bj, pj);
  };
  const auto joint_of = [&](const Contact& c) { return contactJoint(model_, blocks_, c); };
  std::vector<Contact> detected =
      findContacts(blocks_, reach_, depth, previous_face,
                   settings_.detection.keep_pairs ? &candidates_ : nullptr, only, joint_of,
                   settings_.detection.hull_corners);
  // Each entry carries its last step's state over on its own (in parallel); the late ones
  // are counted after.
  std::vector<char> is_late(detected.size(), 0);
  const double late_depth = settings_.allowed_penetration_ratio * half_domain_;
  tbb::parallel_for(std::size_t{0}, detected.size(), [&](std::size_t k) {
    Contact& c = detected[k];
    const int found = previous.find(c);
    if (found >= 0) {
      carryOver(c, before[static_cast<std::size_t>(found)]);
    } else if (c.gap0 < -late_depth) {
      // First seen deeper than the allowed penetration: the detection missed it while it
      // closed (the step control keeps every contact it sees shallower). Its spring starts
      // at the depth found, resisting further penetration only: started at that depth, it
      // gave back 1/2 k_n d^2 in one step, 1.1e7 J for an edge crossing found 5.4 mm deep in
      // a pile of nine boxes whose fall had released 8.6e4 J, and threw the pile apart. The
      // overlap is removed as the blocks part; `late_contacts` counts these.
      c.overlap = -c.gap0;
      is_late[k] = 1;
    }
    startStep(c);
    if (found < 0) {
      // Touching within round-off counts as closed: an open contact only closes once it
      // penetrates past the hysteresis threshold.
      c.state = c.gap0 <= settings_.open_threshold_ratio * half_domain_ ? ContactState::Locked
                                                                        : ContactState::Open;
    }
  });
  late = static_cast<int>(std::count(is_late.begin(), is_late.end(), 1));
  return detected;
}

void Simulation::useContacts(std::vector<Contact> contacts) {
  // By pairs of blocks (either holding the point), in the order found within a pair: the
  // assembly sums a pair's entries before it adds them to K (assembleSystem), and reads them
  // one after the other. Found, the entries of a pair of blocks are interleaved with the
  // other pairs of their pieces (about 2 in a row on the Xiangjiaba region, 17 a pair); a
  // pair of pieces' entries both ways stay together, for the passes that read the pieces.
  const auto byPair = [](const Contact& a, const Contact& b) {
    return blockPair(a) < blockPair(b);
  };
  if (!std::is_sorted(contacts.begin(), contacts.end(), byPair)) {
    std::vector<std::uint32_t> order(contacts.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<std::uint32_t>(k);
    tbb::parallel_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
      const Contact& ca = contacts[a];
      const Contact& cb = contacts[b];
      return std::make_pair(blockPair(ca), a) < std::make_pair(blockPair(cb), b);
    });
    std::vector<Contact> sorted(contacts.size());
    tbb::parallel_for(std::size_t{0}, order.size(),
                      [&](std::size_t k) { sorted[k] = std::move(contacts[order[k]]); });
    contacts = std::move(sorted);
  }
  // The coupled pairs of movable blocks (and the bolts'), in entry order.
  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(contacts.size());
  for (const Contact& c : contacts) {
    const int i = movableIndex(c.block_i), j = movableIndex(c.block_j);
    if (i >= 0 && j >= 0) pairs.emplace_back(std::min(i, j), std::max(i, j));
  }
  for (std::size_t k = 0; k < bolt_a_.size(); ++k) {
    const int i = bolt_a_[k].block >= 0 ? movableIndex(bolt_a_[k].block) : -1;
    const int j = bolt_b_[k].block >= 0 ? movableIndex(bolt_b_[k].block) : -1;
    if (i >= 0 && j >= 0 && i != j) pairs.emplace_back(std::min(i, j), std::max(i, j));
  }
  contacts_ = std::move(contacts);
  startFromCreep();
  if (system_->setPairs(std::move(pairs))) ++pattern_changes_;
  splitAssembly();
}

void Simulation::startFromCreep() {
  // A contact that crept in the last step (its slip no longer than the shear spring's stretch
  // at the shear strength) starts this one stuck, its spring carrying the shear strength along
  // the last slip (an elastic predictor). Where the loads still need more, the first iteration
  // finds it over the limit and it slides again; where they need less (the block came to rest,
  // the load moved to other contacts), it stays stuck. Carried over as sliding, such a contact
  // kept its friction f N until its slip reversed: a block whose heel slid on its way to rest
  // under an eccentric load kept creeping on a diagonal pattern of stuck and sliding corners,
  // and was never at rest below the limit load (K 12 % below f W / H on a block on a plane).
  // A contact that slid farther is sliding: stuck for a trial, a moving block would pivot on
  // its base springs.
  tbb::parallel_for(std::size_t{0}, contacts_.size(),
                    [&](std::size_t k) { startFromCreep(contacts_[k]); });
}

void Simulation::startFromCreep(Contact& c) const {
  if (c.state != ContactState::Sliding || c.slide_direction.squaredNorm() == 0.0) return;
  const double stretch = shearStrength(c, jointOf(c)) / (penalty_ / settings_.shear_penalty_ratio);
  if (!(c.slip_length <= stretch)) return;
  c.state = ContactState::Locked;
  c.shear = stretch * c.slide_direction;
}

void Simulation::assembleBlockTerms(double dt, bool defer_water) {
  ActiveTerms step;
  step.inertia = true;
  const bool deformable = settings_.kinematics == Kinematics::Deformable;
  const bool body_force = !model_.gravity.isZero(0.0) || !model_.seismic.isZero(0.0);
  // Each block's own terms in parallel (each writes only its own), the loads on a block then
  // added in the order of their lists: the same sums as one loop.
  tbb::parallel_for(std::size_t{0}, blocks_.size(), [&](std::size_t b) {
    const BlockState& block = blocks_[b];
    if (block.fixed) return;
    const std::size_t m = static_cast<std::size_t>(block.dof_offset);
    BlockMatrix& k = base_k_[m];
    BlockVector& f = base_f_[m];
    BlockVector& loads = load_f_[m];
    k.setZero();
    f.setZero();
    loads.setZero();
    if (deformable) {
      k += elasticStiffness(block, elastic_[static_cast<std::size_t>(block.material)]);
      if (!block.stress.isZero(0.0)) f += initialStressLoad(block);
    }
    inertiaTerms(inertiaMatrix(block), block.velocity, block.acceleration, dt, scheme_, k, f);
    if (body_force) {
      loads += bodyForceLoad(
          block, model_.seismic.isZero(0.0) ? model_.gravity : model_.gravity + model_.seismic);
    }
  });
  for (const BlockState& block : blocks_) {
    if (block.fixed) continue;
    step.elastic |= deformable;
    step.initial_stress |= deformable && !block.stress.isZero(0.0);
    step.body_force |= body_force;
  }
  for (std::size_t l = 0; l < load_points_.size(); ++l) {
    const BlockState& block = blocks_[static_cast<std::size_t>(load_points_[l].block)];
    if (block.fixed) continue;
    load_f_[static_cast<std::size_t>(block.dof_offset)] +=
        pointLoad(block, load_points_[l].current, model_.point_loads[l].force);
    step.point_loads = true;
  }
  // With pores in the blocks, the area each entry wets (from the same clipped face).
  const bool pores = settings_.biot_coefficient > 0.0 && deformable;
  water_ = defer_water && !pores && !model_.pressures.empty() ? DeferredWater::Pending
                                                              : DeferredWater::None;
  if (water_ == DeferredWater::None) {
    std::vector<double> wetted(pores ? model_.pressures.size() : 0, 0.0);
    const std::vector<BlockVector> water =
        blockWaterLoads(pores ? &wetted : nullptr, step.surface_pressure);
    for (std::size_t m = 0; m < water.size(); ++m) load_f_[m] += water[m];
    if (pores) step.block_pore_pressure |= addBlockPorePressure(wetted);
  }
  for (const DdaHydrodynamicPressure& p : model_.hydrodynamic) {
    const BlockState& block = blocks_[static_cast<std::size_t>(p.block)];
    if (block.fixed) continue;
    load_f_[static_cast<std::size_t>(block.dof_offset)] +=
        hydrodynamicLoad(block, block.pieces[static_cast<std::size_t>(p.piece)], p.face, p);
    step.surface_pressure = true;
  }
  const double fixed_k = settings_.fixed_point_penalty_ratio * penalty_;
  for (const MaterialPoint& fp : fixed_points_) {
    const BlockState& block = blocks_[static_cast<std::size_t>(fp.block)];
    if (block.fixed) continue;
    const DisplacementMatrix t = displacementMatrix(fp.current, block.centroid);
    const std::size_t m = static_cast<std::size_t>(block.dof_offset);
    if (fp.direction.isZero(0.0)) {
      base_k_[m] += fixed_k * t.transpose() * t;
      base_f_[m] -= fixed_k * t.transpose() * (fp.current - fp.initial);
      step.fixed_points = true;
    } else {
      // A roller: the spring acts along its direction n only, energy 1/2 k (n . u)^2.
      const BlockVector e = t.transpose() * fp.direction;
      base_k_[m] += fixed_k * e * e.transpose();
      base_f_[m] -= fixed_k * e * fp.direction.dot(fp.current - fp.initial);
      step.rollers = true;
    }
  }
  for (std::size_t m = 0; m < base_f_.size(); ++m) base_f_[m] += load_f_[m];
  step.bolts = !model_.bolts.empty();
  active_ |= step;
}

std::vector<BlockVector> Simulation::blockWaterLoads(std::vector<double>* wetted, bool& any) const {
  // Each face's water load in parallel (a clipped face integrated: the region has some
  // 10 000), then added to its block in the list's order.
  std::vector<BlockVector> face_loads(model_.pressures.size());
  tbb::parallel_for(std::size_t{0}, model_.pressures.size(), [&](std::size_t e) {
    const DdaPressure& p = model_.pressures[e];
    const BlockState& block = blocks_[static_cast<std::size_t>(p.block)];
    if (block.fixed) return;
    face_loads[e] = pressureLoad(block, block.pieces[static_cast<std::size_t>(p.piece)], p.face, p,
                                 wetted ? &(*wetted)[e] : nullptr);
  });
  std::vector<BlockVector> sums(base_f_.size(), BlockVector::Zero());
  for (std::size_t e = 0; e < model_.pressures.size(); ++e) {
    const BlockState& block = blocks_[static_cast<std::size_t>(model_.pressures[e].block)];
    if (block.fixed) continue;
    sums[static_cast<std::size_t>(block.dof_offset)] += face_loads[e];
    any = true;
  }
  return sums;
}

void Simulation::addWaterLoads() {
  water_f_ = blockWaterLoads(nullptr, active_.surface_pressure);
  for (std::size_t m = 0; m < water_f_.size(); ++m) load_f_[m] += water_f_[m];
  water_ = DeferredWater::Ready;
}

bool Simulation::contactSprings(const Contact& c, ContactSprings& springs,
                                ActiveTerms& active) const {
  if (c.state == ContactState::Open) return false;
  active.contact_normal = true;
  if (c.state == ContactState::Locked) {
    lockedSprings(c, penalty_, penalty_ / settings_.shear_penalty_ratio, springs.s,
                  springs.offsets);
    active.contact_shear = true;
    return true;
  }
  // The normal spring.
  const Vec3& n = c.normal;
  springs.s.noalias() = penalty_ * (n * n.transpose());
  springs.offsets = penalty_ * c.gap0 * n;
  // The shear strength resists the slip: f N, plus c A while a plastic joint's contact keeps
  // its cohesion (a brittle one lost it when it started to slide). As a load it is an offset:
  // F_i -= T_i^T s takes -f N s on block i, F_j += T_j^T s its reaction.
  const double friction = shearStrength(c, jointOf(c));
  springs.offsets += friction * c.slide_direction;
  active.friction = true;
  springs.applied.force = -friction * c.slide_direction;
  if (friction > 0.0 && c.slip_length > 0.0 && c.slide_direction.squaredNorm() > 0.0) {
    // Consistent tangent of F = -f N s / |s| about the last slip s*: -f N / |s*| times the
    // slip across s*. Without it the direction is explicit, and a slip across it (a yaw of a
    // sliding block) is pushed back f N / |s*| per metre, one step late: with the small
    // slips of a static step that over-corrects and grows by ~ -3 per step. Capped at the
    // shear spring (a locked contact resists no more); rigid parts, as the direction. Only
    // once a slip is known: a tangent about a guessed direction would hold a wrong one.
    springs.applied.transverse_stiffness =
        std::min(penalty_ / settings_.shear_penalty_ratio, friction / c.slip_length);
    springs.applied.across = c.normal.cross(c.slide_direction).normalized();
    // A rigid block's unknowns are all rigid-body ones: the tangent joins the normal spring.
    Eigen::Matrix3d& rigid = dofs_ == 6 ? springs.s : springs.s_rigid;
    rigid.noalias() += springs.applied.transverse_stiffness *
                       (springs.applied.across * springs.applied.across.transpose());
  }
  return true;
}

Simulation::AppliedFriction Simulation::addContactTerms(const Contact& c,
                                                        const BlockSystem::Parts& parts,
                                                        ActiveTerms& active) {
  ContactSprings springs;
  if (!contactSprings(c, springs, active)) return {};
  const int i = movableIndex(c.block_i), j = movableIndex(c.block_j);
  DisplacementMatrix ti =
      displacementMatrix(c.point, blocks_[static_cast<std::size_t>(c.block_i)].centroid);
  DisplacementMatrix tj =
      displacementMatrix(c.foot, blocks_[static_cast<std::size_t>(c.block_j)].centroid);
  // The rigid-body parts of T (a rigid block has no others).
  DisplacementMatrix ri = ti, rj = tj;
  ri.rightCols<kVoigtSize>().setZero();
  rj.rightCols<kVoigtSize>().setZero();
  if (dofs_ == 6) {
    ti = ri;
    tj = rj;
  }
  const bool transverse = !springs.s_rigid.isZero(0.0);
  if (i == j) {
    // Both ends on one block: its displacement difference T_i - T_j against nothing.
    if (i < 0 || !parts.i) return springs.applied;
    BlockSystem::Parts own = parts;
    own.j = own.pair = false;
    system_->addPointSprings(i, ti - tj, -1, tj, springs.s, springs.offsets, own);
    if (transverse) {
      system_->addPointSprings(i, ri - rj, -1, rj, springs.s_rigid, Vec3::Zero(), own);
    }
    return springs.applied;
  }
  system_->addPointSprings(i, ti, j, tj, springs.s, springs.offsets, parts);
  if (transverse) system_->addPointSprings(i, ri, j, rj, springs.s_rigid, Vec3::Zero(), parts);
  return springs.applied;
}

void Simulation::assembleSystem() {
  PhaseTimer timer(step_profile_, StepPhase::AssembleContacts);
  system_->clear();
  for (std::size_t m = 0; m < base_k_.size(); ++m) {
    system_->addDiagonal(static_cast<int>(m), base_k_[m]);
    system_->addForce(static_cast<int>(m), base_f_[m]);
    if (water_ == DeferredWater::Ready) system_->addForce(static_cast<int>(m), water_f_[m]);
  }
  // The contacts' terms in parallel, bit for bit the serial loop's sums: each thread goes
  // through its contacts in order (listAssembly) and adds the terms of its own blocks (K_ii,
  // F_i) and of the pairs whose lower block it owns (K_ij) (splitAssembly). Every sum then
  // takes its terms in contact order whatever the threads; a contact between two threads'
  // slabs is computed by both, and its friction recorded by the owner of its first movable
  // block.
  if (assembly_owner_.size() != base_k_.size()) splitAssembly();
  if (assembly_listed_ != contacts_.size() || assembly_pairs_version_ != system_->pairsVersion()) {
    listAssembly();
  }
  applied_friction_.resize(contacts_.size());
  const double shear_penalty = penalty_ / settings_.shear_penalty_ratio;
  std::vector<ActiveTerms> active(static_cast<std::size_t>(assembly_parts_));
  tbb::parallel_for(0, assembly_parts_, [&](int part) {
    const std::vector<AssemblyEntry>& list = assembly_lists_[static_cast<std::size_t>(part)];
    ActiveTerms& terms = active[static_cast<std::size_t>(part)];
    for (std::size_t k = 0; k < list.size();) {
      const AssemblyEntry& entry = list[k];
      const Contact& first = contacts_[entry.contact];
      if (dofs_ != 6 || movableIndex(first.block_i) == movableIndex(first.block_j)) {
        const AppliedFriction applied = addContactTerms(
            first, system_->withSlot(entry.pair, entry.transposed, partsOf(entry.adds)), terms);
        if (entry.adds & kRecords) applied_friction_[entry.contact] = applied;
        ++k;
        continue;
      }
      // Rigid blocks: the run of this pair's entries (useContacts keeps them one after the
      // other) summed first, then added to the blocks once (BlockSystem::RigidSpringSums), in
      // the frame of the pair's lower block: an entry whose point is on the upper block adds
      // its spring with its ends swapped (T_i - T_j and its offsets change sign together).
      const PairFrame frame = pairFrame(first, entry);
      const int i = movableIndex(frame.lower), j = movableIndex(frame.upper);
      const BlockSystem::Parts mine =
          system_->withSlot(entry.pair, frame.transposed, partsOf(frame.adds));
      BlockSystem::RigidSpringSums sums;
      sums.with_i = i >= 0 && mine.i;
      sums.with_j = j >= 0 && mine.j;
      sums.with_pair = i >= 0 && j >= 0 && mine.pair;
      const Vec3& ci = blocks_[static_cast<std::size_t>(frame.lower)].centroid;
      const Vec3& cj = blocks_[static_cast<std::size_t>(frame.upper)].centroid;
      for (; k < list.size(); ++k) {
        const AssemblyEntry& e = list[k];
        const Contact& c = contacts_[e.contact];
        const PairFrame f = pairFrame(c, e);
        if (f.lower != frame.lower || f.upper != frame.upper || f.adds != frame.adds) break;
        const bool swapped = c.block_i != frame.lower;
        const Eigen::Matrix3d ri = rotationColumns((swapped ? c.foot : c.point) - ci);
        const Eigen::Matrix3d rj = rotationColumns((swapped ? c.point : c.foot) - cj);
        if (c.state == ContactState::Locked) {
          // Most entries: contactSprings' locked springs, in line.
          Eigen::Matrix3d s;
          Vec3 offsets;
          lockedSprings(c, penalty_, shear_penalty, s, offsets);
          sums.add(ri, rj, s, swapped ? Vec3(-offsets) : offsets);
          terms.contact_normal = terms.contact_shear = true;
          if (e.adds & kRecords) applied_friction_[e.contact] = {};
          continue;
        }
        ContactSprings springs;
        if (contactSprings(c, springs, terms)) {
          sums.add(ri, rj, springs.s, swapped ? Vec3(-springs.offsets) : springs.offsets);
        }
        if (e.adds & kRecords) applied_friction_[e.contact] = springs.applied;
      }
      system_->addRigidSpringSums(i, j, sums, mine);
    }
  });
  for (const ActiveTerms& terms : active) active_ |= terms;
  addBoltTerms();
}

void Simulation::splitAssembly() {
  const std::size_t movable = base_k_.size();
  assembly_owner_.assign(movable, 0);
  assembly_parts_ = static_cast<int>(std::clamp<std::size_t>(
      static_cast<std::size_t>(tbb::this_task_arena::max_concurrency()), 1, 64));
  if (assembly_parts_ == 1 || movable < 2) {
    assembly_parts_ = 1;
    listAssembly();
    return;
  }
  // Each movable block weighs its contacts (the terms it adds) plus one; slabs along x hold
  // about equal weights, so few contacts join two threads' blocks.
  std::vector<double> weight(movable, 1.0);
  std::vector<double> x(movable, 0.0);
  for (const BlockState& block : blocks_) {
    if (block.dof_offset >= 0) x[static_cast<std::size_t>(block.dof_offset)] = block.centroid.x();
  }
  for (const Contact& c : contacts_) {
    for (const int b : {movableIndex(c.block_i), movableIndex(c.block_j)}) {
      if (b >= 0) weight[static_cast<std::size_t>(b)] += 1.0;
    }
  }
  std::vector<std::size_t> order(movable);
  for (std::size_t m = 0; m < movable; ++m) order[m] = m;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return std::tie(x[a], a) < std::tie(x[b], b); });
  double total = 0.0;
  for (const double w : weight) total += w;
  double before = 0.0;
  for (const std::size_t m : order) {
    const int part = static_cast<int>(before / total * assembly_parts_);
    assembly_owner_[m] = std::min(part, assembly_parts_ - 1);
    before += weight[m];
  }
  listAssembly();
}

void Simulation::listAssembly() {
  assembly_lists_.assign(static_cast<std::size_t>(assembly_parts_), {});
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const Contact& c = contacts_[k];
    const int i = movableIndex(c.block_i), j = movableIndex(c.block_j);
    const auto owner = [&](int b) {
      return b >= 0 ? assembly_owner_[static_cast<std::size_t>(b)] : -1;
    };
    // The threads that add something of it: the owners of its blocks (K_ii, K_jj, and K_ij,
    // which the lower block's owner adds) and the one that records its friction (the first
    // movable block's owner; the first thread when both are fixed).
    const int part_i = owner(i), part_j = owner(j);
    const int part_pair = i >= 0 && j >= 0 ? owner(std::min(i, j)) : -1;
    const int part_records = i >= 0 ? part_i : j >= 0 ? part_j : 0;
    for (const int part : {part_i, part_j, part_records}) {
      if (part < 0) continue;
      std::vector<AssemblyEntry>& list = assembly_lists_[static_cast<std::size_t>(part)];
      if (!list.empty() && list.back().contact == k) continue;  // listed for this part already
      std::uint8_t adds = 0;
      if (part_i == part) adds |= kAddsI;
      if (part_j == part) adds |= kAddsJ;
      if (part_pair == part) adds |= kAddsPair;
      if (part_records == part) adds |= kRecords;
      AssemblyEntry entry{static_cast<std::uint32_t>(k), adds, false, -1};
      if (adds & kAddsPair) entry.pair = system_->pairSlot(i, j, entry.transposed);
      list.push_back(entry);
    }
  }
  assembly_listed_ = contacts_.size();
  assembly_pairs_version_ = system_->pairsVersion();
}

Eigen::VectorXd Simulation::solveSystem(double dt, int iteration, const Eigen::VectorXd& previous) {
  PhaseTimer timer(step_profile_, StepPhase::Solve);
  // First guess (used by iterative backends): the previous iteration's solution, or for the
  // first iteration the last step's scaled to this dt.
  Eigen::VectorXd guess;
  if (iteration > 1) {
    guess = previous;
  } else if (last_solution_.size() == system_->rhs().size() && last_dt_ > 0.0) {
    guess = (dt / last_dt_) * last_solution_;
  }
  Eigen::VectorXd solution = guess.size() == system_->rhs().size()
                                 ? solver_->solveWithGuess(system_->rhs(), guess)
                                 : solver_->solve(system_->rhs());
  solver_iterations_ += solver_->stats().iterations;
  return solution;
}

int Simulation::openCloseIterate(double dt, Eigen::VectorXd& solution, bool& settled) {
  settled = false;
  const int movable = static_cast<int>(base_k_.size());
  for (int iteration = 1; iteration <= settings_.max_open_close_iterations; ++iteration) {
    assembleSystem();
    if (movable == 0) {
      solution.resize(0);
      settled = true;
      return iteration;
    }
    bool positive = false;
    {
      PhaseTimer timer(step_profile_, StepPhase::Factorize);
      const SparseMatrix& k = system_->matrix();
      // The factorization holds one thread: beside it, what the solve and the state updates
      // need and K does not, on the other threads (the same values as before the
      // factorization: each is its own pass over the blocks or the contacts).
      const bool water = water_ == DeferredWater::Pending;
      if (water || step_start_pending_) {
        tbb::task_group beside;
        if (water) beside.run([&] { addWaterLoads(); });
        if (step_start_pending_) beside.run([&] { saveStepStart(contacts_, step_start_); });
        positive = solver_->factorize(k);
        beside.wait();
        step_start_pending_ = false;
        if (water) {
          for (std::size_t m = 0; m < water_f_.size(); ++m) {
            system_->addForce(static_cast<int>(m), water_f_[m]);
          }
        }
      } else {
        positive = solver_->factorize(k);
      }
      if (solver_->stats().analyzed) ++pattern_changes_;
    }
    if (!positive) {
      // No solution this attempt: step() sees the empty vector and redoes the step with a
      // smaller time step (more inertia on the diagonal), or reports the failure.
      solution.resize(0);
      return iteration;
    }
    solution = solveSystem(dt, iteration, solution);
    PhaseTimer update_timer(step_profile_, StepPhase::UpdateStates);
    const bool finite = solution.allFinite();
    const StateChanges changes = finite ? updateContactStates(solution) : StateChanges{};
    last_changes_ = changes;
    if (!finite) return iteration;
    // The allowance covers contacts that opened or changed between locked and sliding (they
    // carried a spring or a friction force one iteration too long), and in a static run those
    // that closed within kStaticClosingShare of the allowed penetration (the next step, from
    // rest, pushes them back); never a deeper closing, nor any closing in a dynamic run: it
    // was solved open and may sit deep in the other block.
    const auto allowed =
        static_cast<int>(settings_.open_close_tolerance * static_cast<double>(contacts_.size()));
    // A sliding contact whose friction was solved with another normal force than its own
    // counts as a change (DdaSettings::friction_tolerance); once the states hold, the last
    // iteration takes the friction it has.
    const bool states_hold = changes.closed_deep == 0 && changes.changed <= allowed;
    if (states_hold && (changes.changed + changes.friction_changed <= allowed ||
                        iteration == settings_.max_open_close_iterations)) {
      settled = true;
      return iteration;
    }
  }
  return settings_.max_open_close_iterations;
}

bool Simulation::addBlockPorePressure(const std::vector<double>& wetted_area) {
  // The water on a block's faces loads its strain by -integral of p n (x - x_c)^T dA, which is
  // -V p(x_c) I for a block wetted all round by a linear field (divergence theorem: the
  // field's gradient loads only the translation and rotation, the buoyancy and seepage
  // force). A block saturated by that water carries it in its pores: the effective stress
  // sigma' = sigma + alpha p I (tension positive) strains it, +alpha V p I in its strain rows,
  // p the water's field at its centroid. That field is the one its wetted faces carry there:
  // of a field given in pieces (the uplift diagram's, between heel, drains and toe), the
  // pieces whose half-spaces hold the centroid; of several fields (the reservoir's on the
  // river bed and the joints'), their mean weighed by the area each wets. A block with dry
  // faces (a face on the region's roller side stands for the saturated rock beyond) carries
  // the same field: its pores do not know where the region was cut. Without this, the joint
  // water of the Xiangjiaba foundation (1-2 MPa at 20-30 m) shrank its blocks by p / K
  // (0.08-0.16 % in the soft interlayer) and opened the joints between them.
  std::vector<double> weighed(blocks_.size(), 0.0), wetted(blocks_.size(), 0.0);
  std::vector<double> weighed_any(blocks_.size(), 0.0), wetted_any(blocks_.size(), 0.0);
  for (std::size_t e = 0; e < model_.pressures.size(); ++e) {
    const DdaPressure& p = model_.pressures[e];
    const auto b = static_cast<std::size_t>(p.block);
    const BlockState& block = blocks_[b];
    if (block.fixed || model_.blocks[b].structure >= 0) continue;
    const double area = wetted_area[e];
    const double field = pressureAt(p, block.centroid);
    weighed_any[b] += area * field;
    wetted_any[b] += area;
    if (pressureApplies(p, block.centroid)) {
      weighed[b] += area * field;
      wetted[b] += area;
    }
  }
  bool any = false;
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    // The pieces that hold the centroid; if none of its faces' pieces does (a block wholly on
    // one side of a knot, its centroid just across), the mean of those it has.
    const double pore = wetted[b] > 0.0       ? weighed[b] / wetted[b]
                        : wetted_any[b] > 0.0 ? weighed_any[b] / wetted_any[b]
                                              : 0.0;
    if (!(pore > 0.0)) continue;
    load_f_[static_cast<std::size_t>(blocks_[b].dof_offset)].tail<kVoigtSize>().head<3>().array() +=
        settings_.biot_coefficient * blocks_[b].volume * pore;
    any = true;
  }
  return any;
}

double Simulation::maxDisplacementRatio(const Eigen::VectorXd& solution, int* fastest,
                                        double* weighed, double* reach_ratio) const {
  // Each block's largest vertex displacement in parallel, then the largest in block order;
  // in the same pass over the vertices, the largest first-order displacement
  // (largestVertexDisplacement) against the block's reach.
  std::vector<double> moved(blocks_.size(), 0.0);
  std::vector<double> reached(blocks_.size(), 0.0);
  tbb::parallel_for(std::size_t{0}, blocks_.size(), [&](std::size_t b) {
    const BlockState& block = blocks_[b];
    if (block.fixed) return;
    const BlockVector d = system_->unknowns(solution, block.dof_offset);
    const BlockMotion motion(block.centroid, d);
    // The first-order field only where the reach is checked and the block moved (zero d:
    // every vertex's displacement is exactly zero).
    std::optional<LinearDisplacement> field;
    if (reach_ratio != nullptr && !d.isZero(0.0)) field.emplace(block, d);
    double block_largest = 0.0;
    double block_linear = 0.0;
    for (const geometry::Polyhedron& piece : block.pieces) {
      for (const Vec3& v : piece.vertices) {
        block_largest = std::max(block_largest, (motion(v) - v).norm());
        if (field) block_linear = std::max(block_linear, field->squaredAt(v));
      }
    }
    moved[b] = block_largest;
    if (reach_ratio) reached[b] = std::sqrt(block_linear) / reach_[b];
  });
  if (reach_ratio) {
    *reach_ratio = 0.0;
    for (std::size_t b = 0; b < blocks_.size(); ++b) {
      if (!blocks_[b].fixed) *reach_ratio = std::max(*reach_ratio, reached[b]);
    }
  }
  double largest = 0.0;
  double largest_weighed = 0.0;
  int largest_block = -1;
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    const BlockState& block = blocks_[b];
    if (block.fixed) continue;
    const double block_largest = moved[b];
    if (block_largest > largest) {
      largest = block_largest;
      largest_block = static_cast<int>(b);
    }
    largest_weighed = std::max(largest_weighed, block_largest * staticMassScale(block));
  }
  if (fastest) *fastest = largest_block;
  if (weighed) *weighed = largest_weighed;
  return largest / (settings_.max_displacement_ratio * half_domain_);
}

double Simulation::maxPenetration() const {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, contacts_.size(), 8192), 0.0,
      [&](const tbb::blocked_range<std::size_t>& range, double deepest) {
        for (std::size_t k = range.begin(); k != range.end(); ++k) {
          deepest = std::max(deepest, -contacts_[k].gap);
        }
        return deepest;
      },
      [](double x, double y) { return std::max(x, y); });
}

void Simulation::updateBlocks(const Eigen::VectorXd& solution, double dt) {
  const double ratio = settings_.mode == AnalysisMode::Static ? 0.0 : settings_.dynamic_ratio;
  const bool rigid = settings_.kinematics != Kinematics::Deformable;
  const auto move = [&](std::vector<MaterialPoint>& points) {
    for (MaterialPoint& p : points) {
      if (p.block < 0) continue;
      const BlockState& block = blocks_[static_cast<std::size_t>(p.block)];
      if (block.fixed) continue;
      p.current = movedPoint(p.current, block.centroid, unknownsOf(solution, p.block));
    }
  };
  move(monitor_points_);
  move(load_points_);
  move(fixed_points_);
  move(bolt_a_);
  move(bolt_b_);
  block_work_.resize(blocks_.size(), 0.0);
  last_largest_.assign(blocks_.size(), 0.0);
  // Each block moves on its own (in parallel); the loads' work is summed in block order.
  std::vector<double> work(blocks_.size(), 0.0);
  tbb::parallel_for(std::size_t{0}, blocks_.size(), [&](std::size_t b) {
    BlockState& block = blocks_[b];
    if (block.fixed) return;
    const BlockVector d = system_->unknowns(solution, block.dof_offset);
    work[b] = load_f_[static_cast<std::size_t>(block.dof_offset)].dot(d);
    const BlockMotion motion(block.centroid, d);
    Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 high = -low;
    for (geometry::Polyhedron& piece : block.pieces) {
      for (Vec3& v : piece.vertices) {
        v = motion(v);
        low = low.cwiseMin(v);
        high = high.cwiseMax(v);
      }
    }
    for (FacePoints& points : block.face_points) {
      for (FacePoint& p : points.points) p.position = motion(p.position);
    }
    const Eigen::Matrix3d& rotation = motion.rotation();
    if (rigid) {
      // A rigid motion keeps the volume and carries the centroid and the central second
      // moments along (S' = R S R^T): the same values as integrating the moved pieces again,
      // to round-off, without the pass over every face (updateMassProperties).
      block.centroid = motion(block.centroid);
      const Eigen::Matrix3d second = rotation * block.second * rotation.transpose();
      block.second = 0.5 * (second + second.transpose());
      block.size = (high - low).norm();
    }
    if (settings_.kinematics == Kinematics::Deformable) {
      const VoigtVector step_strain = d.tail<kVoigtSize>();
      block.stress += elastic_[static_cast<std::size_t>(block.material)] * step_strain;
      block.strain += step_strain;
      block.stress = rotateVoigt(block.stress, rotation, 1.0);
      block.strain = rotateVoigt(block.strain, rotation, 0.5);
    }
    const BlockVector a1 = endAcceleration(d, block.velocity, block.acceleration, dt, scheme_);
    block.velocity =
        ratio * endVelocity(block.velocity, block.acceleration, a1, dt, scheme_).eval();
    block.acceleration = ratio * a1;
    block.last_displacement = d;
    if (!rigid) block.updateMassProperties();
    // On the moved geometry: the next step's reach and the kept pairs' bound (acceptStep).
    last_largest_[b] = largestVertexDisplacement(block, d);
  });
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    if (blocks_[b].fixed) continue;
    work_of_loads_ += work[b];
    block_work_[b] += work[b];
  }
}

Simulation::StepCheck Simulation::checkStep(const Eigen::VectorXd& solution, bool settled,
                                            bool last_chance, double& dt, StepReport& report) {
  const double allowed = settings_.allowed_penetration_ratio * half_domain_;
  // Capped at 1e4 x the initial penalty for the whole run: a cap taken from the current
  // penalty let it climb 1e4 per step (to 1e34 N/m on the Xiangjiaba model while another
  // fault kept the steps failing), until K was not positive definite in floating point.
  const double penalty_cap = 1e4 * initial_penalty_;
  const bool can_shrink = dt > settings_.min_time_step;
  if (!settled && can_shrink && !last_chance) {
    dt = std::max(settings_.min_time_step, dt * settings_.iteration_time_step_factor);
    ++report.redo_iterations;
    return StepCheck::Redo;
  }
  if (solution.size() != system_->rhs().size()) {
    // The factorization found the matrix not positive definite on every attempt, down to
    // the smallest time step: a block with (almost) no mass or stiffness, or a mechanism.
    throw std::runtime_error(singularMatrixMessage(dt));
  }
  if (!solution.allFinite()) {
    throw std::runtime_error(
        "DDA step failed: the system is singular at t = " + std::to_string(time_) + " s");
  }
  double reach_ratio = 0.0;
  {
    PhaseTimer timer(step_profile_, StepPhase::UpdateStates);
    report.displacement_ratio = maxDisplacementRatio(solution, &report.fastest_block,
                                                     &report.unbalanced_displacement, &reach_ratio);
    // A solution's contacts were updated from it (their deepest penetration found in that
    // pass); without movable blocks there was no solve.
    report.max_penetration = solution.size() > 0 ? last_changes_.deepest : maxPenetration();
  }
  const bool too_far = report.displacement_ratio > kAcceptedDisplacementRatio || reach_ratio > 1.0;
  if (too_far && !last_chance && can_shrink) {
    const double over_limit =
        report.displacement_ratio > kAcceptedDisplacementRatio ? report.displacement_ratio : 0.0;
    dt = std::max(settings_.min_time_step,
                  dt * std::max(0.1, 0.9 / std::max(over_limit, reach_ratio)));
    ++report.redo_displacement;
    return StepCheck::Redo;
  }
  if (report.max_penetration > allowed && penalty_ < penalty_cap && !last_chance) {
    const double ratio = report.max_penetration / allowed;
    penalty_ = std::min(penalty_cap, penalty_ * std::clamp(ratio * ratio, 2.0, 10.0));
    ++report.redo_penetration;
    return StepCheck::Redo;
  }
  if (!settled || too_far || report.max_penetration > allowed) {
    // Nothing left to try: dt is at its minimum (or the attempts are used up) and the step
    // still fails a check. Accepting it would go on with a step that broke the method's
    // assumptions, and runs left to do so shrank dt without end (docs/dda3d.md, "Step
    // control").
    throw StepFailure(stepFailureMessage(dt, report.attempts, settled, report, allowed));
  }
  return StepCheck::Accept;
}

void Simulation::acceptStep(const Eigen::VectorXd& solution, double dt, StepReport& report) {
  {
    PhaseTimer timer(step_profile_, StepPhase::UpdateBlocks);
    finishContacts(solution);  // before accountDissipation: the springs' start terms
    accountDissipation(solution, dt);
    updateBlocks(solution, dt);
    // How far each block moved, for the kept broad-phase pairs (a first-order bound, from
    // the moved geometry: 1 % over it covers the difference).
    // (moved_since_search_ is empty before the run's first search.)
    for (std::size_t b = 0; b < blocks_.size(); ++b) {
      const double moved = blocks_[b].fixed ? 0.0 : 1.01 * last_largest_[b];
      candidates_.moved(b, moved);
      if (b < moved_since_search_.size()) moved_since_search_[b] += moved;
    }
    // springEnergy(): the points' springs (moved with their blocks), then the contacts' terms
    // of finishContacts in contact order.
    double springs = pointSpringEnergy();
    sumSprings(springs_after_, springs);
    springs_after_step_ = springs;
    last_solution_ = solution;
    last_dt_ = dt;
  }
  time_ += dt;
  updateBolts();
  steps_at_min_ = dt <= settings_.min_time_step * (1.0 + 1e-12) ? steps_at_min_ + 1 : 0;
  if (steps_at_min_ >= settings_.max_steps_at_min_time_step) {
    throw StepFailure(stalledMessage(report));
  }
  const double grow =
      report.displacement_ratio > 0.0 ? 0.9 / std::sqrt(report.displacement_ratio) : 1.2;
  dt_ = std::clamp(dt * std::clamp(grow, 0.5, 1.2), settings_.min_time_step, settings_.time_step);
  report.time = time_;
  report.time_step = dt;
  report.penalty = penalty_;
}

StepReport Simulation::step() {
  if (interruptRequested()) {
    std::ostringstream where;
    where << "the DDA at t = " << time_ << " s";
    throwIfInterrupted(where.str());
  }
  StepReport report;
  step_profile_ = StepProfile{};
  const int patterns_before = pattern_changes_;
  solver_iterations_ = 0;
  // Saved by a detection that keeps every entry, else beside the first factorization
  // (openCloseIterate), before any state changes.
  step_start_pending_ = true;
  {
    PhaseTimer timer(step_profile_, StepPhase::DetectContacts);
    const int searches_before = searches_;
    const int partial_before = partial_searches_;
    report.late_contacts = detectContacts();
    report.contacts_searched = searches_ > searches_before;
    report.contacts_searched_partly = partial_searches_ > partial_before;
  }
  double dt = dt_;
  Eigen::VectorXd solution;
  for (int attempt = 1;; ++attempt) {
    report.attempts = attempt;
    if (attempt > 1) restoreStepStart(step_start_, contacts_);
    {
      PhaseTimer timer(step_profile_, StepPhase::AssembleBlockTerms);
      assembleBlockTerms(dt, true);
    }
    bool settled = false;
    report.iterations = openCloseIterate(dt, solution, settled);
    if (step_start_pending_) {
      // No factorization ran (no movable block): the contacts are as they started.
      saveStepStart(contacts_, step_start_);
      step_start_pending_ = false;
    }
    if (water_ == DeferredWater::Pending) addWaterLoads();  // for the work of the loads
    const bool last_chance = attempt >= settings_.max_step_attempts;
    if (checkStep(solution, settled, last_chance, dt, report) == StepCheck::Accept) break;
  }
  acceptStep(solution, dt, report);
  report.pattern_changes = pattern_changes_ - patterns_before;
  report.solver_iterations = solver_iterations_;
  report.contacts = finished_counts_;  // counted in acceptStep's pass (finishContacts)
  report.profile = step_profile_;
  timings_ += step_profile_;
  return report;
}

StepReport Simulation::runUntil(double end_time) {
  StepReport last;
  while (time_ < end_time * (1.0 - 1e-12)) {
    dt_ = std::min(dt_, end_time - time_);
    last = step();
  }
  return last;
}

Vec3 Simulation::centroidDisplacement(int b) const {
  return blocks_[static_cast<std::size_t>(b)].centroid -
         initial_centroids_[static_cast<std::size_t>(b)];
}

ContactCounts Simulation::contactCounts() const {
  return countContacts(nullptr);
}

ContactCounts Simulation::countContacts(const std::function<void(std::size_t)>* each) const {
  // Counted in parallel (integer sums: the same in any order).
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, contacts_.size(), 1024), ContactCounts{},
      [&](const tbb::blocked_range<std::size_t>& range, ContactCounts counts) {
        for (std::size_t k = range.begin(); k != range.end(); ++k) {
          if (each != nullptr) (*each)(k);
          const Contact& c = contacts_[k];
          ++counts.total;
          counts.edge_edge += c.kind == ContactKind::EdgeEdge;
          counts.open += c.state == ContactState::Open;
          counts.sliding += c.state == ContactState::Sliding;
          counts.locked += c.state == ContactState::Locked;
        }
        return counts;
      },
      [](ContactCounts a, const ContactCounts& b) {
        a.total += b.total;
        a.edge_edge += b.edge_edge;
        a.open += b.open;
        a.sliding += b.sliding;
        a.locked += b.locked;
        return a;
      });
}

std::vector<MonitorState> Simulation::monitors() const {
  std::vector<MonitorState> out;
  for (std::size_t k = 0; k < monitor_points_.size(); ++k) {
    const MaterialPoint& p = monitor_points_[k];
    const BlockState& block = blocks_[static_cast<std::size_t>(p.block)];
    MonitorState m;
    m.name = model_.monitors[k].name;
    m.position = p.current;
    m.displacement = p.current - p.initial;
    m.velocity = displacementMatrix(p.current, block.centroid) * block.velocity;
    out.push_back(m);
  }
  return out;
}

}  // namespace rockmass::dda3d
