// rockmass rqd: RQD balls, virtual boreholes, the calibration of the fracture intensity
// against measured logs and the RQD/P32 volume (rqd.vdb), from the scene's analysis.rqd section.
#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/command.h"
#include "app/stages.h"
#include "geometry/progress.h"
#include "io/atomic_file.h"
#include "io/borehole_file.h"
#include "io/input_error.h"
#include "io/rqd_output.h"
#include "io/rqd_vdb.h"
#include "io/summary.h"
#include "rqd/ball_mesh.h"
#include "rqd/borehole.h"
#include "rqd/calibration.h"
#include "rqd/embree_scene.h"
#include "rqd/rqd_ball.h"
#include "rqd/rqd_volume.h"

namespace rockmass::app {

namespace fs = std::filesystem;

namespace {

/// Options of `rockmass rqd`: the common ones and the overrides of analysis.rqd.
struct RqdOptions {
  CommonOptions common;
  RqdOverrides overrides;
};

/// The scene's analysis.rqd with the command-line overrides applied and checked.
io::RqdAnalysis rqdSettings(const io::Scene& scene, const RqdOverrides& options,
                            const std::string& file) {
  if (!scene.analysis.rqd) {
    throw io::InputError(file +
                         ": analysis.rqd: missing; the rqd command needs it (balls, "
                         "boreholes)");
  }
  io::RqdAnalysis rqd = *scene.analysis.rqd;
  if (options.thresholds) {
    const std::vector<double>& t = *options.thresholds;
    if (t.empty()) throw io::InputError("--thresholds: expected a non-empty list of numbers");
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (!(t[i] > 0.0) || (i > 0 && !(t[i] > t[i - 1]))) {
        throw io::InputError("--thresholds: expected increasing numbers > 0 (m), got " +
                             io::formatDouble(t[i]) + " at position " + std::to_string(i + 1));
      }
    }
    rqd.thresholds = t;
  }
  if (options.directions) {
    if (*options.directions < 4) {
      throw io::InputError("--directions: expected an integer >= 4, got " +
                           std::to_string(*options.directions));
    }
    for (io::RqdBall& ball : rqd.balls) ball.directions = *options.directions;
  }
  if (options.radius) {
    if (!(*options.radius > 0.0)) throw io::InputError("--ball-radius: expected a number > 0 (m)");
    for (io::RqdBall& ball : rqd.balls) ball.radius = options.radius;
  }
  if (options.merge_distance) {
    if (!(*options.merge_distance >= 0.0)) {
      throw io::InputError("--merge-distance: expected a number >= 0 (m)");
    }
    rqd.merge_distance = *options.merge_distance;
  }
  const geometry::Box& domain = scene.dfn.domain;
  for (const io::RqdBall& ball : rqd.balls) {
    if (!((ball.center.array() > domain.min.array()).all() &&
          (ball.center.array() < domain.max.array()).all())) {
      throw io::InputError(file + ": analysis.rqd.balls: the centre of ball '" + ball.name +
                           "' must lie strictly inside the domain box");
    }
  }
  if (options.no_grid) {
    rqd.grid_spacing.reset();
  } else if (options.grid_spacing) {
    if (!(*options.grid_spacing > 0.0)) {
      throw io::InputError("--grid-spacing: expected a number > 0 (m), got " +
                           io::formatDouble(*options.grid_spacing));
    }
    rqd.grid_spacing = options.grid_spacing;
  }
  if (rqd.balls.empty() && rqd.boreholes_file.empty() && !rqd.grid_spacing) {
    throw io::InputError(file +
                         ": analysis.rqd: nothing to compute; give balls, boreholes or a grid");
  }
  if (options.grid_directions) {
    if (*options.grid_directions < 1) {
      throw io::InputError("--grid-directions: expected an integer >= 1, got " +
                           std::to_string(*options.grid_directions));
    }
    rqd.grid_direction_count = *options.grid_directions;
  }
  return rqd;
}

/// The RQD/P32 volume asked for by `settings` (which must have a grid spacing).
rqd::VolumeSpec volumeSpec(const io::Scene& scene, const io::RqdAnalysis& settings) {
  rqd::VolumeSpec spec;
  spec.region = settings.grid_region.value_or(scene.dfn.domain);
  spec.cell_size = *settings.grid_spacing;
  spec.scanline_length = settings.grid_length.value_or(2.0 * settings.thresholds.back());
  spec.direction_count = settings.grid_direction_count;
  spec.thresholds = settings.thresholds;
  spec.merge_distance = settings.merge_distance;
  return spec;
}

/// A volume spec the library rejects, as bad input in the scene's analysis.rqd.grid.
io::InputError gridError(const std::string& scene_path, const std::invalid_argument& error) {
  return io::InputError(scene_path + ": analysis.rqd.grid: " + error.what());
}

/// Computes the RQD/P32 volume, reporting progress on stderr at most once a second.
rqd::RqdVolume computeGrid(const rqd::ScanlineScene& ray_scene,
                           const geometry::FractureNetwork& network, const rqd::VolumeSpec& spec,
                           const std::string& scene_path) {
  const auto start = Clock::now();
  Progress cells("rqd: grid", 1.0, "", 10.0);
  cells.setQuietPeriod(2.0);  // a grid of seconds says nothing (the summary line follows)
  const auto progress = [&](double fraction) { cells.update(fraction); };
  try {
    rqd::RqdVolume volume = rqd::computeRqdVolume(ray_scene, network, spec, progress);
    std::fprintf(stderr,
                 "rqd: grid: %lld cells of %g m x %d directions x %zu thresholds (%.2f s)\n",
                 static_cast<long long>(volume.grid.cellCount()), spec.cell_size,
                 spec.direction_count, spec.thresholds.size(), secondsSince(start));
    return volume;
  } catch (const std::invalid_argument& error) {
    throw gridError(scene_path, error);
  }
}

/// Evaluates every ball of the scene.
std::vector<io::BallReport> evaluateBalls(const rqd::ScanlineScene& scene,
                                          const io::Scene& scene_file,
                                          const io::RqdAnalysis& settings) {
  std::vector<io::BallReport> reports;
  for (const io::RqdBall& ball : settings.balls) {
    const auto start = Clock::now();
    io::BallReport report;
    report.name = ball.name;
    report.spec = {ball.center, ball.length, ball.directions, scene_file.dfn.domain};
    report.radius = ball.radius.value_or(0.5 * ball.length);
    // Quiet for 2 s: a ball of 0.01 s printed ten lines of "about 0 s left".
    SharedProgress progress("rqd: ball " + ball.name, "scanlines", 10.0, /*quiet=*/2.0);
    report.result =
        rqd::evaluateBall(scene, report.spec, settings.thresholds, settings.merge_distance,
                          [&](std::size_t done, std::size_t total) { progress(done, total); });
    for (std::size_t k = 0; k < settings.thresholds.size(); ++k) {
      report.shapes.push_back(rqd::ballShape(report.result.directions, report.result.column(k)));
    }
    std::fprintf(stderr, "rqd: ball %s: %d directions x %zu thresholds (%.2f s)\n",
                 ball.name.c_str(), ball.directions, settings.thresholds.size(),
                 secondsSince(start));
    reports.push_back(std::move(report));
  }
  return reports;
}

/// The holes and the measured log of the scene, read and checked (before any work is done).
/// With `hole_domain` (run --quick), the holes are read against that larger domain and then
/// cut where they leave the scene's domain: a hole whose collar lies outside is dropped,
/// and so are the measured intervals that reach beyond the cut.
io::BoreholeReport readBoreholeFiles(const io::Scene& scene, const io::RqdAnalysis& settings,
                                     const std::optional<geometry::Box>& hole_domain) {
  io::BoreholeReport report;
  report.holes = io::readBoreholes(settings.boreholes_file, hole_domain.value_or(scene.dfn.domain));
  if (!settings.measured_file.empty()) {
    report.measured = io::readMeasuredLog(settings.measured_file, report.holes);
    report.measured_file = settings.measured_file.filename().string();
    report.measured_threshold = settings.measured_threshold;
  }
  if (!hole_domain) return report;
  const geometry::Box& box = scene.dfn.domain;
  std::vector<rqd::Borehole> kept;
  std::vector<int> index(report.holes.size(), -1);
  for (std::size_t h = 0; h < report.holes.size(); ++h) {
    rqd::Borehole hole = report.holes[h];
    if (!box.contains(hole.collar)) continue;
    const geometry::Vec3 d = hole.direction();
    double inside = hole.length;  // distance to the box's exit along the hole
    for (int axis = 0; axis < 3; ++axis) {
      if (d[axis] > 0.0) inside = std::min(inside, (box.max[axis] - hole.collar[axis]) / d[axis]);
      if (d[axis] < 0.0) inside = std::min(inside, (box.min[axis] - hole.collar[axis]) / d[axis]);
    }
    if (!(inside > settings.run_length)) continue;  // not even one full core run left
    hole.length = inside;
    index[h] = static_cast<int>(kept.size());
    kept.push_back(hole);
  }
  std::vector<rqd::LoggedInterval> measured;
  for (rqd::LoggedInterval entry : report.measured) {
    const int h = index[static_cast<std::size_t>(entry.hole)];
    if (h < 0 || entry.interval.to > kept[static_cast<std::size_t>(h)].length) continue;
    entry.hole = h;
    measured.push_back(entry);
  }
  report.holes = std::move(kept);
  report.measured = std::move(measured);
  return report;
}

/// Simulated logs of the holes, and their error against the measured log if there is one.
void evaluateBoreholes(const rqd::ScanlineScene& scene, const io::RqdAnalysis& settings,
                       io::BoreholeReport& report) {
  report.thresholds = settings.thresholds;
  std::vector<std::vector<double>> hits;
  for (const rqd::Borehole& hole : report.holes) {
    hits.push_back(rqd::boreholeHits(scene, hole));
    report.runs.push_back(rqd::coreRuns(hole.length, settings.run_length));
    report.run_rqd.push_back(rqd::intervalsRqd(hits.back(), hole.length, report.runs.back(),
                                               settings.thresholds, settings.merge_distance));
    const rqd::DepthInterval whole{0.0, hole.length};
    report.hole_rqd.push_back(rqd::intervalsRqd(hits.back(), hole.length, {&whole, 1},
                                                settings.thresholds, settings.merge_distance));
  }
  if (!report.measured.empty()) {
    const double threshold[] = {settings.measured_threshold};
    for (const rqd::LoggedInterval& entry : report.measured) {
      const auto h = static_cast<std::size_t>(entry.hole);
      report.simulated.push_back(rqd::intervalsRqd(hits[h], report.holes[h].length,
                                                   {&entry.interval, 1}, threshold,
                                                   settings.merge_distance)[0]);
    }
  }
  std::fprintf(stderr, "rqd: %zu boreholes%s\n", report.holes.size(),
               report.measured.empty() ? "" : ", compared with the measured log");
}

/// Calibrates the intensity multiplier of the scene's set group (see rqd/calibration.h).
io::CalibrationReport calibrate(const io::Scene& scene, const io::RqdAnalysis& settings,
                                const io::BoreholeReport& boreholes, rqd::DiscForm form,
                                int segments, const std::string& scene_path) {
  const io::RqdCalibration& c = *settings.calibration;
  io::CalibrationReport report;
  for (const int set : c.sets) report.sets.push_back(scene.dfn.joint_sets[set].name);
  report.settings = {.min_multiplier = c.min_multiplier,
                     .max_multiplier = c.max_multiplier,
                     .threshold = settings.measured_threshold,
                     .tolerance = c.tolerance,
                     .max_evaluations = c.max_evaluations,
                     .merge_distance = settings.merge_distance};
  io::Scene scaled = scene;
  scaled.dfn = rqd::scaleIntensity(scene.dfn, c.sets, c.max_multiplier);
  const geometry::FractureNetwork network = generateNetwork(scaled, scene_path);
  report.discs_at_max = network.discs.size();
  // Joint sets come first in the network, in scene order: set index = joint set index.
  const rqd::ScanlineScene ray_scene(network, form, segments);
  const std::vector<rqd::ThinnedHole> holes =
      rqd::thinnedHoles(ray_scene, network, boreholes.holes, c.sets, scene.seed, c.max_multiplier);
  report.result = rqd::calibrateMultiplier(holes, boreholes.measured, report.settings);
  std::fprintf(stderr,
               "rqd: calibration: multiplier %.4g, bias %.3g, rms %.3g (%d evaluations%s)\n",
               report.result.multiplier, report.result.error.bias, report.result.error.rms,
               report.result.evaluations,
               report.result.bracketed ? "" : "; not bracketed, best end of the range");
  return report;
}

}  // namespace

RqdPlan planRqd(const io::Scene& scene, const RqdOverrides& overrides,
                const std::string& scene_path) {
  RqdPlan plan;
  plan.settings = rqdSettings(scene, overrides, scene_path);
  if (!plan.settings.boreholes_file.empty()) {
    plan.boreholes = readBoreholeFiles(scene, plan.settings, overrides.hole_domain);
  }
  if (plan.settings.grid_spacing) {
    plan.grid = volumeSpec(scene, plan.settings);
    try {  // before any work: a bad grid fails at once
      rqd::validateVolumeSpec(*plan.grid, scene.dfn.domain);
    } catch (const std::invalid_argument& error) {
      throw gridError(scene_path, error);
    }
  }
  return plan;
}

RqdStage runRqdStage(const io::Scene& scene, const std::string& scene_path,
                     const geometry::FractureNetwork& network, RqdPlan plan,
                     const RqdOverrides& overrides) {
  const io::RqdAnalysis& settings = plan.settings;
  const rqd::DiscForm form =
      overrides.form == "triangulated" ? rqd::DiscForm::Triangulated : rqd::DiscForm::ExactEllipse;
  RqdStage stage;
  auto start = Clock::now();
  io::RqdReport& report = stage.report;
  report.discs = network.discs.size();
  report.form = overrides.form;
  report.segments = overrides.segments;
  report.merge_distance = settings.merge_distance;
  report.thresholds = settings.thresholds;
  const rqd::ScanlineScene ray_scene(network, form, overrides.segments);
  report.balls = evaluateBalls(ray_scene, scene, settings);
  if (plan.boreholes) {
    evaluateBoreholes(ray_scene, settings, *plan.boreholes);
    report.boreholes = std::move(plan.boreholes);
  }
  stage.stages.push_back("rqd");
  stage.timings.emplace_back("rqd", secondsSince(start));
  if (settings.calibration) {
    start = Clock::now();
    report.calibration =
        calibrate(scene, settings, *report.boreholes, form, overrides.segments, scene_path);
    stage.stages.push_back("calibration");
    stage.timings.emplace_back("calibration", secondsSince(start));
  }
  if (plan.grid) {
    start = Clock::now();
    report.grid = computeGrid(ray_scene, network, *plan.grid, scene_path);
    stage.stages.push_back("grid");
    stage.timings.emplace_back("grid", secondsSince(start));
  }
  return stage;
}

void writeRqdFiles(const fs::path& out, const io::RqdReport& report) {
  if (!report.balls.empty()) {
    io::writeFileAtomically(out / "rqd_balls.csv", io::formatRqdBallsCsv(report.balls));
    std::map<int, std::vector<std::array<int, 3>>> triangles;  // per direction count
    for (const io::BallReport& ball : report.balls) {
      auto [it, fresh] = triangles.try_emplace(ball.spec.directions);
      if (fresh) it->second = rqd::sphereTriangles(ball.result.directions);
      for (std::size_t k = 0; k < ball.result.thresholds.size(); ++k) {
        io::writeFileAtomically(out / io::ballPlyName(ball.name, ball.result.thresholds[k]),
                                io::formatBallPly(ball, k, it->second));
      }
    }
  }
  if (report.boreholes) {
    io::writeFileAtomically(out / "boreholes.csv", io::formatBoreholesCsv(*report.boreholes));
  }
  if (report.grid) io::writeRqdVdb(out / "rqd.vdb", *report.grid);
}

namespace {

int runRqd(const RqdOptions& options) {
  const io::Scene scene = loadScene(options.common);
  RqdPlan plan = planRqd(scene, options.overrides, options.common.scene);
  const fs::path out = prepareOutput(options.common.output);

  auto start = Clock::now();
  const geometry::FractureNetwork network = generateNetwork(scene, options.common.scene);
  const double dfn_seconds = secondsSince(start);
  std::fprintf(stderr, "rqd: %zu discs (%.2f s)\n", network.discs.size(), dfn_seconds);

  RqdStage stage =
      runRqdStage(scene, options.common.scene, network, std::move(plan), options.overrides);
  io::RunInfo run;
  run.command = "rqd";
  run.scene = options.common.scene;
  run.name = scene.name;
  run.seed = scene.seed;
  run.stages = {"dfn"};
  run.stages.insert(run.stages.end(), stage.stages.begin(), stage.stages.end());
  run.timings = {{"dfn", dfn_seconds}};
  run.timings.insert(run.timings.end(), stage.timings.begin(), stage.timings.end());

  start = Clock::now();
  writeRqdFiles(out, stage.report);
  run.timings.emplace_back("write", secondsSince(start));
  io::writeFileAtomically(out / "summary.json", io::formatRqdSummary(run, stage.report));
  std::fprintf(stderr, "rqd: wrote %s\n", out.string().c_str());
  return 0;
}

}  // namespace

Command addRqdCommand(CLI::App& app) {
  auto options = std::make_shared<RqdOptions>();
  CLI::App* cli = app.add_subcommand(
      "rqd",
      "RQD balls, virtual boreholes, intensity calibration and RQD/P32 volume (analysis.rqd)");
  addCommonOptions(*cli, options->common);
  cli->add_option("--directions", options->overrides.directions,
                  "Directions of every RQD ball (overrides balls[].directions, >= 4)");
  cli->add_option("--thresholds", options->overrides.thresholds,
                  "RQD thresholds in m, increasing, comma-separated (overrides thresholds)")
      ->delimiter(',');
  cli->add_option("--form", options->overrides.form, "Disc form for ray casting")
      ->check(CLI::IsMember({"exact", "triangulated"}));
  cli->add_option("--segments", options->overrides.segments,
                  "Fan segments per disc (triangulated form)")
      ->check(CLI::Range(3, 1024));
  cli->add_option("--ball-radius", options->overrides.radius,
                  "Surface radius at RQD 100 of every ball, m (default: half its length)");
  cli->add_option("--merge-distance", options->overrides.merge_distance,
                  "Hits closer than this are one fracture, m (default 0.001)");
  CLI::Option* grid_spacing =
      cli->add_option("--grid-spacing", options->overrides.grid_spacing,
                      "Cell size of the RQD/P32 volume rqd.vdb, m (overrides grid.spacing; adds "
                      "a grid over the domain when the scene has none)");
  cli->add_option("--grid-directions", options->overrides.grid_directions,
                  "Scanline axes per cell of the RQD/P32 volume (overrides grid.direction_count)")
      ->check(CLI::PositiveNumber);
  cli->add_flag("--no-grid", options->overrides.no_grid,
                "Skip the RQD/P32 volume even if the scene has analysis.rqd.grid")
      ->excludes(grid_spacing);
  return {cli, [options] { return runRqd(*options); }};
}

}  // namespace rockmass::app
