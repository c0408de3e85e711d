#include "rqd/scanline_rqd.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rockmass::rqd {
namespace {

void requireNonNegative(double value, const char* what) {
  if (!(std::isfinite(value) && value >= 0.0)) {
    throw std::invalid_argument(std::string(what) + " must be finite and >= 0, got " +
                                std::to_string(value));
  }
}

void requireValidScanline(std::span<const double> hits, double length, double merge_distance) {
  if (!(std::isfinite(length) && length > 0.0)) {
    throw std::invalid_argument("scanline length must be finite and > 0 m, got " +
                                std::to_string(length));
  }
  requireNonNegative(merge_distance, "merge distance (m)");
  for (std::size_t i = 0; i < hits.size(); ++i) {
    if (!(hits[i] >= 0.0 && hits[i] <= length)) {
      throw std::invalid_argument("hit #" + std::to_string(i) + " at " + std::to_string(hits[i]) +
                                  " m lies outside the scanline [0, " + std::to_string(length) +
                                  "] m");
    }
    if (i > 0 && hits[i] < hits[i - 1]) {
      throw std::invalid_argument("hits must be sorted along the scanline: hit #" +
                                  std::to_string(i) + " at " + std::to_string(hits[i]) +
                                  " m comes before hit #" + std::to_string(i - 1) + " at " +
                                  std::to_string(hits[i - 1]) + " m");
    }
  }
}

}  // namespace

std::vector<double> intactPieces(std::span<const double> hits, double length,
                                 double merge_distance) {
  requireValidScanline(hits, length, merge_distance);
  std::vector<double> pieces;
  pieces.reserve(hits.size() + 1);
  double piece_start = 0.0;
  bool have_kept_hit = false;
  for (double hit : hits) {
    if (have_kept_hit && hit - piece_start <= merge_distance) continue;
    if (hit > piece_start) pieces.push_back(hit - piece_start);
    piece_start = hit;
    have_kept_hit = true;
  }
  if (length > piece_start) pieces.push_back(length - piece_start);
  return pieces;
}

std::vector<double> rqd(std::span<const double> hits, double length,
                        std::span<const double> thresholds, double merge_distance) {
  for (double t : thresholds) requireNonNegative(t, "RQD threshold (m)");
  const std::vector<double> pieces = intactPieces(hits, length, merge_distance);
  std::vector<double> result;
  result.reserve(thresholds.size());
  for (double t : thresholds) {
    double intact_length = 0.0;
    for (double piece : pieces) {
      if (piece >= t) intact_length += piece;
    }
    // The pieces sum to the length up to rounding: keep RQD within [0, 100]; one intact
    // piece gives exactly 100.
    result.push_back(std::min(100.0, 100.0 * (intact_length / length)));
  }
  return result;
}

double priestHudsonRqd(double frequency, double threshold) {
  requireNonNegative(frequency, "fracture frequency (1/m)");
  requireNonNegative(threshold, "RQD threshold (m)");
  const double x = frequency * threshold;
  return 100.0 * (1.0 + x) * std::exp(-x);
}

}  // namespace rockmass::rqd
