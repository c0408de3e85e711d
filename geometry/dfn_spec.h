#pragma once
/// What a scene asks the DFN generator to build: stochastic joint sets, faults,
/// interlayers and polygons read from files. Plain values; names are already resolved to
/// indices (joints, materials) by the scene reader.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "geometry/box.h"
#include "geometry/distribution.h"
#include "geometry/vec.h"

namespace rockmass::geometry {

/// Orientation model of a joint set.
struct OrientationSpec {
  bool fisher = false;                ///< true: Fisher about (dip_direction, dip) with kappa
  double fisher_dip_direction = 0.0;  ///< mean pole's plane dip direction (deg), Fisher only
  double fisher_dip = 0.0;            ///< mean plane dip (deg), Fisher only
  double kappa = 0.0;                 ///< Fisher concentration (> 0)
  DistributionSpec dip_direction;     ///< independent dip-direction distribution (deg)
  DistributionSpec dip;               ///< independent dip distribution (deg)
};

/// Direction of the ellipse's major axis within the plane.
enum class MajorAxis { Strike, Dip, Rake };

/// Shape of the elliptical discs of a set.
struct ShapeSpec {
  double aspect_ratio = 1.0;                 ///< b / a, in (0, 1]
  MajorAxis major_axis = MajorAxis::Strike;  ///< along strike, dip, or a rake
  double rake = 0.0;                         ///< angle from strike towards the dip direction (deg)
};

/// A stochastic joint set (one row group of Table 1).
struct JointSetSpec {
  std::string name;                         ///< set name, e.g. "J1"
  OrientationSpec orientation;              ///< orientation model
  std::optional<DistributionSpec> spacing;  ///< normal spacing (m): its mean sets P10
  std::optional<double> p32;                ///< alternative intensity: disc area per volume (m2/m3)
  DistributionSpec trace_length;            ///< trace length (m): sets the disc size
  ShapeSpec shape;                          ///< ellipse shape
  int joint = -1;                           ///< joint (strength) index (-1: none given)
  double min_cut_size = 0.0;                ///< discs with 2a below this (m) do not cut blocks
};

/// A large deterministic discontinuity.
struct FaultSpec {
  std::string name;                           ///< fault name, e.g. "F1"
  Vec3 center = Vec3::Zero();                 ///< a point of the mid-plane (m)
  double dip_direction = 0.0;                 ///< deg
  double dip = 0.0;                           ///< deg
  std::optional<std::array<double, 2>> size;  ///< full ellipse axes (m), major along strike;
                                              ///< none: the fault crosses the whole domain
  double thickness = 0.0;                     ///< > 0: slab between two parallel faces (m)
  int material = -1;                          ///< slab material index (-1 when thickness is 0)
  int joint = -1;                             ///< joint (strength) index (-1: none given)
};

/// The sharpest knee (deg) an interlayer profile with thickness may turn: the mitre point of
/// its offset surfaces lies thickness / (2 cos(turn / 2)) from the knee, 3.9 thicknesses at
/// 150 degrees.
inline constexpr double kMaxInterlayerTurn = 150.0;

/// A weak layer: a polyline profile swept across the domain.
struct InterlayerSpec {
  std::string name;           ///< layer name, e.g. "P1"
  std::vector<Vec2> profile;  ///< (x, z) points for sweep y, (y, z) for sweep x (m)
  char sweep = 'y';           ///< 'x' or 'y': the axis the profile is swept along
  double thickness = 0.0;     ///< slab thickness normal to each segment (m)
  int material = -1;          ///< slab material index (-1 when thickness is 0)
  int joint = -1;             ///< joint (strength) index (-1: none given)
};

/// Polygons read from a file (FracMan FAB), used exactly as given.
struct PolygonSetSpec {
  std::string name;                         ///< set name (the file's stem)
  std::vector<std::vector<Vec3>> polygons;  ///< each a planar polygon (m)
  std::vector<int> file_sets;               ///< set id of each polygon in the file
  int joint = -1;                           ///< joint (strength) index (-1: none given)
};

/// Everything the DFN generator reads.
struct DfnSpec {
  Box domain;                                ///< rock volume (m)
  std::vector<JointSetSpec> joint_sets;      ///< stochastic sets
  std::vector<FaultSpec> faults;             ///< deterministic faults
  std::vector<InterlayerSpec> interlayers;   ///< weak interlayers
  std::vector<PolygonSetSpec> polygon_sets;  ///< polygons from files
};

}  // namespace rockmass::geometry
