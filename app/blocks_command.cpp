// rockmass blocks: cut the rock of a scene into blocks and write them.
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/command.h"
#include "app/stages.h"
#include "io/atomic_file.h"
#include "io/block_mesh.h"
#include "io/block_output.h"
#include "io/input_error.h"
#include "io/summary.h"
#include "scene_model/dda_model.h"
#include "scene_model/scene_blocks.h"

namespace rockmass::app {

namespace fs = std::filesystem;

io::CutInfo cutInfoOf(const scene_model::SceneBlocks& cut, const std::string& cutter) {
  io::CutInfo info;
  info.cutter = cutter;
  info.disc_segments = cut.input.disc_segments;
  info.pieces = cut.pieces;
  info.inconsistent_contacts = cut.inconsistent_contacts;
  return info;
}

void writeBlocksFiles(const fs::path& out, const io::Scene& scene, const blocks::BlockModel& model,
                      const geometry::FractureNetwork& network) {
  std::vector<std::string> structures;
  for (const io::StructureSpec& structure : scene.structures) structures.push_back(structure.name);
  io::writeFileAtomically(out / "blocks.csv",
                          io::formatBlocksCsv(model, scene.materials, structures));
  io::writeFileAtomically(out / "blocks.vtu", io::formatBlocksVtu(model));
  io::writeFileAtomically(
      out / "faces.vtu",
      io::formatFacesVtu(model, [joints = scene_model::FaceJoints(scene, network)](
                                    const blocks::FaceSource& f) { return joints.of(f); }));
}

namespace {

/// The scene's material names, in the order of the blocks' material indices.
std::vector<std::string> materialNames(const io::Scene& scene) {
  std::vector<std::string> names;
  for (const io::Material& material : scene.materials) names.push_back(material.name);
  return names;
}

/// Options of `rockmass blocks` beyond the common ones.
struct BlocksOptions {
  CommonOptions common;
  std::string cutter;       ///< "", "exact" or "fast" ("" : the scene's analysis.blocks.cutter)
  std::string mesh_format;  ///< "", obj, ply, stl or glb
};

int runBlocks(const BlocksOptions& options) {
  const io::Scene scene = loadScene(options.common, /*mesh_domain_supported=*/true);
  const std::string cutter = scene_model::chooseCutter(scene, options.cutter, options.common.scene);
  const fs::path out = prepareOutput(options.common.output);
  const DfnStage dfn = runDfnStage(scene, options.common.scene);

  auto start = Clock::now();
  const scene_model::SceneBlocks cut =
      scene_model::cutSceneBlocks(scene, dfn.network, cutter, options.common.scene);
  const double cut_seconds = secondsSince(start);
  std::fprintf(stderr, "blocks: %zu blocks (%d pieces), %s cutter (%.2f s)\n",
               cut.model.blocks.size(), cut.pieces, cutter.c_str(), cut_seconds);

  start = Clock::now();
  writeBlocksFiles(out, scene, cut.model, dfn.network);
  if (const auto format = io::parseMeshFormat(options.mesh_format)) {
    io::writeFileAtomically(out / ("blocks." + io::meshExtension(*format)),
                            io::formatBlockMesh(cut.model, *format, {}, materialNames(scene)));
  }
  io::RunInfo run;
  run.command = "blocks";
  run.scene = options.common.scene;
  run.name = scene.name;
  run.seed = scene.seed;
  run.stages = {"dfn", "cut"};
  run.timings = {{"dfn", dfn.seconds},
                 {"cut", cut_seconds},
                 {"cut_split", cut.split_seconds},
                 {"cut_assemble", cut.assemble_seconds},
                 {"write", secondsSince(start)}};
  io::writeFileAtomically(out / "summary.json",
                          io::formatBlocksSummary(run, dfn.network, cut.model,
                                                  cutInfoOf(cut, cutter), scene.materials));
  std::fprintf(stderr, "blocks: wrote %s\n", out.string().c_str());
  return 0;
}

}  // namespace

Command addBlocksCommand(CLI::App& app) {
  auto options = std::make_shared<BlocksOptions>();
  CLI::App* cli = app.add_subcommand("blocks", "Cut the rock of a scene into blocks");
  addCommonOptions(*cli, options->common);
  addCutterOption(*cli, options->cutter);
  cli->add_option("--mesh-format", options->mesh_format, "block meshes: obj, ply, stl or glb")
      ->check(CLI::IsMember({"obj", "ply", "stl", "glb"}));
  return {cli, [options] { return runBlocks(*options); }};
}

}  // namespace rockmass::app
