#include "dda3d/equilibrium.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "dda3d/contact_detection.h"
#include "geometry/orientation.h"

namespace rockmass::dda3d {

namespace {

/// The acceleration (m/s2) the unbalanced ratio is measured against: |g|, or standard
/// gravity when the model has none.
double referenceAcceleration(const DdaModel& model) {
  const double g = model.gravity.norm();
  return g > 0.0 ? g : 9.81;
}

/// Block `b` of `sim` as the block that moved most.
MovedBlock movedBlock(const Simulation& sim, int b) {
  const BlockState& block = sim.blocks()[static_cast<std::size_t>(b)];
  return {b, block.volume, block.centroid};
}

/// Two steps' motions go "the same way" when their directions are within this angle (deg).
constexpr double kSameWayDegrees = 8.0;
/// The drift rule's net displacement over the path of a window (EquilibriumSettings::
/// drift_steps): 0.9 lets a sliding block rock (its step directions up to 56 degrees apart at
/// times, as the Xiangjiaba dam's in stick-slip) while a block going back and forth stays well
/// below it.
constexpr double kDriftStraightness = 0.9;

/// Block `b`'s last step displacement as the steady-motion rule compares it: translation
/// and rotation times the block's size (m).
SteadyMotion::Motion stepMotion(const Simulation& sim, int b) {
  const BlockState& block = sim.blocks()[static_cast<std::size_t>(b)];
  SteadyMotion::Motion d = block.last_displacement.head<6>();
  d.tail<3>() *= std::cbrt(block.volume);
  return d;
}

}  // namespace

bool SteadyMotion::add(int block, double ratio, const Motion& motion) {
  if (steps_ <= 0) return false;
  const double norm = motion.norm();
  const Motion direction = norm > 0.0 ? Motion(motion / norm) : Motion::Zero();
  const double same_way = std::cos(geometry::radians(kSameWayDegrees));
  if (!window_.empty() &&
      (block != window_.back().block || direction.dot(window_.back().direction) < same_way)) {
    window_.clear();
  }
  window_.push_back({block, ratio, direction});
  if (static_cast<int>(window_.size()) > steps_) window_.pop_front();
  if (static_cast<int>(window_.size()) < steps_) return false;
  double low = window_.front().ratio, high = low;
  for (const Step& s : window_) {
    low = std::min(low, s.ratio);
    high = std::max(high, s.ratio);
  }
  return high > 0.0 && high - low <= spread_ * high;
}

DriftingMotion::DriftingMotion(std::size_t blocks, int steps, double calm_ratio)
    : steps_(steps), calm_ratio_(calm_ratio), windows_(blocks) {
  // The window's halves need two steps each to show a trend.
  if (steps_ > 0 && steps_ < 4) {
    throw std::invalid_argument("the drift rule needs 0 (off) or at least 4 steps");
  }
}

bool DriftingMotion::add(std::size_t k, double ratio, const Motion& motion) {
  if (steps_ <= 0 || k >= windows_.size()) return false;
  std::deque<Step>& window = windows_[k];
  window.push_back({ratio, motion});
  if (static_cast<int>(window.size()) > steps_) window.pop_front();
  if (static_cast<int>(window.size()) < steps_) return false;
  Motion sum = Motion::Zero();
  double path = 0.0, ratios = 0.0;
  for (const Step& s : window) {
    sum += s.motion;
    path += s.motion.norm();
    ratios += s.ratio;
  }
  const double net = sum.norm();
  if (!(path > 0.0) || net < kDriftStraightness * path) return false;
  if (ratios / static_cast<double>(steps_) < calm_ratio_) return false;
  // The mean step along the net displacement, in the window's first and second half.
  const Motion way = sum / net;
  const std::size_t half = window.size() / 2;
  double first = 0.0, second = 0.0;
  for (std::size_t i = 0; i < window.size(); ++i) {
    (i < half ? first : second) += window[i].motion.dot(way);
  }
  return second / static_cast<double>(window.size() - half) >= first / static_cast<double>(half);
}

std::vector<int> monitoredMovableBlocks(const DdaModel& model) {
  std::vector<int> blocks;
  for (const DdaMonitor& monitor : model.monitors) {
    const auto b = static_cast<std::size_t>(monitor.block);
    if (b < model.blocks.size() && !model.blocks[b].fixed) blocks.push_back(monitor.block);
  }
  std::sort(blocks.begin(), blocks.end());
  blocks.erase(std::unique(blocks.begin(), blocks.end()), blocks.end());
  return blocks;
}

std::vector<int> watchedBlocks(const Simulation& sim, EquilibriumWatch watch) {
  std::vector<int> watched;
  if (watch == EquilibriumWatch::All) {
    for (std::size_t b = 0; b < sim.blocks().size(); ++b) {
      if (!sim.blocks()[b].fixed) watched.push_back(static_cast<int>(b));
    }
    return watched;
  }
  watched = monitoredMovableBlocks(sim.model());
  if (watched.empty()) {
    throw std::invalid_argument(
        "the equilibrium watches the monitored blocks, but no monitor is in a movable block");
  }
  return watched;
}

EquilibriumResult runToEquilibrium(Simulation& sim, const EquilibriumSettings& settings,
                                   const EquilibriumStepCallback& after_step) {
  EquilibriumResult result;
  const double g = referenceAcceleration(sim.model());
  const bool every_block = settings.watch == EquilibriumWatch::All;
  const std::vector<int> watched =
      every_block ? std::vector<int>{} : watchedBlocks(sim, settings.watch);
  // Calm steps in a row that each searched their contacts: the run is at rest only after
  // settle_steps of them, so that rest is judged as with a search every step, never on
  // entries kept from an older search (DdaSettings::detection.search_margin;
  // docs/stability.md, "Equilibrium criterion"). A search after many kept steps changes more
  // entries at once than one a step; judged from it alone, runs at a ratio of 2e-5 never
  // came to rest (each such search broke the calm steps it started).
  int calm_searched = 0;
  int pushed = 0;
  const bool can_fail = sim.settings().mode == AnalysisMode::Static &&
                        settings.failure_ratio > 0.0 && settings.failure_steps > 0;
  const bool can_steady = sim.settings().mode == AnalysisMode::Static && settings.steady_steps > 0;
  SteadyMotion steady(settings.steady_steps, settings.steady_spread);
  // The drift rule tracks every watched block (every movable one when all are watched).
  const bool can_drift = sim.settings().mode == AnalysisMode::Static && settings.drift_steps > 0;
  const std::vector<int> tracked =
      !can_drift ? std::vector<int>{}
                 : (every_block ? watchedBlocks(sim, EquilibriumWatch::All) : watched);
  DriftingMotion drift(tracked.size(), settings.drift_steps, settings.unbalanced_ratio);
  while (result.steps < settings.max_steps) {
    StepReport report;
    try {
      report = sim.step();
    } catch (const StepFailure& e) {
      // A step that cannot be completed at the smallest time step: the model is not at rest
      // and cannot be followed further (some block is flung or crushed).
      result.failing = true;
      result.stalled = e.what();
      break;
    }
    ++result.steps;
    result.min_time_step =
        result.steps == 1 ? report.time_step : std::min(result.min_time_step, report.time_step);
    result.redone_open_close += report.redo_iterations;
    result.redone_displacement += report.redo_displacement;
    result.redone_penetration += report.redo_penetration;
    result.contact_searches += report.contacts_searched;
    result.partial_contact_searches += report.contacts_searched_partly;
    const double free_fall = 0.5 * g * report.time_step * report.time_step;
    // The step's displacement of each block, at its vertices (the blocks have moved; the field
    // is affine, so its largest value is at a vertex), times its inertia scale: a block whose
    // static inertia term was scaled down moves farther for the same out-of-balance force, and
    // the ratio measures that force against the weight (docs/stability.md, "Static runs of
    // massive blocks").
    const auto weighedMotion = [&](int b) {
      const BlockState& block = sim.blocks()[static_cast<std::size_t>(b)];
      return largestVertexDisplacement(block, block.last_displacement) * sim.inertiaScale(b);
    };
    const double all_increment = report.unbalanced_displacement;
    result.all_blocks_ratio = all_increment / free_fall;
    result.increment = all_increment;
    if (!every_block) {
      result.increment = 0.0;
      result.watched = {};
      for (const int b : watched) {
        const double moved = weighedMotion(b);
        if (moved > result.increment) {
          result.increment = moved;
          result.watched = movedBlock(sim, b);
        }
      }
    }
    result.unbalanced_ratio = result.increment / free_fall;
    result.fastest =
        report.fastest_block >= 0 ? movedBlock(sim, report.fastest_block) : MovedBlock{};
    const EnergyAccount energy = sim.energy();
    const double work = std::abs(energy.work_of_loads);
    double kinetic = energy.kinetic;
    double of_loads = work;
    if (!every_block) {
      // The watched blocks' kinetic energy over the work done on them: over the work done on
      // every block, a loose block falling elsewhere would dilute the ratio.
      kinetic = 0.0;
      double watched_work = 0.0;
      for (const int b : watched) {
        const BlockState& block = sim.blocks()[static_cast<std::size_t>(b)];
        kinetic += 0.5 * block.velocity.dot(massMatrix(block) * block.velocity);
        watched_work += sim.workOfLoadsOn(static_cast<std::size_t>(b));
      }
      of_loads = std::abs(watched_work);
    }
    result.kinetic_ratio = kinetic > 0.0 ? kinetic / std::max(of_loads, 1e-300) : 0.0;
    const bool still = result.unbalanced_ratio <= settings.unbalanced_ratio &&
                       result.kinetic_ratio <= settings.kinetic_ratio;
    calm_searched = still && report.contacts_searched ? calm_searched + 1 : 0;
    if (after_step) after_step(result);
    if (calm_searched >= settings.settle_steps) {
      result.reached = true;
      break;
    }
    // Calm: the next step searches its contacts, so that the calm steps that decide do.
    if (still) sim.requestContactSearch();
    pushed = can_fail && result.unbalanced_ratio >= settings.failure_ratio ? pushed + 1 : 0;
    if (pushed >= settings.failure_steps) {
      result.failing = true;
      break;
    }
    const int mover = every_block ? report.fastest_block : result.watched.block;
    if (still || mover < 0) {
      steady.clear();
    } else if (can_steady && steady.add(mover, result.unbalanced_ratio, stepMotion(sim, mover))) {
      result.failing = true;
      result.steady = true;
      break;
    }
    if (still) {
      drift.clear();
    } else if (can_drift) {
      bool drifting = false;
      for (std::size_t k = 0; k < tracked.size(); ++k) {
        // Every window takes its step (no early exit), so that each holds the same steps. The
        // motions over g dt^2 / 2, as the ratios: a step cut or grown back within the window
        // does not read as the block slowing down or speeding up.
        const int b = tracked[k];
        drifting =
            drift.add(k, weighedMotion(b) / free_fall, stepMotion(sim, b) / free_fall) || drifting;
      }
      if (drifting) {
        result.failing = true;
        result.drifting = true;
        break;
      }
    }
  }
  result.time = sim.time();
  return result;
}

}  // namespace rockmass::dda3d
