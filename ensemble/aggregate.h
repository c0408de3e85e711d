// The aggregate of an ensemble: the distribution across realizations of what each stage
// measured (P32 per set, block volumes and their Weibull fit, RQD per ball direction and
// threshold, borehole RQD, K_s and the critical SRF), the probability that a factor is below
// the scene's target, the convergence of each mean with the number of realizations, and the
// rank correlation of the factors with each uncertain input (docs/ensemble.md).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/scene.h"

namespace rockmass::ensemble {

/// The folder of realization `index` in an ensemble's output folder: r<index>.
std::filesystem::path realizationFolder(const std::filesystem::path& out, int index);

/// The marker a realization writes last (realization.json): complete when present.
inline constexpr const char* kRealizationMarker = "realization.json";

/// Statistics of a sample (NaN entries are left out): count, mean, standard deviation,
/// percentiles (linear between order statistics, as numpy's default), and the half-width of
/// the mean's 95 % confidence interval (1.96 s / sqrt(n)).
struct Stats {
  int n = 0;
  double mean = 0.0, std = 0.0, min = 0.0, p05 = 0.0, p50 = 0.0, p95 = 0.0, max = 0.0;
  double ci95 = 0.0;
};
Stats statsOf(std::vector<double> values);
nlohmann::json toJson(const Stats& s);

/// The fraction of `values` below `target` with its binomial standard error, over the values
/// that are known. A NaN value (the search did not bracket the factor) is decided by its
/// bracket where it can be: below when its first unstable factor is at most the target, not
/// below when its last stable factor is at least the target; else it is undetermined, left
/// out and counted. `last_stable` and `first_unstable` are per value (empty: none known).
struct Probability {
  double p = 0.0;
  double standard_error = 0.0;
  int below = 0, known = 0, undetermined = 0;
};
Probability probabilityBelow(const std::vector<double>& values, double target,
                             const std::vector<double>& last_stable = {},
                             const std::vector<double>& first_unstable = {});

/// Spearman's rank correlation of x and y over the pairs where both are numbers (average
/// ranks for ties); NaN with fewer than 3 pairs or a constant variable.
double spearman(const std::vector<double>& x, const std::vector<double>& y);

/// Writes ensemble.json, ensemble_realizations.csv, ensemble_rqd_balls.csv,
/// ensemble_boreholes.csv and ensemble_convergence.csv into `out` from the complete
/// realizations 0..count-1 of `scene` (each file written whole, then renamed). Returns
/// ensemble.json's content.
nlohmann::json writeAggregate(const std::filesystem::path& out, const io::Scene& scene, int count);

}  // namespace rockmass::ensemble
