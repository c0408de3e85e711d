// The outer surface of a block: the real faces of its convex pieces, without the faces (or
// parts of faces) that two pieces of the same block share, as one closed, outward,
// conforming triangle mesh. What the mesh writers (io/block_mesh.h) and mesh tools need.
#pragma once

#include <array>
#include <vector>

#include "blocks/block_model.h"
#include "geometry/polyhedron.h"

namespace rockmass::blocks {

/// A closed triangle surface: triangles CCW seen from outside (right-hand normal outward).
struct TriangleSurface {
  std::vector<geometry::Vec3> vertices;       ///< m
  std::vector<std::array<int, 3>> triangles;  ///< vertex indices, CCW seen from outside
};

/// The outer surface of `block`.
///
/// Faces of its pieces are grouped by plane; in each plane, the parts of outward faces
/// covered by an opposite face of another piece of the block are removed (the fictitious
/// faces between pieces, and the two faces of a crack that ends inside the block), by
/// convex polygon differences. What is left is welded (points closer than 1e-10 of the
/// block's bounding-box diagonal are one vertex), vertices lying on another polygon's edge
/// are inserted into it (no T-junctions), and each polygon is fanned into triangles (from
/// its centroid when it got inserted vertices; from the centroid too where a corner fan would make
/// a flat triangle), and split where the block touches itself (splitNonManifold): a 2-manifold
/// surface. Kept vertices are the pieces' own coordinates. The result encloses the block's volume;
/// deterministic for a given block.
TriangleSurface blockSurface(const Block& block);

/// Makes `surface` 2-manifold: where two parts of a block touch along an edge (four
/// triangles on one edge) or at a vertex (two cones of triangles), the vertices are copied
/// so that each part has its own (same coordinates): every edge then has two triangles, one
/// each way, and every vertex one fan. Around such an edge each triangle is joined to the one
/// that closes the same solid wedge (by angle about the edge and orientation). A surface that
/// is already 2-manifold is unchanged. blockSurface() calls it.
void splitNonManifold(TriangleSurface& surface);

/// The surface as a polyhedron of triangles (for geometry::massProperties and the CGAL checks).
geometry::Polyhedron toPolyhedron(const TriangleSurface& surface);

}  // namespace rockmass::blocks
