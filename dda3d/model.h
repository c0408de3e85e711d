// The input of the DDA engine: blocks made of convex pieces, materials, joints, loads,
// constraints and monitors. Built from a blocks::BlockModel and the scene by the CLI, or
// directly by tests (boxes, prisms, wedges).
#pragma once

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

/// Mohr-Coulomb strength of a contact (SI units).
struct DdaJoint {
  double friction = 0.0;          ///< tan(phi)
  double cohesion = 0.0;          ///< Pa
  double tensile_strength = 0.0;  ///< Pa
};

/// One DDA block.
struct DdaBlock {
  std::vector<geometry::Polyhedron> pieces;  ///< convex pieces sharing one displacement field
  int material = 0;                          ///< index into DdaModel::materials
  bool fixed = false;                        ///< held in place (a fixed block)
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
  /// Joint of the contact between blocks of materials i and j: joints[joint_of(i, j)]; a
  /// single default joint is used when the table is empty.
  std::vector<DdaJoint> joints;
  std::vector<std::vector<int>> joint_table;  ///< [material i][material j] -> joint index
  int default_joint = 0;
  geometry::Vec3 gravity = geometry::Vec3::Zero();  ///< m/s2 (zero: no body force)
  std::vector<DdaMonitor> monitors;
};

}  // namespace rockmass::dda3d
