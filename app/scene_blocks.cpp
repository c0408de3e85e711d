#include "app/scene_blocks.h"

#include <stdexcept>

#include "blocks/prism.h"
#include "io/input_error.h"

namespace rockmass::app {

namespace {

/// THE place that says whether the exact (CGAL Nef) cutter is linked in. Until it is,
/// `--cutter exact` (and a scene that asks for it without --cutter) stops with exit code 2.
constexpr bool kExactCutterBuilt = false;

}  // namespace

void addCutterOption(CLI::App& command, std::string& cutter) {
  command
      .add_option("--cutter", cutter,
                  "exact (CGAL Nef) or fast (convex splitting); overrides analysis.blocks.cutter")
      ->check(CLI::IsMember({"exact", "fast"}));
}

std::string chooseCutter(const io::Scene& scene, const std::string& option,
                         const std::string& scene_path) {
  const std::string cutter =
      !option.empty() ? option
      : (scene.analysis.blocks && scene.analysis.blocks->cutter == io::BlocksAnalysis::Cutter::Fast)
          ? "fast"
          : "exact";
  if (cutter == "exact" && !kExactCutterBuilt) {
    throw io::InputError(scene_path +
                         ": the exact cutter (analysis.blocks.cutter: exact, the default) is " +
                         "not built yet; run with --cutter fast");
  }
  return cutter;
}

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

SceneBlocks cutSceneBlocks(const io::Scene& scene, const geometry::FractureNetwork& network,
                           const std::string& cutter, const std::string& scene_path) {
  (void)cutter;  // only the fast cutter is built (chooseCutter refuses the exact one)
  SceneBlocks cut;
  cut.input = cutInput(scene, network, scene_path);
  try {
    cut.model = blocks::cutFast(cut.input, &cut.report);
  } catch (const std::invalid_argument& e) {
    throw io::InputError(scene_path + ": " + e.what());
  }
  return cut;
}

}  // namespace rockmass::app
