#include "blocks/piece_contacts.h"

#include <CGAL/box_intersection_d.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>
#include <tuple>

#include "blocks/convex_split.h"
#include "blocks/union_find.h"
#include "geometry/disc.h"

namespace rockmass::blocks {
namespace {

using geometry::Vec3;
using BoxWithIndex = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

/// Plane and vertices of one face, computed once.
struct FaceData {
  Vec3 normal;
  double offset = 0.0;
  std::vector<Vec3> points;
  geometry::Box box;  ///< bounding box of the points
};

/// True when the boxes overlap once grown by `tolerance`.
bool boxesMeet(const geometry::Box& a, const geometry::Box& b, double tolerance) {
  return (a.min.array() <= b.max.array() + tolerance).all() &&
         (b.min.array() <= a.max.array() + tolerance).all();
}

std::vector<FaceData> faceData(const Piece& piece) {
  std::vector<FaceData> out;
  out.reserve(piece.shape.faces.size());
  for (std::size_t f = 0; f < piece.shape.faces.size(); ++f) {
    FaceData d;
    d.normal = geometry::faceNormal(piece.shape, static_cast<int>(f));
    Vec3 mean = Vec3::Zero();
    d.box = {piece.shape.vertices[piece.shape.faces[f][0]],
             piece.shape.vertices[piece.shape.faces[f][0]]};
    for (int v : piece.shape.faces[f]) {
      const Vec3& p = piece.shape.vertices[v];
      d.points.push_back(p);
      mean += p;
      d.box.min = d.box.min.cwiseMin(p);
      d.box.max = d.box.max.cwiseMax(p);
    }
    d.offset = d.normal.dot(mean / static_cast<double>(d.points.size()));
    out.push_back(std::move(d));
  }
  return out;
}

/// True when every point of `b` lies within `tolerance` of the plane of `a`.
bool inPlane(const FaceData& a, const FaceData& b, double tolerance) {
  return std::all_of(b.points.begin(), b.points.end(), [&](const Vec3& p) {
    return std::abs(a.normal.dot(p) - a.offset) <= tolerance;
  });
}

/// True when the two faces lie in one plane: the points of the smaller face within
/// `tolerance` of the larger face's plane. The plane of a tiny face is not tested against:
/// its computed normal is off by about the vertex round-off over its size (1e-7 rad for a
/// 1 mm face of a 10 m cut), which would tilt it away from a large neighbour by more than
/// the tolerance and lose a real contact.
bool coplanar(const FaceData& a, const FaceData& b, double tolerance) {
  const bool a_larger =
      (a.box.max - a.box.min).squaredNorm() >= (b.box.max - b.box.min).squaredNorm();
  return a_larger ? inPlane(a, b, tolerance) : inPlane(b, a, tolerance);
}

}  // namespace

bool thinnerThan(const std::vector<Vec3>& polygon, double tolerance) {
  if (polygon.size() < 3) return true;
  const Vec3& origin = polygon.front();
  Vec3 low = origin;
  Vec3 high = origin;
  Vec3 twice_area = Vec3::Zero();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    low = low.cwiseMin(polygon[i]);
    high = high.cwiseMax(polygon[i]);
    if (i >= 1 && i + 1 < polygon.size()) {
      twice_area += (polygon[i] - origin).cross(polygon[i + 1] - origin);
    }
  }
  const double extent = (high - low).norm();
  return extent <= tolerance || 0.5 * twice_area.norm() <= tolerance * extent;
}

void faceOverlap(const std::vector<Vec3>& a, const std::vector<Vec3>& b, const Vec3& normal,
                 std::vector<Vec3>& out) {
  // Two buffers swapped between clips: no allocation once they have grown.
  thread_local std::vector<Vec3> next;
  out.assign(a.begin(), a.end());
  // b runs clockwise about `normal`: walking it backwards, its inside is on the left.
  const std::size_t n = b.size();
  for (std::size_t k = 0; k < n && out.size() >= 3; ++k) {
    const Vec3& p = b[(k + 1) % n];
    const Vec3& q = b[k];
    const Vec3 inward = normal.cross(q - p);
    const double length = inward.norm();
    if (length == 0.0) continue;
    clipPolygon(out, Plane::through(p, inward / length), next);
    std::swap(out, next);
  }
}

bool realContact(const std::vector<Vec3>& overlap, double area, double tolerance, double min_area) {
  return overlap.size() >= 3 && (area > min_area || !thinnerThan(overlap, tolerance));
}

double faceOverlapArea(const std::vector<Vec3>& a, const std::vector<Vec3>& b, const Vec3& normal) {
  thread_local std::vector<Vec3> clipped;
  faceOverlap(a, b, normal, clipped);
  return clipped.size() >= 3 ? geometry::polygonArea(clipped) : 0.0;
}

std::vector<PieceContact> findPieceContacts(std::span<const Piece> pieces, double tolerance,
                                            double min_area) {
  std::vector<BoxWithIndex> boxes;
  std::vector<geometry::Box> piece_boxes(pieces.size());
  boxes.reserve(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const geometry::Box b = geometry::bounds(pieces[i].shape).enlarged(tolerance);
    piece_boxes[i] = b;
    boxes.emplace_back(
        CGAL::Bbox_3(b.min.x(), b.min.y(), b.min.z(), b.max.x(), b.max.y(), b.max.z()),
        static_cast<int>(i));
  }
  std::vector<std::pair<int, int>> pairs;
  CGAL::box_self_intersection_d(
      boxes.begin(), boxes.end(), [&](const BoxWithIndex& a, const BoxWithIndex& b) {
        pairs.emplace_back(std::min(a.info(), b.info()), std::max(a.info(), b.info()));
      });
  std::sort(pairs.begin(), pairs.end());
  std::vector<std::vector<FaceData>> faces(pieces.size());
  tbb::parallel_for(std::size_t{0}, pieces.size(),
                    [&](std::size_t i) { faces[i] = faceData(pieces[i]); });

  // Narrow phase in parallel chunks, concatenated in chunk order (deterministic).
  constexpr std::size_t kChunk = 4096;
  std::vector<std::vector<PieceContact>> found((pairs.size() + kChunk - 1) / kChunk);
  tbb::parallel_for(std::size_t{0}, found.size(), [&](std::size_t chunk) {
    const std::size_t end = std::min(pairs.size(), (chunk + 1) * kChunk);
    std::vector<int> near_a, near_b;
    for (std::size_t k = chunk * kChunk; k < end; ++k) {
      const auto [i, j] = pairs[k];
      // Only faces that reach into the overlap of the two pieces' boxes can touch.
      const geometry::Box overlap{piece_boxes[i].min.cwiseMax(piece_boxes[j].min),
                                  piece_boxes[i].max.cwiseMin(piece_boxes[j].max)};
      near_a.clear();
      near_b.clear();
      for (std::size_t f = 0; f < faces[i].size(); ++f) {
        if (boxesMeet(faces[i][f].box, overlap, tolerance)) near_a.push_back(static_cast<int>(f));
      }
      if (near_a.empty()) continue;
      for (std::size_t f = 0; f < faces[j].size(); ++f) {
        if (boxesMeet(faces[j][f].box, overlap, tolerance)) near_b.push_back(static_cast<int>(f));
      }
      for (int fa : near_a) {
        const FaceData& a = faces[i][fa];
        for (int fb : near_b) {
          const FaceData& b = faces[j][fb];
          // Opposite normals (within ~2.6 degrees; the plane test below decides).
          if (a.normal.dot(b.normal) > -0.999) continue;
          if (!boxesMeet(a.box, b.box, tolerance)) continue;
          if (!coplanar(a, b, tolerance)) continue;
          thread_local std::vector<Vec3> overlap;
          faceOverlap(a.points, b.points, a.normal, overlap);
          const double area = overlap.size() >= 3 ? geometry::polygonArea(overlap) : 0.0;
          if (realContact(overlap, area, tolerance, min_area)) {
            found[chunk].push_back({i, fa, j, fb, area});
          }
        }
      }
    }
  });
  std::vector<PieceContact> contacts;
  for (const std::vector<PieceContact>& list : found) {
    contacts.insert(contacts.end(), list.begin(), list.end());
  }
  return contacts;
}

}  // namespace rockmass::blocks
