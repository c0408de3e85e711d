#pragma once
/// Orientation of lines (scanlines, boreholes, principal directions): trend and plunge.
///
/// Conventions: x = East, y = North, z = Up. The trend is the azimuth of the line's
/// horizontal projection, clockwise from North (+y), in degrees [0, 360); the plunge is the
/// angle below the horizontal, positive downward, in degrees [-90, 90].
#include "geometry/vec.h"

namespace rockmass::rqd {

/// Trend and plunge of a line (unit: degrees).
struct LineOrientation {
  double trend = 0.0;   ///< azimuth clockwise from North (deg), [0, 360)
  double plunge = 0.0;  ///< angle below the horizontal, positive downward (deg)
};

/// Unit vector pointing along trend/plunge: (sin tr cos pl, cos tr cos pl, -sin pl).
geometry::Vec3 directionFromTrendPlunge(const LineOrientation& o);

/// Trend and plunge of the undirected line along `direction` (need not be unit length, not
/// zero): the lower-hemisphere end is taken (plunge >= 0); a horizontal line keeps the trend
/// of `direction` itself. A vertical line gets trend 0.
LineOrientation lineOrientation(const geometry::Vec3& direction);

}  // namespace rockmass::rqd
