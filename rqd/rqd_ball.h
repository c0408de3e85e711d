#pragma once
/// RQD balls: RQD(t) in every direction of space around a point (Figure 2 of the paper).
///
/// A ball has a centre c, a scanline length L and N unit directions d (a Fibonacci sphere).
/// Direction d gives the segment from c - d L/2 to c + d L/2; its RQD(t) for each threshold
/// t is the ball's radius function. The segments of d and -d are the same, so the ball is
/// centrally symmetric by construction.
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "geometry/box.h"
#include "geometry/vec.h"
#include "rqd/embree_scene.h"
#include "rqd/line_orientation.h"
#include "rqd/scanline_rqd.h"

namespace rockmass::rqd {

/// A scanline segment (m).
struct Segment {
  geometry::Vec3 start = geometry::Vec3::Zero();  ///< first end (m)
  geometry::Vec3 end = geometry::Vec3::Zero();    ///< second end (m)
};

/// Called now and then with the number of segments done so far (from any thread, one call
/// at a time); used for progress reports.
using ProgressCallback = std::function<void(std::size_t done, std::size_t total)>;

/// RQD (%) of every segment and threshold: entry [i * thresholds.size() + k] is segment i,
/// threshold k (m, >= 0). Segments are evaluated in parallel (TBB); each one writes only its
/// own entries, so the result does not depend on the number of threads. Hits within
/// `merge_distance` (m) are one fracture. Throws std::invalid_argument for a zero-length
/// segment or a negative threshold.
std::vector<double> segmentRqd(const ScanlineScene& scene, std::span<const Segment> segments,
                               std::span<const double> thresholds,
                               double merge_distance = kDefaultMergeDistance,
                               const ProgressCallback& progress = {});

/// The part of `segment` inside `box` (closed), or nothing when they do not meet or meet in
/// a single point. Slab clipping (Liang & Barsky 1984).
std::optional<Segment> clipSegment(const Segment& segment, const geometry::Box& box);

/// What defines one RQD ball.
struct BallSpec {
  geometry::Vec3 center = geometry::Vec3::Zero();  ///< centre (m)
  double length = 0.0;    ///< scanline length L (m, > 0), centred on the centre
  int directions = 2000;  ///< Fibonacci-sphere directions N (>= 1)
  /// The rock volume (m). When set, each scanline is clipped to it and its RQD is taken over
  /// the clipped length: no fractures were generated outside, so that part is not rock
  /// known to be intact. The centre must then lie strictly inside.
  std::optional<geometry::Box> domain;
};

/// RQD of a ball in every direction, for every threshold.
struct BallResult {
  std::vector<geometry::Vec3> directions;  ///< the N unit directions (fibonacciSphere(N))
  std::vector<double> thresholds;          ///< thresholds t (m)
  std::vector<double> rqd;                 ///< RQD (%), [direction * thresholds.size() + k]

  /// RQD (%) in direction `d` for threshold index `k`.
  double at(std::size_t d, std::size_t k) const { return rqd[d * thresholds.size() + k]; }
  /// RQD (%) of threshold index `k` in every direction, in direction order.
  std::vector<double> column(std::size_t k) const;
};

/// Evaluates a ball (see segmentRqd for threads, merging and errors; also throws for a
/// non-positive length, fewer than one direction, or a centre not strictly inside the
/// domain).
BallResult evaluateBall(const ScanlineScene& scene, const BallSpec& ball,
                        std::span<const double> thresholds,
                        double merge_distance = kDefaultMergeDistance,
                        const ProgressCallback& progress = {});

/// RQD (%) in one direction.
struct DirectionalRqd {
  geometry::Vec3 direction = geometry::Vec3::UnitZ();  ///< unit direction
  double rqd = 0.0;                                    ///< RQD (%)
};

/// The shape of one ball surface (one threshold).
///
/// Sampled extremes are the directions with the lowest and highest RQD (the first in
/// direction order on ties). They carry the scanline noise of one realization, so the
/// shape is also summarised by the least-squares RQD tensor: the symmetric 3x3 matrix A
/// minimising sum over directions of (d^T A d - RQD(d))^2, i.e. the constant and
/// second-degree spherical harmonics of the ball (the odd ones vanish: RQD(d) = RQD(-d)).
/// Its eigenvectors are the principal directions and its eigenvalues the principal RQD.
/// The anisotropy ratio is principal max / principal min; it is 1 for a round ball and is
/// left out (unbounded) when the principal min is <= 0, which happens when RQD is 0 in a
/// whole range of directions. A ball that is 0 everywhere has anisotropy 1.
struct BallShape {
  double mean = 0.0;           ///< mean RQD over the directions (each an equal solid angle) (%)
  DirectionalRqd sampled_min;  ///< lowest sampled RQD and its direction
  DirectionalRqd sampled_max;  ///< highest sampled RQD and its direction
  /// Principal RQD (%) and directions of the RQD tensor: max, middle, min. Empty when the
  /// directions cannot determine the tensor (fewer than 6 directions, or all in one cone).
  std::vector<DirectionalRqd> principal;
  std::optional<double> anisotropy;  ///< principal max / principal min (see above)
};

/// The shape of a ball surface from its directions (unit) and RQD values (%), same order.
/// Throws std::invalid_argument when the sizes differ or there is no direction.
BallShape ballShape(std::span<const geometry::Vec3> directions, std::span<const double> rqd);

}  // namespace rockmass::rqd
