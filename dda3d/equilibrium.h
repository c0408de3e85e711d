// Running a DDA model until it is at rest: the equilibrium criterion of the overload and
// strength-reduction analyses (docs/stability.md).
#pragma once

#include <deque>
#include <functional>
#include <string>

#include "dda3d/simulation.h"

namespace rockmass::dda3d {

/// Which blocks the criterion judges.
enum class EquilibriumWatch {
  All,       ///< every movable block
  Monitors,  ///< the movable blocks that carry a monitor (DdaModel::monitors)
};

/// When a run counts as being at rest. A step is calm when its unbalanced ratio is at most
/// `unbalanced_ratio` and its kinetic energy ratio at most `kinetic_ratio` (a step that fails
/// the step control's checks throws StepFailure); equilibrium is `settle_steps` calm steps in
/// a row, each of which searched its contacts (runToEquilibrium makes the step after a calm
/// one search; DdaSettings::detection.search_margin).
struct EquilibriumSettings {
  int max_steps = 1000;  ///< step limit; a run that is not at rest by then is not in equilibrium
  /// Largest vertex displacement of a step d divided by 1/2 g dt^2, the distance a free body
  /// falls from rest in that step (g = |gravity|, 9.81 m/s2 when the model has none). In a
  /// static run (velocities reset every step) this is the unbalanced acceleration over g;
  /// in a dynamic one it adds 2 v / (g dt). -.
  double unbalanced_ratio = 1e-3;
  /// Kinetic energy over the work done by the loads so far (both J). -.
  double kinetic_ratio = 1e-6;
  int settle_steps = 5;  ///< calm steps in a row that make equilibrium
  /// Static runs only: a run whose unbalanced ratio is at least `failure_ratio` in
  /// `failure_steps` steps in a row is not at rest, and stops there (some block is then
  /// pushed by an unbalanced force at least this many times its weight, step after step).
  /// 0 turns the early stop off.
  double failure_ratio = 1.0;
  int failure_steps = 10;  ///< steps in a row of the early stop
  /// Static runs only: a run whose watched motion is steady for `steady_steps` steps in a row
  /// is not at rest, and stops there: every step not calm, its fastest watched block the
  /// same block, moving the same way (the directions of its step displacements, translation
  /// and rotation times the block's size, within 8 degrees of the step before), and the
  /// unbalanced ratios within `steady_spread` of the window's largest. A block sliding on a
  /// joint at its strength keeps a constant out-of-balance force and moves the same distance
  /// every static step; a run that is coming to rest does not (its ratio falls or wanders).
  /// 0 turns the rule off.
  int steady_steps = 10;
  double steady_spread = 0.01;  ///< (largest - smallest) / largest ratio of the window (-)
  /// Static runs only: a run in which some watched block drifts for `drift_steps` steps in a
  /// row is not at rest, and stops there: every step not calm, and over the window the
  /// block's step displacements (translation and rotation times the block's size, over
  /// g dt^2 / 2) add up to
  /// at least 0.9 of their path (it keeps one way), those of the window's second half carry
  /// it along that way at least as far a step as those of its first half (it does not slow
  /// down), and its unbalanced ratio averages at least `unbalanced_ratio` (it moves faster
  /// than rest allows). A block that slides in stick-slip, its speed and direction wobbling
  /// from step to step, escapes the steady-motion rule but not this one; a run that is
  /// coming to rest slows down, or goes back and forth. 0 turns the rule off (at least 4).
  int drift_steps = 0;
  /// The blocks whose unbalanced ratio, kinetic energy and failure decide the run. With
  /// Monitors, a block elsewhere that keeps moving (a loose block under a free face) does not
  /// keep the run from being at rest, nor stop it early; it is still reported
  /// (EquilibriumResult::all_blocks_ratio and fastest).
  EquilibriumWatch watch = EquilibriumWatch::All;
};

/// A block that moved most in a step: its index (-1: none), volume (m3) and centroid (m).
struct MovedBlock {
  int block = -1;
  double volume = 0.0;
  geometry::Vec3 centroid = geometry::Vec3::Zero();
};

/// How a run to equilibrium ended.
struct EquilibriumResult {
  bool reached = false;           ///< at rest within the step limit
  int steps = 0;                  ///< accepted steps taken
  double time = 0.0;              ///< simulated time at the end (s)
  double unbalanced_ratio = 0.0;  ///< of the last step, over the watched blocks (-)
  double kinetic_ratio = 0.0;     ///< at the end, of the watched blocks (-)
  double increment = 0.0;  ///< largest vertex displacement of the last step, watched blocks (m)
  /// The unbalanced ratio of the last step over every block (equal to unbalanced_ratio when
  /// every block is watched).
  double all_blocks_ratio = 0.0;
  /// The step control over the run: the smallest accepted time step (s; the scene's step when
  /// none was cut) and the attempts redone, by reason (StepReport::redo_*). A block that
  /// moves too far or sinks too deep anywhere cuts dt for the whole model.
  double min_time_step = 0.0;
  int redone_open_close = 0;
  int redone_displacement = 0;
  int redone_penetration = 0;
  /// Steps that searched their contacts (the others kept the last step's entries,
  /// DdaSettings::detection.search_margin).
  int contact_searches = 0;
  /// Steps that searched only the pairs of the blocks that moved beyond the search margin
  /// (not counted in contact_searches: their other entries were kept).
  int partial_contact_searches = 0;
  /// Stopped early (not at rest): by the failure rule (failure_ratio), the steady-motion rule
  /// (`steady`) or a step that cannot progress (`stalled`).
  bool failing = false;
  /// Stopped early by the steady-motion rule (EquilibriumSettings::steady_steps); failing too.
  bool steady = false;
  /// Stopped early by the drift rule (EquilibriumSettings::drift_steps); failing too.
  bool drifting = false;
  /// Why the run could not go on (StepFailure's message), empty when it could: such a run is
  /// failing and not at rest (a step that fails its checks at the smallest time step).
  std::string stalled;
  /// The block that moved most in the last step, of all blocks: where all_blocks_ratio
  /// comes from.
  MovedBlock fastest;
  /// With EquilibriumWatch::Monitors, the watched block that moved most in the last step,
  /// where unbalanced_ratio comes from (none when nothing moved, or every block is watched).
  MovedBlock watched;
};

/// The blocks of `model` that carry a monitor and are not held, in increasing order (what
/// EquilibriumWatch::Monitors watches).
std::vector<int> monitoredMovableBlocks(const DdaModel& model);

/// The movable blocks `watch` selects in `sim`'s model, in increasing order. Throws
/// std::invalid_argument when Monitors selects none (no monitor, or all in held blocks).
std::vector<int> watchedBlocks(const Simulation& sim, EquilibriumWatch watch);

/// The steady-motion rule's window (EquilibriumSettings::steady_steps, steady_spread): the last
/// `steps` steps that were not calm, each with its fastest watched block, its unbalanced ratio
/// and its step displacement (translation and rotation times the block's size, m).
class SteadyMotion {
 public:
  using Motion = Eigen::Matrix<double, 6, 1>;
  SteadyMotion(int steps, double spread) : steps_(steps), spread_(spread) {}
  /// Adds a step; true when the window is full and steady: one block, each step's motion
  /// within 8 degrees of the step's before, the ratios within `spread` of the largest.
  bool add(int block, double ratio, const Motion& motion);
  void clear() { window_.clear(); }

 private:
  struct Step {
    int block;
    double ratio;
    Motion direction;  ///< unit vector (zero: no motion)
  };
  int steps_;
  double spread_;
  std::deque<Step> window_;
};

/// The drift rule's windows (EquilibriumSettings::drift_steps): for each tracked block, its
/// last `steps` step displacements (translation and rotation times the block's size, over
/// g dt^2 / 2 as the ratios, so that a change of dt is not a change of pace) and unbalanced
/// ratios; clear() at every calm step.
class DriftingMotion {
 public:
  using Motion = SteadyMotion::Motion;
  /// `blocks` windows of `steps` steps (0: off; else at least 4, std::invalid_argument);
  /// `calm_ratio` is the rest rule's unbalanced ratio.
  DriftingMotion(std::size_t blocks, int steps, double calm_ratio);
  /// Adds a step of the block in window `k`; true when its window is full and it drifts: the
  /// displacements add up to at least 0.9 of their path, the second half's mean step along
  /// their sum at least the first half's, the mean ratio at least `calm_ratio`.
  bool add(std::size_t k, double ratio, const Motion& motion);
  void clear() {
    for (std::deque<Step>& window : windows_) window.clear();
  }

 private:
  struct Step {
    double ratio;
    Motion motion;
  };
  int steps_;
  double calm_ratio_;
  std::vector<std::deque<Step>> windows_;
};

/// Called after each step with the result so far (progress output).
using EquilibriumStepCallback = std::function<void(const EquilibriumResult&)>;

/// Steps `sim` until it is at rest (EquilibriumSettings) or the step limit is reached.
EquilibriumResult runToEquilibrium(Simulation& sim, const EquilibriumSettings& settings,
                                   const EquilibriumStepCallback& after_step = {});

}  // namespace rockmass::dda3d
