// Small DDA scenes shared by the dda3d tests and the benchmark: boxes, a fixed base, a
// rigid rotation of a whole model.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "dda3d/model.h"
#include "geometry/polyhedron.h"

namespace rockmass::dda3d::scenes {

/// A block made of one box piece.
inline DdaBlock boxBlock(const geometry::Vec3& low, const geometry::Vec3& high, int material,
                         bool fixed) {
  DdaBlock block;
  block.pieces.push_back(geometry::boxPolyhedron({low, high}));
  block.material = material;
  block.fixed = fixed;
  return block;
}

/// A prism: the convex polygon `profile` in the (y, z) plane swept along x from x0 to x1.
inline DdaBlock prismBlock(std::vector<geometry::Vec2> profile, double x0, double x1, int material,
                           bool fixed) {
  double area = 0.0;
  for (std::size_t k = 0; k < profile.size(); ++k) {
    const geometry::Vec2& a = profile[k];
    const geometry::Vec2& b = profile[(k + 1) % profile.size()];
    area += a.x() * b.y() - b.x() * a.y();
  }
  if (area < 0.0) std::reverse(profile.begin(), profile.end());  // CCW: the x1 face looks +x
  const int n = static_cast<int>(profile.size());
  geometry::Polyhedron p;
  for (double x : {x0, x1}) {
    for (const geometry::Vec2& q : profile) p.vertices.emplace_back(x, q.x(), q.y());
  }
  std::vector<int> low, high;
  for (int k = 0; k < n; ++k) {
    high.push_back(n + k);
    low.push_back(n - 1 - k);
    const int next = (k + 1) % n;
    p.faces.push_back({k, next, n + next, n + k});
  }
  p.faces.push_back(low);
  p.faces.push_back(high);
  DdaBlock block;
  block.pieces.push_back(p);
  block.material = material;
  block.fixed = fixed;
  return block;
}

/// One rock material (granite-like unless given) and one joint with friction angle `phi`
/// (degrees), no cohesion or tension.
inline void setRock(DdaModel& model, double phi_degrees, double young = 10e9, double poisson = 0.25,
                    double density = 2600.0) {
  model.materials = {DdaMaterial{density, young, poisson}};
  model.joints = {DdaJoint{std::tan(phi_degrees * 3.14159265358979323846 / 180.0), 0.0, 0.0}};
}

/// Rotates every position and the gravity of the model by r (a rigid change of frame).
inline void rotateModel(DdaModel& model, const Eigen::Matrix3d& r) {
  for (DdaBlock& b : model.blocks) {
    for (geometry::Polyhedron& p : b.pieces) {
      for (geometry::Vec3& v : p.vertices) v = r * v;
    }
    b.initial_velocity = r * b.initial_velocity;
    b.initial_angular_velocity = r * b.initial_angular_velocity;
  }
  model.gravity = r * model.gravity;
  for (DdaMonitor& m : model.monitors) m.point = r * m.point;
  for (DdaPointLoad& l : model.point_loads) {
    l.point = r * l.point;
    l.force = r * l.force;
  }
  for (DdaFixedPoint& f : model.fixed_points) f.point = r * f.point;
  for (DdaBolt& b : model.bolts) {
    b.point_a = r * b.point_a;
    b.point_b = r * b.point_b;
  }
}

/// A generic rotation used to take test scenes off the coordinate axes.
inline Eigen::Matrix3d obliqueFrame() {
  return (Eigen::AngleAxisd(0.7, geometry::Vec3(1.0, 2.0, 3.0).normalized()) *
          Eigen::AngleAxisd(-0.3, geometry::Vec3::UnitX()))
      .toRotationMatrix();
}

}  // namespace rockmass::dda3d::scenes
