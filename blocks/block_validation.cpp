#include "blocks/block_validation.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <cmath>
#include <optional>

namespace rockmass::blocks {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;

/// The piece as a surface mesh (faces fanned into triangles); empty when a face cannot be
/// added (a non-manifold or inconsistently oriented face).
std::optional<Mesh> toMesh(const geometry::Polyhedron& shape) {
  Mesh mesh;
  std::vector<Mesh::Vertex_index> vertices;
  for (const geometry::Vec3& v : shape.vertices) {
    vertices.push_back(mesh.add_vertex(K::Point_3(v.x(), v.y(), v.z())));
  }
  for (const std::vector<int>& face : shape.faces) {
    std::vector<Mesh::Vertex_index> ring;
    for (const int v : face) ring.push_back(vertices[static_cast<std::size_t>(v)]);
    if (mesh.add_face(ring) == Mesh::null_face()) return std::nullopt;
  }
  return mesh;
}

}  // namespace

std::vector<BlockProblem> validateBlocks(const BlockModel& model, double relative_tolerance) {
  std::vector<BlockProblem> problems;
  for (const Block& block : model.blocks) {
    double sum = 0.0;
    for (std::size_t p = 0; p < block.pieces.size(); ++p) {
      const Piece& piece = block.pieces[p];
      const int index = static_cast<int>(p);
      if (piece.face_sources.size() != piece.shape.faces.size()) {
        problems.push_back({block.id, index, "face_sources and faces differ in number"});
      }
      const std::optional<Mesh> mesh = toMesh(piece.shape);
      if (!mesh) {
        problems.push_back({block.id, index, "faces do not form an oriented 2-manifold"});
        continue;
      }
      if (!CGAL::is_closed(*mesh)) {
        problems.push_back({block.id, index, "surface is not closed"});
        continue;
      }
      if (!CGAL::Polygon_mesh_processing::is_outward_oriented(*mesh)) {
        problems.push_back({block.id, index, "surface is not outward-oriented"});
      }
      const double volume = geometry::massProperties(piece.shape).volume;
      if (!(volume > 0.0)) problems.push_back({block.id, index, "volume is not positive"});
      sum += volume;
    }
    if (std::abs(sum - block.mass.volume) > relative_tolerance * std::abs(block.mass.volume)) {
      problems.push_back({block.id, -1,
                          "piece volumes sum to " + std::to_string(sum) + " m3, block volume is " +
                              std::to_string(block.mass.volume) + " m3"});
    }
  }
  return problems;
}

}  // namespace rockmass::blocks
