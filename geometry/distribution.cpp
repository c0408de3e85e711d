#include "geometry/distribution.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>

#include "geometry/orientation.h"

namespace rockmass::geometry {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Standard normal CDF, accurate in the lower tail (erfc, not 1 + erf).
double standardNormalCdf(double z) {
  return 0.5 * std::erfc(-z / std::sqrt(2.0));
}

/// Standard normal density.
double standardNormalPdf(double z) {
  return std::exp(-0.5 * z * z) / std::sqrt(2.0 * kPi);
}

/// "2.5" for 2.5: numbers in messages, 6 significant digits.
std::string str(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

/// Throws unless value > 0 (and finite).
void requirePositive(double value, const char* what, DistributionKind kind) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw std::invalid_argument(std::string("expected ") + what + " > 0 for a " +
                                distributionName(kind) + " distribution, got " + str(value));
  }
}

}  // namespace

const char* distributionName(DistributionKind kind) {
  switch (kind) {
    case DistributionKind::Normal:
      return "normal";
    case DistributionKind::Lognormal:
      return "lognormal";
    case DistributionKind::Uniform:
      return "uniform";
    case DistributionKind::Exponential:
      return "exponential";
    case DistributionKind::Constant:
      return "constant";
  }
  return "unknown";
}

Distribution::Distribution(const DistributionSpec& spec) : spec_(spec) {
  if (!std::isfinite(spec.mean)) throw std::invalid_argument("expected a finite mean");
  if (spec.min && spec.max && *spec.min > *spec.max) {
    throw std::invalid_argument("min (" + str(*spec.min) + ") is greater than max (" +
                                str(*spec.max) + ")");
  }
  double support_lower = -kInf;
  double support_upper = kInf;
  switch (spec.kind) {
    case DistributionKind::Normal:
      requirePositive(spec.std, "std", spec.kind);
      p1_ = spec.mean;
      p2_ = spec.std;
      break;
    case DistributionKind::Lognormal: {
      // Mean m and std s of the variable itself: sigma^2 = ln(1 + (s/m)^2),
      // mu = ln(m) - sigma^2 / 2 (moments of the lognormal distribution).
      requirePositive(spec.mean, "mean", spec.kind);
      requirePositive(spec.std, "std", spec.kind);
      const double variance_log = std::log1p((spec.std / spec.mean) * (spec.std / spec.mean));
      p2_ = std::sqrt(variance_log);
      p1_ = std::log(spec.mean) - 0.5 * variance_log;
      support_lower = 0.0;
      break;
    }
    case DistributionKind::Uniform:
      // A uniform on [a, b] has mean (a + b) / 2 and std (b - a) / sqrt(12).
      requirePositive(spec.std, "std", spec.kind);
      p1_ = spec.mean - std::sqrt(3.0) * spec.std;
      p2_ = spec.mean + std::sqrt(3.0) * spec.std;
      support_lower = p1_;
      support_upper = p2_;
      break;
    case DistributionKind::Exponential:
      requirePositive(spec.mean, "mean", spec.kind);
      p1_ = 1.0 / spec.mean;
      support_lower = 0.0;
      break;
    case DistributionKind::Constant:
      support_lower = support_upper = spec.mean;
      break;
  }
  lower_ = spec.min ? std::max(support_lower, *spec.min) : support_lower;
  upper_ = spec.max ? std::min(support_upper, *spec.max) : support_upper;
  if (spec.kind == DistributionKind::Constant) {
    mass_ = (lower_ <= upper_) ? 1.0 : 0.0;
  } else {
    cdf_lower_ = cdfUntruncated(lower_);
    mass_ = lower_ <= upper_ ? cdfUntruncated(upper_) - cdf_lower_ : 0.0;
  }
  if (!(mass_ >= kMinWindowMass)) {
    std::ostringstream message;
    message << "the truncation window [" << (spec.min ? str(*spec.min) : "-inf") << ", "
            << (spec.max ? str(*spec.max) : "inf") << "] holds only " << mass_
            << " of the probability mass of " << describe() << " (at least " << kMinWindowMass
            << " is needed); check min, max, mean and std";
    throw std::invalid_argument(message.str());
  }
}

double Distribution::sampleUntruncated(Rng& rng) const {
  switch (spec_.kind) {
    case DistributionKind::Normal:
      return std::normal_distribution<double>(p1_, p2_)(rng);
    case DistributionKind::Lognormal:
      return std::lognormal_distribution<double>(p1_, p2_)(rng);
    case DistributionKind::Uniform:
      return p1_ + (p2_ - p1_) * uniformOpen01(rng);
    case DistributionKind::Exponential:
      return -std::log(uniformOpen01(rng)) / p1_;
    case DistributionKind::Constant:
      return spec_.mean;
  }
  return spec_.mean;
}

double Distribution::sample(Rng& rng) const {
  // Rejection: the window holds at least kMinWindowMass, so the expected number of tries
  // is at most 1 / kMinWindowMass. The cap only guards against an impossible state.
  constexpr long kMaxTries = 100'000'000;
  for (long tries = 0; tries < kMaxTries; ++tries) {
    const double x = sampleUntruncated(rng);
    if (x >= lower_ && x <= upper_) return x;
  }
  throw std::runtime_error("rejection sampling of " + describe() + " did not terminate");
}

double Distribution::cdfUntruncated(double x) const {
  switch (spec_.kind) {
    case DistributionKind::Normal:
      return standardNormalCdf((x - p1_) / p2_);
    case DistributionKind::Lognormal:
      return x <= 0.0 ? 0.0 : standardNormalCdf((std::log(x) - p1_) / p2_);
    case DistributionKind::Uniform:
      return x <= p1_ ? 0.0 : (x >= p2_ ? 1.0 : (x - p1_) / (p2_ - p1_));
    case DistributionKind::Exponential:
      return x <= 0.0 ? 0.0 : -std::expm1(-p1_ * x);
    case DistributionKind::Constant:
      return x >= spec_.mean ? 1.0 : 0.0;
  }
  return 0.0;
}

double Distribution::pdfUntruncated(double x) const {
  switch (spec_.kind) {
    case DistributionKind::Normal:
      return standardNormalPdf((x - p1_) / p2_) / p2_;
    case DistributionKind::Lognormal:
      return x <= 0.0 ? 0.0 : standardNormalPdf((std::log(x) - p1_) / p2_) / (p2_ * x);
    case DistributionKind::Uniform:
      return (x < p1_ || x > p2_) ? 0.0 : 1.0 / (p2_ - p1_);
    case DistributionKind::Exponential:
      return x < 0.0 ? 0.0 : p1_ * std::exp(-p1_ * x);
    case DistributionKind::Constant:
      return 0.0;
  }
  return 0.0;
}

double Distribution::cdf(double x) const {
  if (x < lower_) return 0.0;
  if (x >= upper_) return 1.0;
  if (spec_.kind == DistributionKind::Constant) return 1.0;
  return std::clamp((cdfUntruncated(x) - cdf_lower_) / mass_, 0.0, 1.0);
}

double Distribution::pdf(double x) const {
  if (x < lower_ || x > upper_) return 0.0;
  return pdfUntruncated(x) / mass_;
}

std::string Distribution::describe() const {
  std::ostringstream out;
  out << distributionName(spec_.kind) << "(mean=" << spec_.mean;
  if (spec_.kind != DistributionKind::Constant && spec_.kind != DistributionKind::Exponential) {
    out << ", std=" << spec_.std;
  }
  out << ")";
  if (spec_.min || spec_.max) {
    out << " truncated to [" << (spec_.min ? str(*spec_.min) : "-inf") << ", "
        << (spec_.max ? str(*spec_.max) : "inf") << "]";
  }
  return out.str();
}

}  // namespace rockmass::geometry
