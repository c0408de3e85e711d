// The input of the DDA engine: blocks made of convex pieces, materials, joints, loads,
// constraints and monitors. Built from a blocks::BlockModel and the scene by the CLI, or
// directly by tests (boxes, prisms, wedges).
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "geometry/polyhedron.h"
#include "geometry/vec.h"

namespace rockmass::dda3d {

/// Intact material of a block (SI units).
struct DdaMaterial {
  double density = 2600.0;  ///< kg/m3
  double young = 10e9;      ///< Pa
  double poisson = 0.25;    ///< -
};

/// What a contact keeps of its cohesion and tensile strength once it has failed
/// (docs/stability.md, "Joint models").
enum class JointModel : std::uint8_t {
  /// Cohesion kept while the contact slides (the rigid-plastic Mohr-Coulomb law of limit
  /// equilibrium); cohesion and tensile strength lost once it opens.
  Plastic,
  /// Shi's DDA rule: cohesion and tensile strength lost for good once the contact slides or
  /// opens.
  Brittle,
};

/// Mohr-Coulomb strength of a contact (SI units).
struct DdaJoint {
  double friction = 0.0;          ///< tan(phi)
  double cohesion = 0.0;          ///< Pa
  double tensile_strength = 0.0;  ///< Pa
  JointModel model = JointModel::Plastic;
};

/// One DDA block.
struct DdaBlock {
  std::vector<geometry::Polyhedron> pieces;  ///< convex pieces sharing one displacement field
  int material = 0;                          ///< index into DdaModel::materials
  bool fixed = false;                        ///< held in place (a fixed block)
  /// The scene's structure it is (-1: rock): for the reports, and a structure's blocks carry
  /// no pore pressure (DdaSettings::biot_coefficient).
  int structure = -1;
  /// Joint of each face of each piece (index into DdaModel::joints), -1 where the face is no
  /// discontinuity (an internal face between pieces, the domain boundary). Empty: every face
  /// -1. A contact takes the joint of the faces it lies on (dda3d/contact_joint.h).
  std::vector<std::vector<int>> face_joints;
  /// Sub-contact point spacing (m) of this block's faces (0: the corners only); none: the
  /// run's DdaSettings::contact_point_spacing. The scene gives a structure's blocks their
  /// own (io::StructureSpec::contact_point_spacing).
  std::optional<double> contact_point_spacing;
  /// Initial stress (Pa) in Voigt order (sx, sy, sz, tyz, tzx, txy), compression negative.
  Eigen::Matrix<double, 6, 1> initial_stress = Eigen::Matrix<double, 6, 1>::Zero();
  /// Initial velocity (m/s) of the centroid and angular velocity (rad/s) about it.
  geometry::Vec3 initial_velocity = geometry::Vec3::Zero();
  geometry::Vec3 initial_angular_velocity = geometry::Vec3::Zero();
};

/// A constant force applied at a material point of a block (it moves with the block).
struct DdaPointLoad {
  int block = -1;                                 ///< index into DdaModel::blocks
  geometry::Vec3 point = geometry::Vec3::Zero();  ///< initial position (m)
  geometry::Vec3 force = geometry::Vec3::Zero();  ///< N
};

/// A material point held at its initial position by a penalty spring (Shi's fixed point),
/// or, with a `direction`, held only along it (a roller: free to slide across it).
struct DdaFixedPoint {
  int block = -1;                                 ///< index into DdaModel::blocks
  geometry::Vec3 point = geometry::Vec3::Zero();  ///< initial position (m)
  /// Zero: held in every direction. A unit vector: only the displacement along it is held
  /// (a roller support on a plane with this normal).
  geometry::Vec3 direction = geometry::Vec3::Zero();
  /// Where the material point is at the start (m), when it has already moved from `point`
  /// (a model settled before, settledModel): its spring starts stretched by the difference,
  /// carrying the reaction it carried. Unset: at `point`.
  std::optional<geometry::Vec3> current = std::nullopt;
};

/// The half-space normal . x <= offset (m).
struct HalfSpace {
  geometry::Vec3 normal = geometry::Vec3::UnitZ();
  double offset = 0.0;
};

/// Water pressure p(x) = unit_weight * max(0, h(x) - z) acting on one face of one piece,
/// pushing against the face's outward normal, with the piezometric head h(x) = level +
/// head_gradient . x linear in position (a constant head: hydrostatic below the level).
/// Acts on the part of the face inside every half-space of `within` (none: the whole face).
/// Integrated exactly over that part (the integrand is quadratic in position).
struct DdaPressure {
  int block = -1;             ///< index into DdaModel::blocks
  int piece = 0;              ///< index into DdaBlock::pieces
  int face = 0;               ///< index into Polyhedron::faces of that piece
  double level = 0.0;         ///< the head at x = 0: z of the free water surface (m)
  double unit_weight = 9810;  ///< N/m3
  /// Uplift: water in a structure-rock interface or in the rock's discontinuities rather
  /// than on an exposed face. The overload method scales it only when asked
  /// (LoadScaling::uplift: the scene's scale_uplift).
  bool uplift = false;
  /// Pore pressure in a discontinuity (a pore-pressure field), for the reports; uplift too.
  bool pore = false;
  geometry::Vec3 head_gradient = geometry::Vec3::Zero();  ///< dh/dx (m/m)
  std::vector<HalfSpace> within;
};

/// A hydrostatic DdaPressure (no head gradient, the whole face).
inline DdaPressure hydrostaticPressure(int block, int piece, int face, double level,
                                       double unit_weight, bool uplift = false) {
  DdaPressure p;
  p.block = block;
  p.piece = piece;
  p.face = face;
  p.level = level;
  p.unit_weight = unit_weight;
  p.uplift = uplift;
  return p;
}

/// Westergaard's added hydrodynamic pressure of a pseudo-static earthquake on a face in a
/// reservoir: p = 7/8 k_h unit_weight sqrt(depth (level - z)) for level - depth < z < level,
/// pushing against the face's outward normal (Westergaard 1933; USBR Design of Small Dams).
struct DdaHydrodynamicPressure {
  int block = -1;
  int piece = 0;
  int face = 0;
  double level = 0.0;         ///< z of the reservoir surface (m)
  double depth = 0.0;         ///< reservoir depth at the face, H (m)
  double k_h = 0.0;           ///< horizontal seismic coefficient
  double unit_weight = 9810;  ///< N/m3
};

/// A bolt: an elastic spring between a material point of one block and one of another
/// (block_b = -1: anchored to the ground). Its force is stiffness * (length - free length).
struct DdaBolt {
  int block_a = -1;                                 ///< index into DdaModel::blocks
  geometry::Vec3 point_a = geometry::Vec3::Zero();  ///< initial position (m)
  int block_b = -1;                                 ///< index into DdaModel::blocks, or -1
  geometry::Vec3 point_b = geometry::Vec3::Zero();  ///< initial position (m)
  double stiffness = 0.0;                           ///< N/m
  double pretension = 0.0;                          ///< N, > 0 pulls the two points together
  /// Axial force at which the bolt yields (perfectly plastic: the force stays there while it
  /// lengthens); infinite: elastic.
  double yield_force = std::numeric_limits<double>::infinity();
  /// Axial force at which the bolt breaks (it carries nothing from then on); infinite: never.
  double rupture_force = std::numeric_limits<double>::infinity();
  bool broken = false;  ///< already broken (a settled start after a rupture): carries nothing
};

/// A point attached to a block; its displacement and velocity are recorded.
struct DdaMonitor {
  std::string name;
  geometry::Vec3 point = geometry::Vec3::Zero();  ///< initial position (m)
  int block = -1;                                 ///< index into DdaModel::blocks
};

/// Everything the engine needs to know about the physical problem.
struct DdaModel {
  std::vector<DdaBlock> blocks;
  std::vector<DdaMaterial> materials;
  /// Strengths of the contacts. A contact takes the joint of the piece faces it lies on
  /// (DdaBlock::face_joints, dda3d/contact_joint.h), default_joint where they carry none; a
  /// single default joint is used when the list is empty.
  std::vector<DdaJoint> joints;
  int default_joint = 0;
  geometry::Vec3 gravity = geometry::Vec3::Zero();  ///< m/s2 (zero: no body force)
  /// Pseudo-static earthquake: a body acceleration (m/s2) every block carries with gravity
  /// (k_h g horizontally, k_v g vertically); zero: none.
  geometry::Vec3 seismic = geometry::Vec3::Zero();
  std::vector<DdaMonitor> monitors;
  std::vector<DdaPointLoad> point_loads;
  std::vector<DdaFixedPoint> fixed_points;
  std::vector<DdaPressure> pressures;
  std::vector<DdaHydrodynamicPressure> hydrodynamic;  ///< Westergaard's added pressures
  std::vector<DdaBolt> bolts;
};

}  // namespace rockmass::dda3d
