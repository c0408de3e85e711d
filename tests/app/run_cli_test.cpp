// rockmass run end to end: it runs the stages the scene's analysis names and nothing else,
// lists them with their timings in one summary.json, writes every file it lists, is
// reproducible, refuses a stage whose input is missing (exit 2, naming the scene key), and
// runs the Xiangjiaba example in --quick mode.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace rockmass {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

/// Three stacked blocks (two persistent horizontal faults), the bottom one held, a joint
/// set of small discs for RQD, and the analysis section appended by each test.
const std::string kSceneHead = R"(version: 1
name: run-stack
seed: 7
domain:
  box: {min: [0, 0, -3], max: [2, 2, 0]}
materials:
  rock: {density: 2500, young: 10.0e9, poisson: 0.25}
rock_material: rock
joints:
  rj: {friction: 0.6, cohesion: 0}
default_joint: rj
joint_sets:
  - name: J1
    orientation: {distribution: fisher, dip_direction: 90, dip: 80, kappa: 50}
    spacing: {distribution: constant, mean: 0.5}
    trace_length: {distribution: constant, mean: 0.6}
    min_cut_size: 10.0
faults:
  - {name: upper, center: [1, 1, -1], dip_direction: 0, dip: 0}
  - {name: lower, center: [1, 1, -2], dip_direction: 0, dip: 0}
loads:
  gravity: 9.81
supports:
  fixed: [bottom]
monitors:
  - {name: top, point: [1, 1, -0.5]}
)";

const std::string kFullAnalysis = R"(analysis:
  blocks: {cutter: fast}
  rqd:
    thresholds: [0.1, 0.5, 1]
    balls:
      - {name: c, center: [1, 1, -1.5], length: 2, directions: 40}
  dda:
    mode: static
    steps: 10
    time_step: 0.01
    penalty: 1.0e8
  overload: {factors: [1, 2], scales: [gravity]}
)";

Json readJson(const fs::path& file) {
  return Json::parse(test::readFile(file));
}

/// Writes `text` as scene.yaml in `dir` and returns its path.
fs::path writeScene(const test::TempDir& dir, const std::string& text) {
  const fs::path scene = dir.path() / "scene.yaml";
  test::writeFile(scene, text);
  return scene;
}

// With an overload to run, `run` draws the stereonet and the section (inputs final before the
// DDA) beside it and the other figures at the end; on one thread, all at the end. The python
// is a wrapper that logs each call, so the test sees which path each run took. Either way the
// same figures are drawn, named in summary.json, each PNG the same bytes (the figures read
// only the files, which are the same), and the early stereonet names the scene (from the
// command line: summary.json is not written yet). Also: the fractures' and the blocks' files,
// written beside the stages, are the same bytes as those written in turn.
TEST(RunCli, FiguresDrawnBesideTheStabilityAnalysesAreThoseDrawnAtTheEnd) {
  if (std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "no matplotlib for /usr/bin/python3";
  }
  test::TempDir dir("run_cli_figures");
  const fs::path scene = writeScene(dir, kSceneHead + kFullAnalysis);
  const fs::path python = dir.path() / "python";
  test::writeFile(python, "#!/bin/sh\necho \"$*\" >> \"$0.log\"\nexec /usr/bin/python3 \"$@\"\n");
  fs::permissions(python, fs::perms::owner_all);
  std::vector<Json> summaries;
  std::vector<std::vector<std::string>> calls;  // the make_figures.py calls of each run
  for (const char* threads : {"2", "1"}) {
    const fs::path out = dir.path() / (std::string("out") + threads);
    std::string log;
    fs::remove(python.string() + ".log");
    ASSERT_EQ(test::runRockmass("run " + scene.string() + " -o " + out.string() + " --threads " +
                                    threads + " --python " + python.string(),
                                &log),
              0)
        << log;
    summaries.push_back(readJson(out / "summary.json"));
    EXPECT_TRUE(summaries.back()["run"]["warnings"].empty()) << log;
    std::istringstream called(test::readFile(python.string() + ".log"));
    calls.emplace_back();
    for (std::string line; std::getline(called, line);) {
      const std::size_t at = line.find("make_figures.py ");
      if (at == std::string::npos) continue;
      const std::size_t space = line.find(' ', at + 16);  // after OUTDIR
      calls.back().push_back(space == std::string::npos ? "" : line.substr(space + 1));
    }
  }
  std::sort(calls[0].begin(), calls[0].end());
  EXPECT_EQ(calls[0],
            (std::vector<std::string>{"--only stereonet.png,section.png --scene run-stack",
                                      "--skip stereonet.png,section.png"}));
  // One thread: all at the end, no arguments after OUTDIR.
  EXPECT_EQ(calls[1], std::vector<std::string>{""});
  const Json expected =
      Json::array({"block_volumes.png", "histories.png", "overload_curve.png", "rqd_ball_maps.png",
                   "rqd_threshold.png", "section.png", "stereonet.png"});
  for (const Json& s : summaries) EXPECT_EQ(s["run"]["figures"], expected);
  for (const Json& png : expected) {
    const std::string name = png.get<std::string>();
    EXPECT_EQ(test::readFile(dir.path() / "out2" / name),
              test::readFile(dir.path() / "out1" / name))
        << name;
  }
  for (const char* file : {"fractures.csv", "fractures.fab", "fractures.vtu", "blocks.csv",
                           "blocks.vtu", "faces.vtu"}) {
    EXPECT_EQ(test::readFile(dir.path() / "out2" / file),
              test::readFile(dir.path() / "out1" / file))
        << file;
  }
  // The early stereonet names the scene as the others do (its PNG's description, tEXt).
  EXPECT_NE(test::readFile(dir.path() / "out2" / "stereonet.png").find("\"scene\": \"run-stack\""),
            std::string::npos);
}

TEST(RunCli, RunsTheStagesTheSceneNamesAndListsThem) {
  test::TempDir dir("run_cli_full");
  const fs::path scene = writeScene(dir, kSceneHead + kFullAnalysis);
  const fs::path out = dir.path() / "out";
  std::string log;
  ASSERT_EQ(
      test::runRockmass("run " + scene.string() + " -o " + out.string() + " --no-figures", &log), 0)
      << log;
  const Json s = readJson(out / "summary.json");
  EXPECT_EQ(s["command"], "run");
  EXPECT_EQ(s["stages"], Json::array({"dfn", "cut", "rqd", "dda", "overload"}));
  for (const char* key : {"dfn", "cut", "rqd", "dda", "overload", "write", "section"}) {
    ASSERT_TRUE(s["timings"].contains(key)) << key;
    EXPECT_GE(s["timings"][key].get<double>(), 0.0) << key;
  }
  EXPECT_FALSE(s["timings"].contains("strength_reduction"));  // not asked for
  // The DDA's active physics: static gravity on contacts, no water, no point loads.
  const std::set<std::string> effects(s["effects"].begin(), s["effects"].end());
  EXPECT_TRUE(effects.count("body_force"));
  EXPECT_TRUE(effects.count("contact_normal"));
  EXPECT_FALSE(effects.count("water_pressure"));
  // Keys of the stage summaries, at the top level as the contract lists them.
  EXPECT_EQ(s["blocks"], 3);  // the two persistent faults make three blocks
  EXPECT_GT(s["discs"].get<int>(), 2);
  EXPECT_TRUE(s.contains("weibull") && s.contains("volume_stats") && s.contains("sets"));
  EXPECT_NEAR(s["total_volume"].get<double>(), 12.0, 1e-9);  // the 2 x 2 x 3 box
  // The overload stage ran both factors (no bisection asked for): two runs, and the
  // safety factor key of the contract (null or K_s, depending on the runs).
  EXPECT_TRUE(s["run"]["unavailable"].empty());
  ASSERT_TRUE(s.contains("overload"));
  EXPECT_EQ(s["overload"]["runs"].size(), 2u);
  EXPECT_TRUE(s.contains("safety_factor"));
  // Every file listed exists, and every stage's promised file is listed.
  std::set<std::string> files;
  for (const Json& f : s["run"]["files"]) {
    files.insert(f.get<std::string>());
    EXPECT_TRUE(fs::exists(out / f.get<std::string>())) << f;
  }
  for (const char* f :
       {"fractures.fab", "fractures.csv", "fractures.vtu", "blocks.csv", "blocks.vtu", "faces.vtu",
        "section.csv", "section.svg", "rqd_balls.csv", "rqd_ball_c_t0.1.ply", "history.csv",
        "dda.pvd", "dda_000010.vtu", "overload.csv", "summary.json"}) {
    EXPECT_TRUE(files.count(f)) << f;
  }
  EXPECT_EQ(s["run"]["section"], "y=1");  // default: mid-plane normal to y (no structure)
}

TEST(RunCli, SameSceneAndSeedGiveTheSameFiles) {
  test::TempDir dir("run_cli_repeat");
  const fs::path scene = writeScene(dir, kSceneHead + kFullAnalysis);
  for (const char* name : {"a", "b"}) {
    ASSERT_EQ(test::runRockmass("run " + scene.string() + " -o " + (dir.path() / name).string() +
                                " --no-figures"),
              0);
  }
  Json a = readJson(dir.path() / "a" / "summary.json");
  Json b = readJson(dir.path() / "b" / "summary.json");
  for (Json* j : {&a, &b}) j->erase("timings");  // the only part allowed to differ
  EXPECT_EQ(a, b);
  for (const Json& f : a["run"]["files"]) {
    if (f == "summary.json") continue;
    EXPECT_EQ(test::readFile(dir.path() / "a" / f.get<std::string>()),
              test::readFile(dir.path() / "b" / f.get<std::string>()))
        << f;
  }
}

TEST(RunCli, RunsNothingTheSceneDoesNotAskFor) {
  test::TempDir dir("run_cli_blocks_only");
  const fs::path scene = writeScene(dir, kSceneHead + "analysis:\n  blocks: {cutter: fast}\n");
  const fs::path out = dir.path() / "out";
  ASSERT_EQ(test::runRockmass("run " + scene.string() + " -o " + out.string() +
                              " --no-figures --section z=-1.5"),
            0);
  const Json s = readJson(out / "summary.json");
  EXPECT_EQ(s["stages"], Json::array({"dfn", "cut"}));
  EXPECT_TRUE(s["effects"].empty());
  for (const char* key : {"rqd", "dda", "overload", "strength_reduction"}) {
    EXPECT_FALSE(s["timings"].contains(key)) << key;
  }
  EXPECT_FALSE(fs::exists(out / "history.csv"));
  EXPECT_FALSE(fs::exists(out / "rqd_balls.csv"));
  EXPECT_EQ(s["run"]["section"], "z=-1.5");
  EXPECT_TRUE(fs::exists(out / "section.csv"));
}

TEST(RunCli, MissingStageInputNamesTheKey) {
  test::TempDir dir("run_cli_missing");
  // DDA with nothing to cut and no analysis.blocks.
  const std::string bare = R"(version: 1
name: bare
seed: 1
domain:
  box: {min: [0, 0, 0], max: [1, 1, 1]}
materials:
  rock: {density: 2500, young: 1.0e9, poisson: 0.25}
rock_material: rock
joints:
  rj: {friction: 0.6, cohesion: 0}
default_joint: rj
analysis:
  dda: {mode: static, steps: 2, time_step: 0.01}
)";
  std::string log;
  fs::path scene = writeScene(dir, bare);
  EXPECT_EQ(
      test::runRockmass("run " + scene.string() + " -o " + (dir.path() / "o1").string(), &log), 2);
  EXPECT_NE(log.find("analysis.dda"), std::string::npos) << log;
  EXPECT_NE(log.find("add analysis.blocks"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir.path() / "o1" / "fractures.csv"));  // refused before any work

  // Overload without the DDA it runs on.
  scene =
      writeScene(dir, kSceneHead + "analysis:\n  overload: {factors: [1, 2], scales: [gravity]}\n");
  EXPECT_EQ(
      test::runRockmass("run " + scene.string() + " -o " + (dir.path() / "o2").string(), &log), 2);
  EXPECT_NE(log.find("analysis.overload"), std::string::npos) << log;
  EXPECT_NE(log.find("add analysis.dda"), std::string::npos) << log;

  // A section plane outside the domain.
  scene = writeScene(dir, kSceneHead + kFullAnalysis);
  EXPECT_EQ(
      test::runRockmass(
          "run " + scene.string() + " -o " + (dir.path() / "o3").string() + " --section y=5", &log),
      2);
  EXPECT_NE(log.find("--section"), std::string::npos) << log;
}

// analysis.equilibrium.watch: monitors with its only monitor in the held bottom block: `run`
// stops with the error at the line of `watch` before the DDA stage (no history.csv), not after
// it, when the stability stage would have started.
TEST(RunCli, WatchingOnlyHeldMonitorsStopsBeforeTheDda) {
  test::TempDir dir("run_cli_watch_held");
  std::string head = kSceneHead;
  head.replace(head.find("[1, 1, -0.5]"), 12, "[1, 1, -2.5]");
  const std::string text = head + kFullAnalysis + "  equilibrium: {watch: monitors}\n";
  const fs::path scene = writeScene(dir, text);
  const fs::path out = dir.path() / "out";
  std::string log;
  EXPECT_EQ(
      test::runRockmass("run " + scene.string() + " -o " + out.string() + " --no-figures", &log), 2)
      << log;
  const auto line = std::count(text.begin(), text.begin() + text.find("watch: monitors"), '\n') + 1;
  EXPECT_NE(log.find("scene.yaml:" + std::to_string(line) +
                     ": analysis.equilibrium.watch: monitors, but every monitor lies in a held "
                     "block"),
            std::string::npos)
      << log;
  EXPECT_FALSE(fs::exists(out / "history.csv"));
}

// The Xiangjiaba example, --quick (the structure footprint, the top sixth of the depth, 10
// DDA steps, 200 ball directions, at most 4 factors and 20 steps per stability run), with the
// fast cutter (the same 2140 blocks as the scene's exact cutter, in a fifth of the time).
struct QuickRun {
  test::TempDir dir{"run_cli_xiangjiaba"};
  fs::path out = dir.path() / "out";
  std::string log;
  int code = -1;
};

const QuickRun& xiangjiabaQuick() {
  static const QuickRun* run = [] {
    auto* r = new QuickRun;
    r->code = test::runRockmass(std::string("run ") + ROCKMASS_SOURCE_DIR +
                                    "/examples/xiangjiaba/scene.yaml -o " + r->out.string() +
                                    " --quick --cutter fast --no-figures",
                                &r->log);
    return r;
  }();
  return *run;
}

TEST(RunCli, XiangjiabaQuickGivesTheSameBytesOnOneThread) {
  // Every stage's parallel loops (DFN measurement, both cutters' regions, RQD scanlines and
  // volume, DDA contact detection and area assignment) must not depend on how the work is
  // split: the quick run on one thread writes the same files, byte for byte, as on every
  // core (summary.json: all but its timings).
  const QuickRun& all = xiangjiabaQuick();
  ASSERT_EQ(all.code, 0) << all.log;
  test::TempDir dir("run_cli_one_thread");
  const fs::path out = dir.path() / "out";
  std::string log;
  ASSERT_EQ(test::runRockmass(std::string("run ") + ROCKMASS_SOURCE_DIR +
                                  "/examples/xiangjiaba/scene.yaml -o " + out.string() +
                                  " --quick --cutter fast --no-figures --threads 1",
                              &log),
            0)
      << log;
  Json a = readJson(all.out / "summary.json");
  Json b = readJson(out / "summary.json");
  for (Json* j : {&a, &b}) j->erase("timings");
  EXPECT_EQ(a, b);
  int compared = 0;
  for (const Json& f : a["run"]["files"]) {
    if (f == "summary.json") continue;
    EXPECT_EQ(test::readFile(all.out / f.get<std::string>()),
              test::readFile(out / f.get<std::string>()))
        << f;
    ++compared;
  }
  EXPECT_GE(compared, 15);
}

TEST(RunCli, XiangjiabaQuick) {
  const QuickRun& run = xiangjiabaQuick();
  // Written before the DDA starts: the DFN, blocks, section and RQD files.
  for (const char* f : {"fractures.csv", "fractures.fab", "fractures.vtu", "blocks.csv",
                        "blocks.vtu", "section.csv", "section.svg", "rqd_balls.csv",
                        "boreholes.csv", "rqd.vdb", "rqd_ball_heel_t1.ply"}) {
    EXPECT_TRUE(fs::exists(run.out / f)) << f;
  }
  std::ifstream blocks(run.out / "blocks.csv");
  int rows = -1;  // header
  for (std::string line; std::getline(blocks, line);) ++rows;
  EXPECT_GT(rows, 50);  // the quick box still holds far more than 50 blocks
  ASSERT_NE(run.code, -1) << run.log;
  ASSERT_LT(run.code, 128) << "killed by a signal: " << run.log;  // never a crash
  ASSERT_EQ(run.code, 0) << run.log;
  for (const char* f : {"history.csv", "dda.pvd", "overload.csv", "summary.json"}) {
    EXPECT_TRUE(fs::exists(run.out / f)) << f;
  }
  const Json s = readJson(run.out / "summary.json");
  EXPECT_GT(s["blocks"].get<int>(), 50);
  // The blocks below analysis.dda.min_block_volume (5 m3) were glued, not lost: the glued
  // model is still far more than 50 blocks and every glued volume is accounted for.
  EXPECT_GT(s["glued_blocks"]["blocks_after"].get<int>(), 50);
  EXPECT_EQ(s["glued_blocks"]["blocks_before"].get<int>(), s["blocks"].get<int>());
  EXPECT_EQ(s["glued_blocks"]["blocks_before"].get<int>() - s["glued_blocks"]["merged"].get<int>(),
            s["glued_blocks"]["blocks_after"].get<int>());
  for (const char* key : {"dfn", "cut", "rqd", "dda", "overload", "strength_reduction", "write"}) {
    EXPECT_TRUE(s["timings"].contains(key)) << key;
  }
  EXPECT_EQ(s["stages"],
            Json::array({"dfn", "cut", "rqd", "grid", "dda", "overload", "strength_reduction"}));
  for (const Json& f : s["run"]["files"]) {
    EXPECT_TRUE(fs::exists(run.out / f.get<std::string>())) << f;
  }
  // The scene starts every factor from the settled state (analysis.equilibrium.start), timed
  // on its own; a run not at rest either used its 40 steps or stopped as failing after the
  // scene's failure_steps (5) failing steps in a row.
  EXPECT_TRUE(s["timings"].contains("stability_start"));
  const int failure_steps = s["equilibrium"]["failure_steps"].get<int>();
  EXPECT_EQ(failure_steps, 5);
  for (const char* search : {"overload", "strength_reduction"}) {
    for (const Json& r : s[search]["runs"]) {
      if (r["at_rest"].get<bool>()) continue;
      if (r["failing"].get<bool>()) {
        EXPECT_GE(r["steps"].get<int>(), failure_steps) << r.dump();
        EXPECT_LE(r["steps"].get<int>(), 40) << r.dump();
      } else {
        EXPECT_EQ(r["steps"].get<int>(), 40) << r.dump();
      }
    }
  }
  // The scene judges equilibrium on the monitored blocks (analysis.equilibrium.watch), and its
  // monitor D1 in the dam stays in the dam: the quick run moves into its box only the points
  // inside the scene's domain (P4, 20 m deep below the toe), not one on a structure above it.
  EXPECT_EQ(s["equilibrium"]["watch"], "monitors");
  ASSERT_EQ(s["monitors"].size(), 5u);
  EXPECT_EQ(s["monitors"][4]["name"], "D1");
  EXPECT_NE(s["monitors"][4]["block"], s["monitors"][1]["block"]);  // P2, 1 m under the dam
  for (const Json& w : s["run"]["warnings"]) {
    EXPECT_EQ(w.get<std::string>().find("monitor D1"), std::string::npos) << w;
  }
  EXPECT_NE(s["run"]["warnings"].dump().find("monitor P4 moved"), std::string::npos);
  for (const Json& r : s["overload"]["runs"]) EXPECT_TRUE(r.contains("fastest_watched_block"));
  // A finite safety factor (one test with the run above: the quick run is the suite's
  // longest, about 20 s). The dam stands under its own loads: the overload starts at K = 1, at
  // rest.
  ASSERT_TRUE(s["safety_factor"].is_number()) << s["overload"].dump();
  EXPECT_TRUE(std::isfinite(s["safety_factor"].get<double>()));
  EXPECT_GT(s["safety_factor"].get<double>(), 1.0);
  EXPECT_TRUE(s["overload"]["runs"][0]["at_rest"].get<bool>());
  // The dam's uplift (loads.pore_pressure: the USBR diagram, reservoir z = 158 at the heel
  // x = 60, drains 10 m downstream at tailwater + (1 - 0.667) x 110 m, tailwater z = 48 at the
  // toe x = 180; the base at z = 0, 20 m wide): gw * 20 * ((158 + h_d) / 2 * 10 + (h_d + 48) /
  // 2 * 110). The quick box's region planes run through the base's centre and quarter points:
  // the interface is still found there.
  const double h_d = 48.0 + (1.0 - 0.667) * 110.0;
  const double uplift = 9810.0 * 20.0 * ((158.0 + h_d) / 2.0 * 10.0 + (h_d + 48.0) / 2.0 * 110.0);
  ASSERT_EQ(s["uplift"].size(), 1u) << s.dump().substr(0, 200);
  EXPECT_NEAR(s["uplift"][0]["vertical"].get<double>(), uplift, 1e-9 * uplift);
  // The sides are on rollers (supports.rollers), the base fixed.
  EXPECT_NE(std::find(s["effects"].begin(), s["effects"].end(), "rollers"), s["effects"].end());
  // The DDA runs on coarsened pieces (blocks::coarsenPieces): the glued blocks' 30 068 cut
  // pieces become 5 444 convex ones; at least halving them is what keeps this run short.
  EXPECT_LT(2 * s["dda"]["pieces"].get<int>(), s["pieces"].get<int>());
  // The open-close iteration settles within its allowance of state changes
  // (DdaSettings::open_close_tolerance) at nearly every step: at most 2 of the steps are
  // redone, and dt stays within 0.1 of the scene's 2 ms step. Without the allowance step 4
  // failed its 20 iterations again and again and dt fell below 1e-4 of the step; with it, the
  // accepted steps take 2-16 iterations, so a step may still need a second attempt at 0.3 dt.
  int redone = 0;
  for (const auto& retries : s["steps"]["retries"]) redone += retries.get<int>() > 0;
  EXPECT_LE(redone, 2);
  for (const auto& dt : s["steps"]["time_step"]) EXPECT_GE(dt.get<double>(), 2e-4);
}

}  // namespace
}  // namespace rockmass

namespace rockmass {
namespace {

TEST(RunCli, XiangjiabaQuickDeformableHoldsAtTheDesignLoad) {
  // The quick scene with 12-unknown blocks: its dam (2.1e5 m3, one strain field) and the
  // glued rock under it must hold under their weight and the water at K = 1 within the
  // scene's 40 static steps, moving micrometres where the failing factors move the dam by
  // centimetres. Its dam's shear with the translation that keeps its base in place relieved
  // 1.2 % of its out-of-balance force per step before a deformable block's static inertia was
  // held to its elasticity (docs/dda3d.md, "Deformable blocks at scale"): unbalanced ratio
  // 0.035 after 40 steps.
  std::string scene =
      test::readFile(fs::path(ROCKMASS_SOURCE_DIR) / "examples/xiangjiaba/scene.yaml");
  const auto replace = [&](const std::string& from, const std::string& to) {
    const std::size_t at = scene.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    scene.replace(at, from.size(), to);
  };
  replace("kinematics: rigid", "kinematics: deformable");
  replace("factors: [1, 2, 4, 6, 7, 7.5, 8, 9]", "factors: [1]");
  // Only the DDA and the overload at K = 1: no RQD, no strength reduction.
  const std::size_t rqd = scene.find("\n  rqd:\n"), dda = scene.find("\n  dda:\n");
  ASSERT_TRUE(rqd != std::string::npos && dda != std::string::npos && rqd < dda);
  scene.erase(rqd, dda - rqd);
  const std::size_t srf = scene.find("\n  strength_reduction:");
  ASSERT_NE(srf, std::string::npos);
  scene.erase(srf, scene.find('\n', srf + 1) - srf);
  test::TempDir dir("run_cli_deformable");
  const fs::path file = dir.path() / "scene.yaml";
  std::ofstream(file) << scene;
  std::string log;
  ASSERT_EQ(test::runRockmass("run " + file.string() + " -o " + (dir.path() / "out").string() +
                                  " --quick --no-figures",
                              &log),
            0)
      << log;
  const Json s = readJson(dir.path() / "out" / "summary.json");
  EXPECT_EQ(s["kinematics"], "deformable");
  // The rock carries the joint water in its pores (the scene's biot_coefficient: 1).
  const std::vector<std::string> effects = s["effects"].get<std::vector<std::string>>();
  EXPECT_NE(std::find(effects.begin(), effects.end(), "block_pore_pressure"), effects.end());
  // The settled start runs to its own limit, start_steps 80, beyond the runs' 40 (not at rest
  // after its 80 with ATLAS's BLAS, ratio 8.0e-3, nor with the reference BLAS, 0.032).
  const std::size_t start = log.find("start state ");
  ASSERT_NE(start, std::string::npos) << log;
  const std::size_t after = log.find(" after ", start);
  ASSERT_NE(after, std::string::npos) << log;
  EXPECT_GT(std::stoi(log.substr(after + 7)), 40) << log.substr(start, 120);
  const Json& run = s["overload"]["runs"][0];
  EXPECT_EQ(run["factor"].get<double>(), 1.0);
  // Whether the run is also at rest by the rule (an unbalanced ratio below 1e-3 for 5 steps
  // in a row) within its 40 steps is set by the round-off: the static relaxation of this
  // deformable box is chaotic near rest (docs/dda3d.md, "Deformable blocks at scale"), its
  // small rock blocks at the toe, wedged between the dam and the downstream rollers by 30
  // times their weight, reading ratios of 0.01 to 0.3 from step to step. Measured on
  // 2026-11-29: at rest after 23 steps with ATLAS's BLAS when the copies of an edge crossing
  // were counted as two entries, and not at rest (0.095) with them as one; with the reference
  // BLAS not at rest either way (0.073, 0.088). In all four the monitors moved 1.5e-9 to
  // 1.8e-4 m over the run. The run must hold: not stopped as failing or moving steadily, and
  // every monitor within 1 mm (the rigid region's dam moves 1 cm in 40 steps at K = 4).
  EXPECT_FALSE(run["failing"].get<bool>()) << run.dump(2);
  EXPECT_FALSE(run["steady"].get<bool>()) << run.dump(2);
  EXPECT_LE(run["steps"].get<int>(), 40);
  EXPECT_LT(run["unbalanced_ratio"].get<double>(), 0.5);  // the scene's failure_ratio
  std::ifstream curve(dir.path() / "out" / "overload.csv");
  std::string row;
  ASSERT_TRUE(std::getline(curve, row));  // factor,monitor,ux,uy,uz,u,at_rest,steps
  int monitors = 0;
  while (std::getline(curve, row)) {
    std::vector<std::string> fields;
    std::stringstream in(row);
    for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
    ASSERT_EQ(fields.size(), 8u) << row;
    EXPECT_LT(std::stod(fields[5]), 1e-3) << row;
    ++monitors;
  }
  EXPECT_EQ(monitors, 5);
  EXPECT_TRUE(s["coarse_strain"].is_array());
  // The DDA stage's 10 static steps: each open-close iteration closes a few contacts by
  // 1e-6..1e-4 m as the blocks strain, and a static step may leave those (no deeper than 1 %
  // of the allowed penetration) to the next step (docs/dda3d.md, "Open-close allowance"):
  // 16.1 iterations a step on average (16.2 with the reference BLAS and with OpenBLAS);
  // requiring no closing at all, 20.9 (with the blocks impermeable, biot_coefficient 0: 13.0,
  // and 18.9). The bound lies between.
  std::ifstream steps(dir.path() / "out" / "steps.csv");
  std::string line;
  ASSERT_TRUE(std::getline(steps, line));  // header: step,time,time_step,contacts,...
  int count = 0;
  double iterations = 0.0;
  while (std::getline(steps, line)) {
    std::stringstream fields(line);
    std::string field;
    for (int column = 0; column <= 7 && std::getline(fields, field, ','); ++column) {
      if (column == 7) iterations += std::stod(field);  // the `iterations` column
    }
    ++count;
  }
  ASSERT_EQ(count, 10);
  EXPECT_LT(iterations / count, 18.5);
}

}  // namespace
}  // namespace rockmass
