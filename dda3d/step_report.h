// What one DDA step reports: the terms it assembled, its contacts by state, its checks and
// redos, and the time spent in each of its phases (StepProfile).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/vec.h"

namespace rockmass::dda3d {

/// Which sub-matrices were assembled (cumulative over the run, or for one step).
struct ActiveTerms {
  bool elastic = false;
  bool initial_stress = false;
  bool inertia = false;
  bool body_force = false;
  bool point_loads = false;
  bool surface_pressure = false;
  bool block_pore_pressure = false;  ///< water carried by deformable blocks' pores (Biot)
  bool fixed_points = false;
  bool rollers = false;  ///< fixed points held along one direction only
  bool fixed_blocks = false;
  bool contact_normal = false;
  bool contact_shear = false;
  bool friction = false;
  bool bolts = false;
  /// Names of the active terms, in the order above ("elastic", "inertia", ...).
  std::vector<std::string> names() const;
  ActiveTerms& operator|=(const ActiveTerms& other);
};

/// The phases of a DDA step, in the order a step runs them (Simulation::step).
enum class StepPhase {
  DetectContacts,      ///< broad and narrow phase, contact persistence
  AssembleBlockTerms,  ///< inertia, elasticity, loads, supports of every block
  AssembleContacts,    ///< contact springs and friction (each open-close iteration)
  Factorize,           ///< the linear solver's factorization (each iteration)
  Solve,               ///< the solve (each iteration)
  UpdateStates,        ///< contact states and the step's checks
  UpdateBlocks,        ///< exact rotation, stresses, velocities, contact shear
};
inline constexpr int kStepPhases = 7;

/// Seconds spent in each phase, of one step (StepReport::profile) or summed over a run
/// (Simulation::timings).
struct StepProfile {
  double seconds[kStepPhases] = {};
  double& operator[](StepPhase p) { return seconds[static_cast<int>(p)]; }
  double operator[](StepPhase p) const { return seconds[static_cast<int>(p)]; }
  double total() const {
    double sum = 0.0;
    for (const double s : seconds) sum += s;
    return sum;
  }
  StepProfile& operator+=(const StepProfile& o) {
    for (int k = 0; k < kStepPhases; ++k) seconds[k] += o.seconds[k];
    return *this;
  }
  /// The phase's name in outputs: "detect_contacts", "assemble_block_terms", ...
  static const char* name(StepPhase p);
};

/// Adds the wall time from its construction to its destruction to one phase of a profile.
class PhaseTimer {
 public:
  PhaseTimer(StepProfile& profile, StepPhase phase);
  ~PhaseTimer();
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  StepProfile& profile_;
  StepPhase phase_;
  double start_;  ///< steady clock, s
};

/// Contact counts by state.
struct ContactCounts {
  int total = 0;
  int open = 0;
  int sliding = 0;
  int locked = 0;
  int edge_edge = 0;  ///< of the total, the edge-to-edge entries
};

/// Account of one accepted step.
struct StepReport {
  double time = 0.0;          ///< s, simulated time at the end of the step
  double time_step = 0.0;     ///< s, the accepted dt
  int iterations = 0;         ///< open-close iterations of the accepted attempt
  int attempts = 1;           ///< 1 + redos
  int redo_iterations = 0;    ///< redos because the open-close iteration did not settle
  int redo_displacement = 0;  ///< redos because of the displacement ratio
  int redo_penetration = 0;   ///< redos with a stiffer penalty
  /// Contacts the step's detection found first deeper than the allowed penetration: a miss
  /// of the detection, their depth then not pushed back (Contact::overlap).
  int late_contacts = 0;
  /// The step searched its contacts (else it kept the last step's entries,
  /// DdaSettings::detection.search_margin).
  bool contacts_searched = false;
  /// The step searched only the pairs of the blocks that moved beyond the search margin and
  /// kept the other entries (Simulation::partialSearches); contacts_searched is then false.
  bool contacts_searched_partly = false;
  double displacement_ratio = 0.0;  ///< max vertex displacement / (g2 l0)
  int fastest_block = -1;           ///< the block of that vertex (-1: none moved)
  /// m: the largest vertex displacement of a block times its inertia scale
  /// (Simulation::inertiaScale); the same as the displacement unless a massive block's static
  /// inertia was scaled down. The equilibrium's unbalanced ratio is this over g dt^2 / 2.
  double unbalanced_displacement = 0.0;
  double max_penetration = 0.0;  ///< m, deepest penetration after the step (>= 0)
  double penalty = 0.0;          ///< N/m, normal penalty used
  int pattern_changes = 0;       ///< symbolic analyses redone
  /// Iterative-solver (PCG) iterations summed over every solve of the step, redone attempts
  /// included (0 for direct solvers).
  int solver_iterations = 0;
  ContactCounts contacts;
  StepProfile profile;  ///< seconds per phase, redone attempts included
};

/// A monitored point: displacement since time 0 and current velocity.
struct MonitorState {
  std::string name;
  geometry::Vec3 position = geometry::Vec3::Zero();      ///< m
  geometry::Vec3 displacement = geometry::Vec3::Zero();  ///< m
  geometry::Vec3 velocity = geometry::Vec3::Zero();      ///< m/s
};

/// A step that cannot be completed: the time step is at its minimum (or the attempts are used
/// up) and the step still fails a check of the step control. what() names the time, the time
/// step, the check, and the block or contact that failed it.
class StepFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rockmass::dda3d
