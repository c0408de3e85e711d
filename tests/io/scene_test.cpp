#include "io/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "io/input_error.h"
#include "tests/support/test_support.h"

namespace rockmass::io {
namespace {

namespace fs = std::filesystem;

/// The message of the InputError that parsing `yaml` as "bad.yaml" throws, or "no error".
std::string errorOf(const std::string& yaml) {
  try {
    parseScene(yaml, "bad.yaml");
  } catch (const InputError& error) {
    return error.what();
  }
  return "no error";
}

/// Lines 1-2 of most malformed scenes: a valid version and domain.
const std::string valid_head =
    "version: 1\n"
    "domain: {box: {min: [0, 0, -10], max: [10, 10, 0]}}\n";

/// Line 3: two joints.
const std::string two_joints = "joints: {rock_joint: {friction: 0.8}, soft: {friction: 0.3}}\n";

/// One `joint_sets` item, 5 lines: name, dip_direction, dip, spacing (4th line) and
/// trace_length (5th line); `spacing` and `trace_length` are written after their key.
std::string jointSet(const std::string& name, const std::string& spacing,
                     const std::string& trace_length) {
  std::string item = "  - name: " + name + "\n";
  item += "    dip_direction: {distribution: normal, mean: 90, std: 10}\n";
  item += "    dip: {distribution: normal, mean: 30, std: 5}\n";
  item += "    spacing: " + spacing + "\n";
  item += "    trace_length: " + trace_length + "\n";
  return item;
}

/// Valid spacing and trace length distributions.
const std::string lognormal_spacing = "{distribution: lognormal, mean: 0.6, std: 0.8}";
const std::string lognormal_trace = "{distribution: lognormal, mean: 20, std: 10}";

/// A temporary folder, removed with everything in it at the end of the test.
class SceneFiles : public ::testing::Test {
 protected:
  /// Writes `text` to dir/name and returns the path.
  fs::path write(const std::string& name, const std::string& text) const {
    return test::writeFile(dir / name, text);
  }

  test::TempDir temp{std::string("scene_") +
                     ::testing::UnitTest::GetInstance()->current_test_info()->name()};
  const fs::path& dir = temp.path();  ///< the temporary folder of the test
};

// ----- malformed scenes: each message is checked in full -----

TEST(SceneErrors, UnknownKeySuggestsTheClosestOne) {
  EXPECT_EQ(errorOf("version: 1\n"
                    "domain:\n"
                    "  bx: {min: [0, 0, 0], max: [1, 1, 1]}\n"),
            "bad.yaml:3:3: domain: unknown key 'bx'; expected one of: box, mesh "
            "(did you mean 'box'?)");
}

TEST(SceneErrors, UnknownTopLevelKeyHasNoPath) {
  EXPECT_EQ(errorOf(valid_head + "joint_set: []\n"),
            "bad.yaml:3:1: unknown key 'joint_set'; expected one of: version, name, seed, domain, "
            "materials, rock_material, joints, default_joint, joint_sets, fractures, faults, "
            "interlayers, structures, loads, supports, monitors, bolts, bolt_patterns, analysis, "
            "uncertainty "
            "(did you mean 'joint_sets'?)");
}

TEST(SceneErrors, WrongTypes) {
  EXPECT_EQ(
      errorOf(valid_head + "materials:\n  rock: {density: 2600, young: abc, poisson: 0.25}\n"),
      "bad.yaml:4:32: materials.rock.young: expected a number, got 'abc'");
  EXPECT_EQ(
      errorOf(valid_head + "faults:\n  - {name: F1, center: [1, 2], dip_direction: 0, dip: 0}\n"),
      "bad.yaml:4:24: faults[0].center: expected a list of 3 numbers");
  EXPECT_EQ(errorOf(valid_head + "materials: [rock]\n"),
            "bad.yaml:3:12: materials: expected a map");
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  dda: {steps: 2.5}\n"),
            "bad.yaml:4:16: analysis.dda.steps: expected an integer, got '2.5'");
  EXPECT_EQ(errorOf(valid_head +
                    "loads:\n  water:\n    - {level: 10, uplift: yes, on: {domain_top: true}}\n"),
            "bad.yaml:5:27: loads.water[0].uplift: expected true or false, got 'yes'");
  // An empty value is located at its key (yaml-cpp marks it at the next token).
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  dda:\n    steps:\n  rqd: {}\n"),
            "bad.yaml:5:5: analysis.dda.steps: expected an integer, got nothing");
}

// Values that would run away (../shared/repro/bad-input/r2, r3 and the steps bomb): refused
// at their line with the allowed range, before any work.
TEST(SceneErrors, RunawayValuesAreOutOfRange) {
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  blocks: {disc_segments: 2147483647}\n"),
            "bad.yaml:4:27: analysis.blocks.disc_segments: expected an integer in [3, 1024], "
            "got 2147483647");
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  dda: {steps: 1000000000}\n"),
            "bad.yaml:4:16: analysis.dda.steps: expected an integer in [1, 1e+07], got "
            "1000000000");
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  dda: {time_step: 1e-300}\n"),
            "bad.yaml:4:20: analysis.dda.time_step: expected a time step >= min_time_step "
            "(1e-09 s; set min_time_step to go lower), got 1e-300");
}

// Strings reach the JSON summary and the VTU names: a scene that is not UTF-8 is refused at
// its first bad byte, before any output (../shared/repro/bad-input/r1_invalid_utf8_name.yaml).
TEST(SceneErrors, InvalidUtf8IsRefusedAtItsByte) {
  EXPECT_EQ(errorOf("version: 1\nname: \xC0\xAF\n"),
            "bad.yaml:2:7: invalid UTF-8 (byte 0xC0); the scene file must be UTF-8 text");
  EXPECT_EQ(errorOf(valid_head + "name: ok \xE2\x82\n"),  // truncated 3-byte sequence
            "bad.yaml:3:10: invalid UTF-8 (byte 0xE2); the scene file must be UTF-8 text");
  EXPECT_EQ(errorOf(valid_head + "name: \xED\xA0\x80\n"),  // a UTF-16 surrogate
            "bad.yaml:3:7: invalid UTF-8 (byte 0xED); the scene file must be UTF-8 text");
  // Valid multi-byte text (2, 3 and 4 bytes) is read as it is.
  EXPECT_EQ(
      parseScene(valid_head + "name: \"Xiàngjiābà 向家坝 \xF0\x9F\xAA\xA8\"\n", "ok.yaml").name,
      "Xiàngjiābà 向家坝 \xF0\x9F\xAA\xA8");
}

// An RQD grid is refused at its spacing when it would have more than 1e7 cells (the repro
// bombs/grid1e6.yaml: 4e21 cells, never finished).
TEST(SceneErrors, RqdGridOfTooManyCells) {
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  rqd:\n    grid: {spacing: 0.001}\n"),
            "bad.yaml:5:21: analysis.rqd.grid.spacing: expected a spacing that gives at most "
            "1e+07 cells in the grid's region, got 0.001 m (1e+12 cells)");
  // The same spacing in a region of 10 x 10 x 10 cm: 1e6 cells, accepted.
  EXPECT_EQ(
      parseScene(valid_head +
                     "analysis:\n  rqd:\n    grid: {spacing: 0.001, region: {min: [1, 1, -2], "
                     "max: [1.1, 1.1, -1.9]}}\n",
                 "ok.yaml")
          .analysis.rqd->grid_spacing,
      0.001);
}

// Values whose consequences overflow further on (../shared/repro/bad-input r4, r10): a domain
// of 1e-300 m edges (no volume in floating point) and a denormal trace length (NaN discs).
TEST(SceneErrors, VanishingDomainAndTraceLength) {
  EXPECT_EQ(errorOf("version: 1\ndomain: {box: {min: [0, 0, 0], max: [1e-300, 1e-300, 1e-300]}}\n"),
            "bad.yaml:2:15: domain.box: expected a box with a finite volume > 0, got 0 m3");
  EXPECT_EQ(
      errorOf(valid_head + "joint_sets:\n" +
              jointSet("J1", lognormal_spacing, "{distribution: constant, mean: 5e-324}")),
      "bad.yaml:8:50: joint_sets[0].trace_length.mean: expected a mean trace length >= 1e-06 m, "
      "got 5e-324");
  EXPECT_EQ(
      errorOf(valid_head + "joint_sets:\n" +
              jointSet("J1", "{distribution: constant, mean: 1e-300}", lognormal_trace)),
      "bad.yaml:7:45: joint_sets[0].spacing.mean: expected a mean spacing >= 1e-06 m, got 1e-300");
}

TEST(SceneErrors, NegativeSpacing) {
  EXPECT_EQ(errorOf(valid_head + "joint_sets:\n" +
                    jointSet("J1", "{distribution: normal, mean: -1, std: 0.1}", lognormal_trace)),
            "bad.yaml:7:43: joint_sets[0].spacing.mean: expected a mean > 0 for a spacing, got -1");
}

TEST(SceneErrors, LognormalStdMustBePositive) {
  EXPECT_EQ(
      errorOf(valid_head + "joint_sets:\n" +
              jointSet("J1", "{distribution: lognormal, mean: 0.6, std: -0.5}", lognormal_trace)),
      "bad.yaml:7:56: joint_sets[0].spacing.std: expected a number > 0 for a lognormal "
      "distribution, got -0.5");
}

TEST(SceneErrors, MinAboveMax) {
  EXPECT_EQ(errorOf(valid_head + "joint_sets:\n" +
                    jointSet("J1", lognormal_spacing,
                             "{distribution: lognormal, mean: 20, std: 10, min: 60, max: 50}")),
            "bad.yaml:8:78: joint_sets[0].trace_length.max: expected a number > 60 "
            "(max must exceed min), got 50");
}

TEST(SceneErrors, UnknownMaterial) {
  EXPECT_EQ(
      errorOf(valid_head + "materials: {granite: {density: 2600, young: 5e10, poisson: 0.25}}\n"
                           "rock_material: granit\n"),
      "bad.yaml:4:16: rock_material: unknown material 'granit'; defined materials: granite "
      "(did you mean 'granite'?)");
}

TEST(SceneErrors, UnknownJoint) {
  EXPECT_EQ(errorOf(valid_head + two_joints + "joint_sets:\n" +
                    jointSet("J1", lognormal_spacing, lognormal_trace) +
                    jointSet("J2", lognormal_spacing, lognormal_trace) + "    joint: rok\n"),
            "bad.yaml:15:12: joint_sets[1].joint: unknown joint 'rok'; defined joints: "
            "rock_joint, soft");
}

TEST(SceneErrors, Version2) {
  EXPECT_EQ(errorOf("version: 2\ndomain: {box: {min: [0, 0, 0], max: [1, 1, 1]}}\n"),
            "bad.yaml:1:10: version: expected format version 1, got 2");
}

TEST(SceneErrors, MissingDomain) {
  EXPECT_EQ(errorOf("version: 1\nseed: 3\n"), "bad.yaml:1:1: domain: required key is missing");
}

TEST(SceneErrors, BothBoxAndMesh) {
  EXPECT_EQ(errorOf("version: 1\ndomain:\n  box: {min: [0, 0, 0], max: [1, 1, 1]}\n"
                    "  mesh: rock.stl\n"),
            "bad.yaml:3:3: domain: give either 'box' or 'mesh', not both");
}

TEST(SceneErrors, BoxMinNotBelowMax) {
  EXPECT_EQ(errorOf("version: 1\ndomain: {box: {min: [0, 0, 5], max: [10, 10, 5]}}\n"),
            "bad.yaml:2:15: domain.box: expected min < max in every component, got 5 >= 5 in z");
}

TEST(SceneErrors, PoissonHalf) {
  EXPECT_EQ(
      errorOf(valid_head + "materials:\n  rock: {density: 2600, young: 5e10, poisson: 0.5}\n"),
      "bad.yaml:4:47: materials.rock.poisson: expected a number in (-1, 0.5), got 0.5");
}

TEST(SceneErrors, ExponentialWithStd) {
  EXPECT_EQ(
      errorOf(valid_head + "joint_sets:\n" +
              jointSet("J1", lognormal_spacing, "{distribution: exponential, mean: 20, std: 20}")),
      "bad.yaml:8:62: joint_sets[0].trace_length.std: exponential takes only mean "
      "(its std equals its mean)");
}

TEST(SceneErrors, DuplicateSetName) {
  EXPECT_EQ(
      errorOf(valid_head + "joint_sets:\n" + jointSet("J1", lognormal_spacing, lognormal_trace) +
              "faults:\n  - {name: J1, center: [0, 0, 0], dip_direction: 0, dip: 0}\n"),
      "bad.yaml:10:12: faults[0].name: name 'J1' is already used by joint_sets[0]");
}

TEST(SceneErrors, FaultWithThicknessNeedsMaterial) {
  EXPECT_EQ(errorOf(valid_head + "faults:\n  - name: F1\n    center: [5, 5, -5]\n"
                                 "    dip_direction: 90\n    dip: 60\n    thickness: 0.5\n"),
            "bad.yaml:4:5: faults[0]: a fault with thickness > 0 needs a material");
}

TEST(SceneErrors, InterlayerWithOnePoint) {
  EXPECT_EQ(errorOf(valid_head + "interlayers:\n  - {name: P1, profile: [[0, -4]], sweep: y}\n"),
            "bad.yaml:4:25: interlayers[0].profile: expected a list of at least 2 points [a, b], "
            "got 1");
}

TEST(SceneErrors, InterlayerZeroLengthSegment) {
  EXPECT_EQ(
      errorOf(valid_head + "interlayers:\n  - {name: P1, profile: [[0, -4], [0, -4]], sweep: y}\n"),
      "bad.yaml:4:35: interlayers[0].profile[1]: zero-length segment: this point repeats "
      "the previous one");
}

TEST(SceneErrors, BadSweepAxis) {
  EXPECT_EQ(errorOf(valid_head +
                    "interlayers:\n  - {name: P1, profile: [[0, -4], [10, -5]], sweep: z}\n"),
            "bad.yaml:4:53: interlayers[0].sweep: unknown sweep axis 'z'; expected one of: x, y");
}

TEST(SceneErrors, BadSupportsName) {
  EXPECT_EQ(errorOf(valid_head + "supports: {fixed: [west, botom]}\n"),
            "bad.yaml:3:26: supports.fixed[1]: unknown face 'botom'; expected one of: bottom, top, "
            "west, east, south, north (did you mean 'bottom'?)");
  EXPECT_EQ(errorOf(valid_head + "supports: {fixed: [west, west]}\n"),
            "bad.yaml:3:26: supports.fixed[1]: duplicate face 'west'");
  // A face is fixed or on rollers, not both (the error names the roller list's line).
  EXPECT_NE(errorOf(valid_head + "supports: {fixed: [west], rollers: [west]}\n")
                .find("face 'west' is already in supports.fixed"),
            std::string::npos);
  EXPECT_NE(errorOf(valid_head + "supports: {}\n").find("supports needs `fixed` or `rollers`"),
            std::string::npos);
}

TEST(SceneErrors, YamlSyntaxError) {
  EXPECT_EQ(errorOf("version: 1\n  seed: 2\n"), "bad.yaml:2:7: invalid YAML: illegal map value");
}

TEST(SceneErrors, TruncationWindowWithoutMass) {
  // A standard normal holds no representable mass in [50, 60]: geometry::Distribution rejects
  // it, and its message is located at the distribution's map.
  EXPECT_EQ(errorOf(valid_head +
                    "joint_sets:\n  - name: J1\n"
                    "    dip_direction: {distribution: normal, mean: 0, std: 1, min: 50, "
                    "max: 60}\n"
                    "    dip: {distribution: normal, mean: 30, std: 5}\n"
                    "    spacing: " +
                    lognormal_spacing + "\n    trace_length: " + lognormal_trace + "\n"),
            "bad.yaml:5:20: joint_sets[0].dip_direction: the truncation window [50, 60] holds "
            "only 0 of the probability mass of normal(mean=0, std=1) truncated to [50, 60] "
            "(at least 0.001 is needed); check min, max, mean and std");
}

TEST(SceneErrors, UnknownDistribution) {
  EXPECT_EQ(
      errorOf(valid_head + "joint_sets:\n" +
              jointSet("J1", "{distribution: lognormale, mean: 0.6, std: 0.8}", lognormal_trace)),
      "bad.yaml:7:29: joint_sets[0].spacing.distribution: unknown distribution "
      "'lognormale'; expected one of: normal, lognormal, uniform, exponential, constant "
      "(did you mean 'lognormal'?)");
}

TEST(SceneErrors, NormalTraceLengthNeedsPositiveMin) {
  EXPECT_EQ(errorOf(valid_head + "joint_sets:\n" +
                    jointSet("J1", lognormal_spacing, "{distribution: normal, mean: 20, std: 5}")),
            "bad.yaml:8:19: joint_sets[0].trace_length: a normal trace length can be negative; "
            "give min > 0");
}

TEST(SceneErrors, UniformTraceLengthReachingBelowZero) {
  EXPECT_EQ(errorOf(valid_head + "joint_sets:\n" +
                    jointSet("J1", lognormal_spacing, "{distribution: uniform, min: -1, max: 5}")),
            "bad.yaml:8:19: joint_sets[0].trace_length: expected only values > 0 for a trace "
            "length, but the distribution reaches -1");
}

TEST(SceneErrors, MissingOrientationSaysWhatToAdd) {
  EXPECT_EQ(errorOf(valid_head + "joint_sets:\n  - name: J1\n    spacing: " + lognormal_spacing +
                    "\n    trace_length: " + lognormal_trace + "\n"),
            "bad.yaml:4:5: joint_sets[0]: expected an orientation: 'dip_direction' and 'dip' "
            "distributions, or 'orientation'");
}

TEST(SceneErrors, ConstantTakesOnlyMean) {
  EXPECT_EQ(errorOf(valid_head + "joint_sets:\n" +
                    jointSet("J1", "{distribution: constant, mean: 1, min: 0}", lognormal_trace)),
            "bad.yaml:7:53: joint_sets[0].spacing.min: a constant takes only mean");
}

TEST(SceneErrors, MaterialWithUnitWeightAndDensity) {
  EXPECT_EQ(errorOf(valid_head + "materials:\n  rock:\n    unit_weight: 26000\n    density: 2600\n"
                                 "    young: 5e10\n    poisson: 0.2\n"),
            "bad.yaml:5:5: materials.rock: give either 'unit_weight' or 'density', not both");
}

TEST(SceneErrors, DuplicateKey) {
  EXPECT_EQ(errorOf(valid_head + "materials:\n  rock: {density: 2600, young: 5e10, young: 6e10, "
                                 "poisson: 0.2}\n"),
            "bad.yaml:4:38: materials.rock: duplicate key 'young'");
}

TEST(SceneErrors, FrictionAngleOf90) {
  EXPECT_EQ(errorOf(valid_head + "joints: {j: {friction_angle: 90}}\n"),
            "bad.yaml:3:30: joints.j.friction_angle: expected a number in [0, 90), got 90");
}

TEST(SceneErrors, NegativeSeed) {
  EXPECT_EQ(errorOf(valid_head + "seed: -1\n"),
            "bad.yaml:3:7: seed: expected an integer >= 0, got -1");
}

TEST(SceneErrors, ThresholdsMustIncrease) {
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  rqd: {thresholds: [1, 2, 2]}\n"),
            "bad.yaml:4:28: analysis.rqd.thresholds[2]: expected a number > 2 "
            "(the list must increase), got 2");
}

TEST(SceneRqdGrid, ReadsLengthAndRegion) {
  const Scene scene =
      parseScene(valid_head +
                     "analysis:\n  rqd:\n    grid: {spacing: 2, direction_count: 50, length: 12.5,"
                     " region: {min: [1, 2, -9], max: [9, 8, -1]}}\n",
                 "scene.yaml");
  const RqdAnalysis& rqd = *scene.analysis.rqd;
  EXPECT_EQ(rqd.grid_spacing, 2.0);
  EXPECT_EQ(rqd.grid_direction_count, 50);
  EXPECT_EQ(rqd.grid_length, 12.5);
  ASSERT_TRUE(rqd.grid_region.has_value());
  EXPECT_EQ(rqd.grid_region->min, Vec3(1, 2, -9));
  EXPECT_EQ(rqd.grid_region->max, Vec3(9, 8, -1));
}

TEST(SceneErrors, RqdGridRegionMustHaveVolume) {
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  rqd:\n    grid: {spacing: 2, region: {min: [0, 0, "
                                 "5], max: [10, 10, 5]}}\n"),
            "bad.yaml:5:32: analysis.rqd.grid.region: expected min < max in every component, got "
            "5 >= 5 in z");
}

TEST(SceneErrors, WaterOnUnknownStructure) {
  EXPECT_EQ(errorOf(valid_head + "loads:\n  water:\n"
                                 "    - {level: 10, on: {structure: dan, facing: [1, 0, 0]}}\n"),
            "bad.yaml:5:35: loads.water[0].on.structure: unknown structure 'dan'; "
            "no structures are defined");
}

TEST(SceneErrors, WaterLevelBelowTheDomainBottom) {
  EXPECT_EQ(errorOf(valid_head + "loads:\n  water:\n"
                                 "    - {level: -12, on: {domain_top: true}}\n"),
            "bad.yaml:5:15: loads.water[0].level: the water level -12 m lies below the domain "
            "bottom z = -10 m and would wet nothing");
}

TEST(SceneErrors, UnknownLoadInOverloadScales) {
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  overload: {factors: [1, 2], scales: [water, "
                                 "wind]}\n"),
            "bad.yaml:4:47: analysis.overload.scales[1]: unknown load 'wind'; expected one of: "
            "water, gravity, point_loads, seismic");
}

TEST(SceneStability, ReadsTheEquilibriumAndSearchExtensions) {
  const Scene scene = parseScene(valid_head +
                                     "monitors:\n"
                                     "  - {name: m, point: [1, 1, -1]}\n"
                                     "analysis:\n"
                                     "  overload: {factors: [1, 2], scales: [water], "
                                     "tolerance: 0.05, scale_uplift: true}\n"
                                     "  strength_reduction: {factors: [1, 1.5], tolerance: 0.01, "
                                     "path: incremental}\n"
                                     "  equilibrium: {max_steps: 50, unbalanced_ratio: 1e-4, "
                                     "kinetic_ratio: 1e-7, settle_steps: 3, dynamic_ratio: 0.9, "
                                     "start: settled, start_steps: 90, failure_ratio: 2, "
                                     "failure_steps: 7, drift_steps: 12, watch: monitors}\n",
                                 "ok.yaml");
  EXPECT_EQ(scene.monitors.at(0).line, 4);  // the monitor's line, for messages
  EXPECT_EQ(scene.analysis.overload->tolerance, 0.05);
  EXPECT_TRUE(scene.analysis.overload->scale_uplift);
  EXPECT_EQ(scene.analysis.strength_reduction->tolerance, 0.01);
  EXPECT_TRUE(scene.analysis.strength_reduction->incremental);
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  strength_reduction: {factors: [1], path: onward}\n"),
            "bad.yaml:4:44: analysis.strength_reduction.path: unknown path 'onward'; expected "
            "one of: restart, incremental");
  // The overload always restarts (docs/stability.md, "Path of the runs").
  EXPECT_EQ(errorOf(valid_head +
                    "analysis:\n  overload: {factors: [1], scales: [water], path: incremental}\n"),
            "bad.yaml:4:45: analysis.overload: unknown key 'path'; expected one of: factors, "
            "scales, tolerance, scale_uplift");
  ASSERT_TRUE(scene.analysis.equilibrium.has_value());
  EXPECT_EQ(scene.analysis.equilibrium->max_steps, 50);
  EXPECT_EQ(scene.analysis.equilibrium->unbalanced_ratio, 1e-4);
  EXPECT_EQ(scene.analysis.equilibrium->kinetic_ratio, 1e-7);
  EXPECT_EQ(scene.analysis.equilibrium->settle_steps, 3);
  EXPECT_EQ(scene.analysis.equilibrium->dynamic_ratio, 0.9);
  EXPECT_TRUE(scene.analysis.equilibrium->settled_start);
  EXPECT_EQ(scene.analysis.equilibrium->start_steps, 90);
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  equilibrium: {start: settled, start_steps: 0}\n"),
            "bad.yaml:4:46: analysis.equilibrium.start_steps: expected an integer > 0, got 0");
  // Without `start: settled` there is no settled start for the limit to apply to.
  const std::string no_start =
      ": analysis.equilibrium.start_steps: the step limit of the settled start: it needs "
      "`start: settled` (every run starts unloaded here)";
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  equilibrium: {start_steps: 90}\n"),
            "bad.yaml:4:30" + no_start);
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  equilibrium: {start: unloaded, start_steps: 90}\n"),
            "bad.yaml:4:47" + no_start);
  EXPECT_EQ(scene.analysis.equilibrium->failure_ratio, 2.0);
  EXPECT_EQ(scene.analysis.equilibrium->failure_steps, 7);
  EXPECT_EQ(scene.analysis.equilibrium->drift_steps, 12);
  // The drift rule compares the window's halves: 1-3 steps have no trend.
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  equilibrium: {drift_steps: 3}\n"),
            "bad.yaml:4:30: analysis.equilibrium.drift_steps: 0 (no drift stop) or at least 4 "
            "steps");
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  equilibrium: {drift_steps: -1}\n"),
            "bad.yaml:4:30: analysis.equilibrium.drift_steps: expected an integer >= 0, got -1");
  EXPECT_TRUE(scene.analysis.equilibrium->watch_monitors);
  EXPECT_EQ(scene.analysis.equilibrium->watch_line, 8);
  // watch: monitors without a monitor to watch.
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  equilibrium: {watch: monitors}\n"),
            "bad.yaml:4:24: analysis.equilibrium.watch: `monitors` needs a `monitors` list in the "
            "scene (the blocks it watches)");
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  equilibrium: {watch: dam}\n"),
            "bad.yaml:4:24: analysis.equilibrium.watch: unknown watch 'dam'; expected one of: "
            "all, monitors");
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  equilibrium: {start: halfway}\n"),
            "bad.yaml:4:24: analysis.equilibrium.start: unknown start 'halfway'; expected one "
            "of: unloaded, settled");
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  equilibrium: {failure_ratio: -1}\n"),
            "bad.yaml:4:32: analysis.equilibrium.failure_ratio: expected a number >= 0, got -1");
  // Defaults when absent.
  const Scene plain =
      parseScene(valid_head + "analysis:\n  strength_reduction: {factors: [1]}\n", "ok.yaml");
  EXPECT_EQ(plain.analysis.strength_reduction->tolerance, 0.02);
  EXPECT_FALSE(plain.analysis.strength_reduction->incremental);  // restart
  EXPECT_FALSE(plain.analysis.equilibrium.has_value());
  EXPECT_EQ(EquilibriumAnalysis{}.drift_steps, 0);  // the drift rule is off unless asked for
  EXPECT_FALSE(EquilibriumAnalysis{}.watch_monitors);
}

TEST(SceneErrors, MissingMeshFile) {
  const fs::path looked_for = fs::weakly_canonical(fs::current_path() / "no_such_rock.stl");
  EXPECT_EQ(errorOf("version: 1\ndomain: {mesh: no_such_rock.stl}\n"),
            "bad.yaml:2:16: domain.mesh: expected an existing file, got 'no_such_rock.stl' "
            "(looked for " +
                looked_for.string() + ")");
}

TEST(SceneErrors, UnreadableSceneFile) {
  try {
    loadScene("/nonexistent/rockmass/scene.yaml");
    FAIL() << "loadScene accepted a missing file";
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(), "/nonexistent/rockmass/scene.yaml: cannot read the scene file");
  }
}

TEST(SceneErrors, TwoDocuments) {
  EXPECT_EQ(errorOf(valid_head + "---\nversion: 1\n"),
            "bad.yaml:3:1: expected one YAML document; a second one starts here");
}

TEST(SceneErrors, StrayCommaIsInvalidYamlNotAnEndlessLoad) {
  // yaml-cpp 0.7's LoadAll never returns on a ',' outside [ ] or { } (jbeder/yaml-cpp#1040):
  // a 328-byte scene found by the fuzz target (fuzz/fuzz_scene.cpp) took 24 GB in 80 s.
  EXPECT_EQ(errorOf(","),
            "bad.yaml:1:1: invalid YAML: a ',' outside a flow collection ([ ] or { })");
  EXPECT_EQ(errorOf(", 0.0]\njoint_sets:\n  - ution: fishe14}\n"),
            "bad.yaml:1:1: invalid YAML: a ',' outside a flow collection ([ ] or { })");
  EXPECT_EQ(errorOf(valid_head + ",\n"), "bad.yaml:3:1: invalid YAML: end of map not found");
}

TEST(SceneErrors, InterlayerTurningTooSharplyIsRefusedAtItsPoint) {
  // The slab's offset surfaces meet at mitred knees; a knee of more than 150 degrees would
  // put its mitre point more than 3.9 thicknesses away (was exit 2 with no line, from the
  // DFN). Without thickness the same profile is a plain surface and is accepted.
  const std::string layer =
      "materials:\n  soft: {density: 2000, young: 1e9, poisson: 0.3}\n"
      "interlayers:\n  - {name: P1, profile: [[0, -5], [10, -5], [0, -6]], sweep: y, "
      "thickness: 0.4, material: soft}\n";
  EXPECT_EQ(errorOf(valid_head + layer),
            "bad.yaml:6:35: interlayers[0].profile[1]: the profile turns by 174.3 degrees at point "
            "2, more than the 150 an interlayer with thickness can turn");
  std::string thin = valid_head + layer;
  thin.replace(thin.find("thickness: 0.4, material: soft"), 30, "thickness: 0");
  EXPECT_EQ(errorOf(thin), "no error");
}

TEST(SceneErrors, OrientationGivenTwice) {
  EXPECT_EQ(
      errorOf(valid_head + "joint_sets:\n" + jointSet("J1", lognormal_spacing, lognormal_trace) +
              "    orientation: {distribution: fisher, dip_direction: 0, dip: 10, kappa: 5}\n"),
      "bad.yaml:4:5: joint_sets[0]: give either 'orientation' or 'dip_direction' and 'dip', "
      "not both");
}

TEST(SceneErrors, MissingStructureMesh) {
  EXPECT_EQ(errorOf(valid_head +
                    "materials: {c: {density: 2400, young: 2e10, poisson: 0.2}}\n"
                    "structures:\n  - {name: dam, mesh: scene_test_missing.stl, material: c}\n"),
            "bad.yaml:5:23: structures[0].mesh: expected an existing file, got "
            "'scene_test_missing.stl' (looked for " +
                fs::weakly_canonical(fs::current_path() / "scene_test_missing.stl").string() + ")");
}

TEST(SceneErrors, ZeroFacingVector) {
  EXPECT_EQ(errorOf(valid_head +
                    "materials: {c: {density: 2400, young: 2e10, poisson: 0.2}}\n"
                    "structures:\n"
                    "  - name: dam\n"
                    "    prism: {profile: [[0, 0], [1, 0], [0, 1]], sweep: x, from: 0, to: 1}\n"
                    "    material: c\n"
                    "loads:\n  water: [{level: 3, on: {structure: dam, facing: [0, 0, 0]}}]\n"),
            "bad.yaml:9:51: loads.water[0].on.facing: expected a nonzero vector");
}

// A structure's sub-contact points: `auto` (the default, none stored), a spacing, 0 (the
// corners only); anything else refused at its line.
TEST(SceneStructures, ContactPointSpacingIsAutoANumberOrZero) {
  const std::string head =
      valid_head +
      "materials: {c: {density: 2400, young: 2e10, poisson: 0.2}}\n"
      "structures:\n"
      "  - name: dam\n"
      "    prism: {profile: [[0, 0], [1, 0], [0, 1]], sweep: x, from: 0, to: 1}\n"
      "    material: c\n";
  EXPECT_FALSE(parseScene(head, "ok.yaml").structures[0].contact_point_spacing.has_value());
  const Scene automatic = parseScene(head + "    contact_point_spacing: auto\n", "ok.yaml");
  EXPECT_FALSE(automatic.structures[0].contact_point_spacing.has_value());
  EXPECT_EQ(automatic.structures[0].contact_point_spacing_line, 8);
  EXPECT_EQ(parseScene(head + "    contact_point_spacing: 0.5\n", "ok.yaml")
                .structures[0]
                .contact_point_spacing,
            0.5);
  EXPECT_EQ(parseScene(head + "    contact_point_spacing: 0\n", "ok.yaml")
                .structures[0]
                .contact_point_spacing,
            0.0);
  EXPECT_EQ(errorOf(head + "    contact_point_spacing: fine\n"),
            "bad.yaml:8:28: structures[0].contact_point_spacing: expected 'auto' or a number >= 0 "
            "(m), got 'fine'");
  EXPECT_EQ(errorOf(head + "    contact_point_spacing: -1\n"),
            "bad.yaml:8:28: structures[0].contact_point_spacing: expected a number >= 0, got -1");
}

// Every discontinuity carries its own joint (the DDA takes a contact's joint from the faces
// it lies on, not from the materials of its blocks): two structures of one material with
// different joints to the rock, a fault zone and an interlayer of one material with different
// joints, and a slab of the rock's own material with another joint than default_joint all
// read, with analysis.dda, and each keeps its joint. (These were "joint_conflict" errors while
// joints were chosen by material pair.)
TEST(SceneJoints, EachDiscontinuityKeepsItsJoint) {
  const std::string dda = "analysis:\n  dda: {steps: 1}\n";
  const Scene structures =
      parseScene(valid_head +
                     "materials: {c: {density: 2400, young: 2e10, poisson: 0.2}}\n"
                     "joints: {rj: {friction: 0.6}}\n"
                     "default_joint: rj\n"
                     "structures:\n"
                     "  - name: dam\n"
                     "    prism: {profile: [[0, 0], [1, 0], [0, 1]], sweep: x, from: 0, to: 1}\n"
                     "    material: c\n"
                     "    joint: {friction: 1.2, cohesion: 1.4e6}\n"
                     "  - name: cube\n"
                     "    prism: {profile: [[5, 0], [6, 0], [6, 1], [5, 1]], sweep: x, from: 0, "
                     "to: 1}\n"
                     "    material: c\n"
                     "    joint: {friction: 0.9}\n" +
                     dda,
                 "ok.yaml");
  ASSERT_EQ(structures.structures.size(), 2u);
  ASSERT_EQ(structures.joints.size(), 3u);  // rj, dam.joint, cube.joint
  EXPECT_EQ(structures.structures[0].joint, 1);
  EXPECT_EQ(structures.structures[1].joint, 2);
  EXPECT_EQ(structures.joints[1].friction, 1.2);
  EXPECT_EQ(structures.joints[2].friction, 0.9);
  const Scene slabs =
      parseScene(valid_head +
                     "materials: {rock: {density: 2600, young: 1e10, poisson: 0.25},"
                     " clay: {density: 2000, young: 1e9, poisson: 0.4}}\n"
                     "rock_material: rock\n"
                     "joints: {rj: {friction: 0.6}, soft: {friction: 0.3}, weak: {friction: 0.2}}\n"
                     "default_joint: rj\n"
                     "faults:\n"
                     "  - {name: F1, center: [5, 5, -5], dip_direction: 0, dip: 60, "
                     "size: [4, 2], thickness: 0.2, material: clay, joint: soft}\n"
                     "  - {name: F2, center: [5, 5, -5], dip_direction: 90, dip: 30, "
                     "thickness: 0.2, material: rock, joint: weak}\n"
                     "interlayers:\n"
                     "  - {name: P1, profile: [[0, -3], [10, -4]], sweep: y, thickness: 0.3, "
                     "material: clay}\n" +
                     dda,
                 "ok.yaml");
  ASSERT_EQ(slabs.dfn.faults.size(), 2u);
  EXPECT_EQ(slabs.dfn.faults[0].joint, 1);       // soft
  EXPECT_EQ(slabs.dfn.faults[1].joint, 2);       // weak, in a slab of the rock's material
  EXPECT_EQ(slabs.dfn.interlayers[0].joint, 0);  // default_joint, same material as F1
  EXPECT_EQ(slabs.dfn.interlayers[0].material, 1);
}

// `model` of a joint: plastic (the default) or brittle, in named and inline joints; any other
// value is an error at its line.
TEST(SceneJoints, JointModelIsPlasticOrBrittle) {
  const Scene scene =
      parseScene(valid_head +
                     "materials: {c: {density: 2400, young: 2e10, poisson: 0.2}}\n"
                     "joints: {a: {friction: 0.5}, b: {friction: 0.5, model: brittle},"
                     " p: {friction: 0.5, model: plastic}}\n"
                     "structures:\n"
                     "  - {name: dam, prism: {profile: [[0, 0], [1, 0], [0, 1]], sweep: x, from: 0,"
                     " to: 1}, material: c, joint: {friction: 1, model: brittle}}\n",
                 "ok.yaml");
  ASSERT_EQ(scene.joints.size(), 4u);
  EXPECT_FALSE(scene.joints[0].brittle);
  EXPECT_TRUE(scene.joints[1].brittle);
  EXPECT_FALSE(scene.joints[2].brittle);
  EXPECT_TRUE(scene.joints[3].brittle);  // dam.joint
  EXPECT_EQ(errorOf(valid_head + "joints:\n  a: {friction: 0.5, model: elastic}\n"),
            "bad.yaml:4:29: joints.a.model: unknown joint model 'elastic'; expected one of: "
            "plastic, brittle (did you mean 'plastic'?)");
  EXPECT_EQ(errorOf(valid_head + "joints:\n  a: {friction: 0.5, model: [brittle]}\n"),
            "bad.yaml:4:29: joints.a.model: expected one of: plastic, brittle");
  EXPECT_EQ(errorOf(valid_head + "joints:\n  a: {friction: 0.5, model: britle}\n"),
            "bad.yaml:4:29: joints.a.model: unknown joint model 'britle'; expected one of: "
            "plastic, brittle (did you mean 'brittle'?)");
}

// ----- valid scenes -----

TEST(SceneDefaults, MinimalSceneGetsTheDocumentedDefaults) {
  const Scene scene =
      parseScene(valid_head + "joint_sets:\n" + jointSet("J1", lognormal_spacing, lognormal_trace) +
                     "analysis:\n  blocks:\n",
                 "minimal.yaml");
  EXPECT_EQ(scene.file, fs::path("minimal.yaml"));
  EXPECT_EQ(scene.name, "");
  EXPECT_EQ(scene.seed, 0u);
  EXPECT_EQ(scene.rock_material, -1);
  EXPECT_EQ(scene.default_joint, -1);
  EXPECT_TRUE(scene.domain_mesh.empty());
  EXPECT_EQ(scene.dfn.domain.min, Vec3(0, 0, -10));
  EXPECT_EQ(scene.dfn.domain.max, Vec3(10, 10, 0));
  ASSERT_EQ(scene.dfn.joint_sets.size(), 1u);
  const geometry::JointSetSpec& set = scene.dfn.joint_sets[0];
  EXPECT_EQ(set.joint, -1);
  EXPECT_EQ(set.min_cut_size, 0.0);
  EXPECT_EQ(set.shape.aspect_ratio, 1.0);
  EXPECT_EQ(set.shape.major_axis, geometry::MajorAxis::Strike);
  EXPECT_FALSE(set.orientation.fisher);
  EXPECT_FALSE(scene.loads.gravity.has_value());
  // `blocks:` with an empty value turns the stage on with its defaults; the others stay off.
  ASSERT_TRUE(scene.analysis.blocks.has_value());
  EXPECT_EQ(scene.analysis.blocks->cutter, BlocksAnalysis::Cutter::Exact);
  EXPECT_EQ(scene.analysis.blocks->disc_segments, 24);
  EXPECT_FALSE(scene.analysis.rqd.has_value());
  EXPECT_FALSE(scene.analysis.dda.has_value());
  EXPECT_FALSE(scene.analysis.overload.has_value());
  EXPECT_FALSE(scene.analysis.strength_reduction.has_value());
}

TEST(SceneDefaults, GravityVectorAndAutoPenalty) {
  const Scene scene = parseScene(valid_head +
                                     "loads: {gravity: [0, 1, -9]}\n"
                                     "analysis: {dda: {penalty: auto}}\n",
                                 "vector.yaml");
  EXPECT_EQ(scene.loads.gravity, Vec3(0, 1, -9));
  ASSERT_TRUE(scene.analysis.dda.has_value());
  const dda3d::DdaSettings& engine = scene.analysis.dda->engine;
  EXPECT_EQ(engine.penalty, 0.0);  // auto
  EXPECT_EQ(engine.mode, dda3d::AnalysisMode::Dynamic);
  EXPECT_EQ(scene.analysis.dda->steps, 1000);
  // Default time integration: Bossak with rho_inf = 0 (docs/dda3d.md, "Time integration").
  EXPECT_EQ(engine.integration, dda3d::TimeIntegration::Bossak);
  EXPECT_EQ(engine.spectral_radius, 0.0);
  // One set of defaults: the scene contract's are the engine's (docs/scene-reference.md).
  EXPECT_EQ(engine.time_step, 0.002);
  EXPECT_EQ(engine.max_displacement_ratio, 0.001);
  EXPECT_EQ(engine.open_close_tolerance, dda3d::DdaSettings{}.open_close_tolerance);
}

TEST(SceneDdaTimeIntegration, SchemeAndSpectralRadius) {
  const auto dda = [](const std::string& integration) {
    return parseScene(valid_head + "analysis:\n  dda:\n    time_integration: " + integration + "\n",
                      "ti.yaml")
        .analysis.dda->engine;
  };
  using dda3d::TimeIntegration;
  const dda3d::DdaSettings bossak = dda("{scheme: bossak, spectral_radius: 0.5}");
  EXPECT_EQ(bossak.integration, TimeIntegration::Bossak);
  EXPECT_EQ(bossak.spectral_radius, 0.5);
  EXPECT_EQ(dda("{spectral_radius: 1}").spectral_radius, 1.0);  // bossak is the default scheme
  const dda3d::DdaSettings shi = dda("{scheme: shi}");
  EXPECT_EQ(shi.integration, TimeIntegration::Shi);
  EXPECT_EQ(shi.spectral_radius, 0.0);
  EXPECT_EQ(dda("{}").integration, TimeIntegration::Bossak);  // an empty map keeps the defaults
}

TEST(SceneDdaTimeIntegration, BadValuesNameTheKey) {
  const auto error = [](const std::string& integration) {
    return errorOf(valid_head + "analysis:\n  dda:\n    time_integration: " + integration + "\n");
  };
  EXPECT_EQ(error("{scheme: newmark}"),
            "bad.yaml:5:32: analysis.dda.time_integration.scheme: unknown scheme 'newmark'; "
            "expected one of: bossak, shi");
  EXPECT_EQ(error("{spectral_radius: 1.5}"),
            "bad.yaml:5:41: analysis.dda.time_integration.spectral_radius: expected a number in "
            "[0, 1], got 1.5");
  EXPECT_EQ(error("{spectral_radius: -0.1}"),
            "bad.yaml:5:41: analysis.dda.time_integration.spectral_radius: expected a number in "
            "[0, 1], got -0.1");
  EXPECT_EQ(error("{scheme: shi, spectral_radius: 0.5}"),
            "bad.yaml:5:54: analysis.dda.time_integration.spectral_radius: only with scheme: "
            "bossak (Shi's scheme has no parameter)");
  EXPECT_EQ(error("{rho_inf: 0.5}"),
            "bad.yaml:5:24: analysis.dda.time_integration: unknown key 'rho_inf'; expected one "
            "of: scheme, spectral_radius");
  EXPECT_EQ(error("bossak"),
            "bad.yaml:5:23: analysis.dda.time_integration: expected a map, got 'bossak'");
}

/// The example of scene-format.md with a few values changed to exercise every form.
const std::string full_scene = R"(version: 1
name: test-site
seed: 20131001
domain:
  box: {min: [0, 0, -120], max: [240, 160, 0]}
materials:
  bedrock: {unit_weight: 26.0e3, young: 7.0e9, poisson: 0.25}
  concrete: {density: 2446.5, young: 17.6e9, poisson: 0.167}
  soft_layer: {unit_weight: 20.0e3, young: 0.75e9, poisson: 0.40}
rock_material: bedrock
joints:
  rock_joint: {friction: 0.86, cohesion: 0.8e6}
  soft: {friction_angle: 30, tensile_strength: 1.0e4}
default_joint: rock_joint
joint_sets:
  - name: J1
    dip_direction: {distribution: normal, mean: 85.24, std: 13.32, min: 45.54, max: 115.54}
    dip: {distribution: uniform, min: 10, max: 50}
    spacing: {distribution: lognormal, mean: 0.60, std: 0.79}
    trace_length: {distribution: lognormal, mean: 23.80, std: 19.76}
    shape: {aspect_ratio: 0.5, major_axis: {rake: 30}}
    min_cut_size: 2.0
  - name: J2
    orientation: {distribution: fisher, dip_direction: 200, dip: 70, kappa: 25}
    intensity: {p32: 1.2}
    trace_length: {distribution: exponential, mean: 5}
    shape: {major_axis: dip}
    joint: soft
fractures:
  - {file: mapped.fab, joint: soft}
faults:
  - name: F1
    center: [120, 80, -20]
    dip_direction: 290
    dip: 75
    size: [400, 300]
    thickness: 0.5
    material: soft_layer
    joint: soft
  - {name: F2, center: [10, 10, -10], dip_direction: 0, dip: 90}
interlayers:
  - name: P1
    profile: [[0, -40], [100, -45], [140, -30], [240, -35]]
    sweep: y
    thickness: 1.0
    material: soft_layer
    joint: soft
structures:
  - name: dam
    prism: {profile: [[60, 0], [170, 0], [80, 160], [60, 160]], sweep: y, from: 20, to: 140}
    material: concrete
    joint: {friction: 1.2, cohesion: 1.4e6}
loads:
  gravity: 9.81
  water:
    - {level: 150.0, unit_weight: 9810, on: {structure: dam, facing: [-1, 0, 0]}}
    - {level: 150.0, uplift: true, on: {domain_top: true, region: {x_max: 60}}}
  point_loads:
    - {point: [100, 80, 10], force: [0, 0, -1.0e6]}
supports:
  fixed: [bottom, west, east, south, north]
monitors:
  - {name: P4, point: [65, 80, 0]}
analysis:
  blocks: {cutter: fast}
  rqd:
    thresholds: [0.1, 1, 2]
    balls:
      - {name: centre, center: [120, 80, -30], length: 40}
    boreholes: {file: holes.csv, measured: logs/rqd_log.csv}
    grid: {spacing: 5.0}
  dda:
    mode: static
    kinematics: rigid
    steps: 500
    time_step: 0.001
    max_displacement_ratio: 0.002
    penalty: 1.0e9
  overload:
    factors: [1, 2, 7.5]
    scales: [water, gravity]
)";

TEST_F(SceneFiles, FullSceneParsesToTheExpectedValues) {
  write("mapped.fab", test::kSceneFormatFab);
  write("holes.csv", "id,x,y,z,azimuth,plunge,length\n");
  fs::create_directories(dir / "logs");
  write("logs/rqd_log.csv", "id,from,to,rqd\n");
  const Scene scene = loadScene(write("scene.yaml", full_scene));

  EXPECT_EQ(scene.name, "test-site");
  EXPECT_EQ(scene.seed, 20131001u);
  EXPECT_EQ(scene.dfn.domain.max, Vec3(240, 160, 0));

  ASSERT_EQ(scene.materials.size(), 3u);
  EXPECT_EQ(scene.materials[0].name, "bedrock");
  EXPECT_DOUBLE_EQ(scene.materials[0].density, 26.0e3 / 9.81);  // unit weight / g
  EXPECT_EQ(scene.materials[1].density, 2446.5);
  EXPECT_EQ(scene.materials[1].young, 17.6e9);
  EXPECT_EQ(scene.materials[2].poisson, 0.40);
  EXPECT_EQ(scene.rock_material, 0);

  // Two named joints, then the dam's inline joint.
  ASSERT_EQ(scene.joints.size(), 3u);
  EXPECT_EQ(scene.joints[0].friction, 0.86);
  EXPECT_EQ(scene.joints[0].cohesion, 0.8e6);
  EXPECT_EQ(scene.joints[0].tensile_strength, 0.0);
  // tan(30 deg) = 1/sqrt(3); 1e-15 allows the last-bit rounding of tan.
  EXPECT_NEAR(scene.joints[1].friction, 1.0 / std::sqrt(3.0), 1e-15);
  EXPECT_EQ(scene.joints[1].cohesion, 0.0);
  EXPECT_EQ(scene.joints[1].tensile_strength, 1.0e4);
  EXPECT_EQ(scene.joints[2].name, "dam.joint");
  EXPECT_EQ(scene.joints[2].friction, 1.2);
  EXPECT_EQ(scene.joints[2].cohesion, 1.4e6);
  EXPECT_EQ(scene.default_joint, 0);

  ASSERT_EQ(scene.dfn.joint_sets.size(), 2u);
  const geometry::JointSetSpec& j1 = scene.dfn.joint_sets[0];
  EXPECT_EQ(j1.name, "J1");
  EXPECT_EQ(j1.joint, 0);  // default_joint
  EXPECT_EQ(j1.orientation.dip_direction.kind, geometry::DistributionKind::Normal);
  EXPECT_EQ(j1.orientation.dip_direction.min, 45.54);
  EXPECT_EQ(j1.orientation.dip_direction.max, 115.54);
  // uniform {min, max}: mean (a + b) / 2, std (b - a) / sqrt(12), and [min, max] kept.
  EXPECT_EQ(j1.orientation.dip.kind, geometry::DistributionKind::Uniform);
  EXPECT_EQ(j1.orientation.dip.mean, 30.0);
  EXPECT_DOUBLE_EQ(j1.orientation.dip.std, 40.0 / std::sqrt(12.0));
  EXPECT_EQ(j1.orientation.dip.min, 10.0);
  EXPECT_EQ(j1.orientation.dip.max, 50.0);
  ASSERT_TRUE(j1.spacing.has_value());
  EXPECT_EQ(j1.spacing->kind, geometry::DistributionKind::Lognormal);
  EXPECT_EQ(j1.spacing->mean, 0.60);
  EXPECT_EQ(j1.spacing->std, 0.79);
  EXPECT_FALSE(j1.p32.has_value());
  EXPECT_EQ(j1.trace_length.mean, 23.80);
  EXPECT_EQ(j1.shape.aspect_ratio, 0.5);
  EXPECT_EQ(j1.shape.major_axis, geometry::MajorAxis::Rake);
  EXPECT_EQ(j1.shape.rake, 30.0);
  EXPECT_EQ(j1.min_cut_size, 2.0);

  const geometry::JointSetSpec& j2 = scene.dfn.joint_sets[1];
  EXPECT_TRUE(j2.orientation.fisher);
  EXPECT_EQ(j2.orientation.fisher_dip_direction, 200.0);
  EXPECT_EQ(j2.orientation.fisher_dip, 70.0);
  EXPECT_EQ(j2.orientation.kappa, 25.0);
  EXPECT_FALSE(j2.spacing.has_value());
  EXPECT_EQ(j2.p32, 1.2);
  EXPECT_EQ(j2.trace_length.kind, geometry::DistributionKind::Exponential);
  EXPECT_EQ(j2.trace_length.std, 5.0);  // an exponential's std equals its mean
  EXPECT_EQ(j2.shape.major_axis, geometry::MajorAxis::Dip);
  EXPECT_EQ(j2.joint, 1);

  ASSERT_EQ(scene.dfn.polygon_sets.size(), 1u);
  EXPECT_EQ(scene.dfn.polygon_sets[0].name, "mapped");
  EXPECT_EQ(scene.dfn.polygon_sets[0].joint, 1);

  ASSERT_EQ(scene.dfn.faults.size(), 2u);
  const geometry::FaultSpec& f1 = scene.dfn.faults[0];
  EXPECT_EQ(f1.center, Vec3(120, 80, -20));
  EXPECT_EQ(f1.dip_direction, 290.0);
  EXPECT_EQ(f1.dip, 75.0);
  ASSERT_TRUE(f1.size.has_value());
  EXPECT_EQ((*f1.size)[0], 400.0);
  EXPECT_EQ((*f1.size)[1], 300.0);
  EXPECT_EQ(f1.thickness, 0.5);
  EXPECT_EQ(f1.material, 2);
  EXPECT_EQ(f1.joint, 1);
  const geometry::FaultSpec& f2 = scene.dfn.faults[1];
  EXPECT_FALSE(f2.size.has_value());
  EXPECT_EQ(f2.thickness, 0.0);
  EXPECT_EQ(f2.material, -1);
  EXPECT_EQ(f2.joint, 0);

  ASSERT_EQ(scene.dfn.interlayers.size(), 1u);
  const geometry::InterlayerSpec& p1 = scene.dfn.interlayers[0];
  ASSERT_EQ(p1.profile.size(), 4u);
  EXPECT_EQ(p1.profile[1], Vec2(100, -45));
  EXPECT_EQ(p1.sweep, 'y');
  EXPECT_EQ(p1.thickness, 1.0);
  EXPECT_EQ(p1.material, 2);
  // soft, like the fault F1 of the same material: with analysis.dda a different joint to the
  // rock would be an error (the DDA picks joints by material pair).
  EXPECT_EQ(p1.joint, 1);

  ASSERT_EQ(scene.structures.size(), 1u);
  const StructureSpec& dam = scene.structures[0];
  EXPECT_EQ(dam.name, "dam");
  ASSERT_EQ(dam.prism_profile.size(), 4u);
  EXPECT_EQ(dam.prism_profile[2], Vec2(80, 160));
  EXPECT_EQ(dam.prism_sweep, 'y');
  EXPECT_EQ(dam.prism_from, 20.0);
  EXPECT_EQ(dam.prism_to, 140.0);
  EXPECT_TRUE(dam.mesh.empty());
  EXPECT_EQ(dam.material, 1);
  EXPECT_EQ(dam.joint, 2);

  ASSERT_TRUE(scene.loads.gravity.has_value());
  EXPECT_EQ(*scene.loads.gravity, Vec3(0, 0, -9.81));
  ASSERT_EQ(scene.loads.water.size(), 2u);
  EXPECT_EQ(scene.loads.water[0].structure, "dam");
  EXPECT_EQ(scene.loads.water[0].facing, Vec3(-1, 0, 0));
  EXPECT_FALSE(scene.loads.water[0].uplift);
  EXPECT_FALSE(scene.loads.water[0].domain_top);
  EXPECT_TRUE(scene.loads.water[1].domain_top);
  EXPECT_TRUE(scene.loads.water[1].uplift);
  EXPECT_EQ(scene.loads.water[1].unit_weight, 9810.0);
  EXPECT_EQ(scene.loads.water[1].region.x_max, 60.0);
  EXPECT_FALSE(scene.loads.water[1].region.x_min.has_value());
  ASSERT_EQ(scene.loads.point_loads.size(), 1u);
  EXPECT_EQ(scene.loads.point_loads[0].force, Vec3(0, 0, -1.0e6));

  EXPECT_EQ(scene.fixed_faces,
            (std::vector<std::string>{"bottom", "west", "east", "south", "north"}));
  ASSERT_EQ(scene.monitors.size(), 1u);
  EXPECT_EQ(scene.monitors[0].name, "P4");
  EXPECT_EQ(scene.monitors[0].point, Vec3(65, 80, 0));

  ASSERT_TRUE(scene.analysis.blocks.has_value());
  EXPECT_EQ(scene.analysis.blocks->cutter, BlocksAnalysis::Cutter::Fast);
  ASSERT_TRUE(scene.analysis.rqd.has_value());
  const RqdAnalysis& rqd = *scene.analysis.rqd;
  EXPECT_EQ(rqd.thresholds, (std::vector<double>{0.1, 1, 2}));
  ASSERT_EQ(rqd.balls.size(), 1u);
  EXPECT_EQ(rqd.balls[0].length, 40.0);
  EXPECT_EQ(rqd.balls[0].directions, 2000);
  EXPECT_EQ(rqd.boreholes_file, fs::weakly_canonical(dir / "holes.csv"));
  EXPECT_TRUE(rqd.boreholes_file.is_absolute());
  EXPECT_EQ(rqd.measured_file, fs::weakly_canonical(dir / "logs" / "rqd_log.csv"));
  EXPECT_EQ(rqd.run_length, 3.0);
  EXPECT_EQ(rqd.grid_spacing, 5.0);
  EXPECT_EQ(rqd.grid_direction_count, 200);
  EXPECT_FALSE(rqd.grid_length.has_value());  // defaults: 2 x largest threshold, domain box
  EXPECT_FALSE(rqd.grid_region.has_value());
  ASSERT_TRUE(scene.analysis.dda.has_value());
  const DdaAnalysis& dda = *scene.analysis.dda;
  EXPECT_EQ(dda.engine.mode, dda3d::AnalysisMode::Static);
  EXPECT_EQ(dda.engine.kinematics, dda3d::Kinematics::Rigid);
  EXPECT_EQ(dda.steps, 500);
  EXPECT_EQ(dda.engine.time_step, 0.001);
  EXPECT_EQ(dda.engine.max_displacement_ratio, 0.002);
  EXPECT_EQ(dda.engine.penalty, 1.0e9);
  ASSERT_TRUE(scene.analysis.overload.has_value());
  EXPECT_EQ(scene.analysis.overload->factors, (std::vector<double>{1, 2, 7.5}));
  EXPECT_EQ(scene.analysis.overload->scales, (std::vector<std::string>{"water", "gravity"}));
  EXPECT_FALSE(scene.analysis.strength_reduction.has_value());
}

TEST_F(SceneFiles, FabFileBecomesAPolygonSetNamedAfterItsStem) {
  write("mapped_joints.fab", test::kSceneFormatFab);
  const Scene scene = loadScene(
      write("scene.yaml", valid_head + two_joints +
                              "default_joint: soft\nfractures:\n  - {file: mapped_joints.fab}\n"));
  ASSERT_EQ(scene.dfn.polygon_sets.size(), 1u);
  const geometry::PolygonSetSpec& set = scene.dfn.polygon_sets[0];
  EXPECT_EQ(set.name, "mapped_joints");
  EXPECT_EQ(set.joint, 1);  // default_joint
  ASSERT_EQ(set.polygons.size(), 1u);
  EXPECT_EQ(set.polygons[0], (std::vector<Vec3>{Vec3(-1, -1, 5), Vec3(11, -1, 5), Vec3(11, 11, 5),
                                                Vec3(-1, 11, 5)}));
  EXPECT_EQ(set.file_sets, std::vector<int>{1});
}

TEST_F(SceneFiles, FabErrorsPassThroughLocatedInTheFabFile) {
  const fs::path fab = write("broken.fab", "BEGIN FORMAT\n");
  try {
    loadScene(write("scene.yaml", valid_head + "fractures:\n  - {file: broken.fab}\n"));
    FAIL() << "a truncated FAB file was accepted";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.rfind(fs::weakly_canonical(fab).string() + ":", 0), 0u) << message;
  }
}

TEST_F(SceneFiles, DomainMeshIsStoredAbsoluteAndTheBoxStaysZero) {
  write("rock.stl", "solid rock\nendsolid rock\n");
  const Scene scene = loadScene(write("scene.yaml", "version: 1\ndomain: {mesh: rock.stl}\n"));
  EXPECT_EQ(scene.domain_mesh, fs::weakly_canonical(dir / "rock.stl"));
  EXPECT_EQ(scene.dfn.domain.min, Vec3::Zero());
  EXPECT_EQ(scene.dfn.domain.max, Vec3::Zero());
}

TEST(SceneExample, XiangjiabaLoads) {
  const fs::path file = fs::path(ROCKMASS_SOURCE_DIR) / "examples" / "xiangjiaba" / "scene.yaml";
  if (!fs::exists(file)) GTEST_SKIP() << file << " is not written yet";
  EXPECT_NO_THROW(loadScene(file));
}

}  // namespace
}  // namespace rockmass::io

namespace rockmass::io {
namespace {

TEST(SceneDdaServiceRun, SettleDamageMapAndDynamicRatio) {
  const Scene scene = parseScene(valid_head +
                                     "analysis:\n  dda:\n    steps: 400\n"
                                     "    dynamic_ratio: 0.98\n"
                                     "    settle: {without: [water, seismic]}\n"
                                     "    damage_map: {}\n",
                                 "service.yaml");
  const DdaAnalysis& dda = *scene.analysis.dda;
  EXPECT_EQ(dda.engine.dynamic_ratio, 0.98);
  ASSERT_TRUE(dda.settle.has_value());
  EXPECT_TRUE(dda.settle->without_water);
  EXPECT_TRUE(dda.settle->without_seismic);
  EXPECT_FALSE(dda.settle->without_point_loads);
  EXPECT_EQ(dda.settle->max_steps, 200);  // the default
  ASSERT_TRUE(dda.damage_every.has_value());
  EXPECT_EQ(*dda.damage_every, 40);  // default: a tenth of the steps
  // Absent: no settling, no damage map, the engine's ratio (1: fully dynamic).
  const Scene plain = parseScene(valid_head + "analysis:\n  dda: {}\n", "plain.yaml");
  EXPECT_FALSE(plain.analysis.dda->settle.has_value());
  EXPECT_FALSE(plain.analysis.dda->damage_every.has_value());
  EXPECT_EQ(plain.analysis.dda->engine.dynamic_ratio, 1.0);
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  dda:\n    settle: {without: []}\n"),
            "bad.yaml:5:23: analysis.dda.settle.without: expected a non-empty list");
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  dda:\n    settle: {without: [wind]}\n"),
            "bad.yaml:5:24: analysis.dda.settle.without[0]: unknown load 'wind'; expected one "
            "of: water, seismic, point_loads");
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  dda:\n    damage_map: {every: 0}\n"),
            "bad.yaml:5:25: analysis.dda.damage_map.every: expected an integer in [1, 1e+07], "
            "got 0");
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  dda:\n    dynamic_ratio: 1.5\n"),
            "bad.yaml:5:20: analysis.dda.dynamic_ratio: expected a number in [0, 1], got 1.5");
}

TEST(SceneDdaWater, BiotCoefficientOfDeformableBlocks) {
  const Scene scene =
      parseScene(valid_head + "analysis:\n  dda:\n    biot_coefficient: 1\n", "biot.yaml");
  EXPECT_EQ(scene.analysis.dda->engine.biot_coefficient, 1.0);
  // Absent: impermeable blocks, the water on their faces a surface load (3DEC's joint water).
  const Scene plain = parseScene(valid_head + "analysis:\n  dda: {}\n", "plain.yaml");
  EXPECT_EQ(plain.analysis.dda->engine.biot_coefficient, 0.0);
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  dda:\n    biot_coefficient: -0.5\n"),
            "bad.yaml:5:23: analysis.dda.biot_coefficient: expected a number in [0, 1], got -0.5");
}

TEST(SceneDdaBlocks, GlueAcrossMaterials) {
  const Scene scene = parseScene(
      valid_head + "analysis:\n  dda:\n    min_block_volume: 2\n    glue_across_materials: true\n",
      "glue.yaml");
  EXPECT_TRUE(scene.analysis.dda->glue_across_materials);
  // Absent: a block is glued only to a neighbour of its own material.
  const Scene plain = parseScene(valid_head + "analysis:\n  dda: {}\n", "plain.yaml");
  EXPECT_FALSE(plain.analysis.dda->glue_across_materials);
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  dda:\n    glue_across_materials: 1\n"),
            "bad.yaml:5:28: analysis.dda.glue_across_materials: expected true or false, got '1'");
}

TEST(SceneDdaBlocks, SurfaceOnlyDetection) {
  const Scene scene =
      parseScene(valid_head + "analysis:\n  dda:\n    surface_only: true\n", "surface.yaml");
  EXPECT_TRUE(scene.analysis.dda->engine.detection.surface_only);
  // Absent: every face of every piece is searched (the engine's default).
  const Scene plain = parseScene(valid_head + "analysis:\n  dda: {}\n", "plain.yaml");
  EXPECT_FALSE(plain.analysis.dda->engine.detection.surface_only);
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  dda:\n    surface_only: yes\n"),
            "bad.yaml:5:19: analysis.dda.surface_only: expected true or false, got 'yes'");
}

TEST(SceneDdaBlocks, ContactSearchMargin) {
  const Scene scene = parseScene(valid_head + "analysis:\n  dda:\n    contact_search_margin: 0\n",
                                 "every_step.yaml");
  EXPECT_EQ(scene.analysis.dda->engine.detection.search_margin, 0.0);
  // Absent: the engine's default, 1e-3 g2 l0.
  const Scene plain = parseScene(valid_head + "analysis:\n  dda: {}\n", "plain.yaml");
  EXPECT_EQ(plain.analysis.dda->engine.detection.search_margin, 1e-3);
  // Above the resting reach's half (0.05 g2 l0) a step's cut reach could reach zero.
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  dda:\n    contact_search_margin: 0.1\n"),
            "bad.yaml:5:28: analysis.dda.contact_search_margin: expected a number in [0, 0.05], "
            "got 0.1");
}

TEST(SceneDdaBlocks, FrictionTolerance) {
  const Scene scene =
      parseScene(valid_head + "analysis:\n  dda:\n    friction_tolerance: 1\n", "lagged.yaml");
  EXPECT_EQ(scene.analysis.dda->engine.friction_tolerance, 1.0);
  // Absent: the engine's default, 1 % of a sliding contact's strength.
  const Scene plain = parseScene(valid_head + "analysis:\n  dda: {}\n", "plain.yaml");
  EXPECT_EQ(plain.analysis.dda->engine.friction_tolerance, 0.01);
  EXPECT_EQ(errorOf(valid_head + "analysis:\n  dda:\n    friction_tolerance: -0.1\n"),
            "bad.yaml:5:25: analysis.dda.friction_tolerance: expected a number in [0, 1], "
            "got -0.1");
}

}  // namespace
}  // namespace rockmass::io
