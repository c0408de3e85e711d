// rockmass ensemble through the command line: the aggregate against known answers (Priest &
// Hudson's RQD of exponential spacings, the probability of sliding of a block whose friction is
// normally distributed), realizations that are the same alone, in an ensemble and under MPI,
// resuming, load balancing over ranks, and the errors of bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"
#include "tests/support/verification.h"

namespace rockmass {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

constexpr double kPi = 3.14159265358979323846;

class EnsembleCli : public ::testing::Test {
 protected:
  test::TempDir dir{"ensemble_cli"};

  /// Writes `text` as <dir>/<name>.yaml; returns its path.
  std::string scene(const std::string& name, const std::string& text) {
    return test::writeFile(dir.path() / (name + ".yaml"), text).string();
  }
  /// `rockmass ensemble SCENE -o <dir>/<out> <more>`.
  test::CliResult ensemble(const std::string& scene_path, const std::string& out,
                           const std::string& more) {
    return test::runCli("ensemble " + scene_path + " -o " + (dir.path() / out).string() +
                        " --no-figures " + more);
  }
  Json aggregate(const std::string& out) {
    return Json::parse(test::readFile(dir.path() / out / "ensemble.json"));
  }
};

/// Horizontal joints of exponential spacing (mean 0.1 m) crossing a 40 m vertical borehole.
std::string priestHudsonScene() {
  return R"(version: 1
name: priest-hudson
seed: 5
domain:
  box: {min: [0, 0, -40], max: [10, 10, 0]}
joint_sets:
  - name: H
    dip_direction: {distribution: constant, mean: 0}
    dip: {distribution: constant, mean: 0}
    spacing: {distribution: exponential, mean: 0.1}
    trace_length: {distribution: constant, mean: 100}
analysis:
  rqd:
    thresholds: [0.1, 0.2]
    boreholes: {file: holes.csv, run_length: 40}
)";
}

TEST_F(EnsembleCli, MeanBoreholeRqdAcrossRealizationsIsPriestAndHudsons) {
  // Priest & Hudson (1976): joints at exponential spacing of rate lambda along a line give
  // E[RQD_t] = 100 e^{-lambda t} (1 + lambda t). Each realization is one 40 m hole through
  // about 400 joints; the mean over 30 realizations must hold the formula within its 95 %
  // confidence interval (the bias of the hole's two truncated end pieces, about 1 / (lambda L)
  // = 0.25 % of RQD, is below it).
  test::writeFile(dir.path() / "holes.csv", "id,x,y,z,azimuth,plunge,length\nA,5,5,0,0,90,40\n");
  const auto r = ensemble(scene("ph", priestHudsonScene()), "ph", "--realizations 30");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string csv = test::readFile(dir.path() / "ph" / "ensemble_boreholes.csv");
  for (const double t : {0.1, 0.2}) {
    const double expected = 100.0 * std::exp(-10.0 * t) * (1.0 + 10.0 * t);
    std::smatch m;
    const std::regex row("\nA," + std::string(t == 0.1 ? "0.1" : "0.2") +
                         ",30,([-0-9.e]+),([-0-9.e]+),");
    ASSERT_TRUE(std::regex_search(csv, m, row)) << csv;
    const double mean = std::stod(m[1]), ci95 = std::stod(m[2]);
    EXPECT_GT(ci95, 0.0);
    EXPECT_LT(ci95, 2.0);  // 30 realizations of ~400 joints: the mean is known to ~1 %
    EXPECT_NEAR(mean, expected, ci95) << "t = " << t;
    test::recordVerification({.group = "Ensembles",
                              .name = "mean borehole RQD of 30 realizations, exponential "
                                      "spacing 0.1 m, t = " +
                                      std::string(t == 0.1 ? "0.1" : "0.2") + " m",
                              .source = "Priest & Hudson (1976): 100 e^{-lambda t}(1 + lambda t)",
                              .expected = expected,
                              .measured = mean,
                              .tolerance = ci95,
                              .relative = false,
                              .unit = "%"});
  }
}

/// The block above a 30 degree joint (tests/app/water_loads_cli_test.cpp), its friction
/// normal N(mean, 0.1), sampled by a Latin hypercube of `size`.
std::string inclineScene(double mean, int size) {
  return R"(version: 1
name: block-on-an-inclined-joint
seed: 3
domain:
  box: {min: [0, 0, -15], max: [20, 10, 0]}
materials:
  rock: {density: 2600, young: 10.0e9, poisson: 0.25}
rock_material: rock
joints:
  plane: {friction: )" +
         std::to_string(mean) + R"(, cohesion: 0}
default_joint: plane
faults:
  - {name: plane, center: [10, 5, -5.773502691896258], dip_direction: 90, dip: 30}
loads:
  gravity: 9.81
supports:
  fixed: [bottom]
monitors:
  - {name: top, point: [15, 5, -1]}
analysis:
  blocks: {cutter: fast}
  dda: {mode: static, kinematics: rigid, steps: 5, time_step: 0.001}
  equilibrium: {max_steps: 300}
  strength_reduction: {factors: [0.5, 0.7, 0.9, 1.1, 1.3, 1.5, 1.7], tolerance: 0.02}
uncertainty:
  sampling: latin_hypercube
  size: )" +
         std::to_string(size) +
         R"(
  targets: {strength_reduction: 1.0}
  inputs:
    - {key: joints.plane.friction, distribution: normal, std: 0.1}
)";
}

TEST_F(EnsembleCli, ProbabilityOfSlidingMatchesTheNormalCdf) {
  // A block on a 30 degree joint without cohesion slides when f < tan 30 (Hoek & Bray, ch. 6):
  // its critical SRF is f / tan 30. With f ~ N(0.65, 0.1), P(SRF < 1) = Phi((tan 30 - 0.65) /
  // 0.1) = 0.234. 60 realizations of a Latin hypercube: the estimate must hold the CDF within
  // two of its binomial standard errors (0.055), and every realization's SRF its own
  // f / tan 30 within the bisection's 0.02.
  const int n = 60;
  const auto r = ensemble(scene("incline", inclineScene(0.65, n)), "incline",
                          "--realizations " + std::to_string(n) + " --jobs 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Json j = aggregate("incline");
  ASSERT_EQ(j["complete"], n);
  const double tan30 = std::tan(30.0 * kPi / 180.0);
  const double expected = 0.5 * std::erfc(-((tan30 - 0.65) / 0.1) / std::sqrt(2.0));
  const Json& srf = j["stability"]["critical_srf"];
  const double p = srf["probability_below"].get<double>();
  const double se = srf["standard_error"].get<double>();
  EXPECT_EQ(srf["known"], n);
  EXPECT_NEAR(se, std::sqrt(p * (1 - p) / n), 1e-12);
  EXPECT_NEAR(p, expected, 2.0 * se);
  test::recordVerification({.group = "Ensembles",
                            .name = "P(critical SRF < 1) of a block on a 30 deg joint, friction "
                                    "N(0.65, 0.1), 60 realizations (Latin hypercube)",
                            .source = "Phi((tan psi - mean) / std), plane sliding (Hoek & Bray)",
                            .expected = expected,
                            .measured = p,
                            .tolerance = 2.0 * se,
                            .relative = false,
                            .unit = "-"});
  // Each realization: SRF = f / tan 30 (the bisection's tolerance 0.02).
  const std::string csv = test::readFile(dir.path() / "incline" / "ensemble_realizations.csv");
  std::stringstream lines(csv);
  std::string line;
  std::getline(lines, line);
  const auto split = [](const std::string& text) {
    std::vector<std::string> f;
    std::stringstream fields(text);
    for (std::string x; std::getline(fields, x, ',');) f.push_back(x);
    return f;
  };
  const std::vector<std::string> header = split(line);
  const auto column = [&](const std::string& name) {
    const auto at = std::find(header.begin(), header.end(), name);
    EXPECT_NE(at, header.end()) << name << " in " << line;
    return static_cast<std::size_t>(at - header.begin());
  };
  const std::size_t friction_at = column("input:joints.plane.friction");
  const std::size_t srf_at = column("critical_srf");
  int rows = 0;
  while (std::getline(lines, line)) {
    const std::vector<std::string> f = split(line);
    ASSERT_GT(f.size(), srf_at) << line;
    const double friction = std::stod(f[friction_at]), factor = std::stod(f[srf_at]);
    EXPECT_NEAR(factor, friction / tan30, 0.02 + 1e-9) << line;
    ++rows;
  }
  EXPECT_EQ(rows, n);
  // The sensitivity names the friction, perfectly rank-correlated with the SRF.
  EXPECT_EQ(srf["sensitivity"][0]["key"], "joints.plane.friction");
  EXPECT_GT(srf["sensitivity"][0]["spearman"].get<double>(), 0.99);
  // The Latin hypercube puts one realization in each of the 60 strata of the friction.
  std::set<int> strata;
  std::stringstream again(csv);
  std::getline(again, line);
  while (std::getline(again, line)) {
    const double z = (std::stod(split(line)[friction_at]) - 0.65) / 0.1;
    const double u = 0.5 * std::erfc(-z / std::sqrt(2.0));
    strata.insert(static_cast<int>(std::floor(u * n)));
  }
  EXPECT_EQ(strata.size(), static_cast<std::size_t>(n));
}

/// One joint set in a 20 m cube and one RQD ball of `directions` in its middle: a
/// realization whose cost the ball sets.
std::string rqdBallScene(const std::string& name, const std::string& thresholds, int directions) {
  return "version: 1\nname: " + name + R"(
seed: 9
domain:
  box: {min: [0, 0, -20], max: [20, 20, 0]}
joint_sets:
  - name: S1
    dip_direction: {distribution: normal, mean: 90, std: 10}
    dip: {distribution: normal, mean: 45, std: 8}
    spacing: {distribution: exponential, mean: 0.5}
    trace_length: {distribution: lognormal, mean: 4, std: 2}
analysis:
  rqd:
    thresholds: [)" +
         thresholds + R"(]
    balls:
      - {name: mid, center: [10, 10, -10], length: 16, directions: )" +
         std::to_string(directions) + "}\n";
}

/// A small cut with sampled joint strength and orientation: blocks and a short DDA.
std::string smallScene(const std::string& extra_inputs = "") {
  return R"(version: 1
name: small-ensemble
seed: 42
domain:
  box: {min: [0, 0, -6], max: [6, 6, 0]}
materials:
  rock: {density: 2600, young: 10.0e9, poisson: 0.25}
rock_material: rock
joints:
  rj: {friction: 0.7, cohesion: 0}
default_joint: rj
joint_sets:
  - name: S1
    dip_direction: {distribution: normal, mean: 90, std: 10}
    dip: {distribution: normal, mean: 45, std: 8}
    spacing: {distribution: exponential, mean: 2.0}
    trace_length: {distribution: lognormal, mean: 8, std: 2}
  - name: S2
    dip_direction: {distribution: normal, mean: 200, std: 10}
    dip: {distribution: normal, mean: 70, std: 8}
    spacing: {distribution: exponential, mean: 2.5}
    trace_length: {distribution: lognormal, mean: 8, std: 2}
loads:
  gravity: 9.81
supports:
  fixed: [bottom]
analysis:
  blocks: {cutter: fast}
  dda: {mode: static, kinematics: rigid, steps: 3, time_step: 0.002}
uncertainty:
  inputs:
    - {key: joint_sets.S1.dip.mean, distribution: sample_mean, count: 40}
    - {key: joints.rj.friction, distribution: uniform, min: 0.5, max: 0.9}
)" + extra_inputs;
}

/// The 1-based line of the first occurrence of `key` in `text`.
int lineOf(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(key);
  EXPECT_NE(at, std::string::npos) << key;
  return 1 + static_cast<int>(
                 std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

/// Every file of a realization folder, summary.json without its timings.
std::map<std::string, std::string> filesOf(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::directory_iterator(folder)) {
    std::string text = test::readFile(entry.path());
    if (entry.path().filename() == "summary.json") {
      Json j = Json::parse(text);
      j.erase("timings");
      text = j.dump();
    }
    files[entry.path().filename().string()] = text;
  }
  return files;
}

bool haveMpirun() {
  return std::system("command -v mpirun > /dev/null 2>&1") == 0;
}

/// mpirun's environment for the tests: as root too, more ranks than cores.
std::string mpirun(int ranks) {
  return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
         "OMPI_MCA_rmaps_base_oversubscribe=1 "
         "mpirun -n " +
         std::to_string(ranks) + " --oversubscribe " + ROCKMASS_BINARY;
}

TEST_F(EnsembleCli, RealizationIsTheSameAloneInAnEnsembleAndUnderMpi) {
  const std::string path = scene("small", smallScene());
  const auto alone = ensemble(path, "alone", "--realizations 4 --only 2");
  ASSERT_EQ(alone.exit_code, 0) << alone.output;
  EXPECT_FALSE(fs::exists(dir.path() / "alone" / "ensemble.json"));  // --only: no aggregate
  EXPECT_FALSE(fs::exists(dir.path() / "alone" / "r0"));
  const auto one = ensemble(path, "one", "--realizations 4 --threads 1");
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const auto two = ensemble(path, "jobs", "--realizations 4 --jobs 2");
  ASSERT_EQ(two.exit_code, 0) << two.output;
  const auto reference = filesOf(dir.path() / "alone" / "r2");
  ASSERT_GT(reference.size(), 5u);
  EXPECT_EQ(filesOf(dir.path() / "one" / "r2"), reference);
  EXPECT_EQ(filesOf(dir.path() / "jobs" / "r2"), reference);
  // The realizations differ: their own seeds and samples.
  EXPECT_NE(test::readFile(dir.path() / "one" / "r1" / "fractures.csv"),
            test::readFile(dir.path() / "one" / "r2" / "fractures.csv"));
  const Json marker = Json::parse(test::readFile(dir.path() / "one" / "r2" / "realization.json"));
  EXPECT_EQ(marker["status"], "complete");
  EXPECT_EQ(marker["inputs"].size(), 2u);
  const double friction = marker["inputs"][1]["value"].get<double>();
  EXPECT_GE(friction, 0.5);
  EXPECT_LE(friction, 0.9);
  // The aggregate is the same whatever ran the realizations.
  EXPECT_EQ(test::readFile(dir.path() / "one" / "ensemble.json"),
            test::readFile(dir.path() / "jobs" / "ensemble.json"));

  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  if (test::runCli("--version").output.find("\n  MPI ") == std::string::npos) {
    GTEST_SKIP() << "rockmass built without MPI";
  }
  std::string output;
  const std::string command = mpirun(3) + " ensemble " + path + " -o " +
                              (dir.path() / "mpi").string() +
                              " --realizations 4 --no-figures --threads 1 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  ASSERT_EQ(pclose(pipe), 0) << output;
  EXPECT_NE(output.find("over 3 MPI ranks"), std::string::npos) << output;
  EXPECT_EQ(filesOf(dir.path() / "mpi" / "r2"), reference);
  EXPECT_EQ(test::readFile(dir.path() / "mpi" / "ensemble.json"),
            test::readFile(dir.path() / "one" / "ensemble.json"));
}

TEST_F(EnsembleCli, ResumeRunsOnlyTheMissingRealizations) {
  const std::string path = scene("small", smallScene());
  const auto whole = ensemble(path, "whole", "--realizations 5");
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  // A run stopped half-way: realizations 0 and 3 complete, 1 half-written (no marker).
  ASSERT_EQ(ensemble(path, "resumed", "--realizations 5 --only 0").exit_code, 0);
  ASSERT_EQ(ensemble(path, "resumed", "--realizations 5 --only 3").exit_code, 0);
  test::writeFile(dir.path() / "resumed" / "r1" / "fractures.csv", "half-written");
  const auto r0_before = fs::last_write_time(dir.path() / "resumed" / "r0" / "summary.json");
  const auto resumed = ensemble(path, "resumed", "--realizations 5");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("realization 0 already complete"), std::string::npos);
  EXPECT_NE(resumed.output.find("realization 3 already complete"), std::string::npos);
  for (int i : {1, 2, 4}) {
    EXPECT_NE(resumed.output.find("ensemble: realization " + std::to_string(i) + " of 5"),
              std::string::npos)
        << resumed.output;
  }
  EXPECT_EQ(resumed.output.find("ensemble: realization 0 of 5"), std::string::npos);
  EXPECT_EQ(fs::last_write_time(dir.path() / "resumed" / "r0" / "summary.json"), r0_before);
  EXPECT_EQ(test::readFile(dir.path() / "resumed" / "ensemble.json"),
            test::readFile(dir.path() / "whole" / "ensemble.json"));
  EXPECT_EQ(filesOf(dir.path() / "resumed" / "r1"), filesOf(dir.path() / "whole" / "r1"));
  // Another scene in the same folder is refused, not mixed in.
  const std::string changed =
      std::regex_replace(test::readFile(path), std::regex("seed: 42"), "seed: 43");
  const auto mixed = ensemble(scene("changed", changed), "resumed", "--realizations 5");
  EXPECT_EQ(mixed.exit_code, 2) << mixed.output;
  EXPECT_NE(mixed.output.find("was made from another scene, seed or sample"), std::string::npos)
      << mixed.output;
}

TEST_F(EnsembleCli, AnEnsembleStoppedByCtrlCResumesWhereItStopped) {
  // Six realizations of about half a second each (an RQD ball of 30 000 directions), SIGINT
  // after 1.5 s: the ensemble stops at the running realization's next safe point (exit 130), the
  // realizations done have their markers, the one it was running has none. The same command
  // again runs only the others, and the aggregate is that of an uninterrupted ensemble.
  const std::string path = scene("interrupted", rqdBallScene("interrupted", "0.1, 1", 30000));
  const fs::path out = dir.path() / "stopped";
  const auto whole = test::runCli("ensemble " + path + " -o " + out.string() +
                                  " --realizations 6 --no-figures --threads 1");
  ASSERT_EQ(whole.exit_code, 0) << whole.output;  // the uninterrupted reference
  const auto reference = test::readFile(out / "ensemble.json");
  fs::remove_all(out);
  const int code = std::system(("timeout --preserve-status -s INT 1.5 " +
                                std::string(ROCKMASS_BINARY) + " ensemble " + path + " -o " +
                                out.string() + " --realizations 6 --no-figures --threads 1 > " +
                                (dir.path() / "stopped.log").string() + " 2>&1")
                                   .c_str());
  const std::string output = test::readFile(dir.path() / "stopped.log");
  ASSERT_TRUE(WIFEXITED(code)) << output;
  EXPECT_EQ(WEXITSTATUS(code), 130) << output;
  std::vector<int> done;
  for (int i = 0; i < 6; ++i) {
    if (fs::exists(out / ("r" + std::to_string(i)) / "realization.json")) done.push_back(i);
  }
  EXPECT_LT(done.size(), 6u) << output;
  EXPECT_FALSE(fs::exists(out / "ensemble.json")) << output;  // no aggregate of a part
  const auto resumed = ensemble(path, "stopped", "--realizations 6 --threads 1");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  for (int i = 0; i < 6; ++i) {
    const bool was_done = std::find(done.begin(), done.end(), i) != done.end();
    EXPECT_EQ(resumed.output.find("ensemble: realization " + std::to_string(i) + " of 6") ==
                  std::string::npos,
              was_done)
        << i << "\n"
        << resumed.output;
  }
  EXPECT_EQ(test::readFile(out / "ensemble.json"), reference);
}

TEST_F(EnsembleCli, RanksTakeTheNextRealizationWhenTheyAreFree) {
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  if (test::runCli("--version").output.find("\n  MPI ") == std::string::npos) {
    GTEST_SKIP() << "rockmass built without MPI";
  }
  // Realization 0 casts an RQD ball of 200 000 directions, the nine others 2 000 (a `list`
  // input): about 15 times the work (measured: 2.5 s against 0.15 s on one thread). Over two
  // ranks, the one that runs realization 0 must run few others while the other rank takes
  // the rest (dynamic balancing); a fixed half of the list each would give it five.
  const std::string text = rqdBallScene("balance", "0.1", 2000) + R"(uncertainty:
  inputs:
    - {key: analysis.rqd.balls.mid.directions, distribution: list,
       values: [200000, 2000, 2000, 2000, 2000, 2000, 2000, 2000, 2000, 2000]}
)";
  const std::string path = scene("balance", text);
  std::string output;
  const std::string command = mpirun(2) + " ensemble " + path + " -o " +
                              (dir.path() / "balance").string() +
                              " --realizations 10 --no-figures --threads 1 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) output += buffer;
  ASSERT_EQ(pclose(pipe), 0) << output;
  std::map<int, std::string> owner;  // realization -> rank
  const std::regex line("ensemble: (rank [0-9]+): realization ([0-9]+) of 10");
  for (std::sregex_iterator it(output.begin(), output.end(), line), end; it != end; ++it) {
    owner[std::stoi((*it)[2])] = (*it)[1];
  }
  ASSERT_EQ(owner.size(), 10u) << output;
  const std::string slow = owner[0];
  const auto with_slow =
      std::count_if(owner.begin(), owner.end(), [&](const auto& e) { return e.second == slow; });
  EXPECT_LE(with_slow, 3) << output;  // 1 + at most two started before it was handed out
  const Json r0 = Json::parse(test::readFile(dir.path() / "balance" / "r0" / "summary.json"));
  EXPECT_EQ(r0["balls"][0]["directions"], 200000);
}

TEST_F(EnsembleCli, BadInputIsRefusedWithTheFileLineAndKey) {
  const std::string path = scene("small", smallScene());
  // --realizations 0
  auto r = ensemble(path, "zero", "--realizations 0");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--realizations"), std::string::npos) << r.output;
  // --only beyond the ensemble
  r = ensemble(path, "only", "--realizations 3 --only 3");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--only 3"), std::string::npos) << r.output;
  // A key that does not exist: file, line, the key.
  const std::string missing = smallScene(
      "    - {key: joints.rk.friction, distribution: uniform, "
      "min: 0.1, max: 0.2}\n");
  r = ensemble(scene("missing", missing), "missing", "--realizations 2");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("missing.yaml:" + std::to_string(lineOf(missing, "joints.rk")) + ":"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("uncertainty.inputs[2].key: the scene has no key joints.rk"),
            std::string::npos)
      << r.output;
  // Impossible distributions.
  const std::vector<std::pair<std::string, std::string>> impossible = {
      {"{key: joints.rj.friction, distribution: normal, std: 0}", "expected a number > 0"},
      {"{key: joints.rj.friction, distribution: uniform, min: 0.9, max: 0.5}",
       "expected max > min"},
      {"{key: joints.rj.friction, distribution: triangular, min: 0.1, max: 0.5}",
       "the mode 0.7 is outside [min, max]"},
      {"{key: joints.rj.friction, distribution: lognormal, mean: -1, std: 0.1}",
       "needs a mean > 0"},
      {"{key: joints.rj.friction, distribution: sample_mean, count: 10}",
       "needs `std`: the scene has no std > 0 next to joints.rj.friction"},
      {"{key: joints.rj.friction, distribution: normal, std: 0.1, count: 3}",
       "a normal distribution takes mean, std, min, max, not count"},
      {"{key: joints.rj.friction, distribution: beta}", "unknown distribution 'beta'"},
      {"{key: materials.rock, distribution: uniform, min: 0, max: 1}",
       "the scene's materials.rock is not a number"},
  };
  int k = 0;
  for (const auto& [entry, message] : impossible) {
    std::string text = smallScene();
    text = std::regex_replace(
        text,
        std::regex(
            R"(    - \{key: joints\.rj\.friction, distribution: uniform, min: 0\.5, max: 0\.9\})"),
        "    - " + entry);
    const std::string name = "impossible" + std::to_string(k++);
    r = ensemble(scene(name, text), name, "--realizations 2");
    EXPECT_EQ(r.exit_code, 2) << entry << "\n" << r.output;
    EXPECT_NE(r.output.find(name + ".yaml:" + std::to_string(lineOf(text, entry)) + ":"),
              std::string::npos)
        << entry << "\n"
        << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << entry << "\n" << r.output;
  }
  // A sampled value the key cannot take: the realization, the key's line, what was drawn.
  std::string negative = std::regex_replace(
      smallScene(),
      std::regex(R"(\{key: joints\.rj\.friction, distribution: uniform, min: 0\.5, max: 0\.9\})"),
      "{key: joints.rj.friction, distribution: uniform, min: -0.5, max: 0.1}");
  r = ensemble(scene("negative", negative), "negative", "--realizations 8");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("realization "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("negative.yaml:" + std::to_string(lineOf(negative, "  rj: {")) + ":"),
            std::string::npos)
      << r.output;  // the key's own line
  EXPECT_NE(r.output.find("a sampled value of uncertainty.inputs"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.path() / "negative" / "r0"));  // nothing ran
  // A Latin hypercube smaller than the ensemble.
  const std::string lhs =
      std::regex_replace(smallScene(), std::regex("uncertainty:\n"),
                         "uncertainty:\n  sampling: latin_hypercube\n  size: 3\n");
  r = ensemble(scene("lhs", lhs), "lhs", "--realizations 4");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("lhs.yaml:" + std::to_string(lineOf(lhs, "  size: 3")) + ":"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("--realizations 4 asks for more"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace rockmass
