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

TEST(Cli, DiscBudgetIsCheckedBeforeAnyDiscAtTheKeyThatDrivesIt) {
  // The bad-input bombs: a joint set of p32 0.4 in a 1 km cube with 1 m traces would draw
  // ~4e8 discs (27 s, 4.8 GB, then std::bad_alloc before the budget); an exponential trace
  // length of mean 4e6 m in a 20 m cube draws its centres millions of metres around the
  // domain (still generating after 120 s). Both are refused by the pilot's estimate, at the
  // key that drives them, before anything is written.
  TempDir dir("cli_disc_budget");
  const std::string header = R"(version: 1
name: disc-budget
seed: 1
domain:
  box: {min: [0, 0, -1000], max: [1000, 1000, 0]}
joint_sets:
)";
  const std::string dense = header + R"(  - name: J1
    orientation: {distribution: fisher, dip_direction: 90, dip: 20, kappa: 30}
    intensity: {p32: 0.4}
    trace_length: {distribution: lognormal, mean: 1.0, std: 0.5}
)";
  std::string output;
  EXPECT_EQ(test::runOnScene("dfn", dir.path(), "dense", dense, &output), 2) << output;
  const std::string dense_scene = (dir.path() / "dense.yaml").string();
  EXPECT_NE(output.find(dense_scene + ":9:16: joint_sets[0].intensity: "), std::string::npos)
      << output;
  EXPECT_NE(output.find("--max-discs"), std::string::npos) << output;
  EXPECT_NE(output.find("4.01e+08 discs"), std::string::npos) << output;  // lambda V, 3 digits
  EXPECT_FALSE(fs::exists(dir.path() / "dense" / "fractures.fab"));

  std::string huge = header + R"(  - name: J2
    orientation: {distribution: fisher, dip_direction: 300, dip: 70, kappa: 40}
    intensity: {p32: 0.3}
    trace_length: {distribution: exponential, mean: 4000000.0, min: 0.5}
)";
  huge.replace(huge.find("-1000], max: [1000, 1000"), 24, "-20], max: [20, 20");
  EXPECT_EQ(test::runOnScene("dfn", dir.path(), "huge", huge, &output), 2) << output;
  const std::string huge_scene = (dir.path() / "huge.yaml").string();
  EXPECT_NE(output.find(huge_scene + ":10:19: joint_sets[0].trace_length: "), std::string::npos)
      << output;
  EXPECT_NE(output.find("check the trace length"), std::string::npos) << output;

  // The limit is the user's: the small scene draws a few hundred discs, refused under
  // --max-discs 100, written with the default.
  writeFile(dir.path() / "small.yaml", kScene);
  const std::string small = (dir.path() / "small.yaml").string();
  const Result refused =
      test::runCli("dfn " + small + " -o " + (dir.path() / "s1").string() + " --max-discs 100");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("over the limit of 100 "), std::string::npos) << refused.output;
  const Result accepted = test::runCli("dfn " + small + " -o " + (dir.path() / "s2").string());
  EXPECT_EQ(accepted.exit_code, 0) << accepted.output;
}

TEST(Cli, MissingSceneAndBadArgumentsExitWithTwo) {
  EXPECT_EQ(test::runCli("dfn /nonexistent/scene.yaml -o /tmp/rockmass_cli_none").exit_code, 2);
  EXPECT_EQ(test::runCli("dfn").exit_code, 2);  // no scene, no -o
  EXPECT_EQ(test::runCli("unknown-command x").exit_code, 2);
  EXPECT_EQ(test::runCli("dfn a.yaml -o b --seed notanumber").exit_code, 2);
  const Result version = test::runCli("--version");
  EXPECT_EQ(version.exit_code, 0);
  // The version, the commit (git describe, "unknown" outside a checkout) and one line per
  // library with the version its headers give.
  EXPECT_EQ(version.output.rfind("rockmass 0.1.0 (commit ", 0), 0u) << version.output;
  for (const char* library :
       {"\n  CGAL 5.", "\n  CHOLMOD (SuiteSparse) ", "\n  CLI11 ", "\n  Eigen 3.", "\n  Embree 3.",
        "\n  nlohmann-json 3.", "\n  OpenVDB ", "\n  assimp 5.", "\n  oneTBB ", "\n  zlib 1."}) {
    EXPECT_NE(version.output.find(library), std::string::npos) << library << version.output;
  }
}

TEST(Cli, TheProgramRunsOnTheBlasItWasBuiltWith) {
  // CHOLMOD's factorizations run on ATLAS's BLAS and LAPACK when the build found them
  // (CMakeLists.txt): the program loads them whatever LD_LIBRARY_PATH says (here the
  // reference BLAS's and LAPACK's own directories, which alone would give CHOLMOD those and
  // their round-off; installing ATLAS makes it the system's default, so only such a path
  // tells the pin from the default).
  const Result plain = test::runCli("--version");
  for (const char* library : {"\n  BLAS ", "\n  LAPACK "}) {
    const std::size_t at = plain.output.find(library);
    ASSERT_NE(at, std::string::npos) << library << plain.output;
  }
#ifdef ROCKMASS_ATLAS_DIR
  const std::string atlas = ROCKMASS_ATLAS_DIR;
  EXPECT_NE(plain.output.find("\n  BLAS " + atlas + "/libblas.so"), std::string::npos)
      << plain.output;
  EXPECT_NE(plain.output.find("\n  LAPACK " + atlas + "/liblapack.so"), std::string::npos)
      << plain.output;
  const std::string reference = "/usr/lib/x86_64-linux-gnu/blas/libblas.so.3";
  ASSERT_TRUE(fs::exists(reference))
      << reference << " (libblas3, which CHOLMOD's package depends on) is needed to check that "
      << "LD_LIBRARY_PATH cannot take the program off ATLAS";
  std::string output;
  ASSERT_EQ(test::runRockmass("--version", &output,
                              "LD_LIBRARY_PATH=/usr/lib/x86_64-linux-gnu/blas:"
                              "/usr/lib/x86_64-linux-gnu/lapack"),
            0);
  EXPECT_NE(output.find("\n  BLAS " + atlas + "/libblas.so"), std::string::npos) << output;
  EXPECT_NE(output.find("\n  LAPACK " + atlas + "/liblapack.so"), std::string::npos) << output;
#endif
}

TEST(Cli, MistypedCommandsAndOptionsAreNamedWithTheClosestValidOne) {
  // CLI11 alone said "A subcommand is required" for `rockmass rn`.
  const Result command = test::runCli("rn scene.yaml -o out");
  EXPECT_EQ(command.exit_code, 2);
  EXPECT_NE(command.output.find("error: unknown command 'rn'; expected one of: dfn, blocks, rqd, "
                                "dda, overload, strength, run, ensemble (did you mean 'run'?)"),
            std::string::npos)
      << command.output;
  const Result option = test::runCli("dda scene.yaml -o out --solvr pcg");
  EXPECT_EQ(option.exit_code, 2);
  EXPECT_NE(option.output.find("error: unknown option '--solvr' for rockmass dda (did you mean "
                               "'--solver'?)"),
            std::string::npos)
      << option.output;
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
