#pragma once
/// Calibration of the fracture intensity against measured borehole logs (the paper's
/// "calibration of the borehole", section 2.2.3).
///
/// One multiplier m scales the intensity (P32, and so P10) of a group of joint sets; the
/// other fractures stay as they are. We look for the m at which the simulated RQD of the
/// measured intervals has no bias against the measured RQD.
///
/// Common random numbers: the network is generated once, at the largest multiplier m_max,
/// and each disc of the group gets a uniform variate u (thinningUniform, fixed by the seed
/// and the disc id). At multiplier m the disc exists when u m_max < m. Independent thinning
/// of a Poisson process with probability m / m_max is a Poisson process of m / m_max times
/// the intensity, so every m sees a network with the right statistics, and all of them are
/// nested: raising m only adds discs. A disc added can only split an intact piece, so the
/// simulated RQD(t) never increases with m: the bias is a monotone step function of m,
/// whose steps (one per disc that enters and crosses a hole) are small, instead of the
/// noisy curve that a fresh network per m would give. The holes are cast once, against the
/// m_max network; an evaluation only filters the recorded crossings, so it costs
/// microseconds. The root is found by the Illinois variant of regula falsi (a secant step
/// kept inside a bracket, Dowell & Jarratt 1971), which converges like the secant method on
/// a smooth curve and cannot leave the bracket on a step function.
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/dfn_spec.h"
#include "geometry/fracture_network.h"
#include "rqd/borehole.h"
#include "rqd/embree_scene.h"

namespace rockmass::rqd {

/// The thinning variate of disc `disc_id` under `seed`: uniform in (0, 1), independent
/// between discs (SplitMix64 of the seed and the id; Steele, Lea & Flood 2014).
double thinningUniform(std::uint64_t seed, std::int64_t disc_id);

/// `spec` with the intensity of the joint sets listed in `sets` (indices into
/// spec.joint_sets) multiplied by `factor` (> 0): p32 times factor, or the spacing
/// distribution divided by it (its mean sets P10). Throws std::invalid_argument for a bad
/// index or factor.
geometry::DfnSpec scaleIntensity(geometry::DfnSpec spec, std::span<const int> sets, double factor);

/// A hole's crossings with the network at the largest multiplier, each with the multiplier
/// from which its disc exists.
struct ThinnedHole {
  double length = 0.0;        ///< hole length (m)
  std::vector<double> hits;   ///< crossings (m from the collar), sorted
  std::vector<double> birth;  ///< disc exists for multipliers m > birth (-1: outside the group)
};

/// Casts every hole against `network` (generated at `max_multiplier`) and records the birth
/// multiplier u * max_multiplier of each crossing whose disc belongs to one of `sets`
/// (network set indices), with u = thinningUniform(seed, disc id).
std::vector<ThinnedHole> thinnedHoles(const ScanlineScene& scene,
                                      const geometry::FractureNetwork& network,
                                      std::span<const Borehole> holes, std::span<const int> sets,
                                      std::uint64_t seed, double max_multiplier);

/// The crossings of `hole` at multiplier m (those with birth < m).
std::vector<double> hitsAt(const ThinnedHole& hole, double multiplier);

/// Simulated RQD (%) at threshold `threshold` (m) over each measured interval, at
/// multiplier m.
std::vector<double> simulateIntervals(std::span<const ThinnedHole> holes,
                                      std::span<const LoggedInterval> measured, double multiplier,
                                      double threshold,
                                      double merge_distance = kDefaultMergeDistance);

/// How to search.
struct CalibrationSettings {
  double min_multiplier = 0.25;  ///< lower end of the bracket (> 0)
  double max_multiplier = 4.0;   ///< upper end, the multiplier the network was generated at
  double threshold = 0.1;        ///< RQD threshold of the measured logs (m)
  double tolerance = 0.5;        ///< stop when |bias| <= this (RQD points)
  int max_evaluations = 40;      ///< stop after this many evaluations
  double merge_distance = kDefaultMergeDistance;  ///< hits closer than this are one (m)
};

/// One evaluation of the search.
struct CalibrationStep {
  double multiplier = 0.0;  ///< m
  LogError error;           ///< error of the simulated log at m
};

/// Outcome of the search.
struct CalibrationResult {
  double multiplier = 1.0;             ///< best multiplier found (smallest |bias| evaluated)
  LogError error;                      ///< error at that multiplier
  int evaluations = 0;                 ///< number of evaluations of the simulated log
  bool bracketed = false;              ///< the bias changes sign over the bracket
  bool converged = false;              ///< |bias| <= tolerance, or the bracket shrank to 1e-6 m_max
  std::vector<CalibrationStep> steps;  ///< every evaluation, in order
};

/// Finds the multiplier whose simulated log has no bias against `measured`. When the bias
/// has the same sign at both ends of the bracket, the better end is returned with
/// bracketed = false. Throws std::invalid_argument for an empty log or a bad bracket.
CalibrationResult calibrateMultiplier(std::span<const ThinnedHole> holes,
                                      std::span<const LoggedInterval> measured,
                                      const CalibrationSettings& settings);

}  // namespace rockmass::rqd
