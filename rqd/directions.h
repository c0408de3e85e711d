// Sets of scanline directions: the Fibonacci sphere used by RQD balls and RQD volumes.
#pragma once

#include <vector>

#include "geometry/vec.h"

namespace rockmass::rqd {

/// `count` (>= 1) unit vectors spread almost evenly over the whole sphere by the Fibonacci
/// (golden-angle) spiral: z_i = 1 - (2i + 1)/count, longitude i * pi (3 - sqrt 5). Each
/// direction stands for an equal share 4 pi / count of solid angle. Deterministic: the same
/// count always gives the same vectors. Throws std::invalid_argument for count < 1.
/// Reference: Gonzalez, A. (2010), "Measurement of areas on a sphere using Fibonacci and
/// latitude-longitude lattices", Math. Geosci. 42, 49-64.
std::vector<geometry::Vec3> fibonacciSphere(int count);

}  // namespace rockmass::rqd

namespace rockmass::rqd {

/// `count` (>= 1) scanline axes spread evenly over the directions of space, for measures
/// that do not depend on a scanline's sense (a segment centred on a point and its reverse
/// give the same RQD): the upper half (z > 0) of fibonacciSphere(2 count), which is exactly
/// its first `count` points. Each axis stands for 2 pi / count of solid angle on the
/// hemisphere. Throws std::invalid_argument for count < 1.
std::vector<geometry::Vec3> scanlineAxes(int count);

}  // namespace rockmass::rqd
