// Test geometry shared by the contact detection tests: a cube cut into convex pieces by
// random planes, and blocks made of groups of pieces as the engine holds them.
#pragma once

#include <cstdint>
#include <vector>

#include "blocks/convex_split.h"
#include "dda3d/block_state.h"
#include "dda3d/contact_detection.h"
#include "geometry/polyhedron.h"
#include "geometry/random.h"

namespace rockmass::dda3d::testing {

/// The unit cube cut by `cuts` random planes through random points of it into convex
/// pieces that touch exactly across the cuts and overlap nowhere (blocks::splitPiece).
inline std::vector<geometry::Polyhedron> cutCube(std::uint64_t seed, int cuts) {
  geometry::Rng rng = geometry::makeRng(seed, 0);
  const auto uniform = [&rng] { return static_cast<double>(rng() % 1000001) / 1e6; };
  std::vector<blocks::Piece> pieces(1);
  pieces[0].shape = geometry::boxPolyhedron({geometry::Vec3::Zero(), geometry::Vec3::Ones()});
  pieces[0].face_sources.assign(6, {});
  for (int k = 0; k < cuts; ++k) {
    const geometry::Vec3 normal =
        geometry::Vec3(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5).normalized();
    const auto plane =
        blocks::Plane::through(geometry::Vec3(uniform(), uniform(), uniform()), normal);
    std::vector<blocks::Piece> next;
    for (const blocks::Piece& p : pieces) {
      const auto split = blocks::splitPiece(p, plane, 1e-9, {});
      if (!split) {
        next.push_back(p);
        continue;
      }
      next.push_back(split->below);
      next.push_back(split->above);
    }
    pieces = std::move(next);
  }
  std::vector<geometry::Polyhedron> out;
  for (const blocks::Piece& p : pieces) out.push_back(p.shape);
  return out;
}

inline std::vector<BlockState> blocksOf(
    const std::vector<std::vector<geometry::Polyhedron>>& groups) {
  std::vector<BlockState> blocks(groups.size());
  for (std::size_t b = 0; b < groups.size(); ++b) {
    for (const geometry::Polyhedron& p : groups[b]) {
      blocks[b].pieces.push_back(p);
      blocks[b].topology.push_back(pieceTopology(p));
    }
    markExterior(blocks[b].pieces, blocks[b].topology);  // as the engine does
    blocks[b].updateMassProperties();
  }
  return blocks;
}

/// No vertex used a face last step (a first detection).
inline const PreviousFace kNoPrevious = [](int, int, int, int, int) { return -1; };

}  // namespace rockmass::dda3d::testing
