// The joint (strength) of a DDA contact, from the joints of the piece faces it lies on
// (DdaBlock::face_joints). docs/stability.md, "Joint of a contact".
#pragma once

#include <vector>

#include "dda3d/block_state.h"
#include "dda3d/contact.h"
#include "dda3d/model.h"

namespace rockmass::dda3d {

/// The weaker of joints `a` and `b` (indices into `joints`; -1 for none): the one with the
/// smaller friction, then the smaller cohesion, then the smaller tensile strength; of two
/// equally strong joints the lower index. A joint beats -1 (none): the other is returned.
int weakerJoint(const std::vector<DdaJoint>& joints, int a, int b);

/// Throws std::invalid_argument unless every block of `model` gives no face joints, or one
/// list per piece with one entry per face, each -1 or an index into model.joints; the
/// message names the block, piece and face.
void checkFaceJoints(const DdaModel& model);

/// The joint of face `face` of piece `piece` of block `block` (DdaBlock::face_joints), -1
/// when the block gives no face joints.
int faceJoint(const DdaModel& model, int block, int piece, int face);

/// The joint index of contact `c` (into model.joints), -1 when no face it lies on carries a
/// joint (the contact then takes model.default_joint). `blocks` are the current states of
/// model.blocks (same order): their geometry and topology pick the candidate faces.
///
/// Rule:
/// - vertex-face (vertex of piece i against face `c.face` of piece j): the candidates are that
///   face of j and the face of piece i around the vertex whose outward normal is most opposed
///   to the contact normal (n points out of j, so that face of i looks at j);
/// - edge-edge (edge_i of piece i, edge_j of piece j): the face of j along edge_j whose
///   outward normal is most along n, and the face of i along edge_i most opposed to n;
/// - the contact takes the joint its candidates carry: one carrying a joint and the other
///   none (-1: domain boundary, internal face) gives that joint; two different joints give
///   the weaker (weakerJoint); none gives -1.
int contactJoint(const DdaModel& model, const std::vector<BlockState>& blocks, const Contact& c);

}  // namespace rockmass::dda3d
