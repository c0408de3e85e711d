// The stages of a rockmass run as functions, shared by the single-stage commands (`dfn`,
// `blocks`, `rqd`, `dda`) and by `run`, which chains them: each command is a thin wrapper
// around its stage, so `run` computes exactly what the commands compute.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "dda3d/simulation.h"
#include "geometry/fracture_network.h"
#include "io/atomic_file.h"
#include "io/block_output.h"
#include "io/dda_output.h"
#include "io/dda_summary.h"
#include "io/rqd_output.h"
#include "io/scene.h"
#include "io/summary.h"
#include "rqd/rqd_volume.h"
#include "scene_model/scene_blocks.h"

namespace rockmass::app {

// ---------------------------------------------------------------------------------------------
// DFN (dfn_command.cpp)

/// The fracture network of a scene and its per-set statistics.
struct DfnStage {
  geometry::FractureNetwork network;           ///< all discs, faults, interlayers
  std::vector<geometry::SetStatistics> stats;  ///< one per network set
  double seconds = 0.0;                        ///< generation and measurement time
};

/// Generates the scene's network (io::InputError naming `scene_path` for an impossible
/// distribution) and measures its sets.
DfnStage runDfnStage(const io::Scene& scene, const std::string& scene_path);

/// Writes fractures.fab, fractures.csv and fractures.vtu into `out`.
void writeDfnFiles(const std::filesystem::path& out, const io::Scene& scene,
                   const geometry::FractureNetwork& network);

// ---------------------------------------------------------------------------------------------
// Blocks (blocks_command.cpp; the cut itself is scene_model::cutSceneBlocks in scene_blocks.h)

/// What the blocks summary says about a cut made with `cutter`.
io::CutInfo cutInfoOf(const scene_model::SceneBlocks& cut, const std::string& cutter);

/// Writes blocks.csv, blocks.vtu and faces.vtu (the joint of every piece face, from the
/// discs of `network`) into `out`.
void writeBlocksFiles(const std::filesystem::path& out, const io::Scene& scene,
                      const blocks::BlockModel& model, const geometry::FractureNetwork& network);

// ---------------------------------------------------------------------------------------------
// RQD (rqd_command.cpp)

/// Command-line overrides of analysis.rqd (each one optional).
struct RqdOverrides {
  std::optional<int> directions;                  ///< directions of every ball
  std::optional<std::vector<double>> thresholds;  ///< thresholds (m)
  std::string form = "exact";                     ///< exact | triangulated
  int segments = 24;                              ///< fan segments per disc (triangulated)
  std::optional<double> radius;                   ///< surface radius of every ball (m)
  std::optional<double> merge_distance;           ///< m
  std::optional<double> grid_spacing;             ///< RQD/P32 volume cell size (m)
  std::optional<int> grid_directions;             ///< scanline axes per grid cell
  bool no_grid = false;                           ///< skip the volume even if the scene has one
  /// run --quick: read the boreholes against this (the full) domain, then cut them where
  /// they leave the scene's (quick) domain.
  std::optional<geometry::Box> hole_domain;
};

/// What the RQD stage will compute, read and checked before any work is done.
struct RqdPlan {
  io::RqdAnalysis settings;                     ///< analysis.rqd with the overrides applied
  std::optional<io::BoreholeReport> boreholes;  ///< holes and measured log, when given
  std::optional<rqd::VolumeSpec> grid;          ///< the RQD/P32 volume, when asked for
};

/// The scene's analysis.rqd with the overrides applied: io::InputError (naming
/// `scene_path` or the option) for a missing analysis.rqd, a bad value, a ball centre
/// outside the domain, a bad grid, unreadable borehole files or nothing to compute.
RqdPlan planRqd(const io::Scene& scene, const RqdOverrides& overrides,
                const std::string& scene_path);

/// What the RQD stage computed, with its sub-stage timings (rqd, calibration, grid).
struct RqdStage {
  io::RqdReport report;             ///< balls, boreholes, calibration, grid
  io::Timings timings;              ///< "rqd", then "calibration" and "grid" when they ran
  std::vector<std::string> stages;  ///< "rqd", then "calibration", "grid" when they ran
};

/// Balls, boreholes, calibration and the RQD/P32 volume of `plan` on the scene's
/// `network`.
RqdStage runRqdStage(const io::Scene& scene, const std::string& scene_path,
                     const geometry::FractureNetwork& network, RqdPlan plan,
                     const RqdOverrides& overrides);

/// Writes rqd_balls.csv, the ball PLY surfaces, boreholes.csv and rqd.vdb as they apply.
void writeRqdFiles(const std::filesystem::path& out, const io::RqdReport& report);

// ---------------------------------------------------------------------------------------------
// DDA (dda_command.cpp)

/// Command-line settings of the DDA stage.
struct DdaOverrides {
  std::string solver = "auto";    ///< auto | cholmod | eigen | pcg
  double pcg_tolerance = 1e-10;   ///< relative residual of the pcg solver
  int frame_every = 0;            ///< steps between VTU frames (0: about 50 frames per run)
  std::optional<int> debug_step;  ///< dump K, F and the contacts of this step (1-based)
  std::optional<int> steps;       ///< replaces analysis.dda.steps (run --quick)
};

/// What the DDA stage computed.
struct DdaStage {
  io::DdaRunSummary summary;               ///< model, steps, monitors
  std::vector<std::string> effects;        ///< active physics terms
  std::vector<std::string> monitor_names;  ///< in model order
  /// history.csv and steps.csv, written as the run went; writeDdaFiles commits them.
  std::shared_ptr<io::StreamedFile> history;
  std::shared_ptr<io::StreamedFile> steps_csv;
  /// bolts.csv (only when the scene has bolts), written as the run went.
  std::shared_ptr<io::StreamedFile> bolts_csv;
  std::vector<std::string> bolt_names;   ///< in model order
  std::vector<std::string> frame_files;  ///< dda.pvd's frames (dda_<step>.vtu)
};

/// A DDA ready to step: what runDdaStage runs.
struct DdaRun {
  std::unique_ptr<dda3d::Simulation> simulation;
  std::optional<io::DdaRunSummary::Settled> settled;  ///< analysis.dda.settle's static run
};

/// The DDA of analysis.dda (which must be present) on `blocks`: the model built from the scene
/// (loads, supports, monitors, the joints of the piece faces), the engine settings with
/// `overrides`, settled first when the scene asks (analysis.dda.settle).
DdaRun makeDdaRun(const io::Scene& scene, const blocks::BlockModel& blocks,
                  const geometry::FractureNetwork& network, const DdaOverrides& overrides);

/// Builds the DDA model of `blocks` (cut with the discs of `network`) from the scene (loads,
/// supports, monitors, the joints of the piece faces) and runs
/// analysis.dda (which must be present), writing dda.pvd and the frames into `out` as it
/// goes (and the debug dump when asked). `glued`: what scene_model::ddaBlocks glued, for the
/// summary.
DdaStage runDdaStage(const io::Scene& scene, const blocks::BlockModel& blocks,
                     const geometry::FractureNetwork& network, const DdaOverrides& overrides,
                     const std::filesystem::path& out,
                     const std::optional<blocks::MergeReport>& glued = std::nullopt);

/// Commits history.csv, steps.csv and (with bolts) bolts.csv, written as the run went.
void writeDdaFiles(const std::filesystem::path& out, const DdaStage& stage);

}  // namespace rockmass::app
