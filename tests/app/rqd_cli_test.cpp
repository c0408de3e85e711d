// rockmass rqd end to end: files, reproducibility, calibration, the RQD/P32 volume (read back
// with OpenVDB against the library run directly), and located errors for bad borehole files,
// threshold lists and grids (exit code 2).
#include <gtest/gtest.h>
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/fracture_network.h"
#include "io/rqd_vdb.h"
#include "io/scene.h"
#include "rqd/embree_scene.h"
#include "rqd/rqd_volume.h"
#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"

namespace rockmass {
namespace {

namespace fs = std::filesystem;

using test::readFile;
using test::TempDir;
using test::writeFile;

using Result = test::CliResult;

/// Two joint sets in a 30 m cube, a ball, two holes with a measured log and calibration.
std::string scene(const std::string& thresholds = "[0.1, 1, 2]") {
  return R"(version: 1
name: rqd-cli
seed: 11
domain:
  box: {min: [0, 0, -30], max: [30, 30, 0]}
joint_sets:
  - name: J1
    orientation: {distribution: fisher, dip_direction: 90, dip: 20, kappa: 30}
    spacing: {distribution: lognormal, mean: 1.0, std: 0.8}
    trace_length: {distribution: lognormal, mean: 4.0, std: 2.0}
  - name: J2
    orientation: {distribution: fisher, dip_direction: 200, dip: 75, kappa: 30}
    spacing: {distribution: lognormal, mean: 2.0, std: 1.5}
    trace_length: {distribution: lognormal, mean: 3.0, std: 1.5}
analysis:
  rqd:
    thresholds: )" +
         thresholds + R"(
    balls:
      - {name: mid, center: [15, 15, -15], length: 20, directions: 200}
    boreholes:
      file: holes.csv
      run_length: 3.0
      measured: log.csv
      measured_threshold: 1.0
      calibration: {sets: [J1], range: [0.25, 4]}
)";
}

const char* kHoles = "id,x,y,z,azimuth,plunge,length\nA,10,10,0,0,90,25\nB,20,20,0,90,60,20\n";
const char* kLog = "id,from,to,rqd\nA,0,10,70\nA,10,25,60\nB,0,20,65\n";

/// Writes the scene and its files into `dir`; returns the scene path.
std::string prepare(const TempDir& dir, const std::string& holes = kHoles,
                    const std::string& text = scene()) {
  writeFile(dir.path() / "holes.csv", holes);
  writeFile(dir.path() / "log.csv", kLog);
  return writeFile(dir.path() / "scene.yaml", text).string();
}

std::string withoutTimings(const std::string& summary) {
  return summary.substr(0, summary.find("\"timings\""));
}

TEST(RqdCli, WritesBallsBoreholesAndCalibrationReproducibly) {
  TempDir dir("rqd_cli_files");
  const std::string scene_path = prepare(dir);
  const Result first = test::runCli("rqd " + scene_path + " -o " + (dir.path() / "a").string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const Result second = test::runCli("rqd " + scene_path + " -o " + (dir.path() / "b").string());
  ASSERT_EQ(second.exit_code, 0) << second.output;
  for (const char* file : {"rqd_balls.csv", "boreholes.csv", "rqd_ball_mid_t0.1.ply",
                           "rqd_ball_mid_t1.ply", "rqd_ball_mid_t2.ply"}) {
    const std::string a = readFile(dir.path() / "a" / file);
    EXPECT_FALSE(a.empty()) << file;
    EXPECT_EQ(a, readFile(dir.path() / "b" / file)) << file;  // same scene + seed: same bytes
  }
  const std::string summary = readFile(dir.path() / "a" / "summary.json");
  EXPECT_EQ(withoutTimings(summary), withoutTimings(readFile(dir.path() / "b" / "summary.json")));

  // rqd_balls.csv: header + 200 directions x 3 thresholds.
  const std::string balls = readFile(dir.path() / "a" / "rqd_balls.csv");
  EXPECT_EQ(balls.substr(0, balls.find('\n')), "ball,dir_x,dir_y,dir_z,threshold,rqd");
  EXPECT_EQ(std::count(balls.begin(), balls.end(), '\n'), 1 + 200 * 3);
  // boreholes.csv: hole A 25 m -> 9 runs (last 1 m), hole B 20 m -> 7 runs; x 3 thresholds.
  const std::string holes = readFile(dir.path() / "a" / "boreholes.csv");
  EXPECT_EQ(std::count(holes.begin(), holes.end(), '\n'), 1 + (9 + 7) * 3);
  EXPECT_NE(holes.find("\nA,24,25,0.1,"), std::string::npos);
  // The PLY surface: 200 vertices, 2 * 200 - 4 triangles.
  const std::string ply = readFile(dir.path() / "a" / "rqd_ball_mid_t1.ply");
  EXPECT_NE(ply.find("element vertex 200\n"), std::string::npos);
  EXPECT_NE(ply.find("element face 396\n"), std::string::npos);

  const nlohmann::json j = nlohmann::json::parse(summary);
  EXPECT_EQ(j["command"], "rqd");
  EXPECT_EQ(j["stages"], nlohmann::json({"dfn", "rqd", "calibration"}));
  EXPECT_EQ(j["balls"][0]["thresholds"].size(), 3u);
  EXPECT_EQ(j["balls"][0]["radius"], 10.0);  // default: half the scanline length
  EXPECT_EQ(j["boreholes"]["holes"].size(), 2u);
  EXPECT_EQ(j["boreholes"]["measured"]["intervals"], 3);
  EXPECT_EQ(j["boreholes"]["measured"]["length"], 45.0);
  EXPECT_EQ(j["calibration"]["sets"], nlohmann::json({"J1"}));
  EXPECT_GE(j["calibration"]["evaluations"].get<int>(), 2);
  for (const char* key : {"dfn", "rqd", "calibration", "write"}) {
    EXPECT_TRUE(j["timings"].contains(key)) << key;
  }
}

TEST(RqdCli, OptionsOverrideTheScene) {
  TempDir dir("rqd_cli_options");
  const std::string scene_path = prepare(dir);
  const Result r =
      test::runCli("rqd " + scene_path + " -o " + (dir.path() / "o").string() +
                   " --directions 50 --thresholds 0.5,3 --form triangulated --ball-radius 4");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = nlohmann::json::parse(readFile(dir.path() / "o" / "summary.json"));
  EXPECT_EQ(j["balls"][0]["directions"], 50);
  EXPECT_EQ(j["balls"][0]["radius"], 4.0);
  EXPECT_EQ(j["rqd"]["form"], "triangulated");
  EXPECT_EQ(j["rqd"]["thresholds"], nlohmann::json({0.5, 3.0}));
  EXPECT_TRUE(fs::exists(dir.path() / "o" / "rqd_ball_mid_t3.ply"));
}

/// Runs `rqd` on a scene whose holes file is `holes` and returns the result.
Result runWithHoles(const TempDir& dir, const std::string& holes) {
  const std::string scene_path = prepare(dir, holes);
  return test::runCli("rqd " + scene_path + " -o " + (dir.path() / "out").string());
}

TEST(RqdCli, BadBoreholeFilesAreLocatedInputErrors) {
  TempDir dir("rqd_cli_bad_holes");
  const std::string file = (dir.path() / "holes.csv").string();
  const std::string header = "id,x,y,z,azimuth,plunge,length\n";
  struct Case {
    std::string rows;
    std::string message;
  };
  const Case cases[] = {
      {"A,10,10,0,0,90,25\nB,5,5,0,0,90,35\n",
       file + ":3: hole 'B' leaves the domain: its bottom (5, 5, -35) lies outside the box (0, 0, "
              "-30) - (30, 30, 0)"},
      {"A,10,10,0,0,90,-5\n", file + ":2: length: expected a number > 0 (m), got -5"},
      {"A,10,10,0,0,90\n",
       file + ":2: expected 7 comma-separated fields (id,x,y,z,azimuth,plunge,length), got 6"},
      {"A,10,ten,0,0,90,25\n", file + ":2: y: expected a number, got 'ten'"},
      {"A,10,10,0,0,90,25\nA,20,20,0,0,90,25\n", file + ":3: id: hole 'A' is listed twice"},
  };
  for (const Case& c : cases) {
    const Result r = runWithHoles(dir, header + c.rows);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_EQ(r.output, "error: " + c.message + "\n");
  }
  const Result bad_header = runWithHoles(dir, "id,x,y,z,azimuth,dip,length\nA,10,10,0,0,90,25\n");
  EXPECT_EQ(bad_header.exit_code, 2);
  EXPECT_EQ(bad_header.output, "error: " + file +
                                   ":1: expected the header row 'id,x,y,z,azimuth,plunge,length', "
                                   "got 'id,x,y,z,azimuth,dip,length'\n");
}

TEST(RqdCli, BadMeasuredLogAndThresholdsAreInputErrors) {
  TempDir dir("rqd_cli_bad_log");
  std::string scene_path = prepare(dir);
  writeFile(dir.path() / "log.csv", "id,from,to,rqd\nA,0,10,70\nC,0,5,50\n");
  Result r = test::runCli("rqd " + scene_path + " -o " + (dir.path() / "out").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.output,
            "error: " + (dir.path() / "log.csv").string() + ":3: id: unknown borehole 'C'\n");
  writeFile(dir.path() / "log.csv", "id,from,to,rqd\nA,10,5,70\n");
  r = test::runCli("rqd " + scene_path + " -o " + (dir.path() / "out").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.output, "error: " + (dir.path() / "log.csv").string() +
                          ":2: from, to: expected 0 <= from < to <= 25 (the length of hole 'A'), "
                          "got 10, 5\n");
  // An empty threshold list, in the scene and on the command line.
  scene_path = prepare(dir, kHoles, scene("[]"));
  r = test::runCli("rqd " + scene_path + " -o " + (dir.path() / "out").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.output,
            "error: " + scene_path +
                ":17:17: analysis.rqd.thresholds: expected a non-empty list of numbers\n");
  scene_path = prepare(dir);
  r = test::runCli("rqd " + scene_path + " -o " + (dir.path() / "out").string() +
                   " --thresholds 2,1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.output,
            "error: --thresholds: expected increasing numbers > 0 (m), got 1 at position 2\n");
}

/// The two joint sets of scene() in the same 30 m cube, with only a grid: 3 x 3 x 2 cells of
/// 8 m in the region below (centred: x, y from 3 to 27, z from -24 to -8).
std::string gridScene(const std::string& region = "{min: [2, 2, -26], max: [28, 28, -6]}") {
  return R"(version: 1
name: rqd-grid
seed: 5
domain:
  box: {min: [0, 0, -30], max: [30, 30, 0]}
joint_sets:
  - name: J1
    orientation: {distribution: fisher, dip_direction: 90, dip: 20, kappa: 30}
    spacing: {distribution: lognormal, mean: 1.0, std: 0.8}
    trace_length: {distribution: lognormal, mean: 4.0, std: 2.0}
  - name: J2
    orientation: {distribution: fisher, dip_direction: 200, dip: 75, kappa: 30}
    spacing: {distribution: lognormal, mean: 2.0, std: 1.5}
    trace_length: {distribution: lognormal, mean: 3.0, std: 1.5}
analysis:
  rqd:
    thresholds: [0.1, 1, 2]
    grid:
      spacing: 8
      direction_count: 30
      length: 12
      region: )" +
         region + "\n";
}

TEST(RqdCli, GridWritesAVolumeEqualToTheLibrary) {
  TempDir dir("rqd_cli_grid");
  const fs::path scene_path = writeFile(dir.path() / "scene.yaml", gridScene());
  const Result r =
      test::runCli("rqd " + scene_path.string() + " -o " + (dir.path() / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;

  // The same volume computed directly by the library from the same scene and seed.
  const io::Scene scene = io::loadScene(scene_path);
  const geometry::FractureNetwork network = geometry::generateNetwork(scene.dfn, scene.seed);
  const rqd::ScanlineScene ray_scene(network, rqd::DiscForm::ExactEllipse, 24);
  rqd::VolumeSpec spec;
  spec.region = *scene.analysis.rqd->grid_region;
  spec.cell_size = 8.0;
  spec.scanline_length = 12.0;
  spec.direction_count = 30;
  spec.thresholds = {0.1, 1.0, 2.0};
  const rqd::RqdVolume expected = rqd::computeRqdVolume(ray_scene, network, spec);
  ASSERT_EQ(expected.grid.dims, (std::array<int, 3>{3, 3, 2}));  // floor(26/8), floor(20/8)

  openvdb::initialize();
  openvdb::io::File file((dir.path() / "out" / "rqd.vdb").string());
  file.open();
  EXPECT_EQ(file.getGrids()->size(), 4u);  // 3 thresholds + p32
  std::vector<std::vector<double>> values = expected.mean_rqd;
  values.push_back(expected.p32);
  const std::vector<std::string> names{"rqd_00100mm", "rqd_01000mm", "rqd_02000mm", "p32"};
  double p32_sum = 0.0;
  for (std::size_t g = 0; g < names.size(); ++g) {
    ASSERT_TRUE(file.hasGrid(names[g])) << names[g];
    const auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(names[g]));
    ASSERT_TRUE(grid) << names[g];
    EXPECT_EQ(grid->voxelSize()[0], 8.0);
    EXPECT_EQ(grid->activeVoxelCount(), 18u);
    const openvdb::FloatGrid::ConstAccessor accessor = grid->getConstAccessor();
    for (std::int64_t cell = 0; cell < expected.grid.cellCount(); ++cell) {
      const auto [i, j, k] = expected.grid.coordinates(cell);
      // Deterministic whatever the thread count: the float of the library's value, exactly.
      EXPECT_EQ(accessor.getValue(openvdb::Coord(i, j, k)),
                static_cast<float>(values[g][static_cast<std::size_t>(cell)]))
          << names[g] << " cell " << cell;
      if (g == 3) p32_sum += values[g][static_cast<std::size_t>(cell)];
    }
  }
  file.close();
  // Not a trivial volume: fractures were found (P32 > 0, some RQD(2 m) < 100).
  EXPECT_GT(p32_sum, 0.0);
  EXPECT_LT(*std::min_element(expected.mean_rqd[2].begin(), expected.mean_rqd[2].end()), 100.0);

  // summary.json: the grid, its statistics over the cells and its timing.
  const nlohmann::json j = nlohmann::json::parse(readFile(dir.path() / "out" / "summary.json"));
  EXPECT_EQ(j["stages"], nlohmann::json({"dfn", "rqd", "grid"}));
  EXPECT_TRUE(j["timings"].contains("grid"));
  const nlohmann::json& g = j["grid"];
  EXPECT_EQ(g["file"], "rqd.vdb");
  EXPECT_EQ(g["cells"], 18);
  EXPECT_EQ(g["spacing"], 8.0);
  EXPECT_EQ(g["origin"], nlohmann::json({3.0, 3.0, -24.0}));
  EXPECT_EQ(g["direction_count"], 30);
  ASSERT_EQ(g["thresholds"].size(), 3u);
  for (std::size_t t = 0; t < 3; ++t) {
    const std::vector<double>& v = expected.mean_rqd[t];
    EXPECT_EQ(g["thresholds"][t]["grid"], names[t]);
    EXPECT_EQ(g["thresholds"][t]["min"].get<double>(), *std::min_element(v.begin(), v.end()));
    EXPECT_EQ(g["thresholds"][t]["max"].get<double>(), *std::max_element(v.begin(), v.end()));
    // The mean over 18 cells, summed in cell order as the summary does: exact.
    double sum = 0.0;
    for (double x : v) sum += x;
    EXPECT_EQ(g["thresholds"][t]["mean"].get<double>(), sum / 18.0);
  }
  EXPECT_EQ(g["p32"]["mean"].get<double>(), p32_sum / 18.0);

  // --no-grid skips the volume; the scene then has nothing else to compute.
  const Result skipped = test::runCli("rqd " + scene_path.string() + " -o " +
                                      (dir.path() / "none").string() + " --no-grid");
  EXPECT_EQ(skipped.exit_code, 2) << skipped.output;
  EXPECT_EQ(skipped.output, "error: " + scene_path.string() +
                                ": analysis.rqd: nothing to compute; give balls, boreholes or a "
                                "grid\n");
}

TEST(RqdCli, BadGridIsAnInputError) {
  TempDir dir("rqd_cli_bad_grid");
  // A region that sticks out of the domain (z above the surface).
  std::string scene_path =
      writeFile(dir.path() / "scene.yaml", gridScene("{min: [2, 2, -26], max: [28, 28, 5]}"))
          .string();
  Result r = test::runCli("rqd " + scene_path + " -o " + (dir.path() / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(r.output, "error: " + scene_path +
                          ": analysis.rqd.grid: the RQD volume region (2, 2, -26) - (28, 28, 5) "
                          "must lie inside the rock domain (0, 0, -30) - (30, 30, 0)\n");
  EXPECT_FALSE(fs::exists(dir.path() / "out" / "rqd.vdb"));
  // A region thinner than one cell (z: 4 m < 8 m).
  scene_path =
      writeFile(dir.path() / "scene.yaml", gridScene("{min: [2, 2, -26], max: [28, 28, -22]}"))
          .string();
  r = test::runCli("rqd " + scene_path + " -o " + (dir.path() / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(r.output.rfind("error: " + scene_path + ": analysis.rqd.grid: ", 0), 0u) << r.output;
  // A bad override on the command line.
  r = test::runCli("rqd " + scene_path + " -o " + (dir.path() / "out").string() +
                   " --grid-spacing -1");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_EQ(r.output, "error: --grid-spacing: expected a number > 0 (m), got -1\n");
}

}  // namespace
}  // namespace rockmass
