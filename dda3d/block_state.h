// The moving state of one DDA block: its current geometry, mass properties, velocity,
// stress and strain, and the kinematics that move it by one step's displacement.
#pragma once

#include <array>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "dda3d/displacement_field.h"
#include "geometry/polyhedron.h"
#include "geometry/vec.h"

namespace rockmass::dda3d {

/// Block unknowns D (12; a rigid block uses the first 6 and keeps the rest zero).
using BlockVector = Eigen::Matrix<double, kBlockDofs, 1>;
/// A 12 x 12 sub-matrix of the system (a rigid block uses the top-left 6 x 6).
using BlockMatrix = Eigen::Matrix<double, kBlockDofs, kBlockDofs>;
/// Stress (Pa) or strain (-) in Voigt order (xx, yy, zz, yz, zx, xy).
using VoigtVector = Eigen::Matrix<double, kVoigtSize, 1>;

/// Topology of a convex piece, fixed for the whole run (vertices only move).
struct PieceTopology {
  std::vector<std::array<int, 2>> edges;       ///< unique vertex pairs
  std::vector<std::vector<int>> neighbours;    ///< vertices joined to each vertex by an edge
  std::vector<std::vector<int>> vertex_faces;  ///< faces around each vertex
  /// Faces along each edge (those holding both its vertices, in face order): edge e's are
  /// edge_face_list[edge_face_start[e] .. edge_face_start[e + 1]).
  std::vector<int> edge_face_start, edge_face_list;
  std::span<const int> edgeFaces(std::size_t e) const {
    return {edge_face_list.data() + edge_face_start[e],
            static_cast<std::size_t>(edge_face_start[e + 1] - edge_face_start[e])};
  }
  /// On the block's surface (markExterior): each face not wholly covered by faces of the
  /// block's other pieces, each vertex and edge with such a face around it, and the piece
  /// when any face is. Empty: everything exterior (a block of one piece).
  std::vector<char> exterior_faces, exterior_vertices, exterior_edges;
  bool exterior = true;
  /// Each vertex's index among the block's corners (markExterior): the copies of one point
  /// in the block's pieces, equal within round-off, share it. Empty: not numbered.
  std::vector<int> block_vertex;
  bool faceExterior(std::size_t f) const { return exterior_faces.empty() || exterior_faces[f]; }
  bool vertexExterior(std::size_t v) const {
    return exterior_vertices.empty() || exterior_vertices[v];
  }
  bool edgeExterior(std::size_t e) const { return exterior_edges.empty() || exterior_edges[e]; }
};

/// Edges, vertex neighbours and vertex faces of a polyhedron given by its faces.
PieceTopology pieceTopology(const geometry::Polyhedron& piece);

/// Marks what of a block's convex pieces lies on the block's surface (PieceTopology's
/// exterior flags). A face is interior when faces of other pieces of the block lying in its
/// plane, facing it, cover its whole area (within 1e-6 of it); the pieces of a glued block
/// meet on such faces. Contacts with other blocks need only the exterior faces, vertices and
/// edges: a point of another block reaches an interior face only through the surface.
/// Also numbers the block's corners (PieceTopology::block_vertex): vertices of its pieces
/// within 1e-9 of the block's size of each other are one corner.
void markExterior(const std::vector<geometry::Polyhedron>& pieces,
                  std::vector<PieceTopology>& topology);

/// A sub-contact point: a material point inside a face of a piece, with its share of the
/// face's area (docs/stability.md, "Contact points").
struct FacePoint {
  geometry::Vec3 position = geometry::Vec3::Zero();  ///< m, current
  int face = -1;                                     ///< face of the piece it lies in
  double area = 0.0;                                 ///< m2, its cell of the face
};

/// The sub-contact points of a piece, face by face (made by dda3d::facePoints).
struct FacePoints {
  std::vector<FacePoint> points;
  /// The points of face f are points[first[f]] .. points[first[f + 1] - 1]; empty when the
  /// piece has none.
  std::vector<int> first;
  /// How many points face f has.
  int count(std::size_t f) const { return first.empty() ? 0 : first[f + 1] - first[f]; }
};

/// The state of one block.
struct BlockState {
  std::vector<geometry::Polyhedron> pieces;  ///< current geometry (m)
  std::vector<PieceTopology> topology;       ///< one per piece
  int material = 0;                          ///< index into DdaModel::materials
  bool fixed = false;                        ///< no unknowns: held in place
  int dof_offset =
      -1;             ///< index among movable blocks (rows start at dof_offset * dofs), -1 if fixed
  double mass = 0.0;  ///< kg, constant through the run
  double volume = 0.0;                               ///< m3, current
  geometry::Vec3 centroid = geometry::Vec3::Zero();  ///< m, current
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  ///< integral of X X^T about the centroid, m5
  BlockVector velocity = BlockVector::Zero();        ///< dD/dt at the start of the step
  /// d2D/dt2 at the start of the step (the time integration's a0).
  BlockVector acceleration = BlockVector::Zero();
  BlockVector last_displacement = BlockVector::Zero();  ///< D of the last accepted step
  VoigtVector stress = VoigtVector::Zero();             ///< Pa, Voigt order
  VoigtVector strain = VoigtVector::Zero();             ///< accumulated strain (-), Voigt order
  /// Sub-contact points of each piece (empty without DdaSettings::contact_point_spacing).
  std::vector<FacePoints> face_points;
  double size = 0.0;  ///< bounding-box diagonal (m)

  /// Recomputes volume, centroid, second moments and size from the current pieces.
  void updateMassProperties();
};

/// Mass matrix rho * integral of T^T T over the block (kg, kg m, kg m2 entries), 12 x 12.
/// Uses the second moments about the centroid; the first moments vanish there.
BlockMatrix massMatrix(const BlockState& block);

/// New position of material point `x` (m) of a block with centroid `centroid` moved by `d`:
/// translation, the rigid rotation applied exactly (Rodrigues, angle |r|) and the strain
/// part linearly: x' = c + u0 + R X + S X, S the symmetric strain tensor.
geometry::Vec3 movedPoint(const geometry::Vec3& x, const geometry::Vec3& centroid,
                          const BlockVector& d);

/// movedPoint of one block's points, its rotation (a sine and a cosine) and strain tensor
/// formed once for all of them: the same arithmetic per point, so the same bits.
class BlockMotion {
 public:
  BlockMotion(const geometry::Vec3& centroid, const BlockVector& d);
  geometry::Vec3 operator()(const geometry::Vec3& x) const {
    const geometry::Vec3 arm = x - centroid_;
    return centroid_ + translation_ + rotation_ * arm + strain_ * arm;
  }
  /// The exact rotation matrix of the motion (rotationMatrix of its rotation vector).
  const Eigen::Matrix3d& rotation() const { return rotation_; }

 private:
  geometry::Vec3 centroid_;
  geometry::Vec3 translation_;
  Eigen::Matrix3d rotation_;
  Eigen::Matrix3d strain_;
};

/// The exact rotation matrix of the rotation vector (rx, ry, rz) (rad).
Eigen::Matrix3d rotationMatrix(const geometry::Vec3& rotation);

}  // namespace rockmass::dda3d
