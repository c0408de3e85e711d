// Cutting a scene into blocks, shared by every sub-command that needs blocks (`blocks`,
// `dda`): the cutter choice, the cut input (box domain, network, prism structures) and the
// cut itself, so that `dda` cuts exactly as `blocks` does.
#pragma once

#include <optional>
#include <string>

#include "blocks/block_merge.h"
#include "blocks/fast_cutter.h"
#include "geometry/fracture_network.h"
#include "io/scene.h"

namespace rockmass::scene_model {

/// The blocks of a scene and how they were cut (by either cutter).
struct SceneBlocks {
  blocks::BlockModel model;       ///< the blocks
  blocks::CutInput input;         ///< what was cut (its network pointer is the caller's)
  int pieces = 0;                 ///< convex pieces of the rock
  int inconsistent_contacts = 0;  ///< fast cutter only (0 in a sound cut)
  double split_seconds = 0.0;     ///< splitting (exact: summed over regions, i.e. CPU time)
  double assemble_seconds = 0.0;  ///< gluing, materials, adjacency
};

/// The cutter to use: `option` when given, else the scene's analysis.blocks.cutter (exact
/// by default). Both cutters handle every scene cutInput accepts; `scene_path` is kept for
/// errors of cutters that cannot.
std::string chooseCutter(const io::Scene& scene, const std::string& option,
                         const std::string& scene_path);

/// The cut input of a scene: its domain (the box, or the checked surface of a mesh domain,
/// scene.domain_surface, with its convex decomposition as domain_pieces), `network` (kept by
/// pointer) and its structures as convex prism pieces. Throws io::InputError for what cannot
/// be cut yet (mesh structures; a mesh domain whose surface was not read) or a bad prism.
blocks::CutInput cutInput(const io::Scene& scene, const geometry::FractureNetwork& network,
                          const std::string& scene_path);

/// Cuts the scene with `cutter` (from chooseCutter). Throws io::InputError naming the scene
/// for an input the cutter rejects.
SceneBlocks cutSceneBlocks(const io::Scene& scene, const geometry::FractureNetwork& network,
                           const std::string& cutter, const std::string& scene_path);

/// The scene a DDA runs on (`dda`, `overload`, `strength`, `run`): `scene` itself, or, with
/// analysis.dda.region, a copy whose domain box is the region: cut from the same network and
/// structures, with supports and `domain_top` loads on the region's faces; bolts with an end
/// outside the region are left out (one line on stderr says how many).
io::Scene ddaScene(const io::Scene& scene);

/// The blocks a DDA of the scene runs on (`dda`, `overload`, `strength`, `run`): `model`
/// with the blocks below analysis.dda.min_block_volume glued to a neighbour
/// (blocks::mergeSmallBlocks; none when the key is absent or 0), then every block's pieces
/// merged where their union is convex (blocks::coarsenPieces: the same solids, fewer
/// pieces). When it glued any, prints one line on stderr and sets `glued` (the summaries'
/// glued_blocks); else leaves `glued` empty. Prints the piece counts on stderr.
blocks::BlockModel ddaBlocks(const io::Scene& scene, const blocks::BlockModel& model,
                             std::optional<blocks::MergeReport>& glued);

}  // namespace rockmass::scene_model
