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

/// Degrees to radians and back.
inline double radians(double degrees) {
  return degrees * 3.14159265358979323846 / 180.0;
}
inline double degrees(double radians) {
  return radians * 180.0 / 3.14159265358979323846;
}

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

/// A prism wedge in a V groove along x: plane A (normal (0, -sin a, cos a), rising to +y)
/// and plane B (normal (0, sin b, cos b), rising to -y), on two fixed supports (blocks 0
/// and 1); the wedge is block 2. Angles in degrees, `phi` the joints' friction angle.
struct Wedge {
  DdaModel model;
  geometry::Vec3 n_a, n_b;  ///< outward normals of the two planes
};
inline Wedge vGrooveWedge(double alpha, double beta, double phi, const geometry::Vec3& gravity) {
  constexpr double kRad = 3.14159265358979323846 / 180.0;
  Wedge w;
  setRock(w.model, phi);
  const double ta = std::tan(alpha * kRad), tb = std::tan(beta * kRad);
  constexpr double kHeight = 1.0, kWidth = 3.0, kDepth = 1.0;
  w.model.blocks.push_back(prismBlock(
      {{0, 0}, {0, -kDepth}, {kWidth, -kDepth}, {kWidth, kWidth * ta}}, -1.0, 6.0, 0, true));
  w.model.blocks.push_back(prismBlock(
      {{0, 0}, {-kWidth, kWidth * tb}, {-kWidth, -kDepth}, {0, -kDepth}}, -1.0, 6.0, 0, true));
  w.model.blocks.push_back(
      prismBlock({{0, 0}, {kHeight / ta, kHeight}, {-kHeight / tb, kHeight}}, 0.0, 1.5, 0, false));
  w.model.gravity = gravity;
  w.n_a = geometry::Vec3(0, -std::sin(alpha * kRad), std::cos(alpha * kRad));
  w.n_b = geometry::Vec3(0, std::sin(beta * kRad), std::cos(beta * kRad));
  return w;
}

/// Block theory of a wedge on two planes (Goodman & Shi 1985, ch. 9), per unit mass under
/// body force `w` (N/kg): sliding direction s along the line of intersection, normal forces
/// N_A, N_B on the two planes and the driving force |w . s|.
struct TwoPlane {
  geometry::Vec3 s;
  double n_a, n_b, drive;
};
inline TwoPlane twoPlane(const geometry::Vec3& n_a, const geometry::Vec3& n_b,
                         const geometry::Vec3& w) {
  const geometry::Vec3 cross = n_a.cross(n_b);
  TwoPlane t;
  t.s = cross.normalized();
  if (t.s.dot(w) < 0) t.s = -t.s;
  t.n_a = w.cross(n_b).dot(n_b.cross(n_a)) / cross.squaredNorm();
  t.n_b = w.cross(n_a).dot(n_a.cross(n_b)) / cross.squaredNorm();
  t.drive = std::abs(w.dot(t.s));
  return t;
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
