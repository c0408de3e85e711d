#include "blocks/block_validation.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "geometry/disc.h"

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
    sum += block.folded_volume;
    if (std::abs(sum - block.mass.volume) > relative_tolerance * std::abs(block.mass.volume)) {
      problems.push_back({block.id, -1,
                          "piece volumes sum to " + std::to_string(sum) + " m3, block volume is " +
                              std::to_string(block.mass.volume) + " m3"});
    }
  }
  return problems;
}

namespace {

/// A value for a message (3 significant digits; std::to_string would print 1e-16 as 0).
std::string text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", value);
  return buffer;
}

/// The smallest features of one piece.
struct OnePiece {
  double volume = 0.0;
  double edge = std::numeric_limits<double>::infinity();
  double vertex_distance = std::numeric_limits<double>::infinity();
  double face_area = std::numeric_limits<double>::infinity();
};

OnePiece measure(const geometry::Polyhedron& shape) {
  OnePiece m;
  m.volume = geometry::massProperties(shape).volume;
  for (std::size_t i = 0; i < shape.vertices.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      m.vertex_distance =
          std::min(m.vertex_distance, (shape.vertices[i] - shape.vertices[j]).norm());
    }
  }
  std::vector<geometry::Vec3> points;
  for (const std::vector<int>& face : shape.faces) {
    points.clear();
    for (const int v : face) points.push_back(shape.vertices[static_cast<std::size_t>(v)]);
    m.face_area = std::min(m.face_area, geometry::polygonArea(points));
    for (std::size_t k = 0; k < points.size(); ++k) {
      m.edge = std::min(m.edge, (points[(k + 1) % points.size()] - points[k]).norm());
    }
  }
  return m;
}

}  // namespace

PieceMeasures measurePieces(const BlockModel& model) {
  PieceMeasures out;
  const double inf = std::numeric_limits<double>::infinity();
  out.min_volume = out.min_edge = out.min_vertex_distance = out.min_face_area = inf;
  const auto keep = [](double value, int block, int piece, double& best, int& best_block,
                       int& best_piece) {
    if (value < best) {
      best = value;
      best_block = block;
      best_piece = piece;
    }
  };
  for (const Block& block : model.blocks) {
    for (std::size_t p = 0; p < block.pieces.size(); ++p) {
      const OnePiece m = measure(block.pieces[p].shape);
      const int index = static_cast<int>(p);
      ++out.pieces;
      keep(m.volume, block.id, index, out.min_volume, out.min_volume_block, out.min_volume_piece);
      keep(m.edge, block.id, index, out.min_edge, out.min_edge_block, out.min_edge_piece);
      keep(m.vertex_distance, block.id, index, out.min_vertex_distance,
           out.min_vertex_distance_block, out.min_vertex_distance_piece);
      keep(m.face_area, block.id, index, out.min_face_area, out.min_face_area_block,
           out.min_face_area_piece);
    }
  }
  if (out.pieces == 0) out.min_volume = out.min_edge = out.min_vertex_distance = 0.0;
  if (out.pieces == 0) out.min_face_area = 0.0;
  return out;
}

std::vector<BlockProblem> findDegeneratePieces(const BlockModel& model,
                                               const SoundnessTolerances& tolerances) {
  std::vector<BlockProblem> problems;
  for (const Block& block : model.blocks) {
    for (std::size_t p = 0; p < block.pieces.size(); ++p) {
      const OnePiece m = measure(block.pieces[p].shape);
      const int index = static_cast<int>(p);
      if (m.volume < tolerances.volume) {
        problems.push_back({block.id, index,
                            "volume " + text(m.volume) + " m3 is below the tolerance " +
                                text(tolerances.volume) + " m3"});
      }
      if (m.vertex_distance < tolerances.distance) {
        problems.push_back({block.id, index,
                            "two vertices are " + text(m.vertex_distance) +
                                " m apart, below the tolerance " + text(tolerances.distance) +
                                " m"});
      }
      if (m.face_area < tolerances.area) {
        problems.push_back({block.id, index,
                            "a face has area " + text(m.face_area) + " m2, below the tolerance " +
                                text(tolerances.area) + " m2"});
      }
    }
  }
  return problems;
}

}  // namespace rockmass::blocks
