#include "io/scene_sections.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

#include "io/fab.h"
#include "rqd/cell_grid.h"

namespace rockmass::io::scene_detail {

// ---------------------------------------------------------------------------------------------
// Readers that need nothing but their node
// ---------------------------------------------------------------------------------------------

/// The names of kDistributionKinds as written in scenes.
std::vector<std::string> distributionNames() {
  std::vector<std::string> names;
  for (DistributionKind kind : kDistributionKinds) {
    names.emplace_back(geometry::distributionName(kind));
  }
  return names;
}

/// The optional bounds `min_key` and `max_key` of the map m; max must exceed min when both are
/// given (distribution truncation, plan regions).
std::pair<std::optional<double>, std::optional<double>> readBounds(const Cursor& m,
                                                                   const std::string& min_key,
                                                                   const std::string& max_key) {
  const std::optional<double> min =
      m.valueOr(min_key, std::optional<double>{}, [](const Cursor& v) { return v.number(); });
  const std::string context = "(" + max_key + " must exceed " + min_key + ")";
  const std::optional<double> max =
      m.valueOr(max_key, std::optional<double>{},
                [&](const Cursor& v) { return min ? v.number(above(*min), context) : v.number(); });
  return {min, max};
}

/// Mean and std of a uniform distribution: from {mean, std}, or from {min, max}.
void readUniformMoments(const Cursor& m, DistributionSpec& spec) {
  if (m.has("mean") || m.has("std")) {
    spec.mean = m.at("mean").number();
    spec.std = m.at("std").number(kPositive, "for a uniform distribution");
    return;
  }
  const auto [min, max] = readBounds(m, "min", "max");
  if (!min || !max) m.fail("a uniform distribution needs min and max, or mean and std");
  spec.mean = 0.5 * (*min + *max);
  spec.std = (*max - *min) / std::sqrt(12.0);
}

/// A distribution map {distribution, mean, std, min, max}, validated by geometry::Distribution.
geometry::Distribution readDistribution(const Cursor& c) {
  const Cursor m = c.map({"distribution", "mean", "std", "min", "max"});
  DistributionSpec spec;
  spec.kind = kDistributionKinds[m.at("distribution").choice("distribution", distributionNames())];
  const std::string context =
      std::string("for a ") + geometry::distributionName(spec.kind) + " distribution";
  switch (spec.kind) {
    case DistributionKind::Normal:
      spec.mean = m.at("mean").number();
      spec.std = m.at("std").number(kPositive, context);
      break;
    case DistributionKind::Lognormal:
      spec.mean = m.at("mean").number(kPositive, context);
      spec.std = m.at("std").number(kPositive, context);
      break;
    case DistributionKind::Uniform:
      readUniformMoments(m, spec);
      break;
    case DistributionKind::Exponential:
      if (m.has("std")) m.at("std").fail("exponential takes only mean (its std equals its mean)");
      spec.mean = m.at("mean").number(kPositive, context);
      spec.std = spec.mean;
      break;
    case DistributionKind::Constant:
      for (const char* key : {"std", "min", "max"}) {
        if (m.has(key)) m.at(key).fail("a constant takes only mean");
      }
      spec.mean = m.at("mean").number();
      break;
  }
  std::tie(spec.min, spec.max) = readBounds(m, "min", "max");
  try {
    return geometry::Distribution(spec);
  } catch (const std::invalid_argument& error) {
    m.fail(error.what());
  }
}

/// Fails unless a trace length distribution gives only values > 0, with a mean of at least
/// kShortestLength.
void checkTraceLength(const Cursor& c, const geometry::Distribution& distribution) {
  const DistributionSpec& spec = distribution.spec();
  if (spec.kind == DistributionKind::Normal && !(spec.min && *spec.min > 0)) {
    c.fail("a normal trace length can be negative; give min > 0");
  }
  const bool positive =
      spec.kind == DistributionKind::Constant ? spec.mean > 0 : distribution.lower() >= 0;
  if (!positive) {
    c.fail("expected only values > 0 for a trace length, but the distribution reaches " +
           formatDouble(distribution.lower()));
  }
  // Below a micrometre the discs' count (P32 over a disc's area) overflows: a mean of 5e-324
  // asked for NaN discs.
  if (!(spec.mean >= kShortestLength)) {
    c.get("mean").value_or(c).fail(
        "expected a mean trace length >= " + formatDouble(kShortestLength) + " m, got " +
        formatDouble(spec.mean));
  }
}

/// A spacing distribution: its mean (which sets P10) must be > 0.
DistributionSpec readSpacing(const Cursor& c) {
  const DistributionSpec spec = readDistribution(c).spec();
  if (spec.mean <= 0) {
    c.get("mean").value_or(c).fail("expected a mean > 0 for a spacing, got " +
                                   formatDouble(spec.mean));
  }
  if (spec.mean < kShortestLength) {
    c.get("mean").value_or(c).fail("expected a mean spacing >= " + formatDouble(kShortestLength) +
                                   " m, got " + formatDouble(spec.mean));
  }
  return spec;
}

/// Orientation of a joint set: dip_direction and dip distributions, or a Fisher `orientation`.
geometry::OrientationSpec readOrientation(const Cursor& set) {
  const bool independent = set.has("dip_direction") || set.has("dip");
  geometry::OrientationSpec orientation;
  if (independent && set.has("orientation")) {
    set.fail("give either 'orientation' or 'dip_direction' and 'dip', not both");
  }
  if (independent) {
    orientation.dip_direction = readDistribution(set.at("dip_direction")).spec();
    orientation.dip = readDistribution(set.at("dip")).spec();
    return orientation;
  }
  if (!set.has("orientation")) {
    set.fail("expected an orientation: 'dip_direction' and 'dip' distributions, or 'orientation'");
  }
  const Cursor m = set.at("orientation").map({"distribution", "dip_direction", "dip", "kappa"});
  m.at("distribution").choice("orientation distribution", {"fisher"});
  orientation.fisher = true;
  orientation.fisher_dip_direction = m.at("dip_direction").number(closed(0, 360));
  orientation.fisher_dip = m.at("dip").number(closed(0, 90));
  orientation.kappa = m.at("kappa").number(kPositive);
  return orientation;
}

/// shape: {aspect_ratio, major_axis: strike | dip | {rake}}.
geometry::ShapeSpec readShape(const Cursor& c) {
  const Cursor m = c.map({"aspect_ratio", "major_axis"});
  geometry::ShapeSpec shape;
  shape.aspect_ratio = m.numberOr("aspect_ratio", 1.0, {.low = 0, .high = 1, .low_open = true});
  if (const std::optional<Cursor> axis = m.get("major_axis")) {
    if (axis->isMap()) {
      shape.major_axis = geometry::MajorAxis::Rake;
      shape.rake = axis->map({"rake"}).at("rake").number(closed(-90, 90));
    } else {
      constexpr std::array kAxes{geometry::MajorAxis::Strike, geometry::MajorAxis::Dip};
      shape.major_axis = kAxes[axis->choice("major axis", {"strike", "dip"})];
    }
  }
  return shape;
}

/// The strength of a joint: `joints` entries and inline structure joints.
Joint readJoint(const Cursor& c, std::string name) {
  const Cursor m = c.map({"friction", "friction_angle", "cohesion", "tensile_strength", "model"});
  Joint joint;
  joint.name = std::move(name);
  if (m.oneOf("friction", "friction_angle") == 0) {
    joint.friction = m.at("friction").number(kNonNegative);
  } else {
    const double angle = m.at("friction_angle").number({.low = 0, .high = 90, .high_open = true});
    joint.friction = std::tan(angle * std::numbers::pi / 180.0);
  }
  joint.cohesion = m.numberOr("cohesion", 0.0, kNonNegative);
  joint.tensile_strength = m.numberOr("tensile_strength", 0.0, kNonNegative);
  joint.brittle = m.valueOr("model", joint.brittle, [](const Cursor& v) {
    return v.choice("joint model", {"plastic", "brittle"}) == 1;
  });
  return joint;
}

/// A polyline of at least `min_points` [a, b] points with no zero-length segment.
std::vector<Vec2> readProfile(const Cursor& c, std::size_t min_points) {
  const std::vector<Cursor> items = c.items();
  if (items.size() < min_points) {
    c.fail("expected a list of at least " + std::to_string(min_points) + " points [a, b], got " +
           std::to_string(items.size()));
  }
  std::vector<Vec2> profile;
  for (const Cursor& item : items) {
    profile.push_back(item.vec2());
    if (profile.size() > 1 && profile.back() == profile[profile.size() - 2]) {
      item.fail("zero-length segment: this point repeats the previous one");
    }
  }
  return profile;
}

/// A sweep axis: 'x' or 'y'.
char readSweep(const Cursor& c) {
  return c.choice("sweep axis", {"x", "y"}) == 0 ? 'x' : 'y';
}

/// A direction vector that is not zero.
Vec3 readDirection(const Cursor& c) {
  const Vec3 direction = c.vec3();
  if (direction.isZero(0.0)) c.fail("expected a nonzero vector");
  return direction;
}

/// region: {x_min, x_max, y_min, y_max}, each optional; a max must exceed its min.
Region readRegion(const Cursor& c) {
  const Cursor m = c.map({"x_min", "x_max", "y_min", "y_max"});
  Region region;
  std::tie(region.x_min, region.x_max) = readBounds(m, "x_min", "x_max");
  std::tie(region.y_min, region.y_max) = readBounds(m, "y_min", "y_max");
  return region;
}

/// A point load {point, force}.
PointLoad readPointLoad(const Cursor& c) {
  const Cursor m = c.map({"point", "force"});
  return {m.at("point").vec3(), m.at("force").vec3()};
}

/// analysis.blocks
BlocksAnalysis readBlocksAnalysis(const Cursor& c) {
  const Cursor m = c.map({"cutter", "disc_segments"});
  BlocksAnalysis blocks;
  constexpr std::array kCutters{BlocksAnalysis::Cutter::Exact, BlocksAnalysis::Cutter::Fast};
  blocks.cutter = m.valueOr("cutter", blocks.cutter, [&](const Cursor& v) {
    return kCutters[v.choice("cutter", {"exact", "fast"})];
  });
  // At 1024 segments the polygon is within 5e-6 of its radius from the ellipse (1 - cos(pi /
  // 1024)); more only costs memory (2^31 ran out of it).
  blocks.disc_segments = m.integerOr("disc_segments", blocks.disc_segments, closed(3, 1024));
  return blocks;
}

/// A box {min, max} with min < max in every component (m).
geometry::Box readBox(const Cursor& c) {
  const Cursor box = c.map({"min", "max"});
  const geometry::Box read{box.at("min").vec3(), box.at("max").vec3()};
  for (int axis = 0; axis < 3; ++axis) {
    if (!(read.min[axis] < read.max[axis])) {
      box.fail("expected min < max in every component, got " + formatDouble(read.min[axis]) +
               " >= " + formatDouble(read.max[axis]) + " in " + "xyz"[axis]);
    }
  }
  return read;
}

/// analysis.rqd.boreholes.calibration; `joint_sets` names the joint sets in order.
RqdCalibration readRqdCalibration(const Cursor& c, const std::vector<std::string>& joint_sets) {
  const Cursor m = c.map({"sets", "range", "tolerance", "max_evaluations"});
  RqdCalibration calibration;
  if (const auto sets = m.get("sets")) {
    const std::vector<Cursor> items = sets->items();
    if (items.empty()) sets->failExpected("a non-empty list of joint set names");
    for (const Cursor& item : items) {
      const int index = lookupName(item, joint_sets, "joint set");
      if (std::find(calibration.sets.begin(), calibration.sets.end(), index) !=
          calibration.sets.end()) {
        item.fail("joint set '" + item.string() + "' is listed twice");
      }
      calibration.sets.push_back(index);
    }
  } else {
    for (int i = 0; i < static_cast<int>(joint_sets.size()); ++i) calibration.sets.push_back(i);
    if (joint_sets.empty()) m.fail("calibration needs at least one joint set in the scene");
  }
  if (const auto range = m.get("range")) {
    const std::vector<double> bounds = range->increasingNumbers(kPositive);
    if (bounds.size() != 2) range->failExpected("a list of 2 increasing numbers > 0");
    calibration.min_multiplier = bounds[0];
    calibration.max_multiplier = bounds[1];
  }
  calibration.tolerance = m.numberOr("tolerance", calibration.tolerance, kPositive);
  calibration.max_evaluations =
      m.integerOr("max_evaluations", calibration.max_evaluations, atLeast(2));
  return calibration;
}

/// analysis.rqd; `joint_sets` names the joint sets in order; the grid fills its region or
/// the domain box (unless the domain is a mesh).
RqdAnalysis readRqdAnalysis(const Cursor& c, const std::vector<std::string>& joint_sets,
                            const geometry::Box& domain, bool mesh_domain) {
  const Cursor m = c.map({"thresholds", "balls", "boreholes", "grid", "merge_distance"});
  RqdAnalysis rqd;
  if (const auto thresholds = m.get("thresholds")) {
    rqd.thresholds = thresholds->increasingNumbers(kPositive);
  }
  rqd.merge_distance = m.numberOr("merge_distance", rqd.merge_distance, kNonNegative);
  UniqueNames ball_names;
  forEachItem(m, "balls", [&](const Cursor& item) {
    const Cursor ball = item.map({"name", "center", "length", "directions", "radius"});
    rqd.balls.push_back(
        {.name = ball_names.claimName(ball),
         .center = ball.at("center").vec3(),
         .length = ball.at("length").number(kPositive),
         .directions = ball.integerOr("directions", 2000, atLeast(4)),
         .radius = ball.valueOr("radius", std::optional<double>{}, [](const Cursor& v) {
           return std::optional(v.number(kPositive));
         })});
  });
  if (const auto holes = m.get("boreholes")) {
    holes->map({"file", "run_length", "measured", "measured_threshold", "calibration"});
    rqd.boreholes_file = holes->at("file").existingFile();
    rqd.run_length = holes->numberOr("run_length", rqd.run_length, kPositive);
    rqd.measured_file = holes->valueOr("measured", fs::path{}, &Cursor::existingFile);
    rqd.measured_threshold =
        holes->numberOr("measured_threshold", rqd.measured_threshold, kPositive);
    if (const auto calibration = holes->get("calibration")) {
      if (rqd.measured_file.empty()) {
        calibration->fail("calibration needs a measured log: give boreholes.measured");
      }
      rqd.calibration = readRqdCalibration(*calibration, joint_sets);
    }
  }
  if (const auto grid = m.get("grid")) {
    grid->map({"spacing", "direction_count", "length", "region"});
    rqd.grid_spacing = grid->at("spacing").number(kPositive);
    rqd.grid_direction_count =
        grid->integerOr("direction_count", rqd.grid_direction_count, atLeast(1));
    if (const auto length = grid->get("length")) rqd.grid_length = length->number(kPositive);
    if (const auto region = grid->get("region")) rqd.grid_region = readBox(*region);
    // The grid fills its region, or the domain box (a mesh domain's box is known later; the
    // grid builder checks it then).
    if (rqd.grid_region || !mesh_domain) {
      const geometry::Vec3 size = (rqd.grid_region ? *rqd.grid_region : domain).size();
      double cells = 1.0;
      for (int axis = 0; axis < 3; ++axis) {
        cells *= std::max(1.0, rqd::cellsAlong(size[axis], *rqd.grid_spacing));
      }
      if (cells > rqd::kMaxGridCells) {
        grid->at("spacing").fail(
            "expected a spacing that gives at most " + formatDouble(rqd::kMaxGridCells) +
            " cells in the grid's region, got " + formatDouble(*rqd.grid_spacing) + " m (" +
            formatDouble(cells) + " cells)");
      }
    }
  }
  return rqd;
}

/// analysis.dda
DdaAnalysis readDdaAnalysis(const Cursor& c, const geometry::Box& domain, bool mesh_domain) {
  const Cursor m = c.map({"mode",
                          "kinematics",
                          "steps",
                          "time_step",
                          "max_displacement_ratio",
                          "penalty",
                          "time_integration",
                          "min_block_volume",
                          "open_close_tolerance",
                          "friction_tolerance",
                          "region",
                          "min_time_step",
                          "contact_point_spacing",
                          "damage_map",
                          "settle",
                          "dynamic_ratio",
                          "biot_coefficient",
                          "glue_across_materials",
                          "surface_only",
                          "contact_search_margin",
                          "contact_hull_corners"});
  DdaAnalysis dda;
  dda3d::DdaSettings& e = dda.engine;
  e.mode = m.valueOr("mode", e.mode, [](const Cursor& v) {
    return v.choice("mode", {"dynamic", "static"}) == 0 ? dda3d::AnalysisMode::Dynamic
                                                        : dda3d::AnalysisMode::Static;
  });
  e.kinematics = m.valueOr("kinematics", e.kinematics, [](const Cursor& v) {
    return v.choice("kinematics", {"deformable", "rigid"}) == 0 ? dda3d::Kinematics::Deformable
                                                                : dda3d::Kinematics::Rigid;
  });
  // At most 1e7 steps: hours on a small model (the histories go to disk as the run goes and
  // summary.json keeps at most 1e5 step records, so memory does not grow with the steps).
  dda.steps = m.integerOr("steps", dda.steps, closed(1, 1e7));
  e.time_step = m.numberOr("time_step", e.time_step, kPositive);
  if (const auto step = m.get("time_step");
      step && !m.get("min_time_step") && e.time_step < e.min_time_step) {
    step->fail("expected a time step >= min_time_step (" + formatDouble(e.min_time_step) +
               " s; set min_time_step to go lower), got " + formatDouble(e.time_step));
  }
  if (const auto min_step = m.get("min_time_step")) {
    e.min_time_step = min_step->number(kPositive);
    if (e.min_time_step > e.time_step) {
      min_step->fail("expected a time step no larger than time_step (" + formatDouble(e.time_step) +
                     " s)");
    }
  }
  e.max_displacement_ratio = m.numberOr("max_displacement_ratio", e.max_displacement_ratio,
                                        {.low = 0, .high = 1, .low_open = true, .high_open = true});
  if (const auto penalty = m.get("penalty"); penalty && !penalty->is("auto")) {
    if (!penalty->isNumber()) penalty->failExpected("'auto' or a number > 0");
    e.penalty = penalty->number(kPositive);
  }
  dda.min_block_volume = m.numberOr("min_block_volume", dda.min_block_volume, kNonNegative);
  dda.glue_across_materials =
      m.valueOr("glue_across_materials", dda.glue_across_materials, &Cursor::boolean);
  e.open_close_tolerance = m.numberOr("open_close_tolerance", e.open_close_tolerance,
                                      {.low = 0, .high = 1, .high_open = true});
  e.friction_tolerance =
      m.numberOr("friction_tolerance", e.friction_tolerance, {.low = 0, .high = 1});
  if (const auto spacing = m.get("contact_point_spacing")) {
    e.contact_point_spacing = spacing->number(kNonNegative);
    dda.contact_point_spacing_line = spacing->line();
  }
  if (const auto region = m.get("region")) {
    if (mesh_domain) region->fail("a DDA region needs a box domain (domain.box)");
    const geometry::Box read = readBox(*region);
    for (int axis = 0; axis < 3; ++axis) {
      if (read.min[axis] < domain.min[axis] || read.max[axis] > domain.max[axis]) {
        region->fail(std::string("expected a box inside the domain box; in ") + "xyz"[axis] +
                     " the region spans " + formatDouble(read.min[axis]) + " .. " +
                     formatDouble(read.max[axis]) + ", the domain " +
                     formatDouble(domain.min[axis]) + " .. " + formatDouble(domain.max[axis]));
      }
    }
    dda.region = read;
  }
  e.dynamic_ratio = m.numberOr("dynamic_ratio", e.dynamic_ratio, {.low = 0, .high = 1});
  e.biot_coefficient = m.numberOr("biot_coefficient", e.biot_coefficient, {.low = 0, .high = 1});
  e.detection.surface_only = m.valueOr("surface_only", e.detection.surface_only, &Cursor::boolean);
  e.detection.search_margin = m.numberOr("contact_search_margin", e.detection.search_margin,
                                         {.low = 0, .high = dda3d::kMaxSearchMargin});
  e.detection.hull_corners =
      m.valueOr("contact_hull_corners", e.detection.hull_corners, &Cursor::boolean);
  if (const auto damage = m.get("damage_map")) {
    const Cursor d = damage->map({"every"});
    dda.damage_every = d.integerOr("every", std::max(1, dda.steps / 10), closed(1, 1e7));
  }
  if (const auto settle = m.get("settle")) {
    const Cursor s = settle->map({"without", "max_steps"});
    DdaAnalysis::Settle read;
    for (const std::string& load :
         s.at("without").distinctChoices("load", {"water", "seismic", "point_loads"})) {
      read.without_water |= load == "water";
      read.without_seismic |= load == "seismic";
      read.without_point_loads |= load == "point_loads";
    }
    read.max_steps = s.integerOr("max_steps", read.max_steps, closed(1, 1e6));
    dda.settle = read;
  }
  if (const auto integration = m.get("time_integration")) {
    const Cursor t = integration->map({"scheme", "spectral_radius"});
    e.integration = t.valueOr("scheme", e.integration, [](const Cursor& v) {
      return v.choice("scheme", {"bossak", "shi"}) == 0 ? dda3d::TimeIntegration::Bossak
                                                        : dda3d::TimeIntegration::Shi;
    });
    if (const auto radius = t.get("spectral_radius")) {
      // Shi's scheme has no parameter: a spectral radius with it would be silently ignored.
      if (e.integration != dda3d::TimeIntegration::Bossak)
        radius->fail("only with scheme: bossak (Shi's scheme has no parameter)");
      e.spectral_radius = radius->number({.low = 0, .high = 1});
    }
  }
  return dda;
}

/// analysis.overload
OverloadAnalysis readOverloadAnalysis(const Cursor& c) {
  const Cursor m = c.map({"factors", "scales", "tolerance", "scale_uplift"});
  OverloadAnalysis overload{.factors = m.at("factors").increasingNumbers(kPositive),
                            .scales = m.at("scales").distinctChoices(
                                "load", {"water", "gravity", "point_loads", "seismic"})};
  overload.tolerance = m.numberOr("tolerance", overload.tolerance, kNonNegative);
  overload.scale_uplift = m.valueOr("scale_uplift", overload.scale_uplift, &Cursor::boolean);
  return overload;
}

/// analysis.strength_reduction
StrengthReductionAnalysis readStrengthReductionAnalysis(const Cursor& c) {
  const Cursor m = c.map({"factors", "tolerance", "path"});
  StrengthReductionAnalysis srf{.factors = m.at("factors").increasingNumbers(kPositive)};
  srf.tolerance = m.numberOr("tolerance", srf.tolerance, kPositive);
  srf.incremental = m.valueOr("path", srf.incremental, [](const Cursor& v) {
    return v.choice("path", {"restart", "incremental"}) == 1;
  });
  return srf;
}

/// analysis.equilibrium
EquilibriumAnalysis readEquilibriumAnalysis(const Cursor& c, bool has_monitors) {
  const Cursor m = c.map({"max_steps", "unbalanced_ratio", "kinetic_ratio", "settle_steps",
                          "dynamic_ratio", "start", "start_steps", "failure_ratio", "failure_steps",
                          "steady_steps", "steady_spread", "drift_steps", "watch"});
  EquilibriumAnalysis e;
  if (const auto watch = m.get("watch")) {
    e.watch_monitors = watch->choice("watch", {"all", "monitors"}) == 1;
    if (e.watch_monitors && !has_monitors) {
      watch->fail("`monitors` needs a `monitors` list in the scene (the blocks it watches)");
    }
    e.watch_line = watch->line();
  }
  e.settled_start = m.valueOr("start", e.settled_start, [](const Cursor& v) {
    return v.choice("start", {"unloaded", "settled"}) == 1;
  });
  if (const auto steps = m.get("max_steps")) e.max_steps = steps->integer(above(0));
  if (const auto steps = m.get("start_steps")) {
    e.start_steps = steps->integer(above(0));
    // A limit for a run that never happens would be silently ignored.
    if (!e.settled_start) {
      steps->fail(
          "the step limit of the settled start: it needs `start: settled` (every run "
          "starts unloaded here)");
    }
  }
  e.unbalanced_ratio = m.numberOr("unbalanced_ratio", e.unbalanced_ratio, kPositive);
  e.kinetic_ratio = m.numberOr("kinetic_ratio", e.kinetic_ratio, kPositive);
  e.failure_ratio = m.numberOr("failure_ratio", e.failure_ratio, kNonNegative);
  e.failure_steps = m.integerOr("failure_steps", e.failure_steps, above(0));
  if (const auto steps = m.get("steady_steps")) {
    e.steady_steps = steps->integer(kNonNegative);
    // One step has no trend: every step that is not calm would stop the run.
    if (e.steady_steps == 1) steps->fail("0 (no steady-motion stop) or at least 2 steps");
  }
  e.steady_spread = m.numberOr("steady_spread", e.steady_spread,
                               {.low = 0, .high = 1, .low_open = true, .high_open = true});
  if (const auto steps = m.get("drift_steps")) {
    e.drift_steps = steps->integer(kNonNegative);
    // The rule compares the window's two halves: fewer than 2 steps each have no trend.
    if (e.drift_steps > 0 && e.drift_steps < 4) {
      steps->fail("0 (no drift stop) or at least 4 steps");
    }
  }
  e.settle_steps = m.integerOr("settle_steps", e.settle_steps, above(0));
  e.dynamic_ratio = m.numberOr("dynamic_ratio", e.dynamic_ratio,
                               {.low = 0, .high = 1, .low_open = false, .high_open = false});
  return e;
}

/// The `analysis` section: each stage present only when its key is.
Analysis readAnalysis(const Cursor& c, const std::vector<std::string>& joint_sets,
                      const geometry::Box& domain, bool mesh_domain, bool has_monitors) {
  const Cursor m = c.map({"blocks", "rqd", "dda", "overload", "strength_reduction", "equilibrium"});
  Analysis analysis;
  if (const auto v = m.get("blocks")) analysis.blocks = readBlocksAnalysis(*v);
  if (const auto v = m.get("rqd")) {
    analysis.rqd = readRqdAnalysis(*v, joint_sets, domain, mesh_domain);
  }
  if (const auto v = m.get("dda")) analysis.dda = readDdaAnalysis(*v, domain, mesh_domain);
  if (const auto v = m.get("overload")) analysis.overload = readOverloadAnalysis(*v);
  if (const auto v = m.get("strength_reduction")) {
    analysis.strength_reduction = readStrengthReductionAnalysis(*v);
  }
  if (const auto v = m.get("equilibrium"))
    analysis.equilibrium = readEquilibriumAnalysis(*v, has_monitors);
  return analysis;
}

}  // namespace rockmass::io::scene_detail
