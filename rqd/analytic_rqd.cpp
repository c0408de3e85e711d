#include "rqd/analytic_rqd.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

namespace rockmass::rqd {
namespace {

/// Simpson's rule on [a, b] from the end and middle values.
double simpson(double a, double b, double fa, double fm, double fb) {
  return (b - a) / 6.0 * (fa + 4.0 * fm + fb);
}

/// Adaptive Simpson (Lyness 1969): splits until the two halves agree with the whole to
/// 15 times the tolerance, then adds Richardson's correction.
double adaptiveSimpson(const std::function<double(double)>& f, double a, double b, double fa,
                       double fm, double fb, double whole, double tolerance, int depth) {
  const double m = 0.5 * (a + b);
  const double lm = 0.5 * (a + m);
  const double rm = 0.5 * (m + b);
  const double flm = f(lm);
  const double frm = f(rm);
  const double left = simpson(a, m, fa, flm, fm);
  const double right = simpson(m, b, fm, frm, fb);
  const double delta = left + right - whole;
  if (depth <= 0 || std::abs(delta) <= 15.0 * tolerance) return left + right + delta / 15.0;
  return adaptiveSimpson(f, a, m, fa, flm, fm, left, 0.5 * tolerance, depth - 1) +
         adaptiveSimpson(f, m, b, fm, frm, fb, right, 0.5 * tolerance, depth - 1);
}

}  // namespace

double lineFrequency(std::span<const PlaneSetIntensity> sets, const geometry::Vec3& direction) {
  double frequency = 0.0;
  for (const PlaneSetIntensity& set : sets) {
    frequency += set.p32 * std::abs(set.normal.dot(direction));
  }
  return frequency;
}

double finiteScanlineRqd(double frequency, double threshold, double length) {
  if (!(std::isfinite(frequency) && frequency >= 0.0 && std::isfinite(threshold) &&
        threshold >= 0.0 && std::isfinite(length) && length > 0.0)) {
    throw std::invalid_argument("finiteScanlineRqd: need frequency >= 0, threshold >= 0 and " +
                                std::string("length > 0, got ") + std::to_string(frequency) + ", " +
                                std::to_string(threshold) + ", " + std::to_string(length));
  }
  if (threshold > length) return 0.0;
  const double lambda = frequency;
  const double L = length;
  // Interior and end pieces together: lambda s e^(-lambda s) (lambda (L - s) + 2).
  const std::function<double(double)> density = [&](double s) {
    return lambda * s * std::exp(-lambda * s) * (lambda * (L - s) + 2.0);
  };
  // The density decays like e^(-lambda s): integrate in chunks of width 1/lambda, so no
  // Simpson panel can step over the peak, and stop 60/lambda past t, where what is left is
  // below e^-60 of the total.
  double integral = 0.0;
  if (lambda > 0.0 && threshold < L) {
    const double end = std::min(L, threshold + 60.0 / lambda);
    const int chunks = static_cast<int>(std::ceil((end - threshold) * lambda));
    // 1e-9 RQD points = 1e-11 L metres of intact length, shared among the chunks.
    const double tolerance = 1e-11 * L / chunks;
    for (int k = 0; k < chunks; ++k) {
      const double a = threshold + (end - threshold) * k / chunks;
      const double b = threshold + (end - threshold) * (k + 1) / chunks;
      const double fa = density(a);
      const double fm = density(0.5 * (a + b));
      const double fb = density(b);
      integral += adaptiveSimpson(density, a, b, fa, fm, fb, simpson(a, b, fa, fm, fb), tolerance,
                                  /*depth=*/40);
    }
  }
  return 100.0 / L * (integral + L * std::exp(-lambda * L));
}

}  // namespace rockmass::rqd
