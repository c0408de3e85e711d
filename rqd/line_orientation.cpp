#include "rqd/line_orientation.h"

#include <cmath>

#include "geometry/orientation.h"

namespace rockmass::rqd {

using geometry::Vec3;

Vec3 directionFromTrendPlunge(const LineOrientation& o) {
  const double trend = geometry::radians(o.trend);
  const double plunge = geometry::radians(o.plunge);
  return {std::sin(trend) * std::cos(plunge), std::cos(trend) * std::cos(plunge),
          -std::sin(plunge)};
}

LineOrientation lineOrientation(const Vec3& direction) {
  Vec3 d = direction.normalized();
  if (d.z() > 0.0) d = -d;
  const double horizontal = std::hypot(d.x(), d.y());
  LineOrientation o;
  o.plunge = geometry::degrees(std::atan2(-d.z(), horizontal));
  o.trend = horizontal > 0.0 ? geometry::azimuthDegrees(d) : 0.0;
  return o;
}

}  // namespace rockmass::rqd
