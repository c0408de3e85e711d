#pragma once
/// Plane orientations: dip direction / dip (ISRM) <-> unit normals, right-hand-rule strike.
///
/// Conventions: x = East, y = North, z = Up. The dip direction is the azimuth of the line
/// of steepest descent, clockwise from North (+y), in degrees [0, 360). The dip is the
/// angle of that line below the horizontal, in degrees [0, 90].
#include "geometry/vec.h"

namespace rockmass::geometry {

/// Orientation of a plane (unit: degrees).
struct PlaneOrientation {
  double dip_direction = 0.0;  ///< azimuth of steepest descent, clockwise from North (deg)
  double dip = 0.0;            ///< angle below horizontal (deg), 0..90
};

/// Upward unit normal (n_z >= 0) of a plane: (sin a sin d, cos a sin d, cos d).
Vec3 normalFromOrientation(const PlaneOrientation& o);

/// Orientation of the plane with normal n (either sign; need not be unit length).
/// A horizontal plane gets dip direction 0. Throws std::invalid_argument for a zero vector.
PlaneOrientation orientationFromNormal(const Vec3& n);

/// Unit vector of the line of steepest descent (points downward unless dip is 0).
Vec3 dipVector(const PlaneOrientation& o);

/// Unit horizontal strike vector by the right-hand rule: looking along it, the plane dips
/// to the right, so its azimuth is the dip direction minus 90 degrees.
Vec3 strikeVector(const PlaneOrientation& o);

/// Azimuth (deg, [0, 360)) of a direction's horizontal projection, clockwise from North.
double azimuthDegrees(const Vec3& v);

/// Wraps an angle in degrees to [0, 360).
double wrapDegrees(double angle);

/// Degrees to radians and back.
constexpr double kPi = 3.14159265358979323846;
constexpr double radians(double deg) {
  return deg * kPi / 180.0;
}
constexpr double degrees(double rad) {
  return rad * 180.0 / kPi;
}

}  // namespace rockmass::geometry
