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
  geometry::Vec3 point = geometry::Vec3::Zero();         ///< where it was at time 0 (m)
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
  /// The uplift on each structure (empty when no water acts in an interface).
  std::vector<StructureUplift> uplift;
  /// Each bolt at the end of the run (empty without bolts).
  std::vector<BoltSample> bolts;
  /// The step records summary.json holds: every `step_stride`-th step (and the last); all of
  /// them when the stride is 1. steps.csv has every step.
  std::vector<DdaStepRecord> steps;
  int step_stride = 1;
  int steps_taken = -1;  ///< accepted steps (-1: steps.size())
  /// Contacts first found deeper than the allowed penetration over the run (a miss of the
  /// detection; their depth is not pushed back: dda3d::Contact::overlap).
  int late_contacts = 0;
  int contact_searches = 0;  ///< steps that searched their contacts (the others kept theirs)
  /// Steps that searched only the pairs of the blocks that moved beyond the search margin.
  int partial_contact_searches = 0;
  /// Seconds per phase over every step (empty: summed from `steps`).
  std::vector<std::pair<std::string, double>> phase_totals;
  /// The small blocks glued before the run (analysis.dda.min_block_volume > 0).
  std::optional<blocks::MergeReport> glued;
  /// analysis.dda.settle: how the static run that settled the model before the run ended.
  struct Settled {
    int steps = 0;                     ///< static steps taken
    bool at_rest = false;              ///< came to rest within max_steps
    double unbalanced_ratio = 0.0;     ///< of its last step
    std::vector<std::string> without;  ///< the loads left out while settling
  };
  std::optional<Settled> settled;
  /// The last damage map's counts (analysis.dda.damage_map): contacts that have been closed,
  /// by damage class (intact, bond_broken, sliding, opened), and the largest opening and slip.
  struct Damage {
    int maps = 0;
    int intact = 0, bond_broken = 0, sliding = 0, opened = 0;
    double max_opening = 0.0;  ///< m
    double max_slip = 0.0;     ///< m
  };
  std::optional<Damage> damage;
  /// Deformable runs: the blocks whose single strain field is too coarse at the end (an
  /// interface's e / h above 1/3, dda3d::interfaceEccentricity), by block id.
  struct CoarseStrain {
    int block = 0;              ///< block id
    double volume = 0.0;        ///< m3
    double eccentricity = 0.0;  ///< e / h of its most eccentric interface
  };
  std::vector<CoarseStrain> coarse_strain;
};

/// summary.json keeps at most this many step records (keepStepRecord).
inline constexpr std::size_t kSummaryStepRecords = 100'000;

/// Keeps `record` (the next step) in `steps` when its step is a multiple of `stride`; once
/// more than `limit` records are kept, the stride doubles and the records off it are dropped,
/// so that a long run's summary stays small and spans the whole run (steps.csv has every
/// step).
void keepStepRecord(std::vector<DdaStepRecord>& steps, int& stride, DdaStepRecord record,
                    std::size_t limit = kSummaryStepRecords);

/// steps.csv's header line (with its newline): `step,time,time_step,contacts,open,sliding,
/// locked,iterations,retries,max_displacement,max_penetration`, one row per accepted step
/// (no wall-clock times, so that the file is the same on every run).
std::string stepsCsvHeader();
/// One steps.csv row, with its newline.
std::string formatStepsRow(const DdaStepRecord& record);

/// summary.json of a dda run: keys command, ..., effects, blocks, fixed_blocks, pieces,
/// unknowns, glued_blocks{...} (when blocks were glued, gluedBlocksJson), mode, kinematics, solver,
/// time_integration{scheme, spectral_radius (bossak only)}, steps_requested, steps_taken,
/// time_step, duration, penalty, monitors[], steps_stride, steps{step, time, time_step,
/// contacts, open, sliding, locked, iterations, retries, max_displacement, max_penetration} (one
/// array entry per kept step: every step_stride-th and the last), then
/// timings (run.timings plus dda_phases: totals per phase, and dda_steps: per phase, one entry per
/// step).
std::string formatDdaSummary(const RunInfo& run, const DdaRunSummary& dda);

}  // namespace rockmass::io
