#pragma once
/// Mesh domains (`domain: {mesh: FILE}` in a scene): the closed surface read with assimp and
/// checked with CGAL (blocks/surface_check.h).
#include <filesystem>
#include <string>

#include "geometry/box.h"
#include "geometry/polyhedron.h"

namespace rockmass::io {

/// A valid mesh domain.
struct MeshDomain {
  /// Outward triangles, vertices welded (m): the file's polygons triangulated by CGAL
  /// (blocks::convexDecomposition hangs on concave polygon faces; triangles work).
  geometry::Polyhedron surface;
  geometry::Box bounds;  ///< bounding box of the surface (m)
  double volume = 0.0;   ///< enclosed volume (m3, divergence theorem)
};

/// Reads the mesh domain `mesh` (any format assimp reads: STL, OBJ, PLY, glTF...) with
/// aiProcess_JoinIdenticalVertices, all meshes of the file together as one surface of
/// polygons as given (not aiProcess_Triangulate: assimp 5.2 fans some concave polygons
/// wrongly, e.g. the top of an L-shaped prism; CGAL triangulates them) (node
/// transforms are not applied: give coordinates in m in the file's frame). Throws InputError
/// "<scene>: domain.mesh: <file name> <problem>" when assimp cannot read it or the surface is not
/// the boundary of a solid (not closed, not manifold, inconsistently oriented, self-intersecting,
/// oriented inward; see surfaceProblem).
MeshDomain readMeshDomain(const std::filesystem::path& mesh, const std::string& scene);

}  // namespace rockmass::io
