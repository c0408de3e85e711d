#pragma once
/// Expected RQD of a Poisson field of fractures along a finite scanline: the reference the
/// simulated RQD balls are checked against.
///
/// Along a line, the crossings of a Poisson field of planar discs form a Poisson process of
/// rate lambda(s) = sum over sets of P32 E|n . s| (P32: disc area per volume, one face
/// counted; n the disc normal; s the unit direction of the line). On a scanline of length L
/// the intact pieces are the gaps between crossings, clipped at both ends, and for t <= L
///   E[RQD_t] = (100 / L) [ int_t^L lambda^2 s (L - s) e^(-lambda s) ds      (interior pieces)
///                        + 2 int_t^L lambda s e^(-lambda s) ds              (the two end pieces)
///                        + L e^(-lambda L) ]                                 (no crossing at all)
/// (Priest & Hudson 1976 for the interior-piece density; the end pieces and the empty line
/// follow from the same Poisson process). As L grows it tends to 100 (1 + lambda t)
/// e^(-lambda t), the infinite-scanline formula, which is badly biased when t nears L.
#include <span>

#include "geometry/vec.h"

namespace rockmass::rqd {

/// One set of parallel planar fractures: its unit normal and its intensity.
struct PlaneSetIntensity {
  geometry::Vec3 normal = geometry::Vec3::UnitZ();  ///< unit normal of the set's discs
  double p32 = 0.0;  ///< disc area per unit volume, one face counted (m2/m3)
};

/// Crossings per metre of a line along unit `direction`: sum of p32 |n . direction| (1/m).
double lineFrequency(std::span<const PlaneSetIntensity> sets, const geometry::Vec3& direction);

/// Expected RQD(t) in percent on a scanline of `length` L (m, > 0) through a Poisson field
/// with `frequency` lambda crossings per metre (>= 0), for `threshold` t (m, >= 0); 0 for
/// t > L. The integral is evaluated by adaptive Simpson quadrature to an absolute error
/// below 1e-9 RQD points. Throws std::invalid_argument for arguments out of range.
double finiteScanlineRqd(double frequency, double threshold, double length);

}  // namespace rockmass::rqd
