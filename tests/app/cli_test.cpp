// The rockmass program end to end: exit codes, located errors, reproducible files.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace rockmass {
namespace {

namespace fs = std::filesystem;

using test::readFile;
using test::TempDir;
using test::writeFile;

using Result = test::CliResult;

/// A small scene: two joint sets, a fault and an interlayer in a 40 m cube.
const char* kScene = R"(version: 1
name: cli-test
seed: 7
domain:
  box: {min: [0, 0, -40], max: [40, 40, 0]}
materials:
  rock: {density: 2650, young: 7.0e9, poisson: 0.25}
  soft: {unit_weight: 20.0e3, young: 0.75e9, poisson: 0.4}
rock_material: rock
joints:
  rj: {friction: 0.86, cohesion: 0.8e6}
default_joint: rj
joint_sets:
  - name: J1
    dip_direction: {distribution: normal, mean: 85, std: 13, min: 45, max: 115}
    dip: {distribution: uniform, mean: 37, std: 11}
    spacing: {distribution: lognormal, mean: 2.0, std: 1.5}
    trace_length: {distribution: lognormal, mean: 6.0, std: 3.0}
    min_cut_size: 3.0
  - name: J2
    orientation: {distribution: fisher, dip_direction: 300, dip: 70, kappa: 40}
    intensity: {p32: 0.3}
    trace_length: {distribution: exponential, mean: 4.0, min: 0.5}
faults:
  - {name: F1, center: [20, 20, -20], dip_direction: 290, dip: 75, thickness: 0.5, material: soft}
interlayers:
  - {name: P1, profile: [[0, -10], [20, -14], [40, -12]], sweep: y, thickness: 0.4, material: soft}
)";

const char* kOutputs[] = {"fractures.fab", "fractures.csv", "fractures.vtu", "summary.json"};

/// summary.json without its last part, the timings (the only part that may change).
std::string withoutTimings(const std::string& summary) {
  return summary.substr(0, summary.find("\"timings\""));
}

TEST(Cli, DfnWritesEveryFileAndTheSameSeedGivesTheSameBytes) {
  TempDir dir("cli_reproducible");
  writeFile(dir.path() / "scene.yaml", kScene);
  const std::string scene = (dir.path() / "scene.yaml").string();
  const Result first = test::runCli("dfn " + scene + " -o " + (dir.path() / "a").string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const Result second = test::runCli("dfn " + scene + " -o " + (dir.path() / "b").string());
  ASSERT_EQ(second.exit_code, 0) << second.output;
  const Result other =
      test::runCli("dfn " + scene + " -o " + (dir.path() / "c").string() + " --seed 8");
  ASSERT_EQ(other.exit_code, 0) << other.output;
  for (const char* name : kOutputs) {
    const std::string a = readFile(dir.path() / "a" / name);
    ASSERT_FALSE(a.empty()) << name;
    const std::string b = readFile(dir.path() / "b" / name);
    const std::string c = readFile(dir.path() / "c" / name);
    if (std::string(name) == "summary.json") {
      EXPECT_EQ(withoutTimings(a), withoutTimings(b));
      EXPECT_NE(withoutTimings(a), withoutTimings(c));
      EXPECT_NE(a.find("\"seed\": 7"), std::string::npos) << "the scene seed is recorded";
      EXPECT_NE(c.find("\"seed\": 8"), std::string::npos) << "--seed overrides it";
    } else {
      EXPECT_EQ(a, b) << name;
      EXPECT_NE(a, c) << name;
    }
  }
  // No temporary file is left next to the outputs.
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir.path() / "a")) {
    ++files;
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos);
  }
  EXPECT_EQ(files, 4);
}

TEST(Cli, BadSceneExitsWithTwoAndALocatedMessage) {
  TempDir dir("cli_bad");
  std::string text = kScene;
  text.replace(text.find("mean: 2.0, std: 1.5"), 19, "mean: -2.0, std: 1.5");
  writeFile(dir.path() / "scene.yaml", text);
  const std::string scene = (dir.path() / "scene.yaml").string();
  const Result result = test::runCli("dfn " + scene + " -o " + (dir.path() / "out").string());
  EXPECT_EQ(result.exit_code, 2);
  // file:line:column, the key, and what was expected.
  EXPECT_NE(result.output.find(scene + ":17:"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("joint_sets[0].spacing"), std::string::npos) << result.output;
  // Nothing was written.
  EXPECT_FALSE(fs::exists(dir.path() / "out" / "fractures.fab"));
}

TEST(Cli, MissingSceneAndBadArgumentsExitWithTwo) {
  EXPECT_EQ(test::runCli("dfn /nonexistent/scene.yaml -o /tmp/rockmass_cli_none").exit_code, 2);
  EXPECT_EQ(test::runCli("dfn").exit_code, 2);  // no scene, no -o
  EXPECT_EQ(test::runCli("unknown-command x").exit_code, 2);
  EXPECT_EQ(test::runCli("dfn a.yaml -o b --seed notanumber").exit_code, 2);
  const Result version = test::runCli("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.output, "0.1.0\n");
}

TEST(Cli, UnwritableOutputIsAFailureNotACrash) {
  TempDir dir("cli_unwritable");
  writeFile(dir.path() / "scene.yaml", kScene);
  writeFile(dir.path() / "file", "not a folder");
  const Result result = test::runCli("dfn " + (dir.path() / "scene.yaml").string() + " -o " +
                                     (dir.path() / "file" / "out").string());
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("cannot create the output folder"), std::string::npos)
      << result.output;
}

}  // namespace
}  // namespace rockmass
