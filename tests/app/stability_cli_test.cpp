// rockmass overload / strength end to end on a dam-like block: a concrete gravity-dam
// section (trapezoid, vertical upstream face) standing on a fixed rock slab, loaded by its
// own weight, reservoir water on its upstream face and uplift under its base.
// Hand calculation (the shear-friction formula of gravity-dam design, e.g. USBR "Design of
// Gravity Dams" 1976, ch. 4; Chinese SL 319): the dam slides on its base when
//   K H = f (W - U) + c A,  so  K = (f (W - U) + c A) / H,
// with H = gw h^2 B / 2 the water thrust, U = gw h A the uplift (full head h over the base,
// docs/stability.md), W the weight, A = L B the base area, f and c of the dam-rock joint.
// The overload method scales H (uplift kept at K = 1: scale_uplift false); strength
// reduction divides f (and c) by SRF, so for a frictional base its critical SRF is the
// same formula. The runs are static (velocities reset every step): a suddenly applied load
// in a dynamic run overshoots and breaks the brittle cohesion early (docs/stability.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"
#include "tests/support/verification.h"

namespace rockmass {
namespace {

namespace fs = std::filesystem;

constexpr double kGammaW = 9810.0;                         // N/m3
constexpr double kConcrete = 2400.0;                       // kg/m3
constexpr double kGravity = 9.81;                          // m/s2
constexpr double kFriction = 0.6;                          // dam-rock f
constexpr double kCohesion = 30.0e3;                       // dam-rock c (Pa)
constexpr double kHeight = 6.0;                            // dam height = water depth (m)
constexpr double kBase = 8.0, kCrest = 3.0, kWidth = 4.0;  // m

const std::string kCrestMonitor = "  - {name: crest, point: [1.5, 2, 5.5]}\n";

/// The dam scene; the arguments change it for the error cases.
std::string damScene(const std::string& monitors = kCrestMonitor, const std::string& level = "6.0",
                     const std::string& scales = "[water]", const std::string& cohesion = "30.0e3",
                     const std::string& equilibrium = "{max_steps: 300}",
                     const std::string& more_structures = "") {
  return R"(version: 1
name: dam-on-slab
seed: 1
domain:
  box: {min: [-4, -2, -2], max: [12, 6, 0]}
materials:
  rock: {density: 2400, young: 20.0e9, poisson: 0.2}
  concrete: {density: 2400, young: 20.0e9, poisson: 0.2}
  steel: {density: 7800, young: 200.0e9, poisson: 0.3}
rock_material: rock
joints:
  rj: {friction: 0.6, cohesion: 0}
default_joint: rj
structures:
  - name: dam
    prism: {profile: [[0, 0], [8, 0], [3, 6], [0, 6]], sweep: y, from: 0, to: 4}
    material: concrete
    joint: {friction: 0.6, cohesion: )" +
         cohesion + R"(}
)" + more_structures +
         R"(loads:
  gravity: 9.81
  water:
    - {level: )" +
         level +
         R"(, uplift: true, on: {structure: dam, facing: [-1, 0, 0]}}
supports:
  fixed: [bottom]
monitors:
)" + monitors +
         R"(analysis:
  blocks: {cutter: fast}
  dda: {mode: static, kinematics: rigid, steps: 300, time_step: 0.001}
  equilibrium: )" +
         equilibrium + R"(
  overload: {factors: [1, 1.5, 2, 2.5, 3], scales: )" +
         scales + R"(, tolerance: 0.02}
  strength_reduction: {factors: [1, 1.5, 2, 2.5, 3], tolerance: 0.02}
)";
}

/// The hand calculation of the header, for a dam-rock cohesion `cohesion` (Pa).
double slidingFactor(double cohesion = kCohesion) {
  const double weight = kConcrete * kGravity * 0.5 * (kBase + kCrest) * kHeight * kWidth;
  const double thrust = 0.5 * kGammaW * kHeight * kHeight * kWidth;
  const double area = kBase * kWidth;
  const double uplift = kGammaW * kHeight * area;
  return (kFriction * (weight - uplift) + cohesion * area) / thrust;
}

/// The dam's hand formula and its source, for the verification manual.
const std::string kDamSource =
    "shear friction K = (f (W - U) + c A) / H (USBR, Design of Gravity Dams, 1976, ch. 4)";

class StabilityCli : public ::testing::Test {
 protected:
  test::TempDir dir{"stability_cli"};
  /// Runs `rockmass <command>` on `scene_text`; returns the exit code, output in `output`.
  int run(const std::string& command, const std::string& scene_text, const std::string& name,
          std::string& output) {
    return test::runOnScene(command, dir.path(), name, scene_text, &output);
  }
};

TEST_F(StabilityCli, DamSlidesAtTheShearFrictionOverloadFactor) {
  std::string output;
  ASSERT_EQ(run("overload", damScene(), "overload", output), 0) << output;
  const nlohmann::json summary =
      nlohmann::json::parse(test::readFile(dir.path() / "overload" / "summary.json"));
  const double expected = slidingFactor();  // 2.40
  ASSERT_TRUE(summary["safety_factor"].is_number()) << summary.dump(2);
  // Issue 6: within 3% (the bisection bracket is 0.02 wide, 0.4% of K).
  EXPECT_NEAR(summary["safety_factor"].get<double>(), expected, 0.03 * expected);
  test::recordVerification({.group = "Dams",
                            .name = "dam 8/3/6 m, f = 0.6, c = 30 kPa, water to the crest, full "
                                    "uplift, static: overload factor K_s",
                            .source = kDamSource,
                            .expected = expected,
                            .measured = summary["safety_factor"].get<double>(),
                            .tolerance = 0.03,
                            .relative = true,
                            .unit = "-"});
  EXPECT_EQ(summary["overload"]["K_s"], summary["safety_factor"]);
  EXPECT_LE(summary["overload"]["first_unstable"].get<double>() -
                summary["overload"]["last_stable"].get<double>(),
            0.02 + 1e-12);
  // Wet faces: the upstream face (one) and the base of the dam and the rock under it.
  EXPECT_EQ(summary["pressures"], 3);
  EXPECT_TRUE(summary["timings"].contains("overload"));
  // overload.csv: the shared contract's columns first, one row per run and monitor, by
  // increasing factor. The crest moves downstream (+x) wherever the dam slides; at rest it
  // moves by its contact springs' deflection only (~1e-9 m; its base resultant lies 0.2 L
  // upstream of the centre at K = 1, so the base tilts upstream and the crest may go back
  // by 1e-11 m).
  std::istringstream csv(test::readFile(dir.path() / "overload" / "overload.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "factor,monitor,ux,uy,uz,u,at_rest,steps");
  int rows = 0;
  double previous = 0.0;
  while (std::getline(csv, line)) {
    std::istringstream fields(line);
    std::string factor, monitor, ux, uy, uz, u, at_rest;
    std::getline(fields, factor, ',');
    std::getline(fields, monitor, ',');
    std::getline(fields, ux, ',');
    std::getline(fields, uy, ',');
    std::getline(fields, uz, ',');
    std::getline(fields, u, ',');
    std::getline(fields, at_rest, ',');
    EXPECT_EQ(monitor, "crest");
    EXPECT_GE(std::stod(factor), previous);
    if (at_rest == "1") {
      EXPECT_LT(std::stod(u), 1e-8) << line;
    } else {
      EXPECT_GT(std::stod(ux), 0.0) << line;
    }
    previous = std::stod(factor);
    ++rows;
  }
  EXPECT_EQ(rows, static_cast<int>(summary["overload"]["runs"].size()));
}

TEST_F(StabilityCli, StrengthReductionOfAFrictionalDamMatchesTheHandCalculation) {
  // Without cohesion: DDA cohesion sits on the base's four corner contacts and is lost at
  // each one that slides, so at K = 1, where the weight's moment puts most of the normal
  // force on the heel, the toe corners fail first and the dam slides at SRF ~1.99 instead
  // of 2.40 (docs/stability.md, "Brittle cohesion"). Friction alone has no such loss.
  std::string output;
  ASSERT_EQ(run("strength", damScene(kCrestMonitor, "6.0", "[water]", "0"), "strength", output), 0)
      << output;
  const nlohmann::json summary =
      nlohmann::json::parse(test::readFile(dir.path() / "strength" / "summary.json"));
  const double expected = slidingFactor(0.0);  // f (W - U) / H = 1.04
  ASSERT_TRUE(summary["safety_factor"].is_number()) << summary.dump(2);
  // Issue 6 tolerance, 3% (the bisection bracket is 0.02 wide).
  EXPECT_NEAR(summary["safety_factor"].get<double>(), expected, 0.03 * expected);
  test::recordVerification({.group = "Dams",
                            .name = "dam 8/3/6 m, f = 0.6, no cohesion, water to the crest, full "
                                    "uplift, static: strength-reduction factor",
                            .source = "SRF = f (W - U) / H (USBR, Design of Gravity Dams, 1976, "
                                      "ch. 4)",
                            .expected = expected,
                            .measured = summary["safety_factor"].get<double>(),
                            .tolerance = 0.03,
                            .relative = true,
                            .unit = "-"});
  EXPECT_EQ(summary["strength_reduction"]["critical_srf"], summary["safety_factor"]);
  EXPECT_TRUE(summary["timings"].contains("strength_reduction"));
  EXPECT_FALSE(fs::exists(dir.path() / "strength" / "overload.csv"));
}

// equilibrium.watch: monitors. A 1 m concrete cube hangs in the air 2 m above the rock
// downstream of the dam (a loose block with nothing under it): in a static run it falls by
// g dt^2 / 2 in every step, an unbalanced ratio of 1, so watching every block no factor is at
// rest (K_s null): each run stops after 10 steps of the cube moving steadily (steady_steps,
// the default; its ratio, 1 but for round-off, stays just below failure_ratio 1). Watching
// the crest monitor's block, the dam, the overload factor is the hand calculation's again,
// within the 3% of issue 6; the cube's fall is still reported (all_blocks_ratio,
// fastest_block).
TEST_F(StabilityCli, WatchingTheMonitorsIgnoresALooseBlockAndFindsTheDamsFactor) {
  const std::string cube =
      "  - name: loose\n"
      "    prism: {profile: [[10, 2], [11, 2], [11, 3], [10, 3]], sweep: y, from: 1, to: 2}\n"
      "    material: steel\n";  // its own material: the dam keeps its dam-rock joint
  std::string output;
  ASSERT_EQ(
      run("overload", damScene(kCrestMonitor, "6.0", "[water]", "30.0e3", "{max_steps: 300}", cube),
          "every", output),
      0)
      << output;
  const nlohmann::json every =
      nlohmann::json::parse(test::readFile(dir.path() / "every" / "summary.json"));
  EXPECT_TRUE(every["overload"]["K_s"].is_null()) << every["overload"].dump(2);
  EXPECT_TRUE(every["overload"]["last_stable"].is_null());
  for (const nlohmann::json& r : every["overload"]["runs"]) {
    EXPECT_FALSE(r["at_rest"].get<bool>());
    EXPECT_EQ(r["steps"], 10);
    EXPECT_TRUE(r["failing"].get<bool>());
    EXPECT_TRUE(r["steady"].get<bool>());
    // Its step is exactly g dt^2 / 2 but for round-off: the ratio of a free fall.
    EXPECT_NEAR(r["unbalanced_ratio"].get<double>(), 1.0, 1e-9);
  }
  EXPECT_EQ(every["equilibrium"]["watch"], "all");

  ASSERT_EQ(run("overload",
                damScene(kCrestMonitor, "6.0", "[water]", "30.0e3",
                         "{max_steps: 300, watch: monitors}", cube),
                "watched", output),
            0)
      << output;
  const nlohmann::json watched =
      nlohmann::json::parse(test::readFile(dir.path() / "watched" / "summary.json"));
  EXPECT_EQ(watched["equilibrium"]["watch"], "monitors");
  const double expected = slidingFactor();  // 2.40
  ASSERT_TRUE(watched["safety_factor"].is_number()) << watched["overload"].dump(2);
  EXPECT_NEAR(watched["safety_factor"].get<double>(), expected, 0.03 * expected);
  test::recordVerification({.group = "Dams",
                            .name = "the same dam with a loose cube falling beside it, watch: "
                                    "monitors: overload factor K_s",
                            .source = kDamSource,
                            .expected = expected,
                            .measured = watched["safety_factor"].get<double>(),
                            .tolerance = 0.03,
                            .relative = true,
                            .unit = "-"});
  const nlohmann::json& first = watched["overload"]["runs"][0];
  EXPECT_TRUE(first["at_rest"].get<bool>());
  // The cube falls freely: its step is g dt^2 / 2 less nothing, a ratio of 1 (round-off).
  EXPECT_NEAR(first["all_blocks_ratio"].get<double>(), 1.0, 1e-9);
  EXPECT_LT(first["unbalanced_ratio"].get<double>(), 1e-3);
  EXPECT_EQ(first["fastest_watched_block"]["block"], 0);  // the dam
  EXPECT_NEAR(first["fastest_block"]["volume"].get<double>(), 1.0, 1e-9);
  // The step control's account: dt never cut below the scene's 1 ms, nothing redone.
  EXPECT_EQ(first["min_time_step"].get<double>(), 0.001);
  EXPECT_EQ(first["redone"]["open_close"], 0);
  EXPECT_EQ(first["redone"]["displacement"], 0);
  EXPECT_EQ(first["redone"]["penetration"], 0);
}

TEST_F(StabilityCli, WatchingMonitorsThatAreAllInHeldBlocksIsAnError) {
  std::string output;
  const std::string scene = damScene("  - {name: slab, point: [6, 2, -1]}\n", "6.0", "[water]",
                                     "30.0e3", "{max_steps: 300, watch: monitors}");
  EXPECT_EQ(run("overload", scene, "held", output), 2);
  const std::string before = scene.substr(0, scene.find("watch: monitors"));
  const auto line = std::count(before.begin(), before.end(), '\n') + 1;
  EXPECT_NE(output.find("held.yaml:" + std::to_string(line) +
                        ": analysis.equilibrium.watch: monitors, but every monitor lies in a held "
                        "block"),
            std::string::npos)
      << output;
}

TEST_F(StabilityCli, MonitorOutsideEveryBlockIsAnErrorNamingIt) {
  std::string output;
  const std::string scene = damScene("  - {name: lost, point: [20, 2, 5]}\n");
  EXPECT_EQ(run("overload", scene, "lost", output), 2);
  EXPECT_NE(output.find("monitors: lost"), std::string::npos) << output;
  // Located at the monitor's line of the scene file.
  const std::string before = scene.substr(0, scene.find("{name: lost"));
  const auto line = std::count(before.begin(), before.end(), '\n') + 1;
  EXPECT_NE(output.find("lost.yaml:" + std::to_string(line) + ":"), std::string::npos) << output;
}

TEST_F(StabilityCli, RunGivesTheAnswersOfEachAnalysisRunAlone) {
  // `run` computes the DDA stage, the overload and the strength reduction side by side on
  // threads of their own (app/run_command.cpp, computeStability); each run's steps are
  // deterministic whatever the threads, so each analysis must give, run for run, what its own
  // command gives alone: the same JSON (timings aside) and the same overload.csv bytes.
  std::string output;
  const std::string scene = damScene();
  ASSERT_EQ(test::runRockmass("run " + test::writeFile(dir.path() / "run.yaml", scene).string() +
                                  " -o " + (dir.path() / "run").string() + " --no-figures",
                              &output),
            0)
      << output;
  ASSERT_EQ(run("overload", scene, "overload", output), 0) << output;
  ASSERT_EQ(run("strength", scene, "strength", output), 0) << output;
  const auto summary = [&](const char* name) {
    return nlohmann::json::parse(test::readFile(dir.path() / name / "summary.json"));
  };
  const nlohmann::json both = summary("run");
  for (const char* search : {"overload", "strength_reduction"}) {
    ASSERT_TRUE(both.contains(search)) << search;
    const nlohmann::json alone =
        summary(search == std::string("overload") ? "overload" : "strength");
    EXPECT_EQ(both[search], alone[search]) << search;
    EXPECT_GT(both[search]["runs"].size(), 2u) << search;  // a search, not a single run
  }
  EXPECT_EQ(test::readFile(dir.path() / "run" / "overload.csv"),
            test::readFile(dir.path() / "overload" / "overload.csv"));
  EXPECT_TRUE(both["timings"].contains("dda"));
}

TEST_F(StabilityCli, WaterLevelBelowTheDomainIsAnError) {
  std::string output;
  EXPECT_EQ(run("overload", damScene(kCrestMonitor, "-5"), "dry", output), 2);
  EXPECT_NE(output.find("level"), std::string::npos) << output;
  EXPECT_NE(output.find("below the domain bottom"), std::string::npos) << output;
}

TEST_F(StabilityCli, UnknownLoadNameInOverloadScalesIsAnError) {
  std::string output;
  EXPECT_EQ(run("overload", damScene(kCrestMonitor, "6.0", "[water, wind]"), "wind", output), 2);
  EXPECT_NE(output.find("unknown load 'wind'"), std::string::npos) << output;
  EXPECT_NE(output.find("analysis.overload.scales"), std::string::npos) << output;
}

}  // namespace
}  // namespace rockmass
