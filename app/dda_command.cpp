// rockmass dda: cut the scene into blocks exactly as `rockmass blocks` does, run the 3D DDA
// of analysis.dda on them, and write history.csv, dda.pvd + frames and summary.json.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "app/command.h"
#include "app/stages.h"
#include "dda3d/simulation.h"
#include "dda3d/stability.h"
#include "dda3d/strain_check.h"
#include "geometry/progress.h"
#include "io/atomic_file.h"
#include "io/block_output.h"
#include "io/damage_output.h"
#include "io/dda_output.h"
#include "io/dda_summary.h"
#include "io/input_error.h"
#include "scene_model/dda_model.h"
#include "scene_model/scene_blocks.h"
#include "scene_model/stability_settings.h"

namespace rockmass::app {

namespace fs = std::filesystem;

namespace {

/// Options of `rockmass dda` beyond the common ones.
struct DdaOptions {
  CommonOptions common;
  std::string cutter;      ///< "", "exact" or "fast" ("": the scene's choice)
  DdaOverrides overrides;  ///< solver, frames, debug dump
};

/// Engine settings from analysis.dda and the command line.
dda3d::DdaSettings settingsOf(const io::DdaAnalysis& dda, const DdaOverrides& options) {
  dda3d::DdaSettings settings = scene_model::ddaSettings(dda);
  settings.solver.kind = options.solver == "pcg"       ? dda3d::SolverKind::Pcg
                         : options.solver == "eigen"   ? dda3d::SolverKind::Eigen
                         : options.solver == "cholmod" ? dda3d::SolverKind::Cholmod
                                                       : dda3d::SolverKind::Auto;
  settings.solver.tolerance = options.pcg_tolerance;
  return settings;
}

/// A contact's state as the output files name it.
io::ContactState outputState(dda3d::ContactState state) {
  return state == dda3d::ContactState::Open      ? io::ContactState::Open
         : state == dda3d::ContactState::Sliding ? io::ContactState::Sliding
                                                 : io::ContactState::Locked;
}

/// The index (in the scene's joints) of the joint a contact acts with.
int jointIndex(const dda3d::Simulation& sim, const dda3d::Contact& c) {
  return c.joint >= 0 ? c.joint : sim.model().default_joint;
}

/// The frame of the simulation's current state.
io::DdaFrame frameOf(const dda3d::Simulation& sim, const blocks::BlockModel& blocks, int step) {
  io::DdaFrame frame;
  frame.step = step;
  frame.time = sim.time();
  frame.static_mode = sim.settings().mode == dda3d::AnalysisMode::Static;
  frame.deformable = sim.settings().kinematics == dda3d::Kinematics::Deformable;
  const std::vector<double> eccentricity = dda3d::interfaceEccentricity(sim);
  for (std::size_t b = 0; b < sim.blocks().size(); ++b) {
    const dda3d::BlockState& state = sim.blocks()[b];
    io::DdaBlockState out;
    out.id = blocks.blocks[b].id;
    out.material = state.material;
    out.pieces = state.pieces;
    out.displacement = sim.centroidDisplacement(static_cast<int>(b));
    out.velocity = state.velocity.head<3>();  // T(centroid) picks the translation rates
    for (int k = 0; k < 6; ++k) out.stress[static_cast<std::size_t>(k)] = state.stress[k];
    out.eccentricity = eccentricity[b];
    frame.blocks.push_back(std::move(out));
  }
  return frame;
}

/// The damage map of the simulation's current state: every contact that is closed or has
/// been closed.
io::DamageMap damageMapOf(const dda3d::Simulation& sim, const blocks::BlockModel& blocks,
                          int step) {
  io::DamageMap map;
  map.step = step;
  map.time = sim.time();
  for (const dda3d::Contact& c : sim.contacts()) {
    if (c.state == dda3d::ContactState::Open && !c.was_closed) continue;
    const dda3d::DdaJoint& joint = sim.jointOf(c);
    io::DamagePoint p;
    p.point = c.point;
    p.normal = c.normal;
    p.block_i = blocks.blocks[static_cast<std::size_t>(c.block_i)].id;
    p.block_j = blocks.blocks[static_cast<std::size_t>(c.block_j)].id;
    p.joint = jointIndex(sim, c);
    p.state = outputState(c.state);
    p.bond_broken = !c.bonded && (joint.cohesion > 0.0 || joint.tensile_strength > 0.0);
    p.damage = io::damageOf(p.state, c.was_closed, p.bond_broken);
    p.opening = p.damage == io::ContactDamage::Opened ? std::max(0.0, c.gap) : 0.0;
    p.slip = c.slipped;
    p.normal_force = c.state == dda3d::ContactState::Open ? 0.0 : c.normal_force;
    map.contacts.push_back(p);
  }
  return map;
}

/// The summary's counts of a damage map.
io::DdaRunSummary::Damage damageCounts(const io::DamageMap& map, int maps) {
  io::DdaRunSummary::Damage d;
  d.maps = maps;
  for (const io::DamagePoint& p : map.contacts) {
    d.intact += p.damage == io::ContactDamage::Intact;
    d.bond_broken += p.damage == io::ContactDamage::BondBroken;
    d.sliding += p.damage == io::ContactDamage::Sliding;
    d.opened += p.damage == io::ContactDamage::Opened;
    d.max_opening = std::max(d.max_opening, p.opening);
    d.max_slip = std::max(d.max_slip, p.slip);
  }
  return d;
}

/// Adds one step's seconds per phase to the run's totals (phases in first-seen order).
void addPhaseSeconds(std::vector<std::pair<std::string, double>>& totals,
                     const std::vector<std::pair<std::string, double>>& step) {
  for (const auto& [name, seconds] : step) {
    const auto at =
        std::find_if(totals.begin(), totals.end(), [&](const auto& p) { return p.first == name; });
    if (at == totals.end()) {
      totals.emplace_back(name, seconds);
    } else {
      at->second += seconds;
    }
  }
}

/// The progress line's detail of one step.
std::string stepDetail(int step, const dda3d::StepReport& report) {
  char detail[200];
  std::snprintf(detail, sizeof detail,
                "step %d, dt = %.3g s, contacts %d (%d open), iterations %d, redone: %d "
                "open-close, %d displacement, %d penetration",
                step, report.time_step, report.contacts.total, report.contacts.open,
                report.iterations, report.redo_iterations, report.redo_displacement,
                report.redo_penetration);
  return detail;
}

/// The summary's description of the run: mode, kinematics, solver, scheme, time, penalty, the
/// monitors at the end.
void describeRun(const dda3d::Simulation& sim, const io::DdaAnalysis& dda,
                 const blocks::BlockModel& blocks, io::DdaRunSummary& summary) {
  summary.dynamic = dda.engine.mode == dda3d::AnalysisMode::Dynamic;
  summary.deformable = dda.engine.kinematics == dda3d::Kinematics::Deformable;
  summary.solver = sim.solverName();
  const bool bossak = sim.settings().integration == dda3d::TimeIntegration::Bossak;
  summary.time_integration = bossak ? "bossak" : "shi";
  summary.spectral_radius = sim.settings().spectral_radius;
  summary.time_step = dda.engine.time_step;
  summary.duration = sim.time();
  summary.penalty = sim.penalty();
  for (const dda3d::MonitorState& m : sim.monitors()) {
    const std::size_t k = summary.monitors.size();
    summary.monitors.push_back(
        {m.name, blocks.blocks[static_cast<std::size_t>(sim.model().monitors[k].block)].id,
         m.displacement, m.position - m.displacement});
  }
}

/// analysis.dda.settle: `model` brought to rest in static mode under its loads less those the
/// scene names, then given every load of `model` back (in place). Returns how the settling
/// ended and the contacts the run starts from.
std::pair<io::DdaRunSummary::Settled, std::vector<dda3d::Contact>> settleFirst(
    const io::DdaAnalysis& dda, dda3d::DdaModel& model, const dda3d::DdaSettings& settings) {
  const io::DdaAnalysis::Settle& settle = *dda.settle;
  dda3d::LoadScaling without;
  without.water = without.uplift = settle.without_water;
  without.seismic = settle.without_seismic;
  without.point_loads = settle.without_point_loads;
  dda3d::DdaSettings quiet = settings;
  quiet.mode = dda3d::AnalysisMode::Static;
  dda3d::Simulation sim(dda3d::scaledLoads(model, without, 0.0), quiet);
  dda3d::EquilibriumSettings rest;
  rest.max_steps = settle.max_steps;
  // Progress at least every 30 s: a foundation of 10^3 blocks settles in minutes.
  Progress progress("dda: settling", settle.max_steps, "static steps");
  progress.setQuietPeriod(10.0);
  const dda3d::EquilibriumResult result =
      dda3d::runToEquilibrium(sim, rest, [&](const dda3d::EquilibriumResult& r) {
        char detail[80];
        std::snprintf(detail, sizeof detail, "unbalanced ratio %.3g", r.unbalanced_ratio);
        progress.update(r.steps, detail);
      });
  io::DdaRunSummary::Settled out{result.steps, result.reached, result.unbalanced_ratio, {}};
  if (settle.without_water) out.without.push_back("water");
  if (settle.without_seismic) out.without.push_back("seismic");
  if (settle.without_point_loads) out.without.push_back("point_loads");
  std::fprintf(stderr, "dda: settled first %s after %d static steps (unbalanced ratio %.3g)\n",
               result.reached ? "at rest" : "NOT at rest", result.steps, result.unbalanced_ratio);
  dda3d::DdaModel settled = dda3d::settledModel(sim);
  // Every load back, acting on the settled geometry (the pressures and point loads name
  // their faces and points, which the settled model keeps).
  settled.gravity = model.gravity;
  settled.seismic = model.seismic;
  settled.pressures = model.pressures;
  settled.hydrodynamic = model.hydrodynamic;
  for (std::size_t k = 0; k < settled.point_loads.size(); ++k) {
    settled.point_loads[k].force = model.point_loads[k].force;
  }
  model = std::move(settled);
  // The damage map tells what the run did: contacts open at its start have not opened in it,
  // and slip counts from the settled state, as the displacements do.
  std::vector<dda3d::Contact> contacts = sim.contacts();
  for (dda3d::Contact& c : contacts) {
    c.was_closed = c.state != dda3d::ContactState::Open;
    c.slipped = 0.0;
  }
  return {out, std::move(contacts)};
}

/// Deformable runs: the movable blocks whose interfaces bend them more than one strain field
/// shows (dda3d::kMiddleThird), said on stderr.
std::vector<io::DdaRunSummary::CoarseStrain> coarseStrainBlocks(const dda3d::Simulation& sim,
                                                                const blocks::BlockModel& blocks) {
  std::vector<io::DdaRunSummary::CoarseStrain> out;
  if (sim.settings().kinematics != dda3d::Kinematics::Deformable) return out;
  const std::vector<double> eccentricity = dda3d::interfaceEccentricity(sim);
  for (std::size_t b = 0; b < eccentricity.size(); ++b) {
    if (sim.blocks()[b].fixed || !(eccentricity[b] > dda3d::kMiddleThird)) continue;
    out.push_back({blocks.blocks[b].id, sim.blocks()[b].volume, eccentricity[b]});
  }
  if (!out.empty()) {
    std::fprintf(stderr,
                 "dda: %zu deformable blocks are bent by their contacts more than one strain field "
                 "shows (a side's contact resultant outside its middle third; summary.json "
                 "coarse_strain, frames' eccentricity): their stress is a mean; split them or "
                 "read their stress with care\n",
                 out.size());
  }
  return out;
}

/// Each bolt as the last accepted step left it.
std::vector<io::BoltSample> boltSamples(const dda3d::Simulation& sim,
                                        const std::vector<std::string>& names) {
  std::vector<io::BoltSample> out;
  for (std::size_t k = 0; k < sim.bolts().size(); ++k) {
    const dda3d::BoltState& b = sim.bolts()[k];
    out.push_back({names.at(k), b.force,
                   b.broken    ? "broken"
                   : b.yielded ? "yielded"
                               : "intact",
                   b.broken_at, sim.model().bolts[k].point_a, sim.model().bolts[k].point_b});
  }
  return out;
}

/// One history row per monitor at the simulation's current time, appended to history.csv.
void recordMonitors(const dda3d::Simulation& sim, const std::vector<std::string>& names,
                    io::StreamedFile& history) {
  const std::vector<dda3d::MonitorState> monitors = sim.monitors();
  for (std::size_t m = 0; m < monitors.size(); ++m) {
    history.write(io::formatHistoryRow(
        names, {sim.time(), static_cast<int>(m), monitors[m].displacement, monitors[m].velocity}));
  }
}

/// Seconds per phase of one step, by the phases' output names.
std::vector<std::pair<std::string, double>> phaseSeconds(const dda3d::StepProfile& profile) {
  std::vector<std::pair<std::string, double>> out;
  for (int k = 0; k < dda3d::kStepPhases; ++k) {
    const auto phase = static_cast<dda3d::StepPhase>(k);
    out.emplace_back(dda3d::StepProfile::name(phase), profile[phase]);
  }
  return out;
}

/// The summary's record of one step.
io::DdaStepRecord stepRecord(int step, const dda3d::StepReport& report,
                             const dda3d::Simulation& sim,
                             std::vector<std::pair<std::string, double>> phases) {
  io::DdaStepRecord r;
  r.step = step;
  r.time = report.time;
  r.time_step = report.time_step;
  r.contacts = report.contacts.total;
  r.open = report.contacts.open;
  r.sliding = report.contacts.sliding;
  r.locked = report.contacts.locked;
  r.open_close_iterations = report.iterations;
  r.retries = report.attempts - 1;
  r.max_displacement =
      report.displacement_ratio * sim.settings().max_displacement_ratio * sim.halfDomainSize();
  r.max_penetration = report.max_penetration;
  r.phase_seconds = std::move(phases);
  return r;
}

/// The contacts of the last step as debug records (block ids, not indices).
std::vector<io::DdaContactRecord> contactRecords(const dda3d::Simulation& sim,
                                                 const blocks::BlockModel& blocks) {
  std::vector<io::DdaContactRecord> out;
  for (const dda3d::Contact& c : sim.contacts()) {
    io::DdaContactRecord r;
    r.kind = c.kind == dda3d::ContactKind::VertexFace  ? io::ContactKind::VertexFace
             : c.kind == dda3d::ContactKind::FacePoint ? io::ContactKind::FacePoint
                                                       : io::ContactKind::EdgeEdge;
    r.state = outputState(c.state);
    r.block_i = blocks.blocks[static_cast<std::size_t>(c.block_i)].id;
    r.piece_i = c.piece_i;
    r.block_j = blocks.blocks[static_cast<std::size_t>(c.block_j)].id;
    r.piece_j = c.piece_j;
    r.face_j = c.face;
    r.point = c.point;
    r.normal = c.normal;
    r.gap = c.gap;
    r.normal_force = c.normal_force;
    r.shear_displacement = c.shear.norm();
    r.joint = jointIndex(sim, c);
    out.push_back(r);
  }
  return out;
}

}  // namespace

DdaRun makeDdaRun(const io::Scene& scene, const blocks::BlockModel& blocks,
                  const geometry::FractureNetwork& network, const DdaOverrides& options) {
  const io::DdaAnalysis& dda = *scene.analysis.dda;
  dda3d::DdaModel model = scene_model::buildDdaModel(scene, blocks, network);
  const dda3d::DdaSettings settings = settingsOf(dda, options);
  DdaRun run;
  std::vector<dda3d::Contact> start_contacts;
  if (dda.settle) std::tie(run.settled, start_contacts) = settleFirst(dda, model, settings);
  run.simulation = std::make_unique<dda3d::Simulation>(std::move(model), settings);
  if (dda.settle) {
    run.simulation->adoptContacts(std::move(start_contacts));
    run.simulation->startAtRest();
  }
  return run;
}

DdaStage runDdaStage(const io::Scene& scene, const blocks::BlockModel& blocks,
                     const geometry::FractureNetwork& network, const DdaOverrides& options,
                     const fs::path& out, const std::optional<blocks::MergeReport>& glued) {
  const io::DdaAnalysis& dda = *scene.analysis.dda;
  const int steps = options.steps.value_or(dda.steps);
  DdaStage stage;
  DdaRun run = makeDdaRun(scene, blocks, network, options);
  dda3d::Simulation& sim = *run.simulation;
  stage.summary.settled = run.settled;
  int fixed_blocks = 0, pieces = 0;
  for (const dda3d::DdaBlock& b : sim.model().blocks) {
    fixed_blocks += b.fixed;
    pieces += static_cast<int>(b.pieces.size());
  }
  for (const dda3d::DdaMonitor& m : sim.model().monitors) stage.monitor_names.push_back(m.name);
  for (const io::BoltSpec& b : scene.bolts) stage.bolt_names.push_back(b.name);

  const int frame_every = options.frame_every > 0 ? options.frame_every : std::max(1, steps / 50);
  // Frames are written beside the steps unless the run may keep only one thread busy.
  io::DdaFrameWriter frames(out, frame_every, allowedThreads() > 1);
  // The histories go to disk as the run goes: a run of 10^7 steps would not fit in memory.
  stage.history = std::make_shared<io::StreamedFile>(out / "history.csv");
  stage.history->write(io::historyCsvHeader());
  stage.steps_csv = std::make_shared<io::StreamedFile>(out / "steps.csv");
  stage.steps_csv->write(io::stepsCsvHeader());
  recordMonitors(sim, stage.monitor_names, *stage.history);
  if (!stage.bolt_names.empty()) {
    stage.bolts_csv = std::make_shared<io::StreamedFile>(out / "bolts.csv");
    stage.bolts_csv->write(io::boltsCsvHeader());
    stage.bolts_csv->write(io::formatBoltRows(sim.time(), boltSamples(sim, stage.bolt_names)));
  }
  frames.write(frameOf(sim, blocks, 0));
  std::optional<io::DamageMapWriter> damage;
  if (dda.damage_every) damage.emplace(out);
  io::DamageMap last_map;
  const auto writeDamage = [&](int at) {
    last_map = damageMapOf(sim, blocks, at);
    damage->write(last_map);
  };

  io::DdaRunSummary& summary = stage.summary;
  const double duration = steps * dda.engine.time_step;
  // The last step may land a round-off short of the duration: no sliver step for it.
  const double end = duration * (1.0 - 1e-9);
  int step = 0;
  io::DdaStepRecord last;
  std::vector<std::pair<std::string, double>> phase_totals;
  // Progress every 10 % of the simulated time, and at least every 30 s of wall time (a
  // large model may take minutes per 10 %).
  Progress progress("dda", duration, "s simulated");
  progress.setSafePoint(false);  // each step is one, naming its time (Simulation::step)
  while (sim.time() < end) {
    const dda3d::StepReport report = sim.step();
    ++step;
    summary.late_contacts += report.late_contacts;
    summary.contact_searches += report.contacts_searched;
    summary.partial_contact_searches += report.contacts_searched_partly;
    last = stepRecord(step, report, sim, phaseSeconds(report.profile));
    stage.steps_csv->write(io::formatStepsRow(last));
    addPhaseSeconds(phase_totals, last.phase_seconds);
    io::keepStepRecord(summary.steps, summary.step_stride, last);
    recordMonitors(sim, stage.monitor_names, *stage.history);
    if (stage.bolts_csv) {
      stage.bolts_csv->write(io::formatBoltRows(sim.time(), boltSamples(sim, stage.bolt_names)));
    }
    if (frames.due(step)) frames.write(frameOf(sim, blocks, step));
    if (damage && step % *dda.damage_every == 0) writeDamage(step);
    if (options.debug_step && *options.debug_step == step) {
      io::writeDdaDebugDump(out, step, sim.lastMatrix(), sim.lastRhs(),
                            contactRecords(sim, blocks));
    }
    progress.update(sim.time(), stepDetail(step, report));
  }
  frames.write(frameOf(sim, blocks, step));
  if (damage) {
    if (last_map.step != step || damage->entries().empty()) writeDamage(step);
    io::writeFileAtomically(out / "damage.csv", io::formatDamageCsv(last_map));
    summary.damage = damageCounts(last_map, static_cast<int>(damage->entries().size()));
  }
  if (step > 0 && (summary.steps.empty() || summary.steps.back().step != step)) {
    summary.steps.push_back(last);
  }
  summary.steps_taken = step;
  summary.coarse_strain = coarseStrainBlocks(sim, blocks);
  summary.phase_totals = std::move(phase_totals);
  for (const io::PvdEntry& entry : frames.entries()) stage.frame_files.push_back(entry.file);

  stage.effects = sim.activeTerms().names();
  summary.blocks = static_cast<int>(blocks.blocks.size());
  summary.fixed_blocks = fixed_blocks;
  summary.pieces = pieces;
  summary.unknowns = (summary.blocks - fixed_blocks) * sim.dofsPerBlock();
  summary.glued = glued;
  summary.uplift = scene_model::structureUplift(scene, sim.model());
  summary.bolts = boltSamples(sim, stage.bolt_names);
  summary.steps_requested = steps;
  describeRun(sim, dda, blocks, summary);
  std::fprintf(stderr, "dda: %d steps to t = %.4g s\n", step, sim.time());
  return stage;
}

void writeDdaFiles(const fs::path& /*out*/, const DdaStage& stage) {
  stage.history->commit();
  stage.steps_csv->commit();
  if (stage.bolts_csv) stage.bolts_csv->commit();
}

namespace {

int runDda(const DdaOptions& options) {
  const io::Scene scene = loadScene(options.common);
  if (!scene.analysis.dda) {
    throw io::InputError(options.common.scene +
                         ": analysis.dda: required by `rockmass dda` (steps, time_step, ...)");
  }
  const std::string cutter = scene_model::chooseCutter(scene, options.cutter, options.common.scene);
  const fs::path out = prepareOutput(options.common.output);
  io::RunInfo run;
  run.command = "dda";
  run.scene = options.common.scene;
  run.name = scene.name;
  run.seed = scene.seed;
  run.stages = {"dfn", "cut", "dda"};

  const DfnStage dfn = runDfnStage(scene, options.common.scene);
  run.timings.emplace_back("dfn", dfn.seconds);

  // The network covers the whole domain; the DDA cuts it in its region when it has one.
  const io::Scene dda_scene = scene_model::ddaScene(scene);
  auto start = Clock::now();
  const scene_model::SceneBlocks cut =
      scene_model::cutSceneBlocks(dda_scene, dfn.network, cutter, options.common.scene);
  run.timings.emplace_back("cut", secondsSince(start));
  std::fprintf(stderr, "dda: %zu blocks cut (%s cutter, %.2f s)%s\n", cut.model.blocks.size(),
               cutter.c_str(), run.timings.back().second,
               scene.analysis.dda->region ? " in analysis.dda.region" : "");

  start = Clock::now();
  std::optional<blocks::MergeReport> glued;
  const blocks::BlockModel dda_blocks = scene_model::ddaBlocks(dda_scene, cut.model, glued);
  const DdaStage stage =
      runDdaStage(dda_scene, dda_blocks, dfn.network, options.overrides, out, glued);
  run.timings.emplace_back("dda", secondsSince(start));

  start = Clock::now();
  writeDdaFiles(out, stage);
  io::writeFileAtomically(
      out / "faces.vtu",
      io::formatFacesVtu(dda_blocks, [joints = scene_model::FaceJoints(dda_scene, dfn.network)](
                                         const blocks::FaceSource& f) { return joints.of(f); }));
  run.effects = stage.effects;
  run.timings.emplace_back("write", secondsSince(start));
  io::writeFileAtomically(out / "summary.json", io::formatDdaSummary(run, stage.summary));
  std::fprintf(stderr, "dda: wrote %s\n", out.string().c_str());
  return 0;
}

}  // namespace

Command addDdaCommand(CLI::App& app) {
  auto options = std::make_shared<DdaOptions>();
  CLI::App* cli = app.add_subcommand(
      "dda", "Cut the scene into blocks and run the 3D DDA of its analysis.dda section");
  addCommonOptions(*cli, options->common);
  addCutterOption(*cli, options->cutter);
  cli->add_option("--solver", options->overrides.solver,
                  "Linear solver: auto (default: cholmod up to 6000 unknowns (1000 rigid or 500 "
                  "deformable movable blocks), else pcg "
                  "warm-started), cholmod, eigen, pcg")
      ->check(CLI::IsMember({"auto", "cholmod", "eigen", "pcg"}));
  cli->add_option("--pcg-tolerance", options->overrides.pcg_tolerance,
                  "Relative residual of the pcg solver (default 1e-10)")
      ->check(CLI::PositiveNumber);
  cli->add_option("--frame-every", options->overrides.frame_every,
                  "Steps between VTU frames (default: steps / 50)")
      ->check(CLI::PositiveNumber);
  cli->add_option("--debug-step", options->overrides.debug_step,
                  "Dump K, F (Matrix Market) and the contacts (CSV) of step N: debug_step<N>_*")
      ->check(CLI::PositiveNumber);
  return {cli, [options] { return runDda(*options); }};
}

}  // namespace rockmass::app
