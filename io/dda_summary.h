#pragma once
/// summary.json of the `dda` stage: the run header (with the active effects), the model
/// (blocks, unknowns, kinematics, solver), per-step statistics (contacts by state,
/// open-close iterations, redone steps, time step) and the final monitor displacements;
/// per-phase times go under "timings" with the other stage timings.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "blocks/block_merge.h"
#include "geometry/vec.h"
#include "io/summary.h"

namespace rockmass::io {

/// What one accepted DDA step did.
struct DdaStepRecord {
  int step = 0;                   ///< 1-based accepted step
  double time = 0.0;              ///< simulated time at the end of the step (s)
  double time_step = 0.0;         ///< Δt used (s)
  int contacts = 0;               ///< contact entries (all states)
  int open = 0;                   ///< open contacts after the last iteration
  int sliding = 0;                ///< sliding contacts
  int locked = 0;                 ///< locked contacts
  int open_close_iterations = 0;  ///< solves of the accepted attempt
  int retries = 0;                ///< attempts redone (smaller Δt or larger penalty)
  double max_displacement = 0.0;  ///< largest vertex displacement of the step (m)
  double max_penetration = 0.0;   ///< deepest penetration after the step (m, >= 0)
  /// Wall-clock seconds per phase (detect, assemble, solve, update, ...), in phase order.
  /// Goes to "timings", the only part of summary.json that differs between identical runs.
  std::vector<std::pair<std::string, double>> phase_seconds;
};

/// A monitor's final reading.
struct DdaMonitorResult {
  std::string name;                                      ///< monitor name
  int block = 0;                                         ///< block id it is attached to
  geometry::Vec3 displacement = geometry::Vec3::Zero();  ///< since time 0 (m)
};

/// What the dda stage reports.
struct DdaRunSummary {
  int blocks = 0;          ///< block count
  int fixed_blocks = 0;    ///< blocks held by supports.fixed
  int pieces = 0;          ///< convex pieces
  int unknowns = 0;        ///< 6 or 12 per block
  bool dynamic = true;     ///< dynamic | static
  bool deformable = true;  ///< deformable | rigid
  std::string solver;      ///< backend name, e.g. "cholmod"
  /// Time integration scheme: "bossak" (with spectral_radius) or "shi".
  std::string time_integration = "bossak";
  double spectral_radius = 0.0;  ///< Bossak's rho_inf in [0, 1] (unused for "shi")
  int steps_requested = 0;       ///< analysis.dda.steps
  double time_step = 0.0;        ///< largest allowed Δt (s)
  double duration = 0.0;         ///< simulated time reached (s)
  double penalty = 0.0;          ///< contact normal penalty at the end (N/m)
  std::vector<DdaMonitorResult> monitors;
  std::vector<DdaStepRecord> steps;
  /// The small blocks glued before the run (analysis.dda.min_block_volume > 0).
  std::optional<blocks::MergeReport> glued;
};

/// summary.json of a dda run: keys command, ..., effects, blocks, fixed_blocks, pieces,
/// unknowns, glued_blocks{...} (when blocks were glued, gluedBlocksJson), mode, kinematics, solver,
/// time_integration{scheme, spectral_radius (bossak only)}, steps_requested, steps_taken,
/// time_step, duration, penalty, monitors[], steps{time, time_step, contacts, open, sliding,
/// locked, iterations, retries, max_displacement, max_penetration} (one array entry per step), then
/// timings (run.timings plus dda_phases: totals per phase, and dda_steps: per phase, one entry per
/// step).
std::string formatDdaSummary(const RunInfo& run, const DdaRunSummary& dda);

}  // namespace rockmass::io
