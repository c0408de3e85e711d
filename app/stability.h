// The stability analyses of a scene (docs/stability.md), shared by `rockmass overload`,
// `rockmass strength` and the whole-run pipeline: the overload method and strength
// reduction on the scene's DDA model, with progress on stderr, and the command that cuts the
// scene, runs one of them and writes its files.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/command.h"
#include "dda3d/model.h"
#include "dda3d/stability.h"
#include "io/scene.h"
#include "io/stability_output.h"

namespace rockmass::app {

/// What the overload and strength-reduction runs start from.
struct StabilityStart {
  dda3d::DdaModel model;  ///< the model of factor 1
  /// The engine settings of every run (scene_model::equilibriumDdaSettings: analysis.dda with the
  /// equilibrium's dynamic ratio).
  dda3d::DdaSettings settings;
  std::vector<dda3d::Contact> contacts;  ///< contacts to start from (empty: none)
  /// The run that settled the model (start: settled); none for an unloaded start.
  std::optional<dda3d::EquilibriumResult> settling;
};

/// `model` itself, or with analysis.equilibrium.start: settled, `model` run to rest as it is
/// (up to max_steps, at rest or not) and taken from there with its contacts
/// (dda3d::settledModel). Prints one line on stderr.
StabilityStart stabilityStart(const io::Scene& scene, const dda3d::DdaModel& model);

/// With analysis.equilibrium.watch: monitors, throws io::InputError (at the line of `watch`)
/// unless some monitor lies in a free block. stabilityStart calls it; `run` calls it before
/// the DDA stage, so that the error comes before minutes of work.
void checkWatchedMonitors(const io::Scene& scene, const dda3d::DdaModel& model);

/// The overload method of analysis.overload from `start` (scene_model::buildDdaModel of the scene's
/// blocks): K_s and the K-displacement runs. Settings from analysis.dda, .equilibrium and
/// .overload (io/stability_settings.h). Throws io::InputError naming the missing key when
/// the scene lacks analysis.dda or analysis.overload.
dda3d::FactorSearchResult runSceneOverload(const io::Scene& scene, const StabilityStart& start);

/// Strength reduction of analysis.strength_reduction from `start`: the critical SRF. Throws
/// io::InputError naming the missing key when the scene lacks analysis.dda or
/// analysis.strength_reduction.
dda3d::FactorSearchResult runSceneStrengthReduction(const io::Scene& scene,
                                                    const StabilityStart& start);

/// Names of the model's monitors, in order (the columns of overload.csv).
std::vector<std::string> monitorNames(const dda3d::DdaModel& model);

/// The stability summary of `model` (block, fixed-block and wet-face counts, the
/// equilibrium criterion of the scene) with the results that ran (null: did not run); the
/// summary points into them, so they must outlive it.
io::StabilitySummary stabilitySummary(const io::Scene& scene, const dda3d::DdaModel& model,
                                      const std::optional<blocks::MergeReport>& glued,
                                      const dda3d::FactorSearchResult* overload,
                                      const dda3d::FactorSearchResult* strength_reduction);

/// The effects (active engine terms) of every run of `result`, merged into `terms`.
void addRunTerms(const dda3d::FactorSearchResult& result, dda3d::ActiveTerms& terms);

/// Which analysis a stability command runs.
enum class StabilityAnalysis { Overload, StrengthReduction };

/// Options of `rockmass overload` / `rockmass strength` beyond the common ones.
struct StabilityOptions {
  CommonOptions common;
  std::string cutter;  ///< "", "exact" or "fast" ("": the scene's choice)
};

/// `rockmass overload|strength`: cuts the scene as `rockmass dda` does, runs the analysis and
/// writes summary.json (and overload.csv for the overload method). Returns the exit code.
int runStabilityCommand(const StabilityOptions& options, StabilityAnalysis analysis);

}  // namespace rockmass::app
