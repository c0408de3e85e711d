// What the block cutters take: the domain, the fracture network, the structures and the
// materials. Both cutters (fast_cutter.h, exact_cutter.h) turn a CutInput into a BlockModel
// with the same blocks.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "blocks/block_model.h"
#include "geometry/fracture_network.h"
#include "geometry/polyhedron.h"

namespace rockmass::blocks {

/// A structure standing on or in the rock (the dam): a solid of its own material, made of
/// convex pieces. Structures are not cut by fractures; each one becomes one block.
struct StructureSolid {
  std::vector<geometry::Polyhedron> pieces;  ///< convex, closed, outward
  int material = -1;                         ///< index into the scene's materials
};

/// Everything a cutter needs.
struct CutInput {
  /// The rock domain as convex pieces: one box for a box domain, or the convex decomposition
  /// of a closed mesh. domain_box bounds it.
  std::vector<geometry::Polyhedron> domain_pieces;
  geometry::Box domain_box;
  /// The closed surface of a mesh domain exactly as read (outward faces, m); empty for a box
  /// domain. The exact cutter builds its Nef polyhedron from it (no rounding of the pieces);
  /// Boundary face ids of a mesh domain index its faces.
  geometry::Polyhedron domain_surface;
  const geometry::FractureNetwork* network = nullptr;  ///< discs (those with cuts == true cut)
  int disc_segments = 24;                              ///< polygon points per ellipse (>= 3)
  int rock_material = -1;                              ///< material of blocks outside every slab
  std::vector<StructureSolid> structures;              ///< each becomes its own block
  /// Called as the cut's regions finish, (regions done, regions in all), from the worker
  /// threads (the callee serializes: geometry/progress.h SharedProgress). None: silent.
  std::function<void(std::size_t, std::size_t)> progress;
};

}  // namespace rockmass::blocks
