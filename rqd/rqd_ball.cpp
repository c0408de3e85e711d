#include "rqd/rqd_ball.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <mutex>
#include <stdexcept>
#include <string>

#include "geometry/interrupt.h"
#include "rqd/directions.h"

namespace rockmass::rqd {

using geometry::Vec3;

namespace {

/// Progress is reported about this many times per call.
constexpr std::size_t kProgressReports = 20;

/// Buffers one thread reuses from segment to segment (no allocation per segment once grown).
struct SegmentBuffers {
  std::vector<ScanlineHit> hits;
  std::vector<double> positions;
};

/// RQD of one segment for every threshold, written to `out`.
void evaluateSegment(const ScanlineScene& scene, const Segment& segment,
                     std::span<const double> thresholds, double merge_distance,
                     std::span<double> out, SegmentBuffers& buffers) {
  const double length = (segment.end - segment.start).norm();
  if (!(length > 0.0)) throw std::invalid_argument("an RQD scanline must have a length > 0");
  scene.hits(segment.start, segment.end, buffers.hits);
  buffers.positions.resize(buffers.hits.size());
  // hits() reports t in the closed [0, L]; clamp the last ulp of rounding in |end - start|.
  std::transform(buffers.hits.begin(), buffers.hits.end(), buffers.positions.begin(),
                 [&](const ScanlineHit& h) { return std::clamp(h.t, 0.0, length); });
  rqd(buffers.positions, length, thresholds, out, merge_distance);
}

}  // namespace

std::optional<Segment> clipSegment(const Segment& segment, const geometry::Box& box) {
  const Vec3 d = segment.end - segment.start;
  double enter = 0.0;
  double leave = 1.0;
  for (int axis = 0; axis < 3; ++axis) {
    if (d[axis] == 0.0) {
      if (segment.start[axis] < box.min[axis] || segment.start[axis] > box.max[axis]) return {};
      continue;
    }
    double t0 = (box.min[axis] - segment.start[axis]) / d[axis];
    double t1 = (box.max[axis] - segment.start[axis]) / d[axis];
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
  }
  if (!(enter < leave)) return {};
  return Segment{enter > 0.0 ? Vec3(segment.start + enter * d) : segment.start,
                 leave < 1.0 ? Vec3(segment.start + leave * d) : segment.end};
}

std::vector<double> segmentRqd(const ScanlineScene& scene, std::span<const Segment> segments,
                               std::span<const double> thresholds, double merge_distance,
                               const ProgressCallback& progress) {
  const std::size_t k = thresholds.size();
  std::vector<double> result(segments.size() * k);
  std::atomic<std::size_t> done{0};
  std::mutex progress_mutex;
  const std::size_t step = std::max<std::size_t>(1, segments.size() / kProgressReports);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, segments.size(), 16),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      throwIfInterrupted("the RQD scanlines");
                      SegmentBuffers buffers;
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        evaluateSegment(scene, segments[i], thresholds, merge_distance,
                                        std::span<double>(result).subspan(i * k, k), buffers);
                      }
                      if (!progress) return;
                      const std::size_t before = done.fetch_add(range.size());
                      if ((before + range.size()) / step != before / step) {
                        const std::lock_guard lock(progress_mutex);
                        progress(before + range.size(), segments.size());
                      }
                    });
  return result;
}

std::vector<double> BallResult::column(std::size_t k) const {
  std::vector<double> values(directions.size());
  for (std::size_t d = 0; d < directions.size(); ++d) values[d] = at(d, k);
  return values;
}

BallResult evaluateBall(const ScanlineScene& scene, const BallSpec& ball,
                        std::span<const double> thresholds, double merge_distance,
                        const ProgressCallback& progress) {
  if (!(ball.length > 0.0)) {
    throw std::invalid_argument("an RQD ball needs a scanline length > 0, got " +
                                std::to_string(ball.length));
  }
  if (ball.domain) {
    const geometry::Box& box = *ball.domain;
    if (!((ball.center.array() > box.min.array()).all() &&
          (ball.center.array() < box.max.array()).all())) {
      throw std::invalid_argument("the centre of an RQD ball must lie strictly inside the domain");
    }
  }
  BallResult result;
  result.directions = fibonacciSphere(ball.directions);
  result.thresholds.assign(thresholds.begin(), thresholds.end());
  std::vector<Segment> segments;
  segments.reserve(result.directions.size());
  for (const Vec3& d : result.directions) {
    const Segment full{ball.center - 0.5 * ball.length * d, ball.center + 0.5 * ball.length * d};
    // A centre strictly inside keeps a piece of every line through it.
    segments.push_back(ball.domain ? *clipSegment(full, *ball.domain) : full);
  }
  result.rqd = segmentRqd(scene, segments, thresholds, merge_distance, progress);
  return result;
}

BallShape ballShape(std::span<const Vec3> directions, std::span<const double> rqd) {
  if (directions.empty() || directions.size() != rqd.size()) {
    throw std::invalid_argument("ballShape needs one RQD value per direction and at least one");
  }
  const std::size_t n = directions.size();
  BallShape shape;
  double sum = 0.0;
  std::size_t lo = 0;
  std::size_t hi = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sum += rqd[i];
    if (rqd[i] < rqd[lo]) lo = i;
    if (rqd[i] > rqd[hi]) hi = i;
  }
  shape.mean = sum / static_cast<double>(n);
  shape.sampled_min = {directions[lo], rqd[lo]};
  shape.sampled_max = {directions[hi], rqd[hi]};

  // d^T A d = a_xx x^2 + a_yy y^2 + a_zz z^2 + 2 a_xy x y + 2 a_xz x z + 2 a_yz y z.
  Eigen::MatrixXd design(n, 6);
  Eigen::VectorXd values(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& d = directions[i];
    design.row(static_cast<Eigen::Index>(i)) << d.x() * d.x(), d.y() * d.y(), d.z() * d.z(),
        2 * d.x() * d.y(), 2 * d.x() * d.z(), 2 * d.y() * d.z();
    values[static_cast<Eigen::Index>(i)] = rqd[i];
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(design);
  if (n < 6 || qr.rank() < 6) return shape;
  const Eigen::VectorXd a = qr.solve(values);
  Eigen::Matrix3d tensor;
  tensor << a[0], a[3], a[4], a[3], a[1], a[5], a[4], a[5], a[2];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(tensor);
  // Eigen sorts eigenvalues in increasing order: report max, middle, min.
  for (int j = 2; j >= 0; --j) {
    shape.principal.push_back({eigen.eigenvectors().col(j), eigen.eigenvalues()[j]});
  }
  const double max = shape.principal.front().rqd;
  const double min = shape.principal.back().rqd;
  if (shape.sampled_max.rqd == 0.0) {
    shape.anisotropy = 1.0;
  } else if (min > 0.0) {
    shape.anisotropy = max / min;
  }
  return shape;
}

}  // namespace rockmass::rqd
