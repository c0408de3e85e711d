#include "io/rqd_output.h"

#include <algorithm>
#include <cmath>

#include "io/atomic_file.h"
#include "io/rqd_vdb.h"
#include "io/summary_json.h"
#include "rqd/line_orientation.h"

namespace rockmass::io {
namespace {

using Json = SummaryJson;

/// [x, y, z]
Json vector3(const geometry::Vec3& v) {
  return Json::array({v.x(), v.y(), v.z()});
}

/// {"rqd", "trend", "plunge"} of a directional value.
Json directional(const rqd::DirectionalRqd& value) {
  const rqd::LineOrientation o = rqd::lineOrientation(value.direction);
  return {{"rqd", value.rqd}, {"trend", o.trend}, {"plunge", o.plunge}};
}

/// {"bias", "rms", "length", "intervals"}
Json logErrorJson(const rqd::LogError& error) {
  return {{"bias", error.bias},
          {"rms", error.rms},
          {"length", error.length},
          {"intervals", error.intervals}};
}

Json ballJson(const BallReport& ball) {
  Json j;
  j["name"] = ball.name;
  j["center"] = vector3(ball.spec.center);
  j["length"] = ball.spec.length;
  j["directions"] = ball.spec.directions;
  j["radius"] = ball.radius;
  Json per_threshold = Json::array();
  for (std::size_t k = 0; k < ball.result.thresholds.size(); ++k) {
    const rqd::BallShape& shape = ball.shapes[k];
    const double t = ball.result.thresholds[k];
    Json s;
    s["threshold"] = t;
    s["file"] = ballPlyName(ball.name, t);
    s["mean"] = shape.mean;
    s["sampled_min"] = directional(shape.sampled_min);
    s["sampled_max"] = directional(shape.sampled_max);
    Json principal = Json::array();
    for (const rqd::DirectionalRqd& p : shape.principal) principal.push_back(directional(p));
    s["principal"] = principal;  // max, middle, min
    s["anisotropy"] = shape.anisotropy ? Json(*shape.anisotropy) : Json(nullptr);
    per_threshold.push_back(s);
  }
  j["thresholds"] = per_threshold;
  return j;
}

/// {"mean", "min", "max"} of the cell values of a volume (arithmetic mean over the cells).
Json cellStatistics(const std::vector<double>& values) {
  if (values.empty()) return {{"mean", nullptr}, {"min", nullptr}, {"max", nullptr}};
  double sum = 0.0;
  for (double v : values) sum += v;
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  return {{"mean", sum / static_cast<double>(values.size())}, {"min", *low}, {"max", *high}};
}

Json gridJson(const rqd::RqdVolume& volume) {
  Json j;
  j["file"] = "rqd.vdb";
  j["cells"] = volume.grid.cellCount();
  j["dims"] = volume.grid.dims;
  j["spacing"] = volume.grid.cell_size;
  j["origin"] = vector3(volume.grid.origin);
  j["scanline_length"] = volume.scanline_length;
  j["direction_count"] = volume.direction_count;
  Json per_threshold = Json::array();
  for (std::size_t k = 0; k < volume.thresholds.size(); ++k) {
    Json s;
    s["threshold"] = volume.thresholds[k];
    s["grid"] = rqdGridName(volume.thresholds[k]);
    s.update(cellStatistics(volume.mean_rqd[k]));
    per_threshold.push_back(s);
  }
  j["thresholds"] = per_threshold;
  j["p32"] = cellStatistics(volume.p32);
  return j;
}

Json boreholesJson(const BoreholeReport& report) {
  Json j;
  const bool measured = !report.measured.empty();
  const std::vector<rqd::LogError> per_hole = rqd::logErrorPerHole(
      report.simulated, report.measured, static_cast<int>(report.holes.size()));
  Json holes = Json::array();
  for (std::size_t h = 0; h < report.holes.size(); ++h) {
    const rqd::Borehole& hole = report.holes[h];
    Json entry;
    entry["id"] = hole.id;
    entry["collar"] = vector3(hole.collar);
    entry["azimuth"] = hole.azimuth;
    entry["plunge"] = hole.plunge;
    entry["length"] = hole.length;
    entry["runs"] = report.runs[h].size();
    Json whole = Json::array();
    for (std::size_t k = 0; k < report.thresholds.size(); ++k) {
      whole.push_back({{"threshold", report.thresholds[k]}, {"rqd", report.hole_rqd[h][k]}});
    }
    entry["rqd"] = whole;
    if (measured) entry["error"] = logErrorJson(per_hole[h]);
    holes.push_back(entry);
  }
  j["holes"] = holes;
  if (measured) {
    Json m = logErrorJson(rqd::logError(report.simulated, report.measured));
    m["file"] = report.measured_file;
    m["threshold"] = report.measured_threshold;
    j["measured"] = m;
  }
  return j;
}

Json calibrationJson(const CalibrationReport& report) {
  const rqd::CalibrationResult& r = report.result;
  Json j;
  j["sets"] = report.sets;
  j["range"] = {report.settings.min_multiplier, report.settings.max_multiplier};
  j["threshold"] = report.settings.threshold;
  j["tolerance"] = report.settings.tolerance;
  j["discs_at_max_multiplier"] = report.discs_at_max;
  j["multiplier"] = r.multiplier;
  j["bias"] = r.error.bias;
  j["rms"] = r.error.rms;
  j["evaluations"] = r.evaluations;
  j["bracketed"] = r.bracketed;
  j["converged"] = r.converged;
  Json steps = Json::array();
  for (const rqd::CalibrationStep& step : r.steps) {
    steps.push_back(
        {{"multiplier", step.multiplier}, {"bias", step.error.bias}, {"rms", step.error.rms}});
  }
  j["steps"] = steps;
  return j;
}

}  // namespace

std::string ballPlyName(const std::string& ball, double threshold) {
  return "rqd_ball_" + ball + "_t" + formatDouble(threshold) + ".ply";
}

std::string formatRqdBallsCsv(const std::vector<BallReport>& balls) {
  std::string out = "ball,dir_x,dir_y,dir_z,threshold,rqd\n";
  for (const BallReport& ball : balls) {
    const rqd::BallResult& r = ball.result;
    for (std::size_t d = 0; d < r.directions.size(); ++d) {
      const std::string direction = formatDouble(r.directions[d].x()) + "," +
                                    formatDouble(r.directions[d].y()) + "," +
                                    formatDouble(r.directions[d].z());
      for (std::size_t k = 0; k < r.thresholds.size(); ++k) {
        out += ball.name + "," + direction + "," + formatDouble(r.thresholds[k]) + "," +
               formatDouble(r.at(d, k)) + "\n";
      }
    }
  }
  return out;
}

std::array<unsigned char, 3> rqdColour(double rqd) {
  // ColorBrewer RdYlBu, 5 classes (Brewer, www.colorbrewer2.org), at RQD 0, 25, 50, 75, 100.
  static constexpr std::array<std::array<double, 3>, 5> kStops{
      {{215, 25, 28}, {253, 174, 97}, {255, 255, 191}, {171, 217, 233}, {44, 123, 182}}};
  const double x = std::clamp(std::isnan(rqd) ? 0.0 : rqd, 0.0, 100.0) / 25.0;
  const std::size_t i = std::min<std::size_t>(3, static_cast<std::size_t>(x));
  const double f = x - static_cast<double>(i);
  std::array<unsigned char, 3> rgb{};
  for (std::size_t c = 0; c < 3; ++c) {
    rgb[c] =
        static_cast<unsigned char>(std::lround((1.0 - f) * kStops[i][c] + f * kStops[i + 1][c]));
  }
  return rgb;
}

std::string formatBallPly(const BallReport& ball, std::size_t k,
                          const std::vector<std::array<int, 3>>& triangles) {
  const rqd::BallResult& r = ball.result;
  std::string out = "ply\nformat ascii 1.0\n";
  out += "comment rockmass RQD ball " + ball.name + ", threshold " + formatDouble(r.thresholds[k]) +
         " m, radius " + formatDouble(ball.radius) + " m at RQD 100, centre " +
         formatDouble(ball.spec.center.x()) + " " + formatDouble(ball.spec.center.y()) + " " +
         formatDouble(ball.spec.center.z()) + "\n";
  out += "comment quality = RQD (%); colour: RdYlBu, red = 0, blue = 100\n";
  out += "element vertex " + std::to_string(r.directions.size()) + "\n";
  out += "property double x\nproperty double y\nproperty double z\n";
  out += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  out += "property double quality\n";
  out += "element face " + std::to_string(triangles.size()) + "\n";
  out += "property list uchar int vertex_indices\nend_header\n";
  for (std::size_t d = 0; d < r.directions.size(); ++d) {
    const double value = r.at(d, k);
    const geometry::Vec3 p = ball.spec.center + value / 100.0 * ball.radius * r.directions[d];
    const std::array<unsigned char, 3> rgb = rqdColour(value);
    out += formatDouble(p.x()) + " " + formatDouble(p.y()) + " " + formatDouble(p.z()) + " " +
           std::to_string(rgb[0]) + " " + std::to_string(rgb[1]) + " " + std::to_string(rgb[2]) +
           " " + formatDouble(value) + "\n";
  }
  for (const std::array<int, 3>& t : triangles) {
    out += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) +
           "\n";
  }
  return out;
}

std::string formatBoreholesCsv(const BoreholeReport& report) {
  std::string out = "borehole,from,to,threshold,rqd\n";
  for (std::size_t h = 0; h < report.holes.size(); ++h) {
    for (std::size_t r = 0; r < report.runs[h].size(); ++r) {
      const std::string run = report.holes[h].id + "," + formatDouble(report.runs[h][r].from) +
                              "," + formatDouble(report.runs[h][r].to) + ",";
      for (std::size_t k = 0; k < report.thresholds.size(); ++k) {
        out += run + formatDouble(report.thresholds[k]) + "," +
               formatDouble(report.run_rqd[h][r * report.thresholds.size() + k]) + "\n";
      }
    }
  }
  return out;
}

std::string formatRqdSummary(const RunInfo& run, const RqdReport& report) {
  Json j = summaryHeader(run);
  j["discs"] = report.discs;
  j["rqd"] = {{"form", report.form},
              {"triangle_segments", report.segments},
              {"merge_distance", report.merge_distance},
              {"thresholds", report.thresholds}};
  Json balls = Json::array();
  for (const BallReport& ball : report.balls) balls.push_back(ballJson(ball));
  j["balls"] = balls;
  if (report.boreholes) j["boreholes"] = boreholesJson(*report.boreholes);
  if (report.calibration) j["calibration"] = calibrationJson(*report.calibration);
  if (report.grid) j["grid"] = gridJson(*report.grid);
  appendTimings(j, run.timings);
  return j.dump(2) + "\n";
}

}  // namespace rockmass::io
