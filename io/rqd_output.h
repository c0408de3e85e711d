#pragma once
/// Files of the `rqd` stage: rqd_balls.csv, rqd_ball_<name>_t<T>.ply, boreholes.csv and
/// the summary.json of the run.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "io/summary.h"
#include "rqd/borehole.h"
#include "rqd/calibration.h"
#include "rqd/rqd_ball.h"
#include "rqd/rqd_volume.h"

namespace rockmass::io {

/// One evaluated RQD ball.
struct BallReport {
  std::string name;                    ///< ball name
  rqd::BallSpec spec;                  ///< centre, length, direction count
  double radius = 0.0;                 ///< surface radius at RQD 100 (m)
  rqd::BallResult result;              ///< RQD per direction and threshold
  std::vector<rqd::BallShape> shapes;  ///< shape per threshold
};

/// Simulated logs of the virtual boreholes, and their comparison with a measured log.
struct BoreholeReport {
  std::vector<rqd::Borehole> holes;                   ///< the holes
  std::vector<double> thresholds;                     ///< thresholds (m)
  std::vector<std::vector<rqd::DepthInterval>> runs;  ///< core runs per hole
  std::vector<std::vector<double>> run_rqd;           ///< per hole, [run * thresholds + k] (%)
  std::vector<std::vector<double>> hole_rqd;  ///< per hole, whole-hole RQD per threshold (%)
  std::vector<rqd::LoggedInterval> measured;  ///< measured intervals (empty: no log)
  std::string measured_file;                  ///< as given in the scene
  double measured_threshold = 0.1;            ///< threshold of the measured RQD (m)
  std::vector<double> simulated;              ///< simulated RQD over each measured interval
};

/// Outcome of the intensity calibration.
struct CalibrationReport {
  std::vector<std::string> sets;      ///< joint sets of the group
  rqd::CalibrationSettings settings;  ///< bracket, tolerance, threshold
  rqd::CalibrationResult result;      ///< multiplier, error, evaluations
  std::size_t discs_at_max = 0;       ///< discs of the network at the largest multiplier
};

/// Everything summary.json says about an rqd run.
struct RqdReport {
  std::size_t discs = 0;                         ///< discs in the ray-casting scene
  std::string form;                              ///< "exact" or "triangulated"
  int segments = 24;                             ///< fan segments (triangulated form)
  double merge_distance = 1e-3;                  ///< m
  std::vector<double> thresholds;                ///< m
  std::vector<BallReport> balls;                 ///< balls
  std::optional<BoreholeReport> boreholes;       ///< boreholes, if any
  std::optional<CalibrationReport> calibration;  ///< calibration, if it ran
  std::optional<rqd::RqdVolume> grid;            ///< RQD/P32 volume (rqd.vdb), if computed
};

/// File name of the surface of `ball` for `threshold`: rqd_ball_<name>_t<T>.ply, T written
/// as formatDouble does (0.1 -> "0.1", 1 -> "1").
std::string ballPlyName(const std::string& ball, double threshold);

/// rqd_balls.csv: `ball,dir_x,dir_y,dir_z,threshold,rqd`, balls in order, then directions,
/// then thresholds.
std::string formatRqdBallsCsv(const std::vector<BallReport>& balls);

/// The ball surface for threshold index `k` as ASCII PLY: vertex i at centre + RQD_i / 100 *
/// radius * d_i, coloured by RQD (ColorBrewer RdYlBu: red = 0, yellow = 50, blue = 100) and
/// with RQD (%) as the vertex `quality`; faces `triangles` (rqd::sphereTriangles).
std::string formatBallPly(const BallReport& ball, std::size_t k,
                          const std::vector<std::array<int, 3>>& triangles);

/// The RdYlBu colour of an RQD value (%, clamped to [0, 100]), as 8-bit RGB.
std::array<unsigned char, 3> rqdColour(double rqd);

/// boreholes.csv: `borehole,from,to,threshold,rqd`, holes in file order, then runs, then
/// thresholds.
std::string formatBoreholesCsv(const BoreholeReport& report);

/// summary.json of the rqd command. With a grid: "grid" {file, cells, dims, spacing, origin,
/// scanline_length, direction_count, "thresholds" [{threshold, grid, mean, min, max}] (RQD,
/// percent, over the cells) and "p32" {mean, min, max} (m2/m3)}.
std::string formatRqdSummary(const RunInfo& run, const RqdReport& report);

}  // namespace rockmass::io
