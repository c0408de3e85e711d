// A DDA contact: one point-to-face entry between two blocks, with its open-close state.
#pragma once

#include <cstdint>

#include "geometry/vec.h"

namespace rockmass::dda3d {

/// How the entry was found.
enum class ContactKind : std::uint8_t {
  VertexFace,  ///< a vertex of piece i near or in a face of piece j
  EdgeEdge,    ///< crossing edges of piece i and piece j
  /// a sub-contact point of a face of piece i (FacePoint) against the face of piece j
  /// facing it; `vertex` is the point's index among the piece's face points
  FacePoint,
};

/// Open-close state of a contact.
enum class ContactState : std::uint8_t {
  Open,     ///< no spring
  Sliding,  ///< normal spring and a friction force f N against the sliding direction
  Locked,   ///< normal spring and two shear springs
};

/// One point-to-face entry (formulation doc, "Point-to-face contact"): point P of block i
/// against a plane of block j through P0 with outward unit normal n (out of j).
struct Contact {
  // The integers and flags first, then the doubles: 240 bytes an entry, without padding
  // between them (the passes over the region's 200 000 entries are bound by memory).
  int block_i = -1;  ///< block of the point
  int piece_i = -1;  ///< piece of block_i
  int block_j = -1;  ///< block of the face
  int piece_j = -1;  ///< piece of block_j
  int vertex = -1;   ///< VertexFace: vertex of piece_i
  int face = -1;     ///< VertexFace: reference face of piece_j
  int edge_i = -1;   ///< EdgeEdge: edge of piece_i (index into PieceTopology::edges)
  int edge_j = -1;   ///< EdgeEdge: edge of piece_j
  /// EdgeEdge: the face of piece_j whose normal the entry takes (a corner of two faces that
  /// touch face to face), -1 when the normal is across the two edges.
  int normal_face = -1;
  /// Joint of the contact (index into DdaModel::joints), from the faces it lies on; -1: the
  /// model's default joint.
  int joint = -1;
  /// VertexFace: the face of piece_i around the vertex that faces the face of piece_j
  /// (opposite normals within 10 deg, the most opposite), -1 when none does: the entry is
  /// then a corner or edge of block i against the face, not a point of two faces in contact
  /// (keepHullCorners).
  int facing_face = -1;
  std::int16_t flips = 0;  ///< locked <-> sliding changes in the current step (reset every step)
  /// Open <-> closed changes in the current step (reset every step); after two, the contact
  /// stays closed for the rest of the step while its pull is below Simulation::holdLimit
  /// (docs/dda3d.md, "Open-close iteration").
  std::int16_t toggles = 0;
  ContactKind kind = ContactKind::VertexFace;
  ContactState state = ContactState::Open;
  bool bonded = true;  ///< cohesion and tensile strength intact (lost once slid or opened)
  /// Closed (locked or sliding) at the end of some accepted step: a contact open now that
  /// was closed has opened (the damage map's "opened").
  bool was_closed = false;
  /// Stuck for the rest of the step: a contact frozen sliding whose friction drove its slip
  /// backwards (reset every step).
  bool held = false;

  geometry::Vec3 point = geometry::Vec3::Zero();    ///< P at the start of the step (m)
  geometry::Vec3 foot = geometry::Vec3::Zero();     ///< P', projection of P on the plane (m)
  geometry::Vec3 normal = geometry::Vec3::UnitZ();  ///< unit, pointing out of block j
  double gap0 = 0.0;  ///< d0 = n . (P - P0) at the start of the step (m), < 0: penetration
  double area = 0.0;  ///< tributary area for cohesion and tension (m2)
  /// Share of its face a sub-contact point stands for (its cell's area over the face's); 1
  /// for the other kinds. The round-off margins of the state changes are forces of k times a
  /// round-off distance: a face of n points, each with the full penalty, would sum n of them
  /// (Simulation::updateContactStates), so each point takes its share.
  double share = 1.0;
  /// Depth the detection found too late (m, >= 0): an entry first seen penetrating deeper
  /// than the allowed penetration has gap0 raised by this much, so its spring resists only
  /// further penetration; carried over while the entry lasts, it shrinks as the blocks part
  /// (Simulation::detectContacts).
  double overlap = 0.0;
  /// Accumulated shear offset of P relative to j while locked (m), in the tangent plane.
  geometry::Vec3 shear = geometry::Vec3::Zero();
  /// Unit direction of i's motion relative to j while sliding.
  geometry::Vec3 slide_direction = geometry::Vec3::Zero();
  double normal_force = 0.0;  ///< N, compression positive, from the last solve
  double gap = 0.0;           ///< d after the last solve (m)
  /// Length of the rigid part of the slip in the last solve while sliding (m); 0 unknown.
  /// Sets the friction's transverse tangent stiffness f N / slip (docs/dda3d.md).
  double slip_length = 0.0;
  /// Sliding distance accumulated over the accepted steps the contact ended sliding (m): the
  /// length of its tangential relative displacement in those steps.
  double slipped = 0.0;
};
static_assert(sizeof(Contact) == 240, "a contact's fields are packed without padding");

/// The fields of a contact that an attempt at a step changes (the open-close iteration's
/// Simulation::updateContactStates): what a redone attempt restores. Everything else of the
/// entry (its geometry, joint, area, history) is fixed from the contact search to the
/// accepted step, so the step keeps this third of each entry instead of a copy of all.
struct ContactStepState {
  ContactStepState() = default;
  explicit ContactStepState(const Contact& c)
      : shear(c.shear),
        slide_direction(c.slide_direction),
        normal_force(c.normal_force),
        gap(c.gap),
        slip_length(c.slip_length),
        flips(c.flips),
        toggles(c.toggles),
        state(c.state),
        bonded(c.bonded),
        held(c.held) {}
  void restore(Contact& c) const {
    c.shear = shear;
    c.slide_direction = slide_direction;
    c.normal_force = normal_force;
    c.gap = gap;
    c.slip_length = slip_length;
    c.flips = flips;
    c.toggles = toggles;
    c.state = state;
    c.bonded = bonded;
    c.held = held;
  }

  geometry::Vec3 shear = geometry::Vec3::Zero();
  geometry::Vec3 slide_direction = geometry::Vec3::Zero();
  double normal_force = 0.0;
  double gap = 0.0;
  double slip_length = 0.0;
  std::int16_t flips = 0;
  std::int16_t toggles = 0;
  ContactState state = ContactState::Open;
  bool bonded = true;
  bool held = false;
};

/// The part of `v` in the plane normal to the unit vector `n` (a contact's shear plane).
inline geometry::Vec3 tangential(const geometry::Vec3& v, const geometry::Vec3& n) {
  return v - n * n.dot(v);
}

}  // namespace rockmass::dda3d
