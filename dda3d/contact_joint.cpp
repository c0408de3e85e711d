#include "dda3d/contact_joint.h"

#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>

#include "geometry/polyhedron.h"

namespace rockmass::dda3d {
namespace {

/// Among `faces` of `shape`, the one whose outward normal n_f maximises sign * n_f . n; -1
/// when `faces` is empty.
int mostAligned(const geometry::Polyhedron& shape, const PieceTopology& topology,
                std::span<const int> faces, const geometry::Vec3& n, double sign) {
  int best = -1;
  double best_dot = -std::numeric_limits<double>::infinity();
  // The block's surface: a face inside a glued block (against another of its pieces) is
  // no contact face, unless the point has no other.
  bool any_exterior = false;
  for (int f : faces) any_exterior |= topology.faceExterior(static_cast<std::size_t>(f));
  for (int f : faces) {
    if (any_exterior && !topology.faceExterior(static_cast<std::size_t>(f))) continue;
    const double dot = sign * geometry::faceNormal(shape, f).dot(n);
    if (dot > best_dot) {
      best_dot = dot;
      best = f;
    }
  }
  return best;
}

}  // namespace

int weakerJoint(const std::vector<DdaJoint>& joints, int a, int b) {
  if (a < 0) return b;
  if (b < 0 || a == b) return a;
  const auto strength = [&](int j) {
    const DdaJoint& joint = joints.at(static_cast<std::size_t>(j));
    return std::make_tuple(joint.friction, joint.cohesion, joint.tensile_strength, j);
  };
  return strength(a) < strength(b) ? a : b;
}

void checkFaceJoints(const DdaModel& model) {
  const std::size_t joints = model.joints.size();
  for (std::size_t b = 0; b < model.blocks.size(); ++b) {
    const DdaBlock& block = model.blocks[b];
    if (block.face_joints.empty()) continue;
    const std::string name = "block " + std::to_string(b);
    if (block.face_joints.size() != block.pieces.size()) {
      throw std::invalid_argument(name + " has face joints for " +
                                  std::to_string(block.face_joints.size()) + " pieces but " +
                                  std::to_string(block.pieces.size()) + " pieces");
    }
    for (std::size_t p = 0; p < block.pieces.size(); ++p) {
      const std::vector<int>& row = block.face_joints[p];
      if (row.size() != block.pieces[p].faces.size()) {
        throw std::invalid_argument(name + " piece " + std::to_string(p) + " has " +
                                    std::to_string(row.size()) + " face joints but " +
                                    std::to_string(block.pieces[p].faces.size()) + " faces");
      }
      for (std::size_t f = 0; f < row.size(); ++f) {
        if (row[f] < -1 || row[f] >= static_cast<int>(joints)) {
          throw std::invalid_argument(name + " piece " + std::to_string(p) + " face " +
                                      std::to_string(f) + " has joint " + std::to_string(row[f]) +
                                      ", which is neither -1 nor an index into the " +
                                      std::to_string(joints) + " joints");
        }
      }
    }
  }
}

int faceJoint(const DdaModel& model, int block, int piece, int face) {
  const DdaBlock& b = model.blocks.at(static_cast<std::size_t>(block));
  if (b.face_joints.empty() || face < 0) return -1;
  return b.face_joints.at(static_cast<std::size_t>(piece)).at(static_cast<std::size_t>(face));
}

int contactJoint(const DdaModel& model, const std::vector<BlockState>& blocks, const Contact& c) {
  const BlockState& bi = blocks.at(static_cast<std::size_t>(c.block_i));
  const BlockState& bj = blocks.at(static_cast<std::size_t>(c.block_j));
  const geometry::Polyhedron& pi = bi.pieces.at(static_cast<std::size_t>(c.piece_i));
  const geometry::Polyhedron& pj = bj.pieces.at(static_cast<std::size_t>(c.piece_j));
  const PieceTopology& ti = bi.topology.at(static_cast<std::size_t>(c.piece_i));
  const PieceTopology& tj = bj.topology.at(static_cast<std::size_t>(c.piece_j));
  int face_i = -1, face_j = -1;
  if (c.kind == ContactKind::VertexFace) {
    face_j = c.face;
    face_i =
        mostAligned(pi, ti, ti.vertex_faces.at(static_cast<std::size_t>(c.vertex)), c.normal, -1.0);
  } else if (c.kind == ContactKind::FacePoint) {
    face_j = c.face;
    face_i = bi.face_points.at(static_cast<std::size_t>(c.piece_i))
                 .points.at(static_cast<std::size_t>(c.vertex))
                 .face;
  } else {
    face_j = mostAligned(pj, tj, tj.edgeFaces(static_cast<std::size_t>(c.edge_j)), c.normal, 1.0);
    face_i = mostAligned(pi, ti, ti.edgeFaces(static_cast<std::size_t>(c.edge_i)), c.normal, -1.0);
  }
  return weakerJoint(model.joints, faceJoint(model, c.block_i, c.piece_i, face_i),
                     faceJoint(model, c.block_j, c.piece_j, face_j));
}

}  // namespace rockmass::dda3d
