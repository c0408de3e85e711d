// The 3D DDA engine: one Simulation advances a DdaModel step by step (Shi's method in 3D,
// formulation in docs dda3d-formulation.md). Each step runs a fixed sequence of named
// phases: detectContacts, assembleBlockTerms, openCloseIterate (assemble contacts,
// factorize, solve, update states), checkStep (redo with a smaller dt or a stiffer
// penalty), updateBlocks (exact rotation, stresses, velocities, contact shear).
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "dda3d/block_state.h"
#include "dda3d/block_system.h"
#include "dda3d/block_terms.h"
#include "dda3d/contact.h"
#include "dda3d/linear_solver.h"
#include "dda3d/model.h"

namespace rockmass::dda3d {

/// Dynamic (velocities carried between steps) or static (velocities reset every step).
enum class AnalysisMode { Dynamic, Static };
/// Deformable blocks (12 unknowns) or rigid blocks (6).
enum class Kinematics { Deformable, Rigid };
/// How the inertia term is integrated in time (docs/dda3d.md, "Time integration").
enum class TimeIntegration {
  /// Bossak alpha scheme (Newmark with a weighted inertia), second-order accurate, damping
  /// the stiff contact modes by the spectral radius DdaSettings::spectral_radius.
  Bossak,
  /// Shi's scheme of the formulation doc (Newmark beta = 1/2, gamma = 1): first order, no
  /// damping of stiff modes (a velocity that flips sign every step on contact springs).
  Shi,
};

/// Settings of a run (scene: analysis.dda). Defaults follow the 2D reference lineage.
struct DdaSettings {
  AnalysisMode mode = AnalysisMode::Dynamic;
  Kinematics kinematics = Kinematics::Deformable;
  /// Share of the velocity (and acceleration) carried to the next step in dynamic mode (1
  /// fully dynamic). Below 1 it is an extra, non-physical velocity damping.
  double dynamic_ratio = 1.0;
  TimeIntegration integration = TimeIntegration::Bossak;
  /// Bossak: spectral radius rho_inf of the scheme for modes much stiffer than M / dt^2 (the
  /// contact springs), in [0, 1]. 0 removes them within two steps; 1 keeps them undamped.
  double spectral_radius = 0.0;
  double time_step = 1e-3;  ///< s, the largest step; shrunk and regrown automatically
  /// s, the smallest step the step control may cut to. A step that fails its checks at this
  /// dt stops the run (StepFailure), and so does a run whose accepted steps stay at it for
  /// `max_steps_at_min_time_step` steps in a row (it cannot progress).
  double min_time_step = 1e-9;
  int max_steps_at_min_time_step = 1000;
  /// g2: largest displacement of any vertex in a step as a share of half the domain size.
  double max_displacement_ratio = 0.01;
  /// g3: allowed penetration as a share of half the domain size.
  double allowed_penetration_ratio = 4e-4;
  /// Normal contact penalty (N/m); 0 = automatic: penalty_factor * E_max * block size.
  double penalty = 0.0;
  double penalty_factor = 40.0;      ///< - (automatic penalty)
  double shear_penalty_ratio = 2.5;  ///< k_n / k_s
  /// Fixed points' spring (N/m) as a multiple of the normal contact penalty.
  double fixed_point_penalty_ratio = 10.0;
  /// Per attempt (the 2D reference allows 6 + 2). A pile of 1000 cubes landing on its base
  /// opens and closes a thousand contacts in one step and settles in 20-30 iterations, the
  /// changes falling off as a cascade; with 20 it redid such steps at 0.3 dt, to 6e-5 s.
  int max_open_close_iterations = 40;
  /// The open-close iteration has settled when no contact closed and at most this share of
  /// the contacts opened or changed between locked and sliding in its last update (rounded
  /// down: below 1 / this many contacts, none may change, the classic rule). Among the 2e5 contacts
  /// of a large model a few always sit at a round-off gap where closing pushes them open and
  /// opening lets them close; with no allowance every step then failed its 20 iterations and cut dt
  /// by 0.3, down to 1e-8 s on the Xiangjiaba foundation. The contacts that changed last keep their
  /// new state for the next step; one that closed always takes another iteration.
  double open_close_tolerance = 1e-4;
  double iteration_time_step_factor = 0.3;  ///< dt multiplier when the iteration fails
  int max_step_attempts = 40;               ///< redo limit per step
  /// An open contact closes when d < -this * l0. The 2D reference uses 2e-4, which lets a
  /// contact that opened by round-off sink 2e-4 l0 without resistance and tilts resting
  /// blocks. A contact closed at that depth starts with 1/2 k_n d^2 in its spring, which the
  /// step gives back as motion: at 1e-6 l0 the vibrating corners of two deformable cubes
  /// closed 4e-6 m deep, 113 J in one step against 1 J of kinetic energy, and the pair
  /// bounced apart at dt = 2.5e-4 s. 1e-8 keeps the hysteresis above round-off.
  double close_threshold_ratio = 1e-8;
  /// A closed contact opens when d > T A / k_n + this * l0. The 2D reference's 2e-7 lets a
  /// stiff penalty pull with k_n * 2e-7 l0 (~10^5 N here) before opening, which glues a
  /// wedge to a plane it should leave; 1e-10 keeps only a round-off margin.
  double open_threshold_ratio = 1e-10;
  /// Sub-contact points (m): 0 = the corners of each face carry its contact (their area
  /// weights spread cohesion over the overlap of the faces); > 0 = every face at least two
  /// cells of this size wide both ways is cut into cells of about this size, and a point at
  /// each cell's centroid, carrying the cell's area, is a contact of its own against the
  /// face facing it (docs/stability.md, "Contact points"). Needed where a face contact opens
  /// in part: a base whose heel lifts keeps its cohesion on the compressed part only.
  double contact_point_spacing = 0.0;
  /// Half the domain size l0 (m); 0 = half the largest extent of all blocks' bounding box.
  double half_domain_size = 0.0;
  /// Auto: CHOLMOD up to solver.auto_cholmod_unknowns unknowns, above it PCG warm-started
  /// from the previous step with the tolerance autoPcgTolerance() (docs/performance.md).
  SolverOptions solver{.kind = SolverKind::Auto};
};

/// The relative residual |K d - F| / |F| that SolverKind::Auto gives PCG. The displacement
/// error it leaves must be a small share of the allowed penetration g3 l0 while a step moves
/// vertices by up to g2 l0: a relative error of 1e-2 g3 / g2 in d, divided by 1e3 for the
/// condition number of the block-Jacobi preconditioned K (the residual bounds the error only
/// up to it). 4e-7 with the default g2 = 0.01, g3 = 4e-4.
double autoPcgTolerance(const DdaSettings& settings);
/// The solver options a run with these settings and `movable` movable blocks uses (Auto
/// resolved; block size set from the kinematics).
SolverOptions resolvedSolverOptions(const DdaSettings& settings, int movable);

/// Which sub-matrices were assembled (cumulative over the run, or for one step).
struct ActiveTerms {
  bool elastic = false;
  bool initial_stress = false;
  bool inertia = false;
  bool body_force = false;
  bool point_loads = false;
  bool surface_pressure = false;
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

/// Seconds spent per phase (cumulative).
struct PhaseTimings {
  double detect_contacts = 0.0;
  double assemble_block_terms = 0.0;
  double assemble_contacts = 0.0;  ///< inside openCloseIterate
  double factorize = 0.0;          ///< inside openCloseIterate
  double solve = 0.0;              ///< inside openCloseIterate
  double update_states = 0.0;      ///< contact state update and checks
  double update_blocks = 0.0;
  double total() const {
    return detect_contacts + assemble_block_terms + assemble_contacts + factorize + solve +
           update_states + update_blocks;
  }
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
};

/// Energies (J), for checking that nothing grows beyond the work of the loads.
/// Balance: stored() + dissipated() = work_of_loads, up to the energy of contact state
/// changes between steps (a contact that closes, a shear spring that starts at the friction
/// force), the geometric non-linearity of a step (exact rotation, moving contact frames) and
/// the solver's residual (docs/dda3d.md, "Energy account").
struct EnergyAccount {
  double kinetic = 0.0;        ///< 1/2 V^T M V
  double strain = 0.0;         ///< 1/2 V eps^T E eps of the accumulated strain
  double springs = 0.0;        ///< contact, fixed-point and bolt springs
  double work_of_loads = 0.0;  ///< cumulative work of body forces, point loads, pressure
  /// Cumulative work done against the friction forces of sliding contacts, f N s . slip
  /// (>= 0 step by step: s is the direction of the slip).
  double friction = 0.0;
  /// Cumulative energy the time integration removed: per step 1/2 d^T K d (forces taken at
  /// the end of the step) + d^T M ((1 - alpha_m) a1 + alpha_m a0) - (T1 - T0), plus the
  /// kinetic energy removed by a dynamic ratio below 1 or by static mode.
  double numerical = 0.0;
  /// Cumulative energy the springs gained between steps (signed): contacts detected, closed
  /// or opened, shear springs restarted, penalty raised. A contact that closes on a moving
  /// block adds here what the end-of-step spring force then removes in `numerical`.
  double contact_changes = 0.0;
  double stored() const { return kinetic + strain + springs; }
  double dissipated() const { return friction + numerical; }
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

/// A DDA run.
class Simulation {
 public:
  /// Validates the model (throws std::invalid_argument with what is wrong) and sets up.
  Simulation(DdaModel model, DdaSettings settings);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// Advances by one accepted step. Throws StepFailure when the step cannot be completed
  /// (every check of the step control met) even at DdaSettings::min_time_step.
  StepReport step();
  /// Steps until time() >= end_time (s); returns the last report.
  StepReport runUntil(double end_time);

  double time() const { return time_; }        ///< s
  double timeStep() const { return dt_; }      ///< s, proposed for the next step
  double penalty() const { return penalty_; }  ///< N/m, current normal penalty
  /// The work the loads have done on block `b` so far (J; its share of
  /// EnergyAccount::work_of_loads).
  double workOfLoadsOn(std::size_t b) const {
    return b < block_work_.size() ? block_work_[b] : 0.0;
  }
  double halfDomainSize() const { return half_domain_; }  ///< l0 (m)
  /// The factor on block `b`'s mass in its inertia term: below 1 for a massive block in
  /// static mode (staticMassScale), else 1. A step moves such a block 1 / this times farther
  /// for the same out-of-balance force (dda3d::runToEquilibrium weighs its motion by it).
  double inertiaScale(int b) const { return staticMassScale(blocks_[static_cast<std::size_t>(b)]); }
  int dofsPerBlock() const { return dofs_; }  ///< 12 or 6
  const DdaModel& model() const { return model_; }
  const DdaSettings& settings() const { return settings_; }

  /// All blocks: current geometry, velocity (12, zero tail when rigid), last step's
  /// displacement, stress, accumulated strain.
  const std::vector<BlockState>& blocks() const { return blocks_; }
  /// Where each point load's material point is now (m), in model().point_loads order.
  std::vector<geometry::Vec3> pointLoadPositions() const {
    std::vector<geometry::Vec3> out;
    for (const MaterialPoint& p : load_points_) out.push_back(p.current);
    return out;
  }
  /// Displacement of block b's centroid since time 0 (m).
  geometry::Vec3 centroidDisplacement(int b) const;
  /// How far each block's vertices could move in the last step (m, 0 for fixed blocks):
  /// the contact search distance of a pair is the sum of its two blocks' reaches (stepReach).
  const std::vector<double>& contactReach() const { return reach_; }
  /// Contacts of the last accepted step, with states.
  const std::vector<Contact>& contacts() const { return contacts_; }
  /// Starts from `contacts` (another run's, of a model with the same blocks and pieces): the
  /// next step's detection carries their states, shear springs and forces over to the entries
  /// it finds again, as between two steps of one run. Call before the first step.
  void adoptContacts(std::vector<Contact> contacts) { contacts_ = std::move(contacts); }
  ContactCounts contactCounts() const;
  std::vector<MonitorState> monitors() const;
  /// Sub-matrices assembled so far.
  const ActiveTerms& activeTerms() const { return active_; }
  const PhaseTimings& timings() const { return timings_; }
  EnergyAccount energy() const;
  /// Name of the linear solver backend.
  std::string solverName() const;
  /// K of the last solve (the accepted attempt's last open-close iteration), for the debug
  /// dump. Only valid after a step.
  const SparseMatrix& lastMatrix() { return system_->matrix(); }
  /// F of the last solve, for the debug dump. Only valid after a step.
  Eigen::VectorXd lastRhs() const { return system_->rhs(); }

 private:
  struct MaterialPoint {
    int block;
    geometry::Vec3 initial;
    geometry::Vec3 current;
    /// Fixed points: zero, or the only direction held (a roller).
    geometry::Vec3 direction = geometry::Vec3::Zero();
  };

  /// Finds the step's contacts, carrying states over; returns how many were found late
  /// (first seen deeper than the allowed penetration, Contact::overlap).
  int detectContacts();
  /// Static mode: the factor on a block's mass matrix in its inertia term (kStaticInertiaRatio,
  /// at the run's time step).
  double staticMassScale(const BlockState& block) const;
  void assembleBlockTerms(double dt);
  int openCloseIterate(double dt, Eigen::VectorXd& solution, bool& settled);
  /// Friction of one sliding contact in one assembly: the force -f N s on block i (N) and
  /// the transverse tangent spring (stiffness N/m along the unit `across`, rigid parts).
  struct AppliedFriction {
    geometry::Vec3 force = geometry::Vec3::Zero();
    double transverse_stiffness = 0.0;
    geometry::Vec3 across = geometry::Vec3::Zero();
  };
  /// Adds c's springs or friction; returns the friction applied (zero unless sliding).
  AppliedFriction addContactTerms(const Contact& c);
  /// The time integration's acceleration at t = 0: M a0 = loads + initial stress + bolt
  /// pretension (contacts and fixed points carry no force yet).
  void initialAccelerations();
  /// Adds the step's friction work and numerical dissipation to the energy account.
  void accountDissipation(const Eigen::VectorXd& solution, double dt);
  /// Energy of the contact, fixed-point and bolt springs now (J).
  double springEnergy() const;
  /// Energy of the fixed-point and bolt springs now (J).
  double pointSpringEnergy() const;
  /// State changes of one open-close update.
  struct StateChanges {
    int changed = 0;   ///< contacts whose state changed
    int closed = 0;    ///< of them, contacts that were open
    int example = -1;  ///< one contact that changed (one that closed when any did), or -1
  };
  /// Largest pull (N) of a contact held closed for the rest of the step.
  double holdLimit(const Contact& c) const;
  /// Shear strength of a closed contact now (N): f N, plus c A while it keeps its cohesion.
  double shearStrength(const Contact& c, const DdaJoint& joint) const;
  /// Updates every contact's state from the iteration's solution.
  StateChanges updateContactStates(const Eigen::VectorXd& solution);
  /// Largest vertex displacement of `solution` over g2 l0; `fastest` (when given) gets the
  /// movable block it belongs to (-1 when none moved).
  /// `weighed`: the largest vertex displacement times its block's inertia scale (m).
  double maxDisplacementRatio(const Eigen::VectorXd& solution, int* fastest = nullptr,
                              double* weighed = nullptr) const;
  double maxPenetration() const;
  void updateBlocks(const Eigen::VectorXd& solution, double dt);
  BlockVector unknownsOf(const Eigen::VectorXd& solution, int block) const;
  int movableIndex(int block) const { return blocks_[static_cast<std::size_t>(block)].dof_offset; }
  const DdaJoint& jointOf(const Contact& c) const;
  /// The largest vertex displacement of the step `report` accounts for (m).
  double stepDisplacement(const StepReport& report) const;
  /// "block b (centroid ..., volume ...)" and a contact's description, for messages.
  std::string blockText(int b) const;
  std::string contactText(const Contact& c) const;
  /// Why step() cannot complete the step at `dt` (StepFailure).
  std::string stepFailureMessage(double dt, int attempts, bool settled, const StepReport& report,
                                 double allowed) const;
  /// u_i(P) - u_j(P') for the solution; with `rigid_part`, of the first 6 unknowns only.
  geometry::Vec3 relativeDisplacement(const Contact& c, const Eigen::VectorXd& solution,
                                      bool rigid_part = false) const;

  DdaModel model_;
  DdaSettings settings_;
  int dofs_ = 12;
  double half_domain_ = 1.0;
  double penalty_ = 0.0;
  double initial_penalty_ = 0.0;  ///< N/m, penalty_ at the start (caps its growth)
  double dt_ = 0.0;
  double time_ = 0.0;
  double work_of_loads_ = 0.0;
  std::vector<double> block_work_;  ///< work_of_loads_ by block (J), empty before a step
  double friction_work_ = 0.0;
  double numerical_dissipation_ = 0.0;
  double contact_changes_ = 0.0;
  double springs_after_step_ = 0.0;  ///< springEnergy() after the last accepted step
  NewmarkCoefficients scheme_;
  /// Friction on block i of each contact in the last assembly (aligned with contacts_).
  std::vector<AppliedFriction> applied_friction_;
  std::vector<BlockState> blocks_;
  std::vector<geometry::Vec3> initial_centroids_;
  std::vector<ElasticMatrix> elastic_;
  std::vector<MaterialPoint> monitor_points_, load_points_, fixed_points_;
  std::vector<MaterialPoint> bolt_a_, bolt_b_;
  std::vector<Contact> contacts_;
  std::vector<double> reach_;  // per block, m (contactReach())
  std::unique_ptr<BlockSystem> system_;
  std::unique_ptr<LinearSolver> solver_;
  std::vector<BlockMatrix> base_k_;  // block terms per movable block
  std::vector<BlockVector> base_f_;
  std::vector<BlockVector> load_f_;  // external loads per movable block (for the work)
  ActiveTerms active_;
  PhaseTimings timings_;
  int pattern_changes_ = 0;
  int solver_iterations_ = 0;  ///< PCG iterations of the current step
  StateChanges last_changes_;  ///< of the last open-close update (for StepFailure's message)
  int steps_at_min_ = 0;       ///< accepted steps in a row at min_time_step
  /// The last accepted step's solution and dt: scaled by dt / last_dt_, the first guess of
  /// an iterative solve (the dynamic predictor d ~ v dt).
  Eigen::VectorXd last_solution_;
  double last_dt_ = 0.0;
};

}  // namespace rockmass::dda3d
