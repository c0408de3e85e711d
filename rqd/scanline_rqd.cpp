#include "rqd/scanline_rqd.h"

#include <algorithm>
#include <cmath>
#include <limits>
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

/// requireValidScanline, with a branch-free pass first: scanlines are checked once per call
/// of rqd() (millions of times in a volume), and the detailed message is built only when
/// something is wrong.
void requireValidScanlineFast(std::span<const double> hits, double length, double merge_distance) {
  bool ok = length > 0.0 && length <= std::numeric_limits<double>::max() && merge_distance >= 0.0 &&
            merge_distance <= std::numeric_limits<double>::max();
  double previous = 0.0;
  for (double hit : hits) {
    ok &= (hit >= previous) & (hit <= length);
    previous = hit;
  }
  if (!ok) [[unlikely]]
    requireValidScanline(hits, length, merge_distance);
}

/// Throws std::invalid_argument unless every threshold is finite and >= 0.
void requireValidThresholds(std::span<const double> thresholds) {
  bool ok = true;
  for (double t : thresholds) ok &= (t >= 0.0) & (t <= std::numeric_limits<double>::max());
  if (!ok) [[unlikely]] {
    for (double t : thresholds) requireNonNegative(t, "RQD threshold (m)");
  }
}

/// Calls `piece(length)` for each intact piece (> 0), in order, between the merged `hits`;
/// the scanline must be valid (requireValidScanline).
template <typename PieceFunction>
void forEachPiece(std::span<const double> hits, double length, double merge_distance,
                  PieceFunction&& piece) {
  double piece_start = 0.0;
  bool have_kept_hit = false;
  for (double hit : hits) {
    if (have_kept_hit && hit - piece_start <= merge_distance) continue;
    if (hit > piece_start) piece(hit - piece_start);
    piece_start = hit;
    have_kept_hit = true;
  }
  if (length > piece_start) piece(length - piece_start);
}

}  // namespace

std::vector<double> intactPieces(std::span<const double> hits, double length,
                                 double merge_distance) {
  requireValidScanline(hits, length, merge_distance);
  std::vector<double> pieces;
  pieces.reserve(hits.size() + 1);
  forEachPiece(hits, length, merge_distance, [&](double piece) { pieces.push_back(piece); });
  return pieces;
}

std::vector<double> rqd(std::span<const double> hits, double length,
                        std::span<const double> thresholds, double merge_distance) {
  std::vector<double> result(thresholds.size());
  rqd(hits, length, thresholds, result, merge_distance);
  return result;
}

void rqd(std::span<const double> hits, double length, std::span<const double> thresholds,
         std::span<double> out, double merge_distance) {
  requireValidThresholds(thresholds);
  if (out.size() != thresholds.size()) {
    throw std::invalid_argument("rqd: " + std::to_string(out.size()) + " outputs for " +
                                std::to_string(thresholds.size()) + " thresholds");
  }
  requireValidScanlineFast(hits, length, merge_distance);
  std::fill(out.begin(), out.end(), 0.0);
  forEachPiece(hits, length, merge_distance, [&](double piece) {
    // Branch-free (a select, not a jump): whether a piece passes a threshold is as good as
    // random, and adding 0.0 leaves the non-negative sums unchanged bit for bit.
    for (std::size_t i = 0; i < thresholds.size(); ++i) {
      out[i] += piece >= thresholds[i] ? piece : 0.0;
    }
  });
  // The pieces sum to the length up to rounding: keep RQD within [0, 100]; one intact piece
  // gives exactly 100.
  for (double& value : out) value = std::min(100.0, 100.0 * (value / length));
}

double priestHudsonRqd(double frequency, double threshold) {
  requireNonNegative(frequency, "fracture frequency (1/m)");
  requireNonNegative(threshold, "RQD threshold (m)");
  const double x = frequency * threshold;
  return 100.0 * (1.0 + x) * std::exp(-x);
}

}  // namespace rockmass::rqd
