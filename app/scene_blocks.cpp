#include "app/scene_blocks.h"

#include <cstdio>

#include <stdexcept>

#include "blocks/exact_cutter.h"
#include "blocks/fast_cutter.h"
#include "blocks/piece_coarsening.h"
#include "blocks/prism.h"
#include "io/input_error.h"

namespace rockmass::app {

void addCutterOption(CLI::App& command, std::string& cutter) {
  command
      .add_option("--cutter", cutter,
                  "exact (exact-kernel splitting, CGAL Nef referee) or fast (floating-point "
                  "convex splitting); overrides analysis.blocks.cutter")
      ->check(CLI::IsMember({"exact", "fast"}));
}

std::string chooseCutter(const io::Scene& scene, const std::string& option,
                         const std::string& /*scene_path*/) {
  return !option.empty() ? option
         : (scene.analysis.blocks &&
            scene.analysis.blocks->cutter == io::BlocksAnalysis::Cutter::Fast)
             ? "fast"
             : "exact";
}

/// The cut input of a scene: its domain (a box, or a mesh domain's surface and its convex
/// decomposition), its network and its structures as convex prism pieces.
blocks::CutInput cutInput(const io::Scene& scene, const geometry::FractureNetwork& network,
                          const std::string& scene_path) {
  if (!scene.domain_mesh.empty() && scene.domain_surface.faces.empty()) {
    throw io::InputError(scene_path + ": domain.mesh: this command reads mesh domains only " +
                         "through loadScene(options, mesh_domain_supported = true)");
  }
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
                           ": mesh: " + s.mesh.filename().string() +
                           ": structures given as a mesh (structures[].mesh) cannot be cut into "
                           "blocks yet by either cutter; give the structure as "
                           "structures[].prism");
    }
    blocks::StructureSolid solid;
    solid.material = s.material;
    try {
      solid.pieces = blocks::prismPieces(s.prism_profile, s.prism_sweep, s.prism_from, s.prism_to);
    } catch (const std::invalid_argument& e) {
      // The outline is checked where it is cut (CGAL's simplicity test): named at its line.
      throw io::InputError(io::locate(scene_path, s.profile_line, s.profile_column,
                                      "structures: " + s.name + ": prism.profile: " + e.what()));
    }
    input.structures.push_back(std::move(solid));
  }
  return input;
}

SceneBlocks cutSceneBlocks(const io::Scene& scene, const geometry::FractureNetwork& network,
                           const std::string& cutter, const std::string& scene_path) {
  SceneBlocks cut;
  cut.input = cutInput(scene, network, scene_path);
  try {
    if (cutter == "exact") {
      blocks::ExactCutReport report;
      cut.model = blocks::cutExact(cut.input, {}, &report);
      cut.pieces = report.pieces;
      cut.split_seconds = report.split_seconds + report.extract_seconds;
      cut.assemble_seconds = report.glue_seconds;
    } else {
      blocks::FastCutReport report;
      cut.model = blocks::cutFast(cut.input, &report);
      cut.pieces = report.pieces;
      cut.inconsistent_contacts = report.inconsistent_contacts;
      cut.split_seconds = report.cut_seconds;
      cut.assemble_seconds = report.assemble_seconds;
    }
  } catch (const std::invalid_argument& e) {
    throw io::InputError(scene_path + ": " + e.what());
  }
  return cut;
}

io::Scene ddaScene(const io::Scene& scene) {
  io::Scene out = scene;
  if (scene.analysis.dda && scene.analysis.dda->region) {
    out.dfn.domain = *scene.analysis.dda->region;
    out.analysis.dda->region.reset();
  }
  return out;
}

blocks::BlockModel ddaBlocks(const io::Scene& scene, const blocks::BlockModel& model,
                             std::optional<blocks::MergeReport>& glued) {
  const double min_volume = scene.analysis.dda ? scene.analysis.dda->min_block_volume : 0.0;
  blocks::BlockModel out = model;
  const blocks::MergeReport merge = blocks::mergeSmallBlocks(out, min_volume);
  glued.reset();
  if (merge.merged > 0) {
    std::fprintf(stderr,
                 "dda: %d blocks below %.3g m3 (%.3g m3 in all) glued to a neighbour: %d blocks, "
                 "%d still below (no neighbour of their material)\n",
                 merge.merged, min_volume, merge.merged_volume, merge.blocks_after,
                 merge.left_small);
    glued = merge;
  }
  const blocks::CoarseningReport coarse = blocks::coarsenPieces(out);
  std::fprintf(stderr,
               "dda: convex pieces merged where their union is convex: %d -> %d pieces, %d -> %d "
               "piece vertices\n",
               coarse.pieces_before, coarse.pieces_after, coarse.vertices_before,
               coarse.vertices_after);
  return out;
}

}  // namespace rockmass::app
