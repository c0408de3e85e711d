#pragma once
/// Univariate distributions of joint-set parameters (spacing, trace length, angles).
///
/// Every family is given by the mean and standard deviation of the variable itself (also
/// for the lognormal). Optional [min, max] truncate it: samples are drawn by rejection.
#include <optional>
#include <string>

#include "geometry/random.h"

namespace rockmass::geometry {

/// The families a scene can name.
enum class DistributionKind { Normal, Lognormal, Uniform, Exponential, Constant };

/// Name of a family as written in scenes ("normal", "lognormal", ...).
const char* distributionName(DistributionKind kind);

/// What a scene says about one variable.
struct DistributionSpec {
  DistributionKind kind = DistributionKind::Constant;  ///< family
  double mean = 0.0;                                   ///< mean of the variable (its unit)
  double std = 0.0;           ///< standard deviation of the variable (its unit)
  std::optional<double> min;  ///< lower truncation bound, if any
  std::optional<double> max;  ///< upper truncation bound, if any
};

/// A sampler with its exact CDF and PDF (of the truncated variable).
class Distribution {
 public:
  /// Smallest probability mass a truncation window may hold. Below it, rejection sampling
  /// would be hopeless and the spec almost surely a mistake.
  static constexpr double kMinWindowMass = 1e-3;

  /// Validates the spec. Throws std::invalid_argument with a message that says what is
  /// wrong and what is expected (the caller adds the file location).
  explicit Distribution(const DistributionSpec& spec);

  /// One sample, inside [min, max] when truncated.
  double sample(Rng& rng) const;
  /// Cumulative distribution of the truncated variable.
  double cdf(double x) const;
  /// Density of the truncated variable (0 for a constant).
  double pdf(double x) const;
  /// Probability mass of the untruncated family inside [min, max] (1 without truncation).
  double windowMass() const { return mass_; }
  /// Lower and upper end of the support after truncation.
  double lower() const { return lower_; }
  double upper() const { return upper_; }
  /// The spec it was built from.
  const DistributionSpec& spec() const { return spec_; }
  /// Short description, e.g. "lognormal(mean=0.6, std=0.79) truncated to [0.1, 5]".
  std::string describe() const;

 private:
  double sampleUntruncated(Rng& rng) const;
  double cdfUntruncated(double x) const;
  double pdfUntruncated(double x) const;

  DistributionSpec spec_;
  double p1_ = 0.0;  ///< family parameter: mu (normal, log-space for lognormal), a, or rate
  double p2_ = 0.0;  ///< family parameter: sigma, or b
  double lower_ = 0.0;
  double upper_ = 0.0;
  double cdf_lower_ = 0.0;
  double mass_ = 1.0;
};

}  // namespace rockmass::geometry
