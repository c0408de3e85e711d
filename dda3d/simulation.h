// The 3D DDA engine: one Simulation advances a DdaModel step by step (Shi's method in 3D,
// formulation in docs dda3d-formulation.md). Each step runs the phases of StepPhase in order:
// detectContacts (contact_detection.cpp, contact_persistence.cpp), assembleBlockTerms,
// openCloseIterate (assembleSystem, factorize, solveSystem, updateContactStates in
// contact_states.cpp), checkStep (redo with a smaller dt or a stiffer penalty; messages in
// step_messages.cpp), acceptStep (updateBlocks: exact rotation, stresses, velocities, contact
// shear; the energy account in energy_account.cpp). Each phase's time is in
// StepReport::profile.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "dda3d/block_state.h"
#include "dda3d/block_system.h"
#include "dda3d/block_terms.h"
#include "dda3d/contact.h"
#include "dda3d/contact_detection.h"
#include "dda3d/energy_account.h"
#include "dda3d/linear_solver.h"
#include "dda3d/model.h"
#include "dda3d/simulation_settings.h"
#include "dda3d/step_report.h"

namespace rockmass::dda3d {

/// A DDA run.
/// The state of one bolt (DdaBolt) after the last accepted step.
struct BoltState {
  double free_length = 0.0;  ///< m: the force is stiffness * (length - free_length), >= 0 pulls
  double force = 0.0;        ///< axial force now (N, > 0 tension)
  bool yielded = false;      ///< reached its yield force (the free length grew)
  bool broken = false;       ///< reached its rupture force: carries nothing from then on
  double broken_at = -1.0;   ///< time of the rupture (s), -1 when intact
};

class PreviousContacts;

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
  std::vector<geometry::Vec3> pointLoadPositions() const { return positionsOf(load_points_); }
  /// Where each fixed point's material point is now (m), in model().fixed_points order.
  std::vector<geometry::Vec3> fixedPointPositions() const { return positionsOf(fixed_points_); }
  /// Displacement of block b's centroid since time 0 (m).
  geometry::Vec3 centroidDisplacement(int b) const;
  /// How far each block's vertices could move in the last step (m, 0 for fixed blocks):
  /// the contact search distance of a pair is the sum of its two blocks' reaches (stepReach).
  const std::vector<double>& contactReach() const { return reach_; }
  /// Where each bolt's two points are now (m), in model().bolts order.
  std::vector<std::pair<geometry::Vec3, geometry::Vec3>> boltPositions() const {
    std::vector<std::pair<geometry::Vec3, geometry::Vec3>> out;
    for (std::size_t k = 0; k < bolt_a_.size(); ++k) {
      out.emplace_back(bolt_a_[k].current, bolt_b_[k].current);
    }
    return out;
  }
  /// The bolts (model().bolts order) after the last accepted step.
  const std::vector<BoltState>& bolts() const { return bolt_state_; }
  /// Contacts of the last accepted step, with states.
  const std::vector<Contact>& contacts() const { return contacts_; }
  /// The joint a contact acts with: its own (Contact::joint), else the model's default.
  const DdaJoint& jointOf(const Contact& c) const;
  /// Starts from `contacts` (another run's, of a model with the same blocks and pieces): the
  /// next step's detection carries their states, shear springs and forces over to the entries
  /// it finds again, as between two steps of one run. Call before the first step.
  void adoptContacts(std::vector<Contact> contacts) {
    contacts_ = std::move(contacts);
    moved_since_search_.clear();  // not this run's search: the next step searches
    assembly_listed_ = static_cast<std::size_t>(-1);
  }
  /// Starts from rest: zero velocities and accelerations (a0). For a model brought to rest
  /// before (settledModel) and run dynamically: its a0 from the loads alone (gravity, the
  /// deformable blocks' initial stress) would ignore the contact forces that hold it, and the
  /// first step would fling every block (1.8 m/s at dt = 10 ms on the Xiangjiaba foundation).
  /// Call before the first step.
  void startAtRest() {
    for (BlockState& block : blocks_) {
      block.velocity.setZero();
      block.acceleration.setZero();
    }
  }
  /// Changes the loads from the next step on (a loading path scripted step by step, e.g. from
  /// Python): gravity (m/s^2, with any seismic coefficient kept apart), and the force of point
  /// load k (N, model().point_loads order; std::out_of_range for another k).
  void setGravity(const geometry::Vec3& gravity) { model_.gravity = gravity; }
  void setPointLoadForce(std::size_t k, const geometry::Vec3& force) {
    model_.point_loads.at(k).force = force;
  }
  /// How many times the broad phase ran (its pairs are kept between steps, CandidatePairs).
  int broadPhaseRuns() const { return candidates_.builds(); }
  /// How many steps searched their contacts (the others kept the last ones,
  /// DdaSettings::detection.search_margin).
  int contactSearches() const { return searches_; }
  /// Steps that searched only the pairs of the blocks that moved beyond the margin, keeping
  /// the other entries (not counted in contactSearches()).
  int partialSearches() const { return partial_searches_; }
  /// The next step searches its contacts whatever the blocks' motion (runToEquilibrium's
  /// calm steps that decide rest each search theirs).
  void requestContactSearch() { search_requested_ = true; }
  /// How far (m) every block may move after a contact search before a step searches again
  /// (DdaSettings::detection.search_margin times g2 l0).
  double keptEntriesMargin() const;
  ContactCounts contactCounts() const;
  std::vector<MonitorState> monitors() const;
  /// Sub-matrices assembled so far.
  const ActiveTerms& activeTerms() const { return active_; }
  /// Seconds per phase, summed over the run's steps.
  const StepProfile& timings() const { return timings_; }
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
  /// The current positions of `points`, in order.
  static std::vector<geometry::Vec3> positionsOf(const std::vector<MaterialPoint>& points) {
    std::vector<geometry::Vec3> out;
    out.reserve(points.size());
    for (const MaterialPoint& p : points) out.push_back(p.current);
    return out;
  }

  /// Finds the step's contacts, carrying states over; returns how many were found late
  /// (first seen deeper than the allowed penetration, Contact::overlap).
  int detectContacts();
  /// The blocks whose pairs this step must search to keep the other entries
  /// (DdaSettings::detection.search_margin), a flag per block: moved farther than
  /// keptEntriesMargin() since their last search, or reaching farther than then. Empty when
  /// no entry may be kept (no margin, no search yet in this run, a search requested).
  std::vector<char> blocksToSearch() const;
  /// `entries` moved to the blocks' geometry, their states carried on, and the reach of the
  /// blocks `searched` does not flag cut by their motion since their search; false (nothing
  /// else changed) when one is deeper than `depth` (m; the step searches instead). With
  /// `creep`, each entry is also started from its creep (startFromCreep) in the same pass;
  /// with `start`, its step's start is saved there too (saveStepStart), `start` resized.
  bool keepEntries(std::vector<Contact>& entries, const std::vector<char>& searched, double depth,
                   bool creep = false, std::vector<ContactStepState>* start = nullptr);
  /// Contacts that crept in the last step start this one stuck (an elastic predictor).
  void startFromCreep();
  /// startFromCreep of one contact.
  void startFromCreep(Contact& c) const;
  /// Searches the pairs of the blocks `only` flags and keeps (refreshed) the entries between
  /// the others; false (nothing changed) when a kept entry is deeper than `depth`. `late`:
  /// the entries first seen deeper than the allowed penetration.
  bool searchPartly(const std::vector<char>& only, double depth, int& late);
  /// The entries found by a search (of the pairs of the blocks `only` flags; all without it),
  /// each carrying its state over from its entry in `before` (the last step's) or started,
  /// with its joint. `late`: those first seen deeper than the allowed penetration.
  std::vector<Contact> searchContacts(const std::vector<Contact>& before,
                                      const std::vector<char>* only, double depth, int& late);
  /// Makes `contacts` the step's: the coupled pairs' pattern, the assembly's split, the
  /// creeping contacts' start.
  void useContacts(std::vector<Contact> contacts);
  /// Static mode: the factor on a block's mass matrix in its inertia term (kStaticInertiaRatio,
  /// at the run's time step).
  double staticMassScale(const BlockState& block) const;
  /// The mass matrix of a block's inertia term: M, or in static mode M scaled by
  /// staticMassScale with a deformable block's strain inertia held to its stiffness.
  BlockMatrix inertiaMatrix(const BlockState& block) const;
  /// The blocks' own terms and loads (base_k_, base_f_, load_f_). With `defer_water`, the
  /// water on the blocks' faces (some 10 000 clipped faces on the Xiangjiaba region) is left
  /// for addWaterLoads, which the first factorization of the attempt runs beside it
  /// (openCloseIterate); not with pores in the blocks, whose pressure needs it at once.
  void assembleBlockTerms(double dt, bool defer_water = false);
  /// The water on the blocks' faces (model_.pressures) of the current geometry into water_f_
  /// and load_f_ (blockWaterLoads).
  void addWaterLoads();
  /// The water loads of model_.pressures summed per block (indexed like base_f_; fixed blocks
  /// take none): each face in parallel, added to its block in the list's order. With
  /// `wetted`, the area each entry wets; `any` is set when some movable block is loaded.
  std::vector<BlockVector> blockWaterLoads(std::vector<double>* wetted, bool& any) const;
  /// Adds the pore pressure the deformable rock blocks carry (DdaSettings::biot_coefficient)
  /// to their loads, given the area each pressure entry wets (assembleBlockTerms); true when
  /// some block carries one.
  bool addBlockPorePressure(const std::vector<double>& wetted_area);
  /// After an accepted step (before the blocks move), one pass over the contacts: marks the
  /// closed ones as having been closed and adds the slip of the sliding ones
  /// (Contact::was_closed, slipped), carries the locked ones' shear by the step's relative
  /// motion (others: none), and keeps each spring's energy at the start of the step in its
  /// end state (springs_start_, for accountDissipation) and after the step (springs_after_),
  /// each contact's friction work in the step (friction_terms_, for accountDissipation), and
  /// counts the contacts in their end states (finished_counts_, the step's report).
  void finishContacts(const Eigen::VectorXd& solution);
  /// finishContacts of contact k; `friction`: it has a friction term (k is below the last
  /// assembly's count).
  void finishContact(std::size_t k, const std::vector<BlockVector>& unknowns, bool solved,
                     bool friction);
  /// The contacts counted by state, in parallel; `each` (when given) is called on each
  /// contact first, in the same pass.
  ContactCounts countContacts(const std::function<void(std::size_t)>* each) const;
  /// A contact's terms of springEnergy() (its normal spring when closed, its shear spring
  /// when locked), summed in contact order by sumSprings.
  struct SpringEnergyTerms {
    double normal = 0.0;
    double shear = 0.0;
    bool closed = false;
    bool apart = false;  ///< the normal spring's gap is positive (it pulls)
    bool locked = false;
  };
  /// The springs of a contact in `state` with normal gap `gap` and shear displacement
  /// `shear`: 1/2 k_n gap^2 when closed, 1/2 k_s |shear|^2 when locked (k_s = k_n over
  /// DdaSettings::shear_penalty_ratio).
  SpringEnergyTerms springTerms(ContactState state, double gap, const geometry::Vec3& shear) const;
  /// `terms`' energy added to `stored` in contact order; with `pulling`, the normal springs
  /// that are apart are added there instead.
  static void sumSprings(const std::vector<SpringEnergyTerms>& terms, double& stored,
                         double* pulling = nullptr);
  std::vector<SpringEnergyTerms> springs_after_;
  /// The springs at the start of the step in the states it ended with (accountDissipation's
  /// terms: gap0 and the shear before the step's motion), from finishContacts' pass.
  std::vector<SpringEnergyTerms> springs_start_;
  /// A contact's friction work in the step (accountDissipation): f N s . (u_i - u_j) and, with
  /// a transverse tangent spring, k x^2; `counts` says which apply (kFrictionWork,
  /// kTransverseWork), so that the sum takes the contacts' terms in contact order.
  struct FrictionTerms {
    double work = 0.0;
    double transverse = 0.0;
    std::uint8_t counts = 0;
  };
  static constexpr std::uint8_t kFrictionWork = 1, kTransverseWork = 2;
  /// finishContacts' friction terms of the contacts that had a friction in the last assembly.
  std::vector<FrictionTerms> friction_terms_;
  /// The contacts counted by state in finishContacts' pass (their states at the step's end).
  ContactCounts finished_counts_;
  /// The system of one open-close iteration: the block terms, every contact's springs or
  /// friction, the bolts.
  void assembleSystem();
  void addBoltTerms();
  /// After an accepted step: each bolt's force; a bolt yields (its free length grows so that
  /// it carries its yield force) or breaks (from then on it carries nothing).
  void updateBolts();
  /// Solves the assembled system; the guess of an iterative solver is `previous` (later
  /// iterations) or the last step's solution scaled to dt (the first).
  Eigen::VectorXd solveSystem(double dt, int iteration, const Eigen::VectorXd& previous);
  int openCloseIterate(double dt, Eigen::VectorXd& solution, bool& settled);
  /// What the step control does with an attempt's solution.
  enum class StepCheck { Accept, Redo };
  /// The step control (docs/dda3d.md, "Step control"): redo with a smaller dt (the
  /// iteration did not settle, a vertex moved too far) or a stiffer penalty (too deep), or
  /// accept; throws StepFailure when nothing is left to try.
  StepCheck checkStep(const Eigen::VectorXd& solution, bool settled, bool last_chance, double& dt,
                      StepReport& report);
  /// Moves the blocks by the accepted solution and chooses the next dt.
  void acceptStep(const Eigen::VectorXd& solution, double dt, StepReport& report);
  /// Friction of one sliding contact in one assembly: the force -f N s on block i (N) and
  /// the transverse tangent spring (stiffness N/m along the unit `across`, rigid parts).
  struct AppliedFriction {
    geometry::Vec3 force = geometry::Vec3::Zero();
    double transverse_stiffness = 0.0;
    geometry::Vec3 across = geometry::Vec3::Zero();
  };
  /// A contact's terms in the step's system, as one point's springs (BlockSystem's
  /// addPointSprings): S and s on all of its blocks' unknowns (the normal spring and, while
  /// locked, the two shear springs; while sliding, the friction force as a load in s), and
  /// S_rigid on their rigid-body unknowns only (a sliding contact's transverse tangent; in S
  /// for rigid blocks, whose unknowns are all rigid-body ones).
  struct ContactSprings {
    Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
    geometry::Vec3 offsets = geometry::Vec3::Zero();
    Eigen::Matrix3d s_rigid = Eigen::Matrix3d::Zero();
    AppliedFriction applied;
  };
  /// c's springs (ContactSprings), marking the terms they add in `active`; false when it adds
  /// none (open).
  bool contactSprings(const Contact& c, ContactSprings& springs, ActiveTerms& active) const;
  /// Adds the terms of c's springs or friction that `parts` names (BlockSystem::Parts),
  /// marking those it adds in `active`; returns the friction applied (zero unless sliding).
  /// Rigid blocks' contacts between two blocks are added by runs instead (assembleSystem).
  AppliedFriction addContactTerms(const Contact& c, const BlockSystem::Parts& parts,
                                  ActiveTerms& active);
  /// Splits the movable blocks among the assembly's threads (assembly_owner_): slabs along x
  /// of about equal numbers of contacts, from the current contacts; then lists each
  /// thread's contacts (listAssembly).
  void splitAssembly();
  /// Each assembly thread's contacts, in contact order, with the terms it adds of each.
  void listAssembly();
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
    int changed = 0;  ///< contacts whose state changed
    int closed = 0;   ///< of them, contacts that were open
    /// Of those, the contacts that closed deeper than a static step may leave them
    /// (kStaticClosingShare of the allowed penetration; all of them in a dynamic run).
    int closed_deep = 0;
    /// The deepest penetration after the update (m, -gap; 0 when none penetrates).
    double deepest = 0.0;
    int example = -1;  ///< one contact that changed (one that closed when any did), or -1
    /// Sliding contacts that kept their state but whose strength f N (+ c A) with this
    /// solution's N differs from the one the solve used by more than friction_tolerance, on a
    /// block whose friction changed by more than that share of its contacts' strength.
    int friction_changed = 0;
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
  /// `reach_ratio`: the largest ratio of a movable block's first-order vertex displacement
  /// (largestVertexDisplacement) to its reach, from the same pass over the vertices.
  double maxDisplacementRatio(const Eigen::VectorXd& solution, int* fastest = nullptr,
                              double* weighed = nullptr, double* reach_ratio = nullptr) const;
  double maxPenetration() const;
  void updateBlocks(const Eigen::VectorXd& solution, double dt);
  BlockVector unknownsOf(const Eigen::VectorXd& solution, int block) const;
  /// unknownsOf of every block (zero for fixed ones), for passes over the contacts.
  std::vector<BlockVector> blockUnknowns(const Eigen::VectorXd& solution) const;
  int movableIndex(int block) const { return blocks_[static_cast<std::size_t>(block)].dof_offset; }
  /// The largest vertex displacement of the step `report` accounts for (m).
  double stepDisplacement(const StepReport& report) const;
  /// "block b (centroid ..., volume ...)" and a contact's description, for messages.
  std::string blockText(int b) const;
  std::string contactText(const Contact& c) const;
  /// Why step() cannot complete the step at `dt` (StepFailure).
  /// The message of a step whose matrix is not positive definite at `dt`.
  std::string singularMatrixMessage(double dt) const;
  /// The message of a run that spent max_steps_at_min_time_step steps at min_time_step.
  std::string stalledMessage(const StepReport& report) const;
  std::string stepFailureMessage(double dt, int attempts, bool settled, const StepReport& report,
                                 double allowed) const;
  /// u_i(P) - u_j(P') for the solution; with `rigid_part`, of the first 6 unknowns only.
  geometry::Vec3 relativeDisplacement(const Contact& c, const Eigen::VectorXd& solution,
                                      bool rigid_part = false) const;
  /// The same with every block's unknowns taken from `unknowns` (unknownsOf of each block).
  geometry::Vec3 relativeDisplacement(const Contact& c, const std::vector<BlockVector>& unknowns,
                                      bool rigid_part = false) const;
  /// The same with block i's unknowns `di` and block j's `dj`.
  geometry::Vec3 relativeDisplacement(const Contact& c, BlockVector di, BlockVector dj,
                                      bool rigid_part) const;

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
  /// The assembly thread that adds each movable block's terms and those of the pairs whose
  /// lower block it is (splitAssembly), and how many threads there are.
  std::vector<int> assembly_owner_;
  int assembly_parts_ = 1;
  /// A contact an assembly thread visits and what it adds of it (kAdds* bits).
  struct AssemblyEntry {
    std::uint32_t contact = 0;
    std::uint8_t adds = 0;
    bool transposed = false;  ///< the pair's block stores K_ji
    int pair = -1;            ///< BlockSystem::pairSlot of the contact's blocks
  };
  /// Each thread's entries in contact order (listAssembly), for contacts_ of
  /// assembly_listed_ entries (npos: to be listed).
  std::vector<std::vector<AssemblyEntry>> assembly_lists_;
  std::size_t assembly_listed_ = static_cast<std::size_t>(-1);
  int assembly_pairs_version_ = -1;  ///< BlockSystem::pairsVersion of the lists' pair slots
  /// Per block, largestVertexDisplacement of its last accepted step on its moved geometry
  /// (acceptStep), for the next step's reach; empty before the first step.
  std::vector<double> last_largest_;
  std::vector<BlockState> blocks_;
  std::vector<geometry::Vec3> initial_centroids_;
  std::vector<ElasticMatrix> elastic_;
  std::vector<MaterialPoint> monitor_points_, load_points_, fixed_points_;
  std::vector<MaterialPoint> bolt_a_, bolt_b_;
  std::vector<BoltState> bolt_state_;
  std::vector<Contact> contacts_;  ///< by pairs of blocks, found order within (useContacts)
  /// The contacts as a step found them, for a redone attempt; its buffer is kept between
  /// steps (a fresh copy of the region's 214 000 entries, 56 MB, faulted its pages in anew
  /// every step: 0.04 s, more than the solve).
  std::vector<ContactStepState> step_start_;
  std::vector<double> reach_;  // per block, m (contactReach())
  /// The broad phase's pairs, kept between steps while the blocks move less than a margin.
  CandidatePairs candidates_;
  /// Contact entries kept between steps (blocksToSearch()): each block's reach in this run's
  /// last search and how far it moved since (m); both empty before the run's first search.
  bool search_requested_ = false;  ///< requestContactSearch()
  std::vector<double> searched_reach_, moved_since_search_;
  int searches_ = 0;
  int partial_searches_ = 0;  ///< searchPartly's searches
  std::unique_ptr<BlockSystem> system_;
  std::unique_ptr<LinearSolver> solver_;
  std::vector<BlockMatrix> base_k_;  // block terms per movable block
  std::vector<BlockVector> base_f_;
  std::vector<BlockVector> load_f_;  // external loads per movable block (for the work)
  /// The attempt's water loads per movable block when assembleBlockTerms deferred them (not
  /// in base_f_): Pending until addWaterLoads computes them, then Ready (assembleSystem adds
  /// them to F); None when they are in base_f_.
  enum class DeferredWater { None, Pending, Ready };
  DeferredWater water_ = DeferredWater::None;
  std::vector<BlockVector> water_f_;
  /// The step's start of the contacts (step_start_) is still to be saved: the first
  /// factorization of the step saves it beside it (a detection that keeps every entry saves
  /// it in its carry-over pass and clears this).
  bool step_start_pending_ = false;
  ActiveTerms active_;
  StepProfile timings_;       ///< summed over the steps
  StepProfile step_profile_;  ///< of the step being run
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
