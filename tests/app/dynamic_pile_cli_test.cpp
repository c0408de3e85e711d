// rockmass dda on piles of unit cubes dropped on a fixed slab (dynamic, the scene of
// ../shared/repro/dynamic-pile/pile1000.yaml scaled down): the pile lands, comes to rest, and
// no cube leaves it. Two sizes: 4 x 4 cubes in 3 layers is the smallest pile of those tried
// that failed when a corner sank unseen into a neighbour (found 1.6 mm deep, its spring threw
// the cubes apart; the time step fell to 2.5e-7 s). 7 x 7 cubes in 5 layers is the smallest
// of those tried (5 x 5 x 4 to 8 x 8 x 5) whose landing collapsed the time step as the 1 000-cube
// pile's did when contacts flipped open and closed without end in a step: 41 steps below
// 1e-4 s, down to 7.6e-6 s (docs/dda3d.md, "Open-close iteration").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <ostream>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/cli_support.h"
#include "tests/support/history_reading.h"
#include "tests/support/test_support.h"

namespace rockmass {
namespace {

namespace fs = std::filesystem;

constexpr double kGravity = 9.81;
constexpr double kFirstGap = 0.05;  // m, first layer above the slab
constexpr double kLayerGap = 0.02;  // m, between layers
constexpr double kPitch = 1.02;     // m, cube spacing in plan (2 cm apart)
constexpr double kShift = 0.3;      // m, odd layers shifted along x

/// `n` x `n` unit cubes per layer, `layers` layers, as the repro's generator lays them out;
/// a monitor at every cube's centre (named `l<layer>_<i>_<j>`).
std::string pileScene(int n, int layers, const std::string& kinematics, int steps) {
  const double size = n * kPitch + kShift + 1.0;
  std::ostringstream s;
  s << "version: 1\nname: pile\nseed: 1\ndomain:\n  box: {min: [-1, -1, -1], max: [" << size << ", "
    << size << ", 0]}\n"
    << "materials:\n  rock: {density: 2600, young: 10.0e9, poisson: 0.25}\n"
    << "rock_material: rock\njoints:\n  j: {friction_angle: 30, cohesion: 0}\n"
    << "default_joint: j\nloads:\n  gravity: 9.81\nsupports:\n  fixed: [bottom]\n"
    << "analysis:\n  blocks: {cutter: exact}\n  dda: {mode: dynamic, kinematics: " << kinematics
    << ", steps: " << steps << ", time_step: 0.002}\n";
  std::ostringstream structures, monitors;
  for (int l = 0; l < layers; ++l) {
    const double z0 = kFirstGap + l * (1.0 + kLayerGap);
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        const double x0 = 0.1 + (l % 2 ? kShift : 0.0) + i * kPitch, y0 = 0.1 + j * kPitch;
        std::ostringstream label;
        label << 'l' << l << '_' << i << '_' << j;
        const std::string name = label.str();
        structures << "  - {name: " << name << ", prism: {profile: [[" << x0 << ", " << z0 << "], ["
                   << x0 + 1 << ", " << z0 << "], [" << x0 + 1 << ", " << z0 + 1 << "], [" << x0
                   << ", " << z0 + 1 << "]], sweep: y, from: " << y0 << ", to: " << y0 + 1
                   << "}, material: rock, joint: j}\n";
        monitors << "  - {name: " << name << ", point: [" << x0 + 0.5 << ", " << y0 + 0.5 << ", "
                 << z0 + 0.5 << "]}\n";
      }
    }
  }
  s << "structures:\n" << structures.str() << "monitors:\n" << monitors.str();
  return s.str();
}

/// The layer of a monitor named by pileScene.
int layerOf(const std::string& monitor) {
  return std::stoi(monitor.substr(1, monitor.find('_') - 1));
}

struct PileCase {
  int side = 4;    ///< cubes per row
  int layers = 3;  ///< layers
  std::string kinematics;
  std::string solver;
};

/// The case's name in test listings (gtest prints the bytes of a struct otherwise).
std::string caseName(const PileCase& p) {
  return std::to_string(p.side) + "x" + std::to_string(p.side) + "x" + std::to_string(p.layers) +
         "_" + p.kinematics + "_" + p.solver;
}

void PrintTo(const PileCase& p, std::ostream* os) {
  *os << caseName(p);
}

class DynamicPile : public ::testing::TestWithParam<PileCase> {
 protected:
  test::TempDir dir{"dynamic_pile"};
};

TEST_P(DynamicPile, LandsAndComesToRestWithEveryCubeInThePile) {
  // 2 s of 2 ms steps at most. The top layer's edge cubes, landing 0.3 m over the edge of the
  // staggered layer below, rock on it for a while: on the 7 x 7 x 5 pile the last came to rest
  // at 1.2 s, 1.43 s or 1.5 s when the springs' sums changed only in their round-off (the
  // order of the contacts' terms, k_s I + (k_n - k_s) n n^T for the tangents' sum; measured).
  constexpr int kSteps = 1000;
  const PileCase& param = GetParam();
  const int side = param.side, layers = param.layers;
  const fs::path scene =
      test::writeFile(dir.path() / "pile.yaml", pileScene(side, layers, param.kinematics, kSteps));
  std::string output;
  ASSERT_EQ(test::runRockmass("dda " + scene.string() + " -o " + (dir.path() / "out").string() +
                                  " --solver " + param.solver,
                              &output),
            0)
      << output;
  const nlohmann::json summary =
      nlohmann::json::parse(test::readFile(dir.path() / "out" / "summary.json"));
  ASSERT_EQ(summary["blocks"], side * side * layers + 1);
  // No time step below 1e-4 s (the failures took 2.5e-7 s and 7.6e-6 s; the landings' worst
  // steps take 6e-4 s to 1e-3 s, measured).
  const std::vector<double> dts = summary["steps"]["time_step"];
  const double smallest = *std::min_element(dts.begin(), dts.end());
  EXPECT_GE(smallest, 1e-4);
  // The springs' compression under the pile is ~1e-6 m; a cube landing at 1 m/s compresses
  // its contact by about v sqrt(m / k_n) = 8e-5 m, and a contact whose state flips during
  // the step may be left open while it penetrates less than the gap it closed in the step and
  // a tenth of the allowed penetration (1.3e-4 m here, updateContactStates): 2.5e-4 m at
  // most. A corner found deep (the failure) read 1.6e-3 m.
  const std::vector<double> penetrations = summary["steps"]["max_penetration"];
  EXPECT_LT(*std::max_element(penetrations.begin(), penetrations.end()), 2.5e-4);

  double fastest = 0.0, moved_sideways = 0.0, settle_error = 0.0, last_speed = 0.0;
  std::map<std::string, test::HistoryRow> last;
  // Per unit mass of a cube (all cubes weigh the same), summed over the cubes at each time:
  // the kinetic energy of their translations and the work of gravity on them.
  std::map<double, std::pair<double, double>> energy_at;
  for (const test::HistoryRow& row : test::readHistory(dir.path() / "out" / "history.csv")) {
    ASSERT_TRUE(std::isfinite(row.ux) && std::isfinite(row.vx) && std::isfinite(row.vz))
        << row.monitor << " at t = " << row.time;
    fastest = std::max(fastest, row.speed());
    last[row.monitor] = row;
    auto& [kinetic, work] = energy_at[row.time];
    kinetic += 0.5 * row.speed() * row.speed();
    work += kGravity * -row.uz;
  }
  ASSERT_EQ(static_cast<int>(last.size()), side * side * layers);
  for (const auto& [name, row] : last) {
    // Each cube comes down by the gaps under it (all closed) and stays in the pile: cubes of
    // the top layer slide up to 4 cm on the staggered layer below as they land (measured,
    // rigid and deformable alike); a cube thrown out of the pile moves metres.
    moved_sideways = std::max(moved_sideways, std::hypot(row.ux, row.uy));
    const double drop = kFirstGap + layerOf(name) * kLayerGap;
    settle_error = std::max(settle_error, std::abs(-row.uz - drop));
    last_speed = std::max(last_speed, row.speed());
  }
  EXPECT_LT(moved_sideways, 0.1);
  // 1 mm: the springs' compression and the tilt of cubes resting on staggered supports.
  EXPECT_LT(settle_error, 1e-3);
  // At rest at the end: 1 cm/s, against 1.3 m/s at landing (measured: 8e-4 m/s or less).
  EXPECT_LT(last_speed, 1e-2);
  // No energy created: at every time, the cubes' kinetic energy at most the work gravity did
  // on them, with 5 % for the Bossak scheme's energy (docs/dda3d.md; the rotations' energy,
  // left out, only makes the check stricter)...
  double most_created = -1.0;
  for (const auto& [time, energy] : energy_at) {
    if (energy.second > 0.0) {
      most_created = std::max(most_created, (energy.first - energy.second) / energy.second);
    } else {
      EXPECT_EQ(energy.first, 0.0) << "t = " << time << ": moving before gravity did work";
    }
  }
  EXPECT_LT(most_created, 0.05);
  // ...and no cube faster than two cubes of the staggered layer above can make it: landing
  // together at their free-fall speed on a cube still in the air, they pass it up to 4/3 of
  // their speed when the impact is elastic (measured up to 1.15 times the top layer's free
  // fall, 1.84 m/s, in the 7 x 7 x 5 rigid pile). The failure threw cubes at 7 m/s.
  const double top_drop = kFirstGap + (layers - 1) * kLayerGap;
  EXPECT_LT(fastest, 1.05 * 4.0 / 3.0 * std::sqrt(2.0 * kGravity * top_drop));
  std::printf(
      "pile %dx%dx%d %s %s: %zu steps, smallest dt %.3g s, fastest %.3g m/s, "
      "energy created %.3g of the work, sideways %.3g m, settlement error %.3g m, "
      "last speed %.3g m/s\n",
      side, side, layers, param.kinematics.c_str(), param.solver.c_str(), dts.size(), smallest,
      fastest, most_created, moved_sideways, settle_error, last_speed);
}

INSTANTIATE_TEST_SUITE_P(
    Piles, DynamicPile,
    ::testing::Values(PileCase{4, 3, "rigid", "cholmod"}, PileCase{4, 3, "rigid", "pcg"},
                      PileCase{4, 3, "deformable", "cholmod"}, PileCase{7, 5, "rigid", "cholmod"},
                      PileCase{7, 5, "deformable", "cholmod"}),
    [](const ::testing::TestParamInfo<PileCase>& info) { return caseName(info.param); });

TEST(DynamicPileThreads, TheSamePileGivesTheSameBytesOnOneThreadAndOnTwo) {
  // Contact detection runs over the candidate pairs in parallel (TBB) and its results are
  // joined in pair order: a pile's landing (contacts opening, closing, sliding every step)
  // must give the same files, byte for byte, whatever the split (summary.json: all but its
  // timings). 3 x 3 x 2 rigid cubes, 150 steps (the landing and the first rebounds).
  test::TempDir dir("dynamic_pile_threads");
  const fs::path scene = test::writeFile(dir.path() / "pile.yaml", pileScene(3, 2, "rigid", 150));
  std::map<int, fs::path> outs;
  for (const int threads : {1, 2}) {
    outs[threads] = dir.path() / ("out" + std::to_string(threads));
    std::string output;
    ASSERT_EQ(test::runRockmass("dda " + scene.string() + " -o " + outs[threads].string() +
                                    " --threads " + std::to_string(threads),
                                &output),
              0)
        << output;
  }
  nlohmann::json a = nlohmann::json::parse(test::readFile(outs[1] / "summary.json"));
  nlohmann::json b = nlohmann::json::parse(test::readFile(outs[2] / "summary.json"));
  for (nlohmann::json* j : {&a, &b}) j->erase("timings");
  EXPECT_GE(a["steps_taken"].get<int>(), 150);  // 0.3 s of steps of at most 2 ms
  EXPECT_EQ(a, b);
  int compared = 0;
  for (const auto& entry : fs::directory_iterator(outs[1])) {
    const std::string name = entry.path().filename().string();
    if (name == "summary.json") continue;
    EXPECT_EQ(test::readFile(entry.path()), test::readFile(outs[2] / name)) << name;
    ++compared;
  }
  EXPECT_GE(compared, 4);  // history.csv, steps.csv, faces.vtu, the frames
}

}  // namespace
}  // namespace rockmass
