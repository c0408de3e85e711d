#pragma once
/// Virtual boreholes: RQD per core run along a straight hole, and the comparison of a
/// simulated log with a measured one.
///
/// Intact core pieces are measured between natural fractures along the whole hole, not cut
/// at run boundaries: a run boundary is a drilling break, which core loggers do not count
/// as a fracture (Deere & Deere 1988, "The rock quality designation (RQD) index in
/// practice", ASTM STP 984). A piece of length >= t credits every run it passes through with
/// the part of it that lies in that run, so RQD_run(t) = 100 (sum of those parts) / run
/// length. Over the whole hole this is the scanline RQD; with thresholds longer than a run
/// (1-10 m against 3 m runs) it still tells sound rock from broken rock.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "geometry/vec.h"
#include "rqd/embree_scene.h"
#include "rqd/scanline_rqd.h"

namespace rockmass::rqd {

/// A straight borehole.
struct Borehole {
  std::string id;                                  ///< hole name (text)
  geometry::Vec3 collar = geometry::Vec3::Zero();  ///< start of the hole (m)
  double azimuth = 0.0;  ///< trend of the hole, clockwise from North (deg)
  double plunge = 90.0;  ///< angle below the horizontal, positive downward (deg); 90 = down
  double length = 0.0;   ///< length along the hole (m, > 0)

  /// Unit vector from the collar down the hole.
  geometry::Vec3 direction() const;
  /// The bottom of the hole (m).
  geometry::Vec3 end() const { return collar + length * direction(); }
};

/// A depth interval along a hole, [from, to] (m from the collar).
struct DepthInterval {
  double from = 0.0;  ///< m
  double to = 0.0;    ///< m
};

/// Core runs of a hole: [k r, min((k + 1) r, length)] for k = 0, 1, ... while k r < length.
/// They partition [0, length] exactly: each run ends where the next starts (bit for bit),
/// the last ends at `length`, and no run is empty. Throws std::invalid_argument unless
/// length > 0 and run_length > 0, or for more than 10^7 runs.
std::vector<DepthInterval> coreRuns(double length, double run_length);

/// RQD (%) of each of `intervals` for every threshold (entry [i * thresholds.size() + k]),
/// on a hole of `hole_length` (m) crossed by fractures at `hits` (m from the collar,
/// sorted, in [0, hole_length]); see the file comment for how pieces are credited. Hits
/// within `merge_distance` (m) are one fracture. Throws std::invalid_argument for an
/// interval outside the hole or of no length, a negative threshold, and as intactPieces().
std::vector<double> intervalsRqd(std::span<const double> hits, double hole_length,
                                 std::span<const DepthInterval> intervals,
                                 std::span<const double> thresholds,
                                 double merge_distance = kDefaultMergeDistance);

/// Distances (m from the collar) at which `hole` crosses the fractures of `scene`.
std::vector<double> boreholeHits(const ScanlineScene& scene, const Borehole& hole);

/// A measured (or simulated) RQD value over a depth interval of a hole.
struct LoggedInterval {
  int hole = 0;            ///< index of the hole
  DepthInterval interval;  ///< depths (m)
  double rqd = 0.0;        ///< RQD (%)
};

/// Error of a simulated log against a measured one, over the measured intervals, each
/// weighted by its length: bias = sum w (sim - meas) / sum w, rms = sqrt(sum w (sim -
/// meas)^2 / sum w). A positive bias means the model's rock is better than the field's.
struct LogError {
  double bias = 0.0;    ///< length-weighted mean of simulated - measured (RQD points)
  double rms = 0.0;     ///< length-weighted root mean square of the difference (points)
  double length = 0.0;  ///< total measured length (m)
  int intervals = 0;    ///< number of measured intervals
};

/// The error of `simulated` against `measured` (same size, same order), overall.
LogError logError(std::span<const double> simulated, std::span<const LoggedInterval> measured);

/// The same, for each hole of `hole_count` (holes without measured intervals get zeros).
std::vector<LogError> logErrorPerHole(std::span<const double> simulated,
                                      std::span<const LoggedInterval> measured, int hole_count);

}  // namespace rockmass::rqd
