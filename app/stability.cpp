#include "app/stability.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "geometry/progress.h"
#include "io/atomic_file.h"
#include "io/input_error.h"
#include "io/stability_output.h"
#include "scene_model/dda_model.h"
#include "scene_model/scene_blocks.h"
#include "scene_model/stability_settings.h"

namespace rockmass::app {

namespace {

/// "; <what> N, V m3 at (x, y, z)", or "" when no block moved.
std::string movedText(const char* what, const dda3d::MovedBlock& moved) {
  if (moved.block < 0) return "";
  char text[160];
  std::snprintf(text, sizeof text, "; %s %d, %.3g m3 at (%.1f, %.1f, %.1f)", what, moved.block,
                moved.volume, moved.centroid.x(), moved.centroid.y(), moved.centroid.z());
  return text;
}

/// The runs a search will most likely make: its sweep (or, stopping at the first factor not
/// at rest, all of it at worst), then the bisections that narrow the widest gap of the sweep
/// to the tolerance.
double expectedRuns(const dda3d::FactorSearch& search) {
  double widest = 0.0;
  for (std::size_t i = 1; i < search.factors.size(); ++i) {
    widest = std::max(widest, search.factors[i] - search.factors[i - 1]);
  }
  const double bisections = search.tolerance > 0.0 && widest > search.tolerance
                                ? std::ceil(std::log2(widest / search.tolerance))
                                : 0.0;
  return std::max(1.0, static_cast<double>(search.factors.size()) + bisections);
}

/// Prints one line per run: "<label>: factor K  at rest|not at rest after N steps", then the
/// search's progress after its first 10 s (runs done of those expected, elapsed time, an
/// estimate of what is left).
dda3d::FactorRunCallback progress(const char* label, const dda3d::FactorSearch& search) {
  auto runs = std::make_shared<Progress>(label, expectedRuns(search), "expected factor runs", 0.0);
  runs->setSafePoint(false);   // each run's DDA steps are the safe points
  runs->setQuietPeriod(10.0);  // a quick search says nothing more than its runs
  auto done = std::make_shared<int>(0);
  return [label, runs, done](const dda3d::FactorRun& run) {
    const dda3d::EquilibriumResult& e = run.equilibrium;
    const std::string fastest =
        movedText("fastest block", e.fastest) + movedText("fastest watched block", e.watched);
    std::fprintf(stderr,
                 "%s: factor %.4g%s  %s after %d steps (unbalanced ratio %.3g, all blocks "
                 "%.3g; dt down to %.3g s, %d attempts redone, contacts searched in %d "
                 "steps (%d more in part)%s)\n",
                 label, run.factor, run.bisection ? " (bisection)" : "",
                 e.reached            ? "at rest"
                 : !e.stalled.empty() ? "NOT at rest (failing: cannot progress)"
                 : e.steady           ? "NOT at rest (failing: moving steadily)"
                 : e.drifting         ? "NOT at rest (failing: drifting)"
                 : e.failing          ? "NOT at rest (failing: stopped early)"
                                      : "NOT at rest",
                 e.steps, e.unbalanced_ratio, e.all_blocks_ratio, e.min_time_step,
                 e.redone_open_close + e.redone_displacement + e.redone_penetration,
                 e.contact_searches, e.partial_contact_searches, fastest.c_str());
    runs->update(++*done);
  };
}

/// "K = 2.41" or the reason there is none.
std::string describe(const dda3d::FactorSearchResult& r) {
  if (r.critical) return std::to_string(*r.critical);
  if (!r.last_stable) return "none: not at rest at the first factor";
  return "none: at rest up to the last factor " + std::to_string(*r.last_stable);
}

}  // namespace

dda3d::FactorSearchResult runSceneOverload(const io::Scene& scene, const StabilityStart& start) {
  dda3d::FactorSearch search = scene_model::overloadSearch(scene);
  search.start_contacts = start.contacts;
  return dda3d::runOverload(start.model, start.settings,
                            scene_model::loadScaling(*scene.analysis.overload), search,
                            progress("overload", search));
}

dda3d::FactorSearchResult runSceneStrengthReduction(const io::Scene& scene,
                                                    const StabilityStart& start) {
  dda3d::FactorSearch search = scene_model::strengthReductionSearch(scene);
  search.start_contacts = start.contacts;
  return dda3d::runStrengthReduction(start.model, start.settings, search,
                                     progress("strength", search));
}

void checkWatchedMonitors(const io::Scene& scene, const dda3d::DdaModel& model) {
  if (!scene.analysis.equilibrium || !scene.analysis.equilibrium->watch_monitors) return;
  if (!dda3d::monitoredMovableBlocks(model).empty()) return;
  throw io::InputError(io::locate(
      scene.file, scene.analysis.equilibrium->watch_line, 0,
      "analysis.equilibrium.watch: monitors, but every monitor lies in a held block (a "
      "support), so no block would decide equilibrium; move a monitor into a free block or "
      "use watch: all"));
}

StabilityStart stabilityStart(const io::Scene& scene, const dda3d::DdaModel& model) {
  checkWatchedMonitors(scene, model);
  const dda3d::DdaSettings settings = scene_model::equilibriumDdaSettings(scene);
  if (!scene.analysis.equilibrium || !scene.analysis.equilibrium->settled_start) {
    return {model, settings, {}, std::nullopt};
  }
  dda3d::Simulation sim(model, settings);
  dda3d::EquilibriumSettings rest = scene_model::equilibriumSettings(scene);
  rest.max_steps = scene.analysis.equilibrium->start_steps.value_or(rest.max_steps);
  // The start settles for all its steps: it decides no factor, and a foundation that is slow
  // to settle (the deformable variant's blocks slow down, then speed up again for a while)
  // would otherwise hand every factor a less settled state (docs/stability.md, "Early stop
  // of a drifting run").
  rest.drift_steps = 0;
  const dda3d::EquilibriumResult settled = dda3d::runToEquilibrium(sim, rest);
  std::fprintf(stderr,
               "stability: start state %s after %d steps (unbalanced ratio %.3g); every factor "
               "runs from it\n",
               settled.reached ? "at rest" : "NOT at rest", settled.steps,
               settled.unbalanced_ratio);
  return {dda3d::settledModel(sim), settings, sim.contacts(), settled};
}

std::vector<std::string> monitorNames(const dda3d::DdaModel& model) {
  std::vector<std::string> names;
  for (const dda3d::DdaMonitor& m : model.monitors) names.push_back(m.name);
  return names;
}

io::StabilitySummary stabilitySummary(const io::Scene& scene, const dda3d::DdaModel& model,
                                      const std::optional<blocks::MergeReport>& glued,
                                      const dda3d::FactorSearchResult* overload,
                                      const dda3d::FactorSearchResult* strength_reduction) {
  io::StabilitySummary summary;
  summary.blocks = static_cast<int>(model.blocks.size());
  for (const dda3d::DdaBlock& b : model.blocks) summary.fixed_blocks += b.fixed;
  summary.pressures = static_cast<int>(model.pressures.size());
  summary.equilibrium = scene_model::equilibriumSettings(scene);
  summary.overload = overload;
  if (overload) {
    summary.overload_scales = scene.analysis.overload->scales;
    summary.scale_uplift = scene.analysis.overload->scale_uplift;
  }
  summary.strength_reduction = strength_reduction;
  summary.glued = glued;
  summary.uplift = scene_model::structureUplift(scene, model);
  return summary;
}

void addRunTerms(const dda3d::FactorSearchResult& result, dda3d::ActiveTerms& terms) {
  for (const dda3d::FactorRun& r : result.runs) terms |= r.terms;
}

int runStabilityCommand(const StabilityOptions& options, StabilityAnalysis analysis) {
  const bool overload = analysis == StabilityAnalysis::Overload;
  const io::Scene scene = loadScene(options.common);
  // Every input check before any work: the settings throw for a missing analysis section.
  const dda3d::FactorSearch search =
      overload ? scene_model::overloadSearch(scene) : scene_model::strengthReductionSearch(scene);
  scene_model::equilibriumDdaSettings(scene);
  const std::string cutter = scene_model::chooseCutter(scene, options.cutter, options.common.scene);
  const std::filesystem::path out = prepareOutput(options.common.output);
  io::RunInfo run;
  run.command = overload ? "overload" : "strength";
  run.scene = options.common.scene;
  run.name = scene.name;
  run.seed = scene.seed;
  run.stages = {"dfn", "cut", overload ? "overload" : "strength_reduction"};

  auto start = Clock::now();
  const geometry::FractureNetwork network = generateNetwork(scene, options.common.scene);
  run.timings.emplace_back("dfn", secondsSince(start));
  // The network covers the whole domain; the DDA cuts it in its region when it has one.
  const io::Scene dda_scene = scene_model::ddaScene(scene);
  start = Clock::now();
  const scene_model::SceneBlocks cut =
      scene_model::cutSceneBlocks(dda_scene, network, cutter, options.common.scene);
  run.timings.emplace_back("cut", secondsSince(start));
  std::optional<blocks::MergeReport> glued;
  start = Clock::now();
  const StabilityStart begin = stabilityStart(
      dda_scene, scene_model::buildDdaModel(
                     dda_scene, scene_model::ddaBlocks(dda_scene, cut.model, glued), network));
  const dda3d::DdaModel& model = begin.model;
  if (begin.settling) run.timings.emplace_back("stability_start", secondsSince(start));
  std::fprintf(stderr, "%s: %zu blocks, %zu wet faces, %zu factors to sweep\n", run.command.c_str(),
               model.blocks.size(), model.pressures.size(), search.factors.size());

  start = Clock::now();
  const dda3d::FactorSearchResult result =
      overload ? runSceneOverload(dda_scene, begin) : runSceneStrengthReduction(dda_scene, begin);
  run.timings.emplace_back(overload ? "overload" : "strength_reduction", secondsSince(start));

  start = Clock::now();
  const io::StabilitySummary summary = stabilitySummary(
      dda_scene, model, glued, overload ? &result : nullptr, overload ? nullptr : &result);
  if (overload) {
    io::writeFileAtomically(out / "overload.csv",
                            io::formatOverloadCsv(monitorNames(model), result));
  }
  dda3d::ActiveTerms terms;
  addRunTerms(result, terms);
  run.effects = terms.names();
  run.timings.emplace_back("write", secondsSince(start));
  io::writeFileAtomically(out / "summary.json", io::formatStabilitySummary(run, summary));
  std::fprintf(stderr, "%s: %s = %s; wrote %s\n", run.command.c_str(),
               overload ? "K_s" : "critical SRF", describe(result).c_str(), out.string().c_str());
  return 0;
}

}  // namespace rockmass::app
