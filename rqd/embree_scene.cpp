// Ray-casting scene of fracture discs on Embree 3.
//
// How all hits along a finite segment are collected: one rtcOccluded1 call per segment,
// and no hit is ever reported to Embree, so the query never ends early. (An occlusion query
// rather than rtcIntersect1: the same primitives are visited, but Embree's any-hit
// traversal does not order each node's children by distance, which nothing here needs:
// 6-10 % faster in bench/rqd_bench.cpp.) Exact form: the user-geometry occluded callback
// records the index of each disc whose box the ray crosses (touching no disc data) and
// leaves the ray untouched; after traversal the candidates' packed records are prefetched
// together and tested in double precision (finishExact). Testing inside the callback made
// each of the ~11 candidates per ray wait for its own cache miss (43 % of the time in
// perf); batched, the misses overlap. Triangulated form: an occlusion filter records the disc of
// each quad hit (an index, nothing else: no disc data is touched during traversal) and rejects it
// (valid = 0). Either way the ray's tfar never shrinks, so Embree visits every primitive
// whose bounds the segment crosses, in one traversal. We chose this over repeated queries
// from just past the last hit because (a) it is one traversal instead of k + 1, and (b) a
// restart offset is an epsilon that would skip two discs closer than it, or find the same
// disc again; here nothing is skipped and duplicates are removed by disc id instead (one disc
// is one fracture; a plane is crossed at most once by a line, so two triangles of one disc
// sharing the edge the segment passes through give the same crossing).
//
// After traversal the few hits (about 5 per 30 m scanline at 10^4 discs) are sorted in the
// caller's reused buffer with an insertion sort (std::sort above 32 hits), so a query makes
// no heap allocation once the buffer has grown.
//
// Scene flags, measured in bench/rqd_bench.cpp: RTC_SCENE_FLAG_ROBUST (watertight Pluecker
// triangle test, conservative box tests) costs about 40 % on the triangulated scene; it is
// set there only, because a ray through an edge two triangles share must find the disc
// (tested). The exact form's boxes are padded far beyond float rounding (below), so robust
// traversal adds nothing there and is off. The triangulated mesh is made of quads (Embree
// intersects a quad as two triangles sharing its diagonal, watertight in robust mode): half
// the primitives of triangles; an ellipse's quads are strips across it rather than a fan
// from its centre (addTriangles). Both forms build their BVH at high quality (spatial
// splits for the quads): 5-15 % faster queries in bench/rqd_bench.cpp.
//
// Precision: doubles in, Embree is float inside. Coordinates are shifted to the centre of
// the discs' bounds before rounding to float, to keep float errors small.
// - Exact form: Embree (float) only culls by bounding boxes, which are padded by
//   `bounds_pad` so that float rounding of the ray and boxes can never cull a true hit; the
//   disc test and t are evaluated in double on the unshifted data: t and the crossing point
//   by Disc::intersectLine's own expressions (centre and normal kept in double), the
//   ellipse test against axes stored in float (one 64-byte record per disc, half the cache
//   footprint of double axes), and Disc::intersectLine itself wherever the float axes could
//   tip the verdict (x^2 + y^2 within 1e-5 x the largest aspect ratio of 1, and polygon
//   discs), so the result is the double-precision brute force result, hit for hit.
// - Triangulated form: Embree decides in float whether a triangle is hit, so a segment
//   passing within ~1e-6 (relative to the coordinates' magnitude) of a disc's rim may be
//   found or missed differently than the double-precision polygon test; hits near a disc's
//   rim may therefore differ between the two forms. The t of every hit found is evaluated
//   in double by Disc::intersectLine's plane expression (the triangles lie in the disc's
//   plane), so the distances returned are exact.
#include "rqd/embree_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

namespace rockmass::rqd {

using geometry::Disc;
using geometry::Vec3;

namespace {

/// What the tests after traversal read of one disc, packed in disc order in one cache line
/// (64 bytes; 0.64 MB at 10^4 discs): the centre and normal of Disc::intersectLine in double,
/// so that t has the same bits, and the in-plane axes in float for the ellipse test, which
/// is decided by Disc::intersectLine itself wherever float axes could change the verdict
/// (finishExact). The triangulated form reads only the centre and normal.
struct alignas(64) DiscTest {
  Vec3 center = Vec3::Zero();                  ///< disc centre (m)
  Vec3 normal = Vec3::UnitZ();                 ///< unit normal
  std::array<float, 3> major_over_a{0, 0, 0};  ///< unit major axis / a (1/m), rounded to float
  float aspect = 0.0F;  ///< a / b, rounded to float; 0 for a polygon disc (always the full test)
};
static_assert(sizeof(DiscTest) == 64, "one cache line per disc");

/// What one hits() call carries through Embree's callbacks (lives on the caller's stack).
struct Query {
  const std::vector<Disc>* discs = nullptr;        ///< the scene's discs
  const std::vector<DiscTest>* tests = nullptr;    ///< packed tests, disc order
  const std::vector<std::int64_t>* ids = nullptr;  ///< Disc::id, disc order
  double rim_band = 0.0;  ///< exact form: |x^2 + y^2 - 1| below which intersectLine decides
  std::uint32_t ellipse_quads = 0;      ///< triangulated: quads of the ellipse discs (first)
  std::uint32_t quads_per_ellipse = 1;  ///< triangulated: quads per ellipse disc
  const std::vector<std::uint32_t>* polygon_quad_disc = nullptr;  ///< polygon quad -> disc
  Vec3 start = Vec3::Zero();                                      ///< segment start, unshifted (m)
  Vec3 dir = Vec3::UnitX();                                       ///< unit direction of the segment
  double length = 0.0;                                            ///< segment length L (m)
  double float_t_shift = 0.0;  ///< Embree ray t minus segment t (m): the ray starts early
  std::vector<ScanlineHit>* found = nullptr;  ///< hits in [0, L], possibly repeated
};

/// Embree's context, extended with the query (the context must come first).
struct QueryContext {
  RTCIntersectContext embree;
  Query* query;
};

const QueryContext& queryContext(const RTCIntersectContext* context) {
  return *reinterpret_cast<const QueryContext*>(context);
}

/// Exact form: records the disc whose (padded) box the ray crosses, as a candidate in
/// `disc_id` (the disc's index); finishExact tests the candidates after traversal. Touches
/// no disc data and never reports a hit, so traversal goes on. `Arguments` is Embree's
/// occluded (queries use rtcOccluded1) or intersect callback argument type.
template <typename Arguments>
void recordDiscCandidate(const Arguments* args) {
  Query& query = *queryContext(args->context).query;
  // rtcOccluded1 only: one ray, and the query's double-precision segment describes it.
  assert(args->N == 1);
  if (args->valid[0] == 0) return;
  // Start loading the disc's record now (no wait): it arrives while traversal goes on.
  __builtin_prefetch(&(*query.tests)[args->primID]);
  query.found->push_back({0.0, static_cast<std::int64_t>(args->primID)});
}

/// Triangulated form: records the index of the disc whose quad was hit (in `disc_id`) and
/// Embree's float distance, both fixed up by finishTriangulated, and rejects the hit, so
/// that traversal continues. The ellipse discs come first and have the same number of
/// quads each, so their disc index is a division (a quad -> disc table of 4 bytes per quad
/// missed the cache on nearly every hit: 12 % of the time in perf); polygon discs use a
/// table. The disc's record is prefetched for finishTriangulated.
void filterTriangleHit(const RTCFilterFunctionNArguments* args) {
  Query& query = *queryContext(args->context).query;
  for (unsigned int i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    args->valid[i] = 0;
    const unsigned int primitive = RTCHitN_primID(args->hit, args->N, i);
    const double float_t =
        static_cast<double>(RTCRayN_tfar(args->ray, args->N, i)) - query.float_t_shift;
    const std::uint32_t disc = primitive < query.ellipse_quads
                                   ? primitive / query.quads_per_ellipse
                                   : (*query.polygon_quad_disc)[primitive - query.ellipse_quads];
    __builtin_prefetch(&(*query.tests)[disc]);
    query.found->push_back({float_t, disc});
  }
}

/// The band of x^2 + y^2 around 1 in which the float axes of DiscTest could decide otherwise
/// than Disc::intersectLine, for a disc of aspect max(a/b, b/a) = 1: x and y are computed in
/// double from the double-precision point, and only the axis vectors carry float rounding
/// (relative 6e-8 per component, about 2e-7 for the minor axis, a cross product of rounded
/// vectors, and the rounded aspect); near the rim that changes x^2 + y^2 by at most
/// 4 * 2e-7 * aspect. The scene's band is this times its largest aspect: 10x margin.
constexpr double kRimBandPerAspect = 1e-5;

/// Exact form, after traversal: `found` holds a disc index per crossed box (each once, their
/// records prefetched by the callback); keeps, in place, the candidates the segment crosses
/// inside [0, L] with their t and Disc::id, exactly as Disc::intersectLine followed by the
/// [0, L] check decides. t is computed by intersectLine's own expression on the same doubles
/// (same bits), and so is the crossing point; the ellipse test uses the record's float axes,
/// and intersectLine itself decides polygon discs and any x^2 + y^2 within the scene's rim
/// band of 1 (where float axes could tip the verdict). The common path has no
/// data-dependent branch (whether a box candidate is a hit is a coin flip, and mispredicted
/// branches behind the division's latency cost more than the arithmetic).
void finishExact(const Query& query, std::vector<ScanlineHit>& found) {
  const std::vector<DiscTest>& tests = *query.tests;
  const double length = query.length;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < found.size(); ++i) {
    // In place: slot `kept` <= i, and candidate i is read before slot `kept` is written.
    const auto index = static_cast<std::size_t>(found[i].disc_id);
    const DiscTest& test = tests[index];
    const double denominator = test.normal.dot(query.dir);
    const double t = test.normal.dot(test.center - query.start) / denominator;
    const Vec3 local = query.start + t * query.dir - test.center;
    const Vec3 major(test.major_over_a[0], test.major_over_a[1], test.major_over_a[2]);
    const double x = local.dot(major);
    const double y = local.dot(test.normal.cross(major)) * static_cast<double>(test.aspect);
    const double r2 = x * x + y * y;
    if (test.aspect == 0.0F || std::abs(r2 - 1.0) <= query.rim_band) [[unlikely]] {
      const std::optional<double> exact =
          (*query.discs)[index].intersectLine(query.start, query.dir);
      if (exact && *exact >= 0.0 && *exact <= length) {
        found[kept++] = {*exact, static_cast<std::int64_t>(index)};
      }
      continue;
    }
    // intersectLine's verdict (its parallel-line guard, then x^2 + y^2 <= 1) and [0, L];
    // a NaN or infinite t fails the comparisons. Written as a select, not a branch.
    const bool hit = (std::abs(denominator) > 1e-300) & (t >= 0.0) & (t <= length) & (r2 < 1.0);
    found[kept] = {t, static_cast<std::int64_t>(index)};
    kept += static_cast<std::size_t>(hit);
  }
  found.resize(kept);
  // Disc indices to Disc::id (a small array, read for the hits only).
  for (ScanlineHit& hit : found) hit.disc_id = (*query.ids)[static_cast<std::size_t>(hit.disc_id)];
}

/// Sorts `hits` by (t, disc id), or by disc id alone when `by_id`: insertion sort for the
/// few hits of a typical scanline, std::sort for long ones.
void sortHits(std::vector<ScanlineHit>& hits, bool by_id) {
  const auto less = [by_id](const ScanlineHit& p, const ScanlineHit& q) {
    if (by_id) return p.disc_id < q.disc_id;
    return p.t != q.t ? p.t < q.t : p.disc_id < q.disc_id;
  };
  constexpr std::size_t kInsertionSortMax = 32;
  if (hits.size() > kInsertionSortMax) {
    std::sort(hits.begin(), hits.end(), less);
    return;
  }
  for (std::size_t i = 1; i < hits.size(); ++i) {
    const ScanlineHit hit = hits[i];
    std::size_t j = i;
    for (; j > 0 && less(hit, hits[j - 1]); --j) hits[j] = hits[j - 1];
    hits[j] = hit;
  }
}

/// Drops repeats of one disc from hits sorted so that they are adjacent.
void dropRepeatedDiscs(std::vector<ScanlineHit>& hits) {
  hits.erase(std::unique(
                 hits.begin(), hits.end(),
                 [](const ScanlineHit& p, const ScanlineHit& q) { return p.disc_id == q.disc_id; }),
             hits.end());
}

/// Triangulated form, after traversal: `found` holds a disc index per quad hit. Evaluates the
/// t of each in double and keeps those in [0, L], with their Disc::id. Repeats of one disc
/// (two triangles sharing the edge the segment passes through, or a spatial split's two
/// references to one quad) get the same t, to the bit, so the caller's one sort by (t, id)
/// makes them adjacent and drops them: no sort by disc first. Only a segment lying in a disc's
/// plane (in double) keeps Embree's float t, which may differ between repeats: then the
/// repeats are dropped here first, by disc.
void finishTriangulated(const Query& query, std::vector<ScanlineHit>& found) {
  std::size_t kept = 0;
  bool in_plane = false;
  for (std::size_t i = 0; i < found.size(); ++i) {
    const ScanlineHit raw = found[i];
    const auto index = static_cast<std::size_t>(raw.disc_id);
    const DiscTest& test = (*query.tests)[index];
    // Disc::intersectLine's plane distance (same expression, same bits); Embree has decided
    // the hit, so where double precision would put the point just outside the rim, Embree's
    // verdict stands.
    const double denominator = test.normal.dot(query.dir);
    in_plane |= denominator == 0.0;
    const double t =
        denominator != 0.0 ? test.normal.dot(test.center - query.start) / denominator : raw.t;
    if (t >= 0.0 && t <= query.length) found[kept++] = {t, (*query.ids)[index]};
  }
  found.resize(kept);
  if (in_plane) [[unlikely]] {
    sortHits(found, /*by_id=*/true);
    dropRepeatedDiscs(found);
  }
}

bool hasArea(const Disc& disc) {
  if (!disc.polygon.empty()) return disc.polygon.size() >= 3 && disc.area() > 0.0;
  return disc.a > 0.0 && disc.b > 0.0 && std::isfinite(disc.a) && std::isfinite(disc.b);
}

}  // namespace

struct ScanlineScene::Impl {
  DiscForm form = DiscForm::ExactEllipse;
  std::vector<Disc> discs;        ///< the discs in the scene (primitive order)
  std::vector<DiscTest> tests;    ///< the discs' packed tests (disc order)
  std::vector<std::int64_t> ids;  ///< the discs' Disc::id (disc order)
  double rim_band = 0.0;          ///< exact form: kRimBandPerAspect x the largest aspect of a disc
  std::uint32_t ellipse_quads = 0;               ///< triangulated form: quads of the ellipse discs
  std::uint32_t quads_per_ellipse = 1;           ///< triangulated form: quads per ellipse disc
  std::vector<std::uint32_t> polygon_quad_disc;  ///< triangulated form: polygon quad -> disc
  Vec3 offset = Vec3::Zero();  ///< subtracted from coordinates given to Embree (m)
  /// Padding of the exact form's boxes and of the ray's ends (m): covers float rounding of
  /// shifted coordinates (relative 6e-8) and of the ray along segments far longer than the
  /// scene, with a wide margin; it only costs a few extra double-precision disc tests.
  double bounds_pad = 0.0;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;

  ~Impl() {
    if (scene != nullptr) rtcReleaseScene(scene);
    if (device != nullptr) rtcReleaseDevice(device);
  }

  void check(const char* what) const {
    const RTCError error = rtcGetDeviceError(device);
    if (error != RTC_ERROR_NONE) {
      throw std::runtime_error(std::string("Embree failed to ") + what + " (error code " +
                               std::to_string(static_cast<int>(error)) + ")");
    }
  }

  static void bounds(const RTCBoundsFunctionArguments* args) {
    const Impl& impl = *static_cast<const Impl*>(args->geometryUserPtr);
    const geometry::Box box = impl.discs[args->primID].bounds();
    const Vec3 low = box.min - impl.offset;
    const Vec3 high = box.max - impl.offset;
    const auto pad = static_cast<float>(impl.bounds_pad);
    RTCBounds& out = *args->bounds_o;
    out.lower_x = static_cast<float>(low.x()) - pad;
    out.lower_y = static_cast<float>(low.y()) - pad;
    out.lower_z = static_cast<float>(low.z()) - pad;
    out.upper_x = static_cast<float>(high.x()) + pad;
    out.upper_y = static_cast<float>(high.y()) + pad;
    out.upper_z = static_cast<float>(high.z()) + pad;
  }

  void addDiscTests() {
    tests.reserve(discs.size());
    ids.reserve(discs.size());
    double largest_aspect = 1.0;
    for (const Disc& disc : discs) {
      DiscTest& test = tests.emplace_back();
      test.center = disc.center;
      test.normal = disc.normal;
      if (disc.polygon.empty()) {
        for (int k = 0; k < 3; ++k) {
          test.major_over_a[k] = static_cast<float>(disc.major[k] / disc.a);
        }
        test.aspect = static_cast<float>(disc.a / disc.b);
        // Semi-axes beyond float's range (a below 1e-38 m, or a/b above 3e38): aspect 0,
        // so that Disc::intersectLine decides this disc every time.
        const bool in_float_range = std::isfinite(test.aspect) && test.aspect > 0.0F &&
                                    std::all_of(test.major_over_a.begin(), test.major_over_a.end(),
                                                [](float v) { return std::isfinite(v); });
        if (in_float_range) {
          largest_aspect = std::max({largest_aspect, disc.a / disc.b, disc.b / disc.a});
        } else {
          test.aspect = 0.0F;
        }
      }
      ids.push_back(disc.id);
    }
    rim_band = kRimBandPerAspect * largest_aspect;
  }

  void addUserGeometry() {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned int>(discs.size()));
    rtcSetGeometryUserData(geometry, this);
    rtcSetGeometryBoundsFunction(geometry, &Impl::bounds, this);
    rtcSetGeometryIntersectFunction(geometry, &recordDiscCandidate<RTCIntersectFunctionNArguments>);
    rtcSetGeometryOccludedFunction(geometry, &recordDiscCandidate<RTCOccludedFunctionNArguments>);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);
  }

  /// Triangulated form. An ellipse's outline (a convex n-gon) is cut into strips across its
  /// major axis: with chain A = v_0, v_1, ..., v_m and chain B = v_0, v_(n-1), ..., v_(n-m)
  /// (m = floor(n / 2)), strip i is the quad (A_i, A_i+1, B_i+1, B_i), a triangle where two
  /// of its corners coincide (the first strip, and the last for even n). m primitives per
  /// disc, as many as a fan of quads, but thin and disjoint: a fan's wedges all reach the
  /// centre, so their boxes overlap there and a segment near a disc's centre visited all of
  /// them (the strips measured 3-8 % faster, bench/rqd_bench.cpp). Polygon discs may be
  /// non-convex: fanned from their centroid (Disc::center), one triangle per quad.
  void addTriangles(int segments) {
    std::vector<Vec3> vertices;
    std::vector<std::uint32_t> quads;
    for (std::size_t d = 0; d < discs.size(); ++d) {
      const Disc& disc = discs[d];
      const std::vector<Vec3> outline = disc.outline(segments);
      const auto n = static_cast<std::uint32_t>(outline.size());
      const auto first = static_cast<std::uint32_t>(vertices.size());
      if (!disc.polygon.empty()) {
        vertices.push_back(disc.center);
        vertices.insert(vertices.end(), outline.begin(), outline.end());
        for (std::uint32_t k = 0; k < n; ++k) {
          const std::uint32_t next = first + 1 + (k + 1) % n;
          quads.insert(quads.end(), {first, first + 1 + k, next, next});
          polygon_quad_disc.push_back(static_cast<std::uint32_t>(d));
        }
        continue;
      }
      vertices.insert(vertices.end(), outline.begin(), outline.end());
      const std::uint32_t m = n / 2;
      const auto chain_a = [first](std::uint32_t i) { return first + i; };
      const auto chain_b = [first, n](std::uint32_t i) { return first + (n - i) % n; };
      for (std::uint32_t i = 0; i < m; ++i) {
        const std::uint32_t a0 = chain_a(i), a1 = chain_a(i + 1);
        const std::uint32_t b0 = chain_b(i), b1 = chain_b(i + 1);
        if (a0 == b0) {
          quads.insert(quads.end(), {a1, b1, a0, a0});  // first strip: triangle
        } else if (a1 == b1) {
          quads.insert(quads.end(), {a0, a1, b0, b0});  // last strip, even n: triangle
        } else {
          quads.insert(quads.end(), {a0, a1, b1, b0});
        }
      }
      // The discs are ordered ellipses first (constructor), each with the same count.
      if (ellipse_quads == 0) quads_per_ellipse = m;
      if (m != quads_per_ellipse || !polygon_quad_disc.empty()) {
        throw std::logic_error("triangulated scene: ellipse discs must come first, with " +
                               std::to_string(quads_per_ellipse) + " quads each");
      }
      ellipse_quads += m;
    }
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_QUAD);
    auto* vertex_buffer = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), vertices.size()));
    auto* index_buffer = static_cast<std::uint32_t*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4,
                                4 * sizeof(std::uint32_t), quads.size() / 4));
    if (vertex_buffer == nullptr || index_buffer == nullptr) check("allocate quad buffers");
    for (std::size_t v = 0; v < vertices.size(); ++v) {
      const Vec3 shifted = vertices[v] - offset;
      for (int k = 0; k < 3; ++k) vertex_buffer[3 * v + k] = static_cast<float>(shifted[k]);
    }
    std::copy(quads.begin(), quads.end(), index_buffer);
    rtcSetGeometryIntersectFilterFunction(geometry, &filterTriangleHit);
    rtcSetGeometryOccludedFilterFunction(geometry, &filterTriangleHit);
    rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);
  }
};

ScanlineScene::ScanlineScene(const geometry::FractureNetwork& network, DiscForm form, int segments)
    : impl_(std::make_unique<Impl>()) {
  if (form == DiscForm::Triangulated && segments < 3) {
    throw std::invalid_argument("a triangulated disc needs at least 3 outline segments, got " +
                                std::to_string(segments));
  }
  Impl& impl = *impl_;
  impl.form = form;
  for (const Disc& disc : network.discs) {
    if (hasArea(disc)) impl.discs.push_back(disc);
  }
  // Ellipses first: the triangulated form computes their disc index from the quad index.
  // (The order of the discs is not visible: hits are sorted by t, then disc id.)
  std::stable_partition(impl.discs.begin(), impl.discs.end(),
                        [](const Disc& disc) { return disc.polygon.empty(); });
  if (!impl.discs.empty()) {
    geometry::Box all = impl.discs.front().bounds();
    for (const Disc& disc : impl.discs) {
      const geometry::Box box = disc.bounds();
      all.min = all.min.cwiseMin(box.min);
      all.max = all.max.cwiseMax(box.max);
    }
    impl.offset = all.center();
    impl.bounds_pad = 1e-4 * (1.0 + all.size().maxCoeff());
  }

  impl.device = rtcNewDevice(nullptr);
  if (impl.device == nullptr) {
    throw std::runtime_error("Embree could not create a device (error code " +
                             std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) +
                             "); check that the CPU supports SSE2");
  }
  impl.scene = rtcNewScene(impl.device);
  // Watertight triangles: a shared edge must never let a ray through (see the top).
  if (form == DiscForm::Triangulated) rtcSetSceneFlags(impl.scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(impl.scene, RTC_BUILD_QUALITY_HIGH);
  if (!impl.discs.empty()) {
    impl.addDiscTests();
    if (form == DiscForm::ExactEllipse) {
      impl.addUserGeometry();
    } else {
      impl.addTriangles(segments);
    }
  }
  rtcCommitScene(impl.scene);
  impl.check("build the scene");
}

ScanlineScene::~ScanlineScene() = default;
ScanlineScene::ScanlineScene(ScanlineScene&&) noexcept = default;
ScanlineScene& ScanlineScene::operator=(ScanlineScene&&) noexcept = default;

DiscForm ScanlineScene::form() const {
  return impl_->form;
}

std::vector<ScanlineHit> ScanlineScene::hits(const Vec3& start, const Vec3& end) const {
  std::vector<ScanlineHit> found;
  hits(start, end, found);
  return found;
}

void ScanlineScene::hits(const Vec3& start, const Vec3& end,
                         std::vector<ScanlineHit>& found) const {
  found.clear();
  const Impl& impl = *impl_;
  const double length = (end - start).norm();
  if (!(length > 0.0) || !std::isfinite(length) || impl.discs.empty()) return;

  Query query;
  query.found = &found;
  query.discs = &impl.discs;
  query.ellipse_quads = impl.ellipse_quads;
  query.quads_per_ellipse = impl.quads_per_ellipse;
  query.polygon_quad_disc = &impl.polygon_quad_disc;
  query.tests = &impl.tests;
  query.ids = &impl.ids;
  query.rim_band = impl.rim_band;
  query.start = start;
  query.dir = (end - start) / length;
  query.length = length;
  query.float_t_shift = impl.bounds_pad;

  QueryContext context;
  rtcInitIntersectContext(&context.embree);
  context.query = &query;

  // The float ray starts `bounds_pad` before the segment and ends `bounds_pad` after it, so
  // that rounding cannot lose a hit at t = 0 or t = L; [0, L] is then enforced in double.
  const Vec3 origin = start - impl.offset - impl.bounds_pad * query.dir;
  RTCRay ray{};
  ray.org_x = static_cast<float>(origin.x());
  ray.org_y = static_cast<float>(origin.y());
  ray.org_z = static_cast<float>(origin.z());
  ray.dir_x = static_cast<float>(query.dir.x());
  ray.dir_y = static_cast<float>(query.dir.y());
  ray.dir_z = static_cast<float>(query.dir.z());
  ray.tnear = 0.0f;
  ray.tfar = static_cast<float>(length + 2.0 * impl.bounds_pad);
  ray.mask = std::numeric_limits<unsigned int>::max();
  ray.flags = 0;
  // An occlusion query: no hit is ever reported, so it visits the same primitives as
  // rtcIntersect1 would, but Embree's any-hit traversal skips ordering the children of each
  // node by distance (8-10 % faster, both forms; bench/rqd_bench.cpp).
  rtcOccluded1(impl.scene, &context.embree, &ray);

  if (impl.form == DiscForm::Triangulated) {
    finishTriangulated(query, found);
  } else {
    finishExact(query, found);
  }
  sortHits(found, /*by_id=*/false);
  // Triangulated form: repeats of a disc have equal t and id, so they are adjacent now.
  // Exact form: one primitive per disc, so repeats are not expected; dropping them keeps
  // "each disc at most once" unconditional.
  dropRepeatedDiscs(found);
}

}  // namespace rockmass::rqd
