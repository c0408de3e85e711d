#pragma once
/// Fisher (von Mises-Fisher on the sphere) orientations: sampling and estimation.
#include <span>

#include "geometry/random.h"
#include "geometry/vec.h"

namespace rockmass::geometry {

/// A unit vector drawn from the Fisher distribution with mean direction `mean` (unit) and
/// concentration kappa > 0, by Wood's (1994) inversion for the sphere, written in a form
/// that stays exact for kappa up to 1e4 and beyond (no exp(kappa) overflow).
Vec3 sampleFisher(const Vec3& mean, double kappa, Rng& rng);

/// Estimate of a Fisher distribution from a sample of axes (plane normals: the sign of each
/// vector is irrelevant; they are flipped onto the hemisphere of the principal axis).
struct FisherEstimate {
  Vec3 mean = Vec3::UnitZ();  ///< mean direction (unit)
  double resultant = 0.0;     ///< mean resultant length R/N in [0, 1]
  double kappa = 0.0;         ///< (N - 1) / (N - R) (Fisher 1953; infinite for identical axes)
};
FisherEstimate estimateFisher(std::span<const Vec3> axes);

/// An orthonormal pair (u, v) perpendicular to unit vector n, chosen deterministically.
void orthonormalBasis(const Vec3& n, Vec3& u, Vec3& v);

}  // namespace rockmass::geometry
