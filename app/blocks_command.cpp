// rockmass blocks: cut the rock of a scene into blocks and write them.
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/command.h"
#include "blocks/exact_cutter.h"
#include "blocks/fast_cutter.h"
#include "blocks/prism.h"
#include "io/atomic_file.h"
#include "io/block_output.h"
#include "io/input_error.h"
#include "io/summary.h"

namespace rockmass::app {

namespace {

namespace fs = std::filesystem;

/// Options of `rockmass blocks` beyond the common ones.
struct BlocksOptions {
  CommonOptions common;
  std::string cutter;       ///< "", "exact" or "fast" ("" : the scene's analysis.blocks.cutter)
  std::string mesh_format;  ///< "", obj, ply, stl or glb
};

/// The cut input of a scene: its box domain, its network and its structures as convex
/// prism pieces.
blocks::CutInput cutInput(const io::Scene& scene, const geometry::FractureNetwork& network,
                          const std::string& scene_path) {
  if (!scene.domain_mesh.empty()) {
    throw io::InputError(scene_path + ": domain: mesh domains are cut by the exact cutter's " +
                         "mesh import, which is not built yet; use a box domain");
  }
  blocks::CutInput input;
  input.domain_box = scene.dfn.domain;
  input.domain_pieces = {geometry::boxPolyhedron(scene.dfn.domain)};
  input.network = &network;
  input.disc_segments = scene.analysis.blocks ? scene.analysis.blocks->disc_segments : 24;
  input.rock_material = scene.rock_material;
  for (const io::StructureSpec& s : scene.structures) {
    if (!s.mesh.empty()) {
      throw io::InputError(scene_path + ": structures: " + s.name +
                           ": mesh structures need the mesh import, which is not built yet; " +
                           "give a prism");
    }
    blocks::StructureSolid solid;
    solid.material = s.material;
    try {
      solid.pieces = blocks::prismPieces(s.prism_profile, s.prism_sweep, s.prism_from, s.prism_to);
    } catch (const std::invalid_argument& e) {
      throw io::InputError(scene_path + ": structures: " + s.name + ": prism: " + e.what());
    }
    input.structures.push_back(std::move(solid));
  }
  return input;
}

/// What either cutter gives the command.
struct CutRun {
  blocks::BlockModel model;
  int pieces = 0;                 ///< convex pieces of the rock
  int inconsistent_contacts = 0;  ///< fast cutter only (0 in a sound cut)
  double split_seconds = 0.0;     ///< splitting (exact: summed over regions, i.e. CPU time)
  double assemble_seconds = 0.0;  ///< gluing, materials, adjacency
};

CutRun runFast(const blocks::CutInput& input) {
  blocks::FastCutReport report;
  CutRun run;
  run.model = blocks::cutFast(input, &report);
  run.pieces = report.pieces;
  run.inconsistent_contacts = report.inconsistent_contacts;
  run.split_seconds = report.cut_seconds;
  run.assemble_seconds = report.assemble_seconds;
  return run;
}

CutRun runExact(const blocks::CutInput& input) {
  blocks::ExactCutReport report;
  CutRun run;
  run.model = blocks::cutExact(input, {}, &report);
  run.pieces = report.pieces;
  run.split_seconds = report.split_seconds + report.extract_seconds;
  run.assemble_seconds = report.glue_seconds;
  return run;
}

int runBlocks(const BlocksOptions& options) {
  const io::Scene scene = loadScene(options.common);
  const std::string cutter =
      !options.cutter.empty() ? options.cutter
      : (scene.analysis.blocks && scene.analysis.blocks->cutter == io::BlocksAnalysis::Cutter::Fast)
          ? "fast"
          : "exact";
  if (!options.mesh_format.empty()) {
    throw io::InputError("--mesh-format: block meshes through assimp are not built yet");
  }
  const fs::path out = prepareOutput(options.common.output);

  auto start = Clock::now();
  const geometry::FractureNetwork network = generateNetwork(scene, options.common.scene);
  const double dfn_seconds = secondsSince(start);

  start = Clock::now();
  const blocks::CutInput input = cutInput(scene, network, options.common.scene);
  CutRun cut;
  try {
    cut = cutter == "exact" ? runExact(input) : runFast(input);
  } catch (const std::invalid_argument& e) {
    throw io::InputError(options.common.scene + ": " + e.what());
  }
  const blocks::BlockModel& model = cut.model;
  const double cut_seconds = secondsSince(start);
  std::fprintf(stderr, "blocks: %zu blocks (%d pieces), %s cutter (%.2f s)\n", model.blocks.size(),
               cut.pieces, cutter.c_str(), cut_seconds);

  start = Clock::now();
  io::writeFileAtomically(out / "blocks.csv", io::formatBlocksCsv(model, scene.materials));
  io::writeFileAtomically(out / "blocks.vtu", io::formatBlocksVtu(model));
  io::RunInfo run;
  run.command = "blocks";
  run.scene = options.common.scene;
  run.name = scene.name;
  run.seed = scene.seed;
  run.stages = {"dfn", "cut"};
  io::CutInfo info;
  info.cutter = cutter;
  info.disc_segments = input.disc_segments;
  info.pieces = cut.pieces;
  info.inconsistent_contacts = cut.inconsistent_contacts;
  run.timings = {{"dfn", dfn_seconds},
                 {"cut", cut_seconds},
                 {"cut_split", cut.split_seconds},
                 {"cut_assemble", cut.assemble_seconds},
                 {"write", secondsSince(start)}};
  io::writeFileAtomically(out / "summary.json",
                          io::formatBlocksSummary(run, network, model, info, scene.materials));
  std::fprintf(stderr, "blocks: wrote %s\n", out.string().c_str());
  return 0;
}

}  // namespace

Command addBlocksCommand(CLI::App& app) {
  auto options = std::make_shared<BlocksOptions>();
  CLI::App* cli = app.add_subcommand("blocks", "Cut the rock of a scene into blocks");
  addCommonOptions(*cli, options->common);
  cli->add_option("--cutter", options->cutter,
                  "exact (exact-kernel splitting) or fast (floating-point convex splitting); "
                  "overrides analysis.blocks.cutter")
      ->check(CLI::IsMember({"exact", "fast"}));
  cli->add_option("--mesh-format", options->mesh_format, "block meshes: obj, ply, stl or glb")
      ->check(CLI::IsMember({"obj", "ply", "stl", "glb"}));
  return {cli, [options] { return runBlocks(*options); }};
}

}  // namespace rockmass::app
