#pragma once
/// A ray-casting scene of all fracture discs (Embree inside, hidden behind a pimpl): every
/// disc a scanline segment crosses, with its distance from the segment start.
///
/// Convention: a segment from `start` to `end` of length L is the closed interval [0, L];
/// a disc crossed exactly at t = 0 or t = L is reported.
#include <cstdint>
#include <memory>
#include <vector>

#include "geometry/fracture_network.h"
#include "geometry/vec.h"

namespace rockmass::rqd {

/// How discs are represented in the ray-casting scene.
enum class DiscForm {
  ExactEllipse,  ///< analytic ray-ellipse (or ray-polygon) test in double precision
  Triangulated,  ///< each disc's outline cut into triangles (strips of Embree quads),
                 ///< intersected by Embree in float, watertight (robust mode)
};

/// One fracture crossed by a segment.
struct ScanlineHit {
  double t = 0.0;            ///< distance from the segment start (m)
  std::int64_t disc_id = 0;  ///< Disc::id of the fracture crossed
};

/// All discs of a network, ready for many segment queries from many threads.
class ScanlineScene {
 public:
  /// Builds the scene from all discs of `network` (including those that do not cut blocks).
  /// Triangulated form: each ellipse's outline(segments), a convex polygon, cut into strips
  /// across its major axis, one Embree quad (two triangles) per strip (polygon discs: their
  /// polygon, fanned from the centroid, one triangle per quad since they may be non-convex).
  /// `segments` (>= 3) is ignored for the exact form. Discs without area (a or b not positive) are
  /// left out. Throws std::invalid_argument for segments < 3 and std::runtime_error when Embree
  /// fails.
  ScanlineScene(const geometry::FractureNetwork& network, DiscForm form, int segments = 24);
  ~ScanlineScene();
  ScanlineScene(ScanlineScene&&) noexcept;
  ScanlineScene& operator=(ScanlineScene&&) noexcept;
  ScanlineScene(const ScanlineScene&) = delete;
  ScanlineScene& operator=(const ScanlineScene&) = delete;

  /// Every disc crossed by the segment from `start` to `end` (m), sorted by t (ties by disc
  /// id), each disc at most once, t in [0, |end - start|] (closed). Thread-safe: each call
  /// keeps its state on its own stack. A zero-length segment hits nothing.
  std::vector<ScanlineHit> hits(const geometry::Vec3& start, const geometry::Vec3& end) const;
  /// The same, written into `out` (cleared first): a caller looping over many segments
  /// reuses one buffer instead of allocating per segment.
  void hits(const geometry::Vec3& start, const geometry::Vec3& end,
            std::vector<ScanlineHit>& out) const;

  /// The form the scene was built with.
  DiscForm form() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rockmass::rqd
