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
#include "io/block_mesh.h"
#include "io/block_output.h"
#include "io/input_error.h"
#include "io/summary.h"

namespace rockmass::app {

namespace {

namespace fs = std::filesystem;

/// THE place that says whether the exact (CGAL Nef) cutter is linked in. Until it is,
/// `--cutter exact` (and a scene that asks for it without --cutter) stops with exit code 2.
constexpr bool kExactCutterBuilt = false;

/// Options of `rockmass blocks` beyond the common ones.
struct BlocksOptions {
  CommonOptions common;
  std::string cutter;       ///< "", "exact" or "fast" ("" : the scene's analysis.blocks.cutter)
  std::string mesh_format;  ///< "", obj, ply, stl or glb
};

/// The cut input of a scene: its domain (a box, or a mesh domain's surface and its convex
/// decomposition), its network and its structures as convex prism pieces.
blocks::CutInput cutInput(const io::Scene& scene, const geometry::FractureNetwork& network,
                          const std::string& scene_path) {
  blocks::CutInput input;
  input.domain_box = scene.dfn.domain;
  if (scene.domain_surface.faces.empty()) {
    input.domain_pieces = {geometry::boxPolyhedron(scene.dfn.domain)};
  } else {
    input.domain_surface = scene.domain_surface;
    input.domain_pieces = blocks::convexDecomposition(scene.domain_surface);
  }
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

int runBlocks(const BlocksOptions& options) {
  const io::Scene scene = loadScene(options.common, /*mesh_domain_supported=*/true);
  const std::string cutter =
      !options.cutter.empty() ? options.cutter
      : (scene.analysis.blocks && scene.analysis.blocks->cutter == io::BlocksAnalysis::Cutter::Fast)
          ? "fast"
          : "exact";
  if (cutter == "exact" && !kExactCutterBuilt) {
    throw io::InputError(options.common.scene +
                         ": the exact cutter (analysis.blocks.cutter: exact, the default) is " +
                         "not built yet; run with --cutter fast");
  }
  const fs::path out = prepareOutput(options.common.output);

  auto start = Clock::now();
  const geometry::FractureNetwork network = generateNetwork(scene, options.common.scene);
  const double dfn_seconds = secondsSince(start);

  start = Clock::now();
  const blocks::CutInput input = cutInput(scene, network, options.common.scene);
  blocks::FastCutReport report;
  blocks::BlockModel model;
  try {
    model = blocks::cutFast(input, &report);
  } catch (const std::invalid_argument& e) {
    throw io::InputError(options.common.scene + ": " + e.what());
  }
  const double cut_seconds = secondsSince(start);
  std::fprintf(stderr, "blocks: %zu blocks (%d pieces) from %d cutting polygons (%.2f s)\n",
               model.blocks.size(), report.pieces, report.cutting_polygons, cut_seconds);

  start = Clock::now();
  io::writeFileAtomically(out / "blocks.csv", io::formatBlocksCsv(model, scene.materials));
  io::writeFileAtomically(out / "blocks.vtu", io::formatBlocksVtu(model));
  if (const auto format = io::parseMeshFormat(options.mesh_format)) {
    io::writeFileAtomically(out / ("blocks." + io::meshExtension(*format)),
                            io::formatBlockMesh(model, *format));
  }
  io::RunInfo run;
  run.command = "blocks";
  run.scene = options.common.scene;
  run.name = scene.name;
  run.seed = scene.seed;
  run.stages = {"dfn", "cut"};
  io::CutInfo info;
  info.cutter = cutter;
  info.disc_segments = input.disc_segments;
  info.pieces = report.pieces;
  info.inconsistent_contacts = report.inconsistent_contacts;
  run.timings = {{"dfn", dfn_seconds},
                 {"cut", cut_seconds},
                 {"cut_split", report.cut_seconds},
                 {"cut_assemble", report.assemble_seconds},
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
                  "exact (CGAL Nef) or fast (convex splitting); overrides analysis.blocks.cutter")
      ->check(CLI::IsMember({"exact", "fast"}));
  cli->add_option("--mesh-format", options->mesh_format, "block meshes: obj, ply, stl or glb")
      ->check(CLI::IsMember({"obj", "ply", "stl", "glb"}));
  return {cli, [options] { return runBlocks(*options); }};
}

}  // namespace rockmass::app
