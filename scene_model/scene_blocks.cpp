#include "scene_model/scene_blocks.h"

#include <cstdio>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "blocks/convex_decomposition.h"
#include "blocks/cut_budget.h"
#include "blocks/exact_cutter.h"
#include "blocks/fast_cutter.h"
#include "blocks/piece_coarsening.h"
#include "blocks/prism.h"
#include "geometry/progress.h"
#include "io/input_error.h"

namespace rockmass::scene_model {

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

/// Refuses a cut whose estimated blocks exceed the scene's limit (--max-blocks), at the key
/// of the set whose discs take part in the most crossings.
void checkBlockBudget(const io::Scene& scene, const geometry::FractureNetwork& network,
                      const blocks::CutInput& input, const std::string& scene_path) {
  const blocks::BlockEstimate estimate = blocks::estimateBlocks(input, scene.max_blocks);
  if (!estimate.stopped) return;
  std::size_t set = 0;
  for (std::size_t i = 1; i < estimate.set_intersections.size(); ++i) {
    if (estimate.set_intersections[i] > estimate.set_intersections[set]) set = i;
  }
  std::ostringstream what;
  what.precision(3);
  what << "the cut would make more than " << scene.max_blocks
       << " blocks, the limit (raise it with --max-blocks): its " << estimate.discs
       << " cutting discs cross " << estimate.intersections << " times";
  if (estimate.vertices > 0) what << " and meet in " << estimate.vertices << " triple points";
  what << " (counted until the estimate passed the limit)";
  if (set < network.sets.size()) {
    what << "; set " << network.sets[set].name << " takes part in the most crossings";
  }
  if (set < scene.joint_set_keys.size()) {
    throw io::InputError(io::locate(scene, scene.joint_set_keys[set].intensity,
                                    what.str() + "; check its spacing or intensity"));
  }
  throw io::InputError(scene_path + ": " + what.str());
}

SceneBlocks cutSceneBlocks(const io::Scene& scene, const geometry::FractureNetwork& network,
                           const std::string& cutter, const std::string& scene_path) {
  SceneBlocks cut;
  cut.input = cutInput(scene, network, scene_path);
  checkBlockBudget(scene, network, cut.input, scene_path);
  auto progress = std::make_shared<SharedProgress>("blocks: cut (" + cutter + ")", "regions",
                                                   /*interval=*/30.0, /*quiet=*/10.0);
  cut.input.progress = [progress](std::size_t done, std::size_t total) {
    (*progress)(done, total);
  };
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
  cut.input.progress = nullptr;
  return cut;
}

io::Scene ddaScene(const io::Scene& scene) {
  io::Scene out = scene;
  if (scene.analysis.dda && scene.analysis.dda->region) {
    out.dfn.domain = *scene.analysis.dda->region;
    out.analysis.dda->region.reset();
    // A bolt outside the region holds nothing the DDA computes: left out, and said.
    const std::size_t bolts = out.bolts.size();
    std::erase_if(out.bolts, [&](const io::BoltSpec& b) {
      return !out.dfn.domain.contains(b.head) || !out.dfn.domain.contains(b.end);
    });
    if (out.bolts.size() < bolts) {
      std::fprintf(stderr, "dda: %zu bolts outside analysis.dda.region left out\n",
                   bolts - out.bolts.size());
    }
  }
  return out;
}

blocks::BlockModel ddaBlocks(const io::Scene& scene, const blocks::BlockModel& model,
                             std::optional<blocks::MergeReport>& glued) {
  const double min_volume = scene.analysis.dda ? scene.analysis.dda->min_block_volume : 0.0;
  blocks::BlockModel out = model;
  const bool across = scene.analysis.dda && scene.analysis.dda->glue_across_materials;
  const blocks::MergeReport merge = blocks::mergeSmallBlocks(out, min_volume, across);
  glued.reset();
  if (merge.merged > 0) {
    std::fprintf(stderr,
                 "dda: %d blocks below %.3g m3 (%.3g m3 in all) glued to a neighbour: %d blocks, "
                 "%d still below (structures; rock with no neighbour of its material%s)\n",
                 merge.merged, min_volume, merge.merged_volume, merge.blocks_after,
                 merge.left_small, across ? " nor any rock neighbour" : "");
    if (merge.merged_across > 0) {
      std::fprintf(stderr,
                   "dda: %d of them (%.3g m3) are in a glued block of another material (no "
                   "neighbour of their own; glue_across_materials)\n",
                   merge.merged_across, merge.merged_across_volume);
    }
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

}  // namespace rockmass::scene_model
