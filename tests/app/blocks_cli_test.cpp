// rockmass blocks end to end on a small scene: two persistent faults cut a 20 m box into
// four blocks, a dam prism on top is a fifth; exit codes and reproducible files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"
#include "tests/support/vtu_reading.h"

namespace rockmass {
namespace {

namespace fs = std::filesystem;

using test::runRockmass;

/// One row of blocks.csv: id, volume, material.
struct CsvBlock {
  int id = 0;
  double volume = 0.0;
  std::string material;
};

/// The rows of blocks.csv (`id,volume,cx,cy,cz,material,...`), header skipped.
std::vector<CsvBlock> readBlocks(const std::string& csv) {
  std::vector<CsvBlock> rows;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::istringstream fields(line);
    std::string cell;
    while (std::getline(fields, cell, ',')) cells.push_back(cell);
    if (cells.size() < 6) continue;
    rows.push_back({std::stoi(cells[0]), std::stod(cells[1]), cells[5]});
  }
  return rows;
}

/// Vertical faults x = 8 (dip direction 90, dip 90) and y = 12 (dip direction 0) through a
/// 20 x 20 x 10 m box; a trapezoid dam prism (base 10 m, x 5..15, 8 m high) on its top.
const char* kScene = R"(version: 1
name: blocks-cli
seed: 3
domain:
  box: {min: [0, 0, -10], max: [20, 20, 0]}
materials:
  rock: {density: 2650, young: 7.0e9, poisson: 0.25}
  concrete: {density: 2400, young: 17.6e9, poisson: 0.167}
rock_material: rock
joints:
  rj: {friction: 0.86, cohesion: 0.8e6}
default_joint: rj
faults:
  - {name: F1, center: [8, 10, -5], dip_direction: 90, dip: 90}
  - {name: F2, center: [10, 12, -5], dip_direction: 0, dip: 90}
structures:
  - name: dam
    prism: {profile: [[5, 0], [15, 0], [7, 8], [5, 8]], sweep: y, from: 2, to: 18}
    material: concrete
analysis:
  blocks: {cutter: exact, disc_segments: 24}
)";

TEST(BlocksCli, CutsTheSmallSceneReproducibly) {
  test::TempDir dir("blocks_cli");
  const fs::path scene = test::writeFile(dir.path() / "scene.yaml", kScene);
  std::string output;
  ASSERT_EQ(runRockmass("blocks " + scene.string() + " -o " + (dir.path() / "a").string() +
                            " --cutter fast",
                        &output),
            0)
      << output;
  ASSERT_EQ(runRockmass("blocks " + scene.string() + " -o " + (dir.path() / "b").string() +
                            " --cutter fast",
                        &output),
            0)
      << output;
  // The scene asks for the exact cutter (also the default): it cuts the scene with its dam.
  ASSERT_EQ(runRockmass("blocks " + scene.string() + " -o " + (dir.path() / "c").string(), &output),
            0)
      << output;
  EXPECT_NE(output.find("exact cutter"), std::string::npos) << output;

  const auto summary = nlohmann::json::parse(test::readFile(dir.path() / "a" / "summary.json"));
  // Four rock blocks (8 x 12, 12 x 12, 8 x 8, 12 x 8 times 10 m) and the dam.
  EXPECT_EQ(summary["blocks"], 5);
  // The dam: trapezoid (10 + 2) / 2 x 8 = 48 m2 times 16 m = 768 m3; rock 4000 m3.
  EXPECT_NEAR(summary["total_volume"].get<double>(), 4000.0 + 768.0, 1e-9);  // round-off
  EXPECT_NEAR(summary["domain_volume"].get<double>(), 4000.0, 1e-12);
  EXPECT_NEAR(summary["volume_stats"]["max"].get<double>(), 1440.0, 1e-9);  // 12 x 12 x 10
  EXPECT_NEAR(summary["volume_stats"]["min"].get<double>(), 640.0, 1e-9);   // 8 x 8 x 10
  EXPECT_FALSE(summary["weibull"].is_null());
  // The legend of blocks.vtu's integer `material`: the scene's materials in order.
  EXPECT_EQ(summary["material_names"], nlohmann::json::array({"rock", "concrete"}));
  const std::string csv = test::readFile(dir.path() / "a" / "blocks.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 6);  // header + 5 blocks
  EXPECT_NE(csv.find(",concrete,1,"), std::string::npos);
  // Same scene and seed: byte-identical data files.
  EXPECT_EQ(csv, test::readFile(dir.path() / "b" / "blocks.csv"));
  EXPECT_EQ(test::readFile(dir.path() / "a" / "blocks.vtu"),
            test::readFile(dir.path() / "b" / "blocks.vtu"));

  // The exact cutter gives the same blocks, dam included, numbered the same way (the shared
  // order of blocks/block_assembly.h): per row the same id and material, and a volume within
  // 1e-9 relative (issue 3: the fast cutter's floating-point volumes against exact ones).
  const std::vector<CsvBlock> fast = readBlocks(csv);
  const std::vector<CsvBlock> exact = readBlocks(test::readFile(dir.path() / "c" / "blocks.csv"));
  ASSERT_EQ(fast.size(), 5u);
  ASSERT_EQ(exact.size(), fast.size());
  for (std::size_t i = 0; i < fast.size(); ++i) {
    EXPECT_EQ(exact[i].id, fast[i].id);
    EXPECT_EQ(exact[i].material, fast[i].material) << "block " << fast[i].id;
    EXPECT_NEAR(exact[i].volume, fast[i].volume, 1e-9 * fast[i].volume) << "block " << fast[i].id;
  }
  const auto exact_summary =
      nlohmann::json::parse(test::readFile(dir.path() / "c" / "summary.json"));
  EXPECT_EQ(exact_summary["cutter"], "exact");
  EXPECT_NEAR(exact_summary["total_volume"].get<double>(), 4000.0 + 768.0, 1e-9);  // round-off
  // The dam stands on the rock top: the same contacts (block pairs and areas) both ways.
  EXPECT_EQ(exact_summary["adjacencies"], summary["adjacencies"]);
  // The rock alone ("rock"): the four blocks fill the 4000 m3 domain, so the cut's volume
  // error is round-off (it read (4768 - 4000) / 4000 with the dam counted); the dam's
  // 768 m3 is reported apart.
  for (const auto* s : {&summary, &exact_summary}) {
    EXPECT_EQ((*s)["rock"]["blocks"], 4);
    EXPECT_NEAR((*s)["rock"]["total_volume"].get<double>(), 4000.0, 1e-9);
    EXPECT_NEAR((*s)["volume_error"].get<double>(), 0.0, 1e-12);
    EXPECT_EQ((*s)["rock"]["volume_error"], (*s)["volume_error"]);
    EXPECT_NEAR((*s)["structure_volume"].get<double>(), 768.0, 1e-9);
    EXPECT_NEAR((*s)["rock"]["volume_stats"]["min"].get<double>(), 640.0, 1e-9);
    EXPECT_NEAR((*s)["rock"]["volume_stats"]["mean"].get<double>(), 1000.0, 1e-9);
    EXPECT_FALSE((*s)["rock"]["weibull"].is_null());
  }
}

TEST(BlocksCli, MeshStructureIsExitTwoNamingTheSceneKey) {
  // A structure given as a closed mesh (structures[].mesh, a 4 x 4 x 4 m cube on the rock
  // top): neither cutter builds blocks from it yet; both stop with exit code 2 and say which
  // scene key to change, before any output is written.
  test::TempDir dir("blocks_cli_mesh_structure");
  test::writeFile(dir.path() / "cube.obj",
                  "v 8 8 0\nv 12 8 0\nv 12 12 0\nv 8 12 0\nv 8 8 4\nv 12 8 4\nv 12 12 4\n"
                  "v 8 12 4\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n"
                  "f 4 1 5 8\n");
  std::string text = kScene;
  text.replace(text.find("    prism: {profile"),
               text.find("    material: concrete") - text.find("    prism: {profile"),
               "    mesh: cube.obj\n");
  const fs::path scene = test::writeFile(dir.path() / "scene.yaml", text);
  for (const char* cutter : {"exact", "fast"}) {
    const test::CliResult r = test::runCli("blocks " + scene.string() + " -o " +
                                           (dir.path() / cutter).string() + " --cutter " + cutter);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(scene.string() + ": structures: dam: mesh:"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("structures[].prism"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir.path() / cutter / "blocks.csv"));
  }
}

TEST(BlocksCli, PrismProfileThatIsNotSimpleIsExitTwoAtItsLine) {
  // A bow-tie outline (../shared/repro/bad-input/r9): refused where it is cut, named at the
  // line and column of prism.profile, before any output is written.
  test::TempDir dir("blocks_cli_bowtie");
  std::string text = kScene;
  const std::size_t at = text.find("profile: [");
  const std::size_t end = text.find("]]", at) + 2;
  text.replace(at, end - at, "profile: [[5, 0], [15, 0], [5, -8], [15, -8]]");
  const fs::path scene = test::writeFile(dir.path() / "scene.yaml", text);
  const test::CliResult r =
      test::runCli("blocks " + scene.string() + " -o " + (dir.path() / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  const int line = static_cast<int>(std::count(text.begin(), text.begin() + at, '\n')) + 1;
  EXPECT_NE(r.output.find(scene.string() + ":" + std::to_string(line) + ":"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("structures: dam: prism.profile: the polygon is not simple"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir.path() / "out" / "blocks.csv"));
}

TEST(BlocksCli, ACutOverTheBlockBudgetIsExitTwoAtTheSetThatDrivesIt) {
  // ../shared/repro/bad-input/scene_02822: a set of constant spacing 0.0015 m with 3 m
  // traces in a 5 m cube (22 936 discs) would cut ~1e8 blocks (blocks ran over 90 s and
  // 7.6 GB). The estimate stops once it passes --max-blocks (default 1e6) and names the
  // set whose discs cross the most, at its spacing's line, before any output is written.
  test::TempDir dir("blocks_cli_budget");
  const std::string bomb = R"(version: 1
name: block-bomb
seed: 18446744073709551615
domain:
  box: {min: [0, 0, -5], max: [5, 5, 0]}
joint_sets:
  - name: A
    orientation: {distribution: fisher, dip_direction: 0, dip: 90, kappa: 100}
    spacing: {distribution: constant, mean: 0.0015}
    trace_length: {distribution: constant, mean: 3}
    shape: {aspect_ratio: 1, major_axis: dip}
  - name: B
    dip_direction: {distribution: constant, mean: 90}
    dip: {distribution: normal, mean: 80, std: 5, min: 60, max: 90}
    intensity: {p32: 0.5}
    trace_length: {distribution: uniform, min: 1, max: 4}
analysis:
  blocks: {cutter: fast}
)";
  std::string output;
  EXPECT_EQ(test::runOnScene("blocks", dir.path(), "bomb", bomb, &output), 2) << output;
  const std::string scene = (dir.path() / "bomb.yaml").string();
  EXPECT_NE(output.find(scene + ":9:14: joint_sets[0].spacing: the cut would make more than "
                                "1e+06 blocks"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("--max-blocks"), std::string::npos) << output;
  EXPECT_FALSE(fs::exists(dir.path() / "bomb" / "blocks.csv"));

  // The limit is the user's: the two faults and the dam above make 5 blocks, with an
  // estimate of 1 + 2 discs + 1 crossing = 4 cells of rock; --max-blocks 3 refuses it (at
  // the scene file: faults have no spacing), the default cuts it.
  const fs::path small = test::writeFile(dir.path() / "small.yaml", kScene);
  const test::CliResult refused = test::runCli("blocks " + small.string() + " -o " +
                                               (dir.path() / "s1").string() + " --max-blocks 3");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find(small.string() + ": the cut would make more than 3 blocks"),
            std::string::npos)
      << refused.output;
  const test::CliResult accepted =
      test::runCli("blocks " + small.string() + " -o " + (dir.path() / "s2").string());
  EXPECT_EQ(accepted.exit_code, 0) << accepted.output;
}

// faces.vtu: every piece face that is not an internal cut, with what made it and its joint.
// The scene above with F1 on its own joint (weak, index 1) and the dam on an inline joint
// (dam.joint, index 2): F1's faces (disc 1) carry joint 1, F2's (disc 2) the default joint 0,
// the dam's faces joint 2, the domain's faces none.
TEST(BlocksCli, FacesVtuCarriesTheJointOfEveryFace) {
  test::TempDir dir("blocks_cli_faces");
  std::string text = kScene;
  text.replace(text.find("default_joint: rj\n"), 18,
               "  weak: {friction: 0.3}\ndefault_joint: rj\n");
  text.replace(text.find("dip: 90}\n"), 9, "dip: 90, joint: weak}\n");
  text.replace(text.find("    material: concrete\n"), 23,
               "    material: concrete\n    joint: {friction: 1.2, cohesion: 1.4e6}\n");
  std::string output;
  for (const char* name : {"a", "b"}) {
    ASSERT_EQ(test::runOnScene("blocks --cutter fast", dir.path(), name, text, &output), 0)
        << output;
  }
  const std::string vtu = test::readFile(dir.path() / "a" / "faces.vtu");
  EXPECT_EQ(vtu, test::readFile(dir.path() / "b" / "faces.vtu"));  // same bytes
  const std::vector<double> block = test::dataArray(vtu, "block");
  const std::vector<double> piece = test::dataArray(vtu, "piece");
  const std::vector<double> kind = test::dataArray(vtu, "kind");
  const std::vector<double> source = test::dataArray(vtu, "source");
  const std::vector<double> joint = test::dataArray(vtu, "joint");
  const std::vector<double> types = test::dataArray(vtu, "types");
  const std::vector<double> offsets = test::dataArray(vtu, "offsets");
  ASSERT_FALSE(kind.empty());
  for (const auto* array : {&block, &piece, &source, &joint, &types, &offsets}) {
    ASSERT_EQ(array->size(), kind.size());
  }
  EXPECT_EQ(test::attribute(vtu, "NumberOfCells"), std::to_string(kind.size()));
  // The dam's block id: its row in blocks.csv is the concrete one.
  double dam_id = 0.0;
  for (const CsvBlock& b : readBlocks(test::readFile(dir.path() / "a" / "blocks.csv"))) {
    if (b.material == "concrete") dam_id = b.id;
  }
  ASSERT_GT(dam_id, 0.0);
  int f1 = 0, f2 = 0, dam = 0;
  for (std::size_t c = 0; c < kind.size(); ++c) {
    EXPECT_EQ(types[c], 7.0) << "a polygon";
    EXPECT_GE(offsets[c] - (c == 0 ? 0.0 : offsets[c - 1]), 3.0) << "at least 3 corners";
    if (kind[c] == 0.0 && source[c] == 1.0) {
      ++f1;
      EXPECT_EQ(joint[c], 1.0);
    } else if (kind[c] == 0.0 && source[c] == 2.0) {
      ++f2;
      EXPECT_EQ(joint[c], 0.0);
    } else if (kind[c] == 2.0) {
      ++dam;
      EXPECT_EQ(source[c], 0.0);
      EXPECT_EQ(joint[c], 2.0);
      EXPECT_EQ(block[c], dam_id);
    } else {
      EXPECT_EQ(kind[c], 1.0) << "cell " << c;
      EXPECT_GE(source[c], 0.0);
      EXPECT_LE(source[c], 5.0);
      EXPECT_EQ(joint[c], -1.0);
    }
  }
  // Each fault plane is a face of the four blocks it bounds; the dam prism has 6 faces.
  EXPECT_EQ(f1, 4);
  EXPECT_EQ(f2, 4);
  EXPECT_EQ(dam, 6);
}

}  // namespace
}  // namespace rockmass
