#include "geometry/orientation.h"

#include <cmath>
#include <stdexcept>

namespace rockmass::geometry {

double wrapDegrees(double angle) {
  double wrapped = std::fmod(angle, 360.0);
  if (wrapped < 0.0) wrapped += 360.0;
  // fmod of a tiny negative number can round up to exactly 360.
  return wrapped >= 360.0 ? 0.0 : wrapped;
}

Vec3 normalFromOrientation(const PlaneOrientation& o) {
  const double a = radians(o.dip_direction);
  const double d = radians(o.dip);
  return {std::sin(a) * std::sin(d), std::cos(a) * std::sin(d), std::cos(d)};
}

double azimuthDegrees(const Vec3& v) {
  return wrapDegrees(degrees(std::atan2(v.x(), v.y())));
}

PlaneOrientation orientationFromNormal(const Vec3& n) {
  const double length = n.norm();
  if (!(length > 0.0) || !std::isfinite(length)) {
    throw std::invalid_argument("a plane normal must be a finite non-zero vector");
  }
  Vec3 up = n / length;
  if (up.z() < 0.0) up = -up;
  const double horizontal = std::hypot(up.x(), up.y());
  PlaneOrientation o;
  o.dip = degrees(std::atan2(horizontal, up.z()));
  // The horizontal part of the upward normal points in the dip direction.
  o.dip_direction = horizontal > 0.0 ? azimuthDegrees(up) : 0.0;
  return o;
}

Vec3 dipVector(const PlaneOrientation& o) {
  const double a = radians(o.dip_direction);
  const double d = radians(o.dip);
  return {std::sin(a) * std::cos(d), std::cos(a) * std::cos(d), -std::sin(d)};
}

Vec3 strikeVector(const PlaneOrientation& o) {
  const double a = radians(o.dip_direction - 90.0);
  return {std::sin(a), std::cos(a), 0.0};
}

}  // namespace rockmass::geometry
