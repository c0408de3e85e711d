// The block model: what both cutters (exact CGAL Nef and fast convex splitting) produce, and
// what the DDA engine, the statistics and the writers consume.
#pragma once

#include <string>
#include <vector>

#include "geometry/box.h"
#include "geometry/polyhedron.h"

namespace rockmass::blocks {

/// What made a face of a convex piece.
enum class FaceKind {
  Disc,        ///< a fracture disc (id = disc id of the FractureNetwork)
  Boundary,    ///< the domain boundary (id = box face 0..5: x_min, x_max, y_min, y_max,
               ///< z_min, z_max; or the face index of a mesh domain)
  Structure,   ///< the outer surface of a structure (id = structure index)
  Fictitious,  ///< an internal cut between two pieces of the same block (id = -1)
};

/// Provenance of one face.
struct FaceSource {
  FaceKind kind = FaceKind::Fictitious;
  int id = -1;
  bool operator==(const FaceSource&) const = default;
};

/// A convex piece of a block: its polyhedron and, per face, where the face came from.
struct Piece {
  geometry::Polyhedron shape;            ///< convex, closed, outward
  std::vector<FaceSource> face_sources;  ///< one per shape.faces entry
};

/// A block: one or more convex pieces glued across fictitious faces; one rigid or
/// deformable body for the DDA.
struct Block {
  int id = 0;         ///< 1..N in a deterministic order
  int material = -1;  ///< index into the scene's materials
  /// Index of the structure this block is (CutInput::structures), -1 for a rock block.
  int structure = -1;
  std::vector<Piece> pieces;  ///< convex decomposition
  /// Sum over pieces and folded slivers (volume m3, moments about the origin).
  geometry::MassProperties mass;
  /// Volume of the slivers of this block that soundPiece folded away (m3; each below
  /// 1e-15 of the domain volume): counted in `mass`, in no piece, so block volumes and
  /// masses stay those of the cut.
  double folded_volume = 0.0;
  geometry::Box bounds;  ///< bounding box of all pieces
};

/// Two blocks touching across real (non-fictitious) faces.
struct Adjacency {
  int block_a = 0;    ///< smaller block id
  int block_b = 0;    ///< larger block id
  double area = 0.0;  ///< shared face area (m2)
  FaceSource source;  ///< what separates them (a disc, or a structure surface)
};

/// All blocks of a domain.
struct BlockModel {
  geometry::Box domain;              ///< bounding box of the domain
  double domain_volume = 0.0;        ///< m3 (the box volume, or the mesh's volume)
  std::vector<Block> blocks;         ///< sorted by id
  std::vector<Adjacency> adjacency;  ///< sorted by (block_a, block_b)
};

}  // namespace rockmass::blocks
