// rockmass run: every stage the scene's `analysis` section names, in order DFN -> blocks ->
// RQD -> DDA -> overload / strength reduction, and nothing else; one summary.json for the
// whole run, the vertical section through the block model, and the figures.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <future>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/command.h"
#include "app/run.h"
#include "app/stability.h"
#include "app/stages.h"
#include "geometry/interrupt.h"
#include "geometry/plane_section.h"
#include "io/atomic_file.h"
#include "io/block_output.h"
#include "io/dda_summary.h"
#include "io/input_error.h"
#include "io/rqd_output.h"
#include "io/run_summary.h"
#include "io/section_output.h"
#include "io/stability_output.h"
#include "io/summary.h"
#include "scene_model/dda_model.h"
#include "scene_model/scene_blocks.h"

namespace rockmass::app {

namespace {

namespace fs = std::filesystem;

// -------------------------------------------------------------------------------------------
// run --quick

/// Fraction of the domain depth that the quick box keeps (from the top).
constexpr double kQuickDepthFraction = 1.0 / 6.0;
/// DDA steps of a quick run (at most).
constexpr int kQuickDdaSteps = 10;
/// RQD directions of every ball and scanline axes per grid cell of a quick run (at most).
constexpr int kQuickBallDirections = 200;
constexpr int kQuickGridDirections = 20;
/// Steps per run to equilibrium of a quick overload / strength-reduction run (at most).
constexpr int kQuickEquilibriumSteps = 40;
/// ... and the settled start's (analysis.equilibrium.start_steps), which runs once.
constexpr int kQuickStartSteps = 2 * kQuickEquilibriumSteps;
/// Factors of each quick overload / strength-reduction list (at most; evenly picked).
constexpr std::size_t kQuickFactors = 4;
/// Bisection tolerance of a quick overload / strength-reduction search (at least).
constexpr double kQuickFactorTolerance = 0.25;

/// At most kQuickFactors of `factors`, evenly spread over the list (first and last kept).
std::vector<double> quickFactors(const std::vector<double>& factors) {
  if (factors.size() <= kQuickFactors) return factors;
  std::vector<double> kept;
  for (std::size_t k = 0; k < kQuickFactors; ++k) {
    kept.push_back(factors[k * (factors.size() - 1) / (kQuickFactors - 1)]);
  }
  return kept;
}

/// The quick box: in plan, the structures' footprint (the union of their plan bounding
/// boxes, clipped to the domain) or, without structures, the central half of the domain in
/// x and y; in depth, the top sixth of the domain (at least 1 m).
geometry::Box quickBox(const io::Scene& scene) {
  const geometry::Box& domain = scene.dfn.domain;
  geometry::Box box = domain;
  if (scene.structures.empty()) {
    for (int axis = 0; axis < 2; ++axis) {
      box.min[axis] = domain.min[axis] + 0.25 * domain.size()[axis];
      box.max[axis] = domain.max[axis] - 0.25 * domain.size()[axis];
    }
  } else {
    box.min.head<2>().setConstant(std::numeric_limits<double>::infinity());
    box.max.head<2>().setConstant(-std::numeric_limits<double>::infinity());
    for (const io::StructureSpec& s : scene.structures) {
      // Prism: the profile's first coordinate runs across the sweep axis.
      const int across = s.prism_sweep == 'x' ? 1 : 0;
      const int along = 1 - across;
      for (const geometry::Vec2& p : s.prism_profile) {
        box.min[across] = std::min(box.min[across], p.x());
        box.max[across] = std::max(box.max[across], p.x());
      }
      box.min[along] = std::min({box.min[along], s.prism_from, s.prism_to});
      box.max[along] = std::max({box.max[along], s.prism_from, s.prism_to});
    }
    for (int axis = 0; axis < 2; ++axis) {
      box.min[axis] = std::max(box.min[axis], domain.min[axis]);
      box.max[axis] = std::min(box.max[axis], domain.max[axis]);
      if (!(box.max[axis] > box.min[axis])) {  // footprint outside the domain in plan
        box.min[axis] = domain.min[axis];
        box.max[axis] = domain.max[axis];
      }
    }
  }
  box.min.z() = domain.max.z() - std::max(1.0, kQuickDepthFraction * domain.size().z());
  box.min.z() = std::max(box.min.z(), domain.min.z());
  return box;
}

/// The point of `box` shrunk by 5% of its size on every side nearest to p.
geometry::Vec3 clampInto(const geometry::Box& box, const geometry::Vec3& p) {
  const geometry::Vec3 inset = 0.05 * box.size();
  return p.cwiseMax(box.min + inset).cwiseMin(box.max - inset);
}

/// Describes a point for the notes.
std::string pointText(const geometry::Vec3& p) {
  return "(" + io::formatDouble(p.x()) + ", " + io::formatDouble(p.y()) + ", " +
         io::formatDouble(p.z()) + ")";
}

/// The quick variant of a scene: the quick box as domain (and as the DDA's region); monitors, RQD
/// ball centres and point loads outside it (but inside the scene's domain: a point outside it is
/// on a structure, which the quick run keeps whole) moved to the nearest point of the box shrunk
/// by 5%; at
/// most kQuickBallDirections ball directions and kQuickGridDirections grid axes; at most
/// kQuickDdaSteps DDA steps (see quickSteps). Returns what it moved, for the summary.
std::vector<std::string> makeQuick(io::Scene& scene) {
  std::vector<std::string> notes;
  const geometry::Box box = quickBox(scene);
  const geometry::Box full = scene.dfn.domain;
  scene.dfn.domain = box;
  for (io::Monitor& m : scene.monitors) {
    if (box.contains(m.point) || !full.contains(m.point)) continue;
    const geometry::Vec3 moved = clampInto(box, m.point);
    notes.push_back("quick: monitor " + m.name + " moved from " + pointText(m.point) + " to " +
                    pointText(moved));
    m.point = moved;
  }
  for (io::PointLoad& load : scene.loads.point_loads) {
    if (box.contains(load.point) || !full.contains(load.point)) continue;
    load.point = clampInto(box, load.point);
  }
  // A bolt outside the quick box would hold nothing there: left out, and said.
  const std::size_t bolts = scene.bolts.size();
  std::erase_if(scene.bolts, [&](const io::BoltSpec& b) {
    return !box.contains(b.head) || !box.contains(b.end);
  });
  if (scene.bolts.size() < bolts) {
    notes.push_back("quick: " + std::to_string(bolts - scene.bolts.size()) +
                    " bolts outside the quick box left out");
  }
  if (scene.analysis.rqd) {
    io::RqdAnalysis& rqd = *scene.analysis.rqd;
    for (io::RqdBall& ball : rqd.balls) {
      ball.directions = std::min(ball.directions, kQuickBallDirections);
      const geometry::Vec3 inset = 0.05 * box.size();
      if (((ball.center - box.min).array() > inset.array()).all() &&
          ((box.max - ball.center).array() > inset.array()).all()) {
        continue;
      }
      const geometry::Vec3 moved = clampInto(box, ball.center);
      notes.push_back("quick: RQD ball " + ball.name + " moved from " + pointText(ball.center) +
                      " to " + pointText(moved));
      ball.center = moved;
    }
    rqd.grid_direction_count = std::min(rqd.grid_direction_count, kQuickGridDirections);
    rqd.grid_region.reset();  // the grid covers the (quick) domain
  }
  io::Analysis& a = scene.analysis;
  if (a.dda && a.dda->region) {
    a.dda->region.reset();
    notes.push_back("quick: analysis.dda.region not used: the DDA runs on the quick box");
  }
  if ((a.overload || a.strength_reduction) && a.dda) {
    if (!a.equilibrium) a.equilibrium.emplace();
    a.equilibrium->max_steps =
        std::min(a.equilibrium->max_steps.value_or(a.dda->steps), kQuickEquilibriumSteps);
    if (a.equilibrium->start_steps) {
      a.equilibrium->start_steps = std::min(*a.equilibrium->start_steps, kQuickStartSteps);
    }
  }
  if (a.overload) {
    a.overload->factors = quickFactors(a.overload->factors);
    if (a.overload->tolerance > 0.0) {
      a.overload->tolerance = std::max(a.overload->tolerance, kQuickFactorTolerance);
    }
  }
  if (a.strength_reduction) {
    a.strength_reduction->factors = quickFactors(a.strength_reduction->factors);
    a.strength_reduction->tolerance =
        std::max(a.strength_reduction->tolerance, kQuickFactorTolerance);
  }
  return notes;
}

// -------------------------------------------------------------------------------------------
// Blocks of the DDA

// -------------------------------------------------------------------------------------------
// Section plane

/// The section plane: `option` AXIS=VALUE (x, y or z; VALUE in m), or by default the
/// domain's mid-plane normal to the sweep axis of the first structure (else of the first
/// interlayer, else y): a vertical section across the dam, as Figure 5 of the paper.
std::pair<geometry::SectionPlane, std::string> sectionPlane(const io::Scene& scene,
                                                            const std::string& option) {
  int axis = 1;
  double offset = 0.0;
  if (option.empty()) {
    char sweep = 'y';
    if (!scene.structures.empty() && scene.structures.front().mesh.empty()) {
      sweep = scene.structures.front().prism_sweep;
    } else if (!scene.dfn.interlayers.empty()) {
      sweep = scene.dfn.interlayers.front().sweep;
    }
    axis = sweep == 'x' ? 0 : 1;
    offset = scene.dfn.domain.center()[axis];
  } else {
    const std::size_t eq = option.find('=');
    const std::string name = option.substr(0, eq);
    if (eq == std::string::npos || (name != "x" && name != "y" && name != "z")) {
      throw io::InputError(
          "--section: expected AXIS=VALUE with AXIS x, y or z (e.g. y=10) or "
          "none, got '" +
          option + "'");
    }
    axis = name[0] - 'x';
    try {
      std::size_t used = 0;
      offset = std::stod(option.substr(eq + 1), &used);
      if (used != option.size() - eq - 1) throw std::invalid_argument("trailing text");
    } catch (const std::exception&) {
      throw io::InputError("--section: expected a number after '" + name + "=', got '" +
                           option.substr(eq + 1) + "'");
    }
    const geometry::Box& d = scene.dfn.domain;
    if (!(offset > d.min[axis] && offset < d.max[axis])) {
      throw io::InputError("--section: " + option + " lies outside the domain (" + name + " from " +
                           io::formatDouble(d.min[axis]) + " to " + io::formatDouble(d.max[axis]) +
                           ")");
    }
  }
  const std::string label =
      std::string(1, static_cast<char>('x' + axis)) + "=" + io::formatDouble(offset);
  return {geometry::axisPlane(axis, offset), label};
}

// -------------------------------------------------------------------------------------------
// Stage plan

/// Which stages run, checked before any work: a stage whose input is missing is an
/// io::InputError naming the scene key to add.
struct StagePlan {
  bool cut = false;
  bool rqd = false;
  bool dda = false;
  bool overload = false;
  bool strength_reduction = false;
  std::string cutter;  ///< when cut
};

/// True when the scene has something that cuts the domain into more than one block.
bool hasCuttingFeatures(const io::Scene& scene) {
  return !scene.dfn.joint_sets.empty() || !scene.dfn.faults.empty() ||
         !scene.dfn.interlayers.empty() || !scene.dfn.polygon_sets.empty() ||
         !scene.structures.empty();
}

StagePlan planStages(const io::Scene& scene, const RunOptions& options) {
  const std::string& file = options.common.scene;
  const io::Analysis& a = scene.analysis;
  StagePlan plan;
  plan.rqd = a.rqd.has_value();
  plan.dda = a.dda.has_value();
  plan.overload = a.overload.has_value();
  plan.strength_reduction = a.strength_reduction.has_value();
  if (plan.dda && !a.blocks && !hasCuttingFeatures(scene)) {
    throw io::InputError(file +
                         ": analysis.dda: the DDA needs blocks, and the scene has neither "
                         "analysis.blocks nor joint_sets, faults, interlayers, fractures or "
                         "structures to cut them; add analysis.blocks (e.g. `blocks: {cutter: "
                         "fast}`) or the discontinuities that make the blocks");
  }
  if (plan.overload && !plan.dda) {
    throw io::InputError(file +
                         ": analysis.overload: the overload analysis runs the DDA under growing "
                         "loads; add analysis.dda (mode, steps, time_step)");
  }
  if (plan.strength_reduction && !plan.dda) {
    throw io::InputError(file +
                         ": analysis.strength_reduction: strength reduction runs the DDA with "
                         "reduced joint strength; add analysis.dda (mode, steps, time_step)");
  }
  plan.cut = a.blocks.has_value() || plan.dda;
  if (plan.cut) plan.cutter = scene_model::chooseCutter(scene, options.cutter, file);
  return plan;
}

/// scripts/figures/make_figures.py, or nothing with the reason (the warning finishRun gives)
/// when it or a python with matplotlib is missing (the figures are then not drawn; not a
/// failure).
struct FigureScript {
  std::optional<fs::path> script;
  std::string missing;  ///< why there is none
};

FigureScript figureScript(const RunOptions& options) {
  const std::string check = shellQuote(options.python) + " -c 'import matplotlib' >/dev/null 2>&1";
  if (std::system(check.c_str()) != 0) {
    return {std::nullopt, "figures: " + options.python +
                              " with matplotlib is not available; no figures were drawn"};
  }
  const fs::path script = fs::path(options.figure_scripts) / "make_figures.py";
  if (!fs::exists(script)) {
    return {std::nullopt, "figures: " + script.string() + " not found; no figures were drawn"};
  }
  return {script, ""};
}

/// Adds the PNG names a make_figures.py run reports ("figure: NAME" lines) to `figures`;
/// false when it failed.
bool addFigures(const ScriptRun& run, const std::string& python,
                std::vector<std::string>& figures) {
  if (!run.started) throw std::runtime_error("figures: cannot start " + python);
  for (const std::string& line : run.lines) {
    if (line.rfind("figure: ", 0) == 0) figures.push_back(line.substr(8));
  }
  return run.succeeded;
}

/// The figures whose inputs are final before the DDA's stages (fractures.csv, section.csv),
/// drawn early (RunContext::startEarlyFigures): on the Xiangjiaba scene about 12 s of Python
/// that would otherwise follow the stability analyses.
constexpr const char* kEarlyFigures = "stereonet.png,section.png";

/// report.html (scripts/report/make_report.py, next to the figure scripts); false with a
/// warning when it could not be written (no numpy, no three.js).
bool makeReport(const RunOptions& options, const fs::path& out,
                std::vector<std::string>& warnings) {
  const fs::path script =
      (fs::path(options.figure_scripts) / ".." / "report" / "make_report.py").lexically_normal();
  bool written = false;
  if (fs::exists(script)) {
    const ScriptRun run = runScript(options.python, script, out, "run");
    written = run.succeeded && std::find(run.lines.begin(), run.lines.end(),
                                         "report: report.html") != run.lines.end();
  }
  if (!written) {
    warnings.push_back("report: report.html was not written (" + script.string() +
                       ", numpy and Debian's libjs-three; see the messages above)");
    std::fprintf(stderr, "run: warning: %s\n", warnings.back().c_str());
  }
  return written;
}

/// An empty RunInfo of `command` for a stage's own summary (its header is dropped when the
/// stage summaries are merged; only its extra timings are kept).
io::RunInfo stageRun(const io::RunInfo& run, io::Timings timings) {
  io::RunInfo info = run;
  info.timings = std::move(timings);
  return info;
}

/// What the stages of one `run` share: the scene, the output folder, and what goes into
/// summary.json (the header with the stages' names and timings, each stage's summary part,
/// the run report with the files written). Each stage adds its name, its timings, its files
/// and its part.
struct RunContext {
  const RunOptions& options;
  io::Scene scene;
  StagePlan plan;
  fs::path out;
  io::RunInfo run;
  io::RunReport report;
  std::vector<io::StageSummary> parts;
  double write_seconds = 0.0;
  /// make_figures.py once checked (figureScript), and the run of the figures drawn early
  /// (startEarlyFigures), if started.
  std::optional<FigureScript> figure_script;
  std::future<ScriptRun> early_figures;

  /// make_figures.py (nothing when it cannot run: figureScript's reason), checked on the
  /// first call.
  const FigureScript& figures() {
    if (!figure_script) figure_script = figureScript(options);
    return *figure_script;
  }

  /// Runs `write`, its time counted in the "write" timing.
  template <class Write>
  void timedWrite(const Write& write) {
    const auto start = Clock::now();
    write();
    write_seconds += secondsSince(start);
  }
  void addFiles(std::initializer_list<std::string> files) {
    report.files.insert(report.files.end(), files);
  }
  /// Adds a stage's name and wall time.
  void addStage(const std::string& name, double seconds) {
    run.stages.push_back(name);
    run.timings.emplace_back(name, seconds);
  }
};

/// Output files written beside the stages that follow (on threads of their own when the run
/// may use more than one): the fractures' and the blocks' files take about 14 s on the
/// Xiangjiaba scene, mostly serial work (welding the points, the pieces' volumes) that the
/// next stages need not wait for. Each write reads only what no later stage changes (the
/// scene, the network, the cut) and writes files of its own, atomically, so the files are
/// those of writing in turn. `wait` joins them before summary.json (their time is in the
/// "write" timing) and rethrows the first error; the destructor joins them on any other
/// way out, before what they read is destroyed (declare it after that).
class WritesBeside {
 public:
  explicit WritesBeside(bool beside) : beside_(beside) {}
  WritesBeside(const WritesBeside&) = delete;
  WritesBeside& operator=(const WritesBeside&) = delete;
  ~WritesBeside() {
    for (std::shared_future<double>& write : writes_) {
      if (write.valid()) write.wait();
    }
  }
  /// Runs `write` beside the caller (returned: its end, to wait for), or at once when the run
  /// keeps to one thread (returned: nothing to wait for).
  template <class Write>
  std::shared_future<double> add(RunContext& ctx, Write write) {
    if (!beside_) {
      ctx.timedWrite(write);
      return {};
    }
    writes_.push_back(std::async(std::launch::async, [write] {
                        const auto start = Clock::now();
                        write();
                        return secondsSince(start);
                      }).share());
    return writes_.back();
  }
  /// Joins every write, adds its time to the "write" timing; rethrows the first error.
  void wait(RunContext& ctx) {
    std::exception_ptr error;
    for (std::shared_future<double>& write : writes_) {
      try {
        ctx.write_seconds += write.get();
      } catch (...) {
        if (!error) error = std::current_exception();
      }
    }
    writes_.clear();
    if (error) std::rethrow_exception(error);
  }

 private:
  bool beside_;
  std::vector<std::shared_future<double>> writes_;
};

/// Starts drawing the figures whose inputs are final now (kEarlyFigures: fractures.csv, once
/// `fractures_written` has ended, and section.csv) on a thread of its own, at low priority, so
/// that they take the time the stability analyses leave idle instead of following them;
/// finishRun draws the others and joins these. Only when the run may use more than one
/// thread and a stability analysis follows (else they are drawn with the others).
void startEarlyFigures(RunContext& ctx, std::shared_future<double> fractures_written) {
  if (ctx.options.no_figures || allowedThreads() < 2 || !fractures_written.valid()) return;
  const std::optional<fs::path>& script = ctx.figures().script;
  if (!script) return;  // finishRun says why
  ctx.early_figures =
      std::async(std::launch::async, [&options = ctx.options, script = *script, out = ctx.out,
                                      scene = ctx.scene.name, fractures_written] {
        fractures_written.wait();  // its error, if any, is the write's (WritesBeside::wait)
        return runScript(options.python, script, out, "run",
                         {"--only", kEarlyFigures, "--scene", scene}, /*low_priority=*/true);
      });
}

/// DFN: always (every other stage is built on the network). Its files are written by the
/// caller (writeDfnFiles), beside the stages that follow.
DfnStage dfnStage(RunContext& ctx) {
  DfnStage dfn = runDfnStage(ctx.scene, ctx.options.common.scene);
  ctx.addStage("dfn", dfn.seconds);
  ctx.addFiles({"fractures.csv", "fractures.fab", "fractures.vtu"});
  ctx.parts.push_back({"dfn", io::formatDfnSummary(stageRun(ctx.run, {}), dfn.network, dfn.stats)});
  return dfn;
}

/// The vertical section through the blocks (section.csv, section.svg).
void sectionStage(RunContext& ctx, const scene_model::SceneBlocks& cut,
                  const geometry::FractureNetwork& network,
                  const std::pair<geometry::SectionPlane, std::string>& section) {
  const auto start = Clock::now();
  const blocks::Section s =
      blocks::sectionOf(cut.model, network, section.first, section.second, cut.input.disc_segments);
  ctx.run.timings.emplace_back("section", secondsSince(start));
  ctx.timedWrite([&] {
    io::writeFileAtomically(ctx.out / "section.csv",
                            io::formatSectionCsv(s, network, ctx.scene.materials));
    io::writeFileAtomically(ctx.out / "section.svg",
                            io::formatSectionSvg(s, network, ctx.scene.materials));
  });
  ctx.report.section = section.second;
  ctx.addFiles({"section.csv", "section.svg"});
  std::fprintf(stderr, "run: section %s: %zu piece polygons, %zu traces\n", section.second.c_str(),
               s.polygons.size(), s.traces.size());
}

/// Blocks (and the section through them). Their files are written by the caller
/// (writeBlocksFiles), beside the stages that follow.
scene_model::SceneBlocks cutStage(
    RunContext& ctx, const geometry::FractureNetwork& network,
    const std::optional<std::pair<geometry::SectionPlane, std::string>>& section) {
  const std::string& cutter = ctx.plan.cutter;
  const auto start = Clock::now();
  scene_model::SceneBlocks cut =
      scene_model::cutSceneBlocks(ctx.scene, network, cutter, ctx.options.common.scene);
  const double seconds = secondsSince(start);
  std::fprintf(stderr, "run: %zu blocks (%d pieces), %s cutter (%.2f s)\n", cut.model.blocks.size(),
               cut.pieces, cutter.c_str(), seconds);
  ctx.addStage("cut", seconds);
  ctx.report.cutter = cutter;
  ctx.addFiles({"blocks.csv", "blocks.vtu", "faces.vtu"});
  ctx.parts.push_back(
      {"cut",
       io::formatBlocksSummary(stageRun(ctx.run, {{"cut_split", cut.split_seconds},
                                                  {"cut_assemble", cut.assemble_seconds}}),
                               network, cut.model, cutInfoOf(cut, cutter), ctx.scene.materials)});
  if (section) sectionStage(ctx, cut, network, *section);
  return cut;
}

/// RQD: balls, boreholes, the grid.
void rqdStage(RunContext& ctx, const geometry::FractureNetwork& network, RqdPlan plan,
              const RqdOverrides& overrides) {
  RqdStage stage =
      runRqdStage(ctx.scene, ctx.options.common.scene, network, std::move(plan), overrides);
  ctx.run.stages.insert(ctx.run.stages.end(), stage.stages.begin(), stage.stages.end());
  ctx.run.timings.insert(ctx.run.timings.end(), stage.timings.begin(), stage.timings.end());
  ctx.timedWrite([&] { writeRqdFiles(ctx.out, stage.report); });
  if (!stage.report.balls.empty()) {
    ctx.report.files.push_back("rqd_balls.csv");
    for (const io::BallReport& ball : stage.report.balls) {
      for (const double t : ball.result.thresholds) {
        ctx.report.files.push_back(io::ballPlyName(ball.name, t));
      }
    }
  }
  if (stage.report.boreholes) ctx.report.files.push_back("boreholes.csv");
  if (stage.report.grid) ctx.report.files.push_back("rqd.vdb");
  ctx.parts.push_back({"rqd", io::formatRqdSummary(stageRun(ctx.run, {}), stage.report)});
}

/// The DDA's blocks: those of the cut with the small ones glued
/// (analysis.dda.min_block_volume), or with analysis.dda.region a second cut of the same
/// network in the region (ddaScene), the blocks stage keeping the whole domain.
blocks::BlockModel ddaStageBlocks(RunContext& ctx, const io::Scene& dda_scene,
                                  const geometry::FractureNetwork& network,
                                  const std::optional<scene_model::SceneBlocks>& cut,
                                  std::optional<blocks::MergeReport>& glued) {
  if (!(ctx.scene.analysis.dda && ctx.scene.analysis.dda->region)) {
    return scene_model::ddaBlocks(ctx.scene, cut->model, glued);
  }
  const auto start = Clock::now();
  const scene_model::SceneBlocks region =
      scene_model::cutSceneBlocks(dda_scene, network, ctx.plan.cutter, ctx.options.common.scene);
  const double seconds = secondsSince(start);
  ctx.run.timings.emplace_back("dda_region_cut", seconds);
  std::fprintf(stderr, "run: DDA region: %zu blocks (%d pieces), %s cutter (%.2f s)\n",
               region.model.blocks.size(), region.pieces, ctx.plan.cutter.c_str(), seconds);
  return scene_model::ddaBlocks(dda_scene, region.model, glued);
}

/// The stability analyses' model, built before the DDA stage so that its input checks (the
/// monitors that analysis.equilibrium.watch: monitors watches) come before minutes of work.
dda3d::DdaModel stabilityModel(RunContext& ctx, io::Scene& dda_scene,
                               const blocks::BlockModel& dda_blocks,
                               const geometry::FractureNetwork& network) {
  dda3d::DdaModel model = scene_model::buildDdaModel(dda_scene, dda_blocks, network);
  io::EquilibriumAnalysis* equilibrium =
      dda_scene.analysis.equilibrium ? &*dda_scene.analysis.equilibrium : nullptr;
  if (ctx.options.quick && equilibrium && equilibrium->watch_monitors &&
      dda3d::monitoredMovableBlocks(model).empty()) {
    // The quick box moved the monitors into blocks its supports hold: watch every block.
    equilibrium->watch_monitors = false;
    ctx.report.warnings.push_back(
        "quick: analysis.equilibrium.watch: monitors changed to all: every monitor lies in "
        "a held block of the quick box");
    std::fprintf(stderr, "run: warning: %s\n", ctx.report.warnings.back().c_str());
  }
  checkWatchedMonitors(dda_scene, model);
  return model;
}

/// The DDA run of analysis.dda as computed (its frames written as it went), and its wall time.
struct DdaStageRun {
  DdaStage stage;
  double seconds = 0.0;
};

/// Runs analysis.dda. Reads only its arguments, so it may run beside the stability analyses.
DdaStageRun computeDdaStage(const fs::path& out, const io::Scene& dda_scene,
                            const blocks::BlockModel& dda_blocks,
                            const geometry::FractureNetwork& network, const DdaOverrides& overrides,
                            const std::optional<blocks::MergeReport>& glued) {
  const auto start = Clock::now();
  DdaStage stage = runDdaStage(dda_scene, dda_blocks, network, overrides, out, glued);
  return {std::move(stage), secondsSince(start)};
}

/// Records the DDA run: its files, timing and summary part.
void recordDdaStage(RunContext& ctx, const DdaStageRun& run) {
  const DdaStage& stage = run.stage;
  ctx.addStage("dda", run.seconds);
  ctx.run.effects = stage.effects;
  ctx.timedWrite([&] { writeDdaFiles(ctx.out, stage); });
  ctx.addFiles({"history.csv", "steps.csv", "dda.pvd"});
  ctx.report.files.insert(ctx.report.files.end(), stage.frame_files.begin(),
                          stage.frame_files.end());
  ctx.parts.push_back({"dda", io::formatDdaSummary(stageRun(ctx.run, {}), stage.summary)});
}

/// A factor search and its wall time.
struct TimedSearch {
  dda3d::FactorSearchResult result;
  double seconds = 0.0;
};

/// What the stability analyses computed, before it is recorded.
struct StabilityRuns {
  std::optional<StabilityStart> begin;
  double start_seconds = 0.0;
  std::optional<TimedSearch> overload;
  std::optional<TimedSearch> strength;
};

/// Overload and strength reduction, from one start state: the one place where they are wired.
/// Both start from that state and share nothing else, so with both the overload runs on a
/// thread of its own beside the strength reduction: each run's steps are deterministic
/// whatever the threads, so the answers are those of running them one after the other. An
/// error of either is reported as it would be then (the overload's first).
StabilityRuns computeStability(const StagePlan& plan, const io::Scene& dda_scene,
                               const dda3d::DdaModel& stability_model, bool side_by_side) {
  StabilityRuns runs;
  const auto start_state = Clock::now();
  runs.begin = stabilityStart(dda_scene, stability_model);
  runs.start_seconds = secondsSince(start_state);
  const StabilityStart& begin = *runs.begin;
  const auto timed = [&](auto search) {
    return [&, search] {
      const auto start = Clock::now();
      dda3d::FactorSearchResult result = search(dda_scene, begin);
      return TimedSearch{std::move(result), secondsSince(start)};
    };
  };
  const auto overload = timed(runSceneOverload);
  const auto strength = timed(runSceneStrengthReduction);
  if (plan.overload && plan.strength_reduction && side_by_side) {
    std::future<TimedSearch> beside = std::async(std::launch::async, overload);
    std::exception_ptr strength_error;
    try {
      runs.strength = strength();
    } catch (...) {
      strength_error = std::current_exception();
    }
    runs.overload = beside.get();  // rethrows the overload's error
    if (strength_error) std::rethrow_exception(strength_error);
  } else {
    if (plan.overload) runs.overload = overload();
    if (plan.strength_reduction) runs.strength = strength();
  }
  return runs;
}

/// Records the stability analyses: their timings, overload.csv and the summary part.
void recordStability(RunContext& ctx, const StabilityRuns& runs,
                     const std::optional<blocks::MergeReport>& glued, const io::Scene& dda_scene) {
  const StabilityStart& begin = *runs.begin;
  const dda3d::DdaModel& model = begin.model;
  if (begin.settling) ctx.run.timings.emplace_back("stability_start", runs.start_seconds);
  dda3d::ActiveTerms terms;
  if (runs.overload) {
    ctx.addStage("overload", runs.overload->seconds);
    addRunTerms(runs.overload->result, terms);
    ctx.timedWrite([&] {
      io::writeFileAtomically(ctx.out / "overload.csv",
                              io::formatOverloadCsv(monitorNames(model), runs.overload->result));
    });
    ctx.report.files.push_back("overload.csv");
  }
  if (runs.strength) {
    ctx.addStage("strength_reduction", runs.strength->seconds);
    addRunTerms(runs.strength->result, terms);
  }
  for (const std::string& effect : terms.names()) {
    if (std::find(ctx.run.effects.begin(), ctx.run.effects.end(), effect) ==
        ctx.run.effects.end()) {
      ctx.run.effects.push_back(effect);
    }
  }
  const io::StabilitySummary summary =
      stabilitySummary(dda_scene, model, glued, runs.overload ? &runs.overload->result : nullptr,
                       runs.strength ? &runs.strength->result : nullptr);
  ctx.parts.push_back({"stability", io::formatStabilitySummary(stageRun(ctx.run, {}), summary)});
}

/// summary.json, then the figures (and summary.json again, with them).
void finishRun(RunContext& ctx) {
  std::sort(ctx.report.files.begin(), ctx.report.files.end());
  ctx.report.files.push_back("summary.json");
  ctx.run.timings.emplace_back("write", ctx.write_seconds);
  io::writeFileAtomically(ctx.out / "summary.json",
                          io::formatRunSummary(ctx.run, ctx.parts, ctx.report));
  if (!ctx.options.no_figures) {
    // The figures not drawn early, then those (startEarlyFigures), in the list's order.
    const auto start = Clock::now();
    std::vector<std::string>& figures = ctx.report.figures;
    const FigureScript& figures_script = ctx.figures();
    if (!figures_script.missing.empty()) {
      ctx.report.warnings.push_back(figures_script.missing);
      std::fprintf(stderr, "run: warning: %s\n", figures_script.missing.c_str());
    }
    if (const std::optional<fs::path>& script = figures_script.script) {
      const bool early = ctx.early_figures.valid();
      std::vector<std::string> arguments;
      if (early) arguments = {"--skip", kEarlyFigures};
      bool drawn = addFigures(runScript(ctx.options.python, *script, ctx.out, "run", arguments),
                              ctx.options.python, figures);
      if (early) drawn = addFigures(ctx.early_figures.get(), ctx.options.python, figures) && drawn;
      if (!drawn) {
        ctx.report.warnings.push_back("figures: make_figures.py failed (see the messages above)");
      }
      std::sort(figures.begin(), figures.end());
    }
    ctx.run.timings.emplace_back("figures", secondsSince(start));
    // The report reads the summary with its figures, then is named in it.
    io::writeFileAtomically(ctx.out / "summary.json",
                            io::formatRunSummary(ctx.run, ctx.parts, ctx.report));
    const auto report_start = Clock::now();
    if (makeReport(ctx.options, ctx.out, ctx.report.warnings)) {
      ctx.report.files.insert(ctx.report.files.end() - 1, "report.html");
    }
    ctx.run.timings.emplace_back("report", secondsSince(report_start));
    io::writeFileAtomically(ctx.out / "summary.json",
                            io::formatRunSummary(ctx.run, ctx.parts, ctx.report));
  }
  double total = 0.0;
  for (const auto& [stage, seconds] : ctx.run.timings) total += seconds;
  std::fprintf(stderr, "run: %zu stages in %.1f s; wrote %s\n", ctx.run.stages.size(), total,
               ctx.out.string().c_str());
}

}  // namespace

int runScene(const RunOptions& options, io::Scene scene_in) {
  const std::string& scene_path = options.common.scene;
  RunContext ctx{options, std::move(scene_in), {}, {}, {}, {}, {}, 0.0, {}, {}};
  io::Scene& scene = ctx.scene;
  const geometry::Box full_domain = scene.dfn.domain;
  ctx.report.quick = options.quick;
  if (options.quick) ctx.report.warnings = makeQuick(scene);
  ctx.report.domain = scene.dfn.domain;
  ctx.plan = planStages(scene, options);
  const StagePlan& plan = ctx.plan;

  // Everything the stages read is checked before any work is done.
  RqdOverrides rqd_overrides;
  if (options.quick) rqd_overrides.hole_domain = full_domain;
  std::optional<RqdPlan> rqd_plan;
  if (plan.rqd) rqd_plan = planRqd(scene, rqd_overrides, scene_path);
  std::optional<std::pair<geometry::SectionPlane, std::string>> section;
  if (plan.cut && options.section != "none") section = sectionPlane(scene, options.section);
  DdaOverrides dda_overrides;
  dda_overrides.solver = options.solver;
  if (options.quick && plan.dda) {
    dda_overrides.steps = std::min(scene.analysis.dda->steps, kQuickDdaSteps);
  }
  ctx.out = prepareOutput(options.common.output);
  ctx.run.command = "run";
  ctx.run.scene = scene_path;
  ctx.run.name = scene.name;
  ctx.run.seed = scene.seed;

  const DfnStage dfn = dfnStage(ctx);
  std::optional<scene_model::SceneBlocks> cut;
  WritesBeside writes(allowedThreads() > 1);  // after what the writes read (see its comment)
  const std::shared_future<double> fractures_written =
      writes.add(ctx, [&] { writeDfnFiles(ctx.out, ctx.scene, dfn.network); });
  if (plan.cut) {
    cut = cutStage(ctx, dfn.network, section);
    writes.add(ctx, [&] { writeBlocksFiles(ctx.out, ctx.scene, cut->model, dfn.network); });
  }
  if (plan.rqd) rqdStage(ctx, dfn.network, std::move(*rqd_plan), rqd_overrides);
  const bool stability = plan.overload || plan.strength_reduction;
  if (plan.dda || stability) {
    io::Scene dda_scene = scene_model::ddaScene(scene);
    std::optional<blocks::MergeReport> glued;
    const blocks::BlockModel dda_blocks = ddaStageBlocks(ctx, dda_scene, dfn.network, cut, glued);
    std::optional<dda3d::DdaModel> stability_model;
    if (stability) stability_model = stabilityModel(ctx, dda_scene, dda_blocks, dfn.network);
    // Once the inputs are checked, the figures whose inputs are final go beside the analyses.
    if (stability) startEarlyFigures(ctx, fractures_written);
    // The DDA stage and the stability analyses share nothing but their inputs: with both,
    // the DDA stage runs on a thread of its own beside them (computeStability), and both are
    // recorded in this order afterwards; an error of the DDA stage is reported first (and
    // said at once: the analyses beside it run to their end before the run stops). With
    // --threads 1 the stages run one after the other, on the one thread.
    const bool side_by_side = allowedThreads() > 1;
    std::future<DdaStageRun> dda_run;
    const auto ddaRun = [&] {
      try {
        return computeDdaStage(ctx.out, dda_scene, dda_blocks, dfn.network, dda_overrides, glued);
      } catch (const Interrupted&) {
        throw;
      } catch (const std::exception& e) {
        if (side_by_side && stability) {
          std::fprintf(stderr,
                       "run: the DDA stage failed (%s); the run stops once the stability "
                       "analyses beside it end\n",
                       e.what());
        }
        throw;
      }
    };
    if (plan.dda && side_by_side) dda_run = std::async(std::launch::async, ddaRun);
    if (plan.dda && !side_by_side) recordDdaStage(ctx, ddaRun());
    std::optional<StabilityRuns> stability_runs;
    std::exception_ptr stability_error;
    try {
      if (stability) {
        stability_runs = computeStability(plan, dda_scene, *stability_model, side_by_side);
      }
    } catch (...) {
      stability_error = std::current_exception();
    }
    if (plan.dda && side_by_side) recordDdaStage(ctx, dda_run.get());
    if (stability_error) std::rethrow_exception(stability_error);
    if (stability) recordStability(ctx, *stability_runs, glued, dda_scene);
  }
  writes.wait(ctx);
  finishRun(ctx);
  return 0;
}

Command addRunCommand(CLI::App& app) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* cli = app.add_subcommand(
      "run",
      "Run every stage the scene's analysis section names (DFN, blocks, RQD, DDA, overload, "
      "strength reduction), the section and the figures");
  addCommonOptions(*cli, options->common);
  cli->add_flag("--quick", options->quick,
                "Smaller domain (structure footprint, top sixth of the depth), at most 10 DDA "
                "steps, 200 RQD ball directions, 20 grid axes");
  addCutterOption(*cli, options->cutter);
  cli->add_option("--section", options->section,
                  "Section plane AXIS=VALUE, e.g. y=10 (default: the domain's mid-plane "
                  "normal to the structure's sweep axis), or none");
  cli->add_option("--solver", options->solver, "DDA linear solver: auto, cholmod, eigen, pcg")
      ->check(CLI::IsMember({"auto", "cholmod", "eigen", "pcg"}));
  cli->add_flag("--no-figures", options->no_figures, "Do not draw the PNG figures");
  cli->add_option("--figure-scripts", options->figure_scripts,
                  "Folder of make_figures.py (default: the source tree's scripts/figures)");
  cli->add_option("--python", options->python,
                  "Python interpreter with matplotlib for the figures (default /usr/bin/python3)");
  return {cli, [options] { return runScene(*options, loadScene(options->common)); }};
}

}  // namespace rockmass::app
