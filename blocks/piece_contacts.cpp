#include "blocks/piece_contacts.h"

#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <mutex>

#include "blocks/convex_split.h"
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
};

std::vector<FaceData> faceData(const Piece& piece) {
  std::vector<FaceData> out;
  out.reserve(piece.shape.faces.size());
  for (std::size_t f = 0; f < piece.shape.faces.size(); ++f) {
    FaceData d;
    d.normal = geometry::faceNormal(piece.shape, static_cast<int>(f));
    Vec3 mean = Vec3::Zero();
    for (int v : piece.shape.faces[f]) {
      d.points.push_back(piece.shape.vertices[v]);
      mean += piece.shape.vertices[v];
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

}  // namespace

double faceOverlapArea(const std::vector<Vec3>& a, const std::vector<Vec3>& b, const Vec3& normal) {
  std::vector<Vec3> clipped = a;
  // b runs clockwise about `normal`: walking it backwards, its inside is on the left.
  const std::size_t n = b.size();
  for (std::size_t k = 0; k < n && clipped.size() >= 3; ++k) {
    const Vec3& p = b[(k + 1) % n];
    const Vec3& q = b[k];
    const Vec3 inward = normal.cross(q - p);
    const double length = inward.norm();
    if (length == 0.0) continue;
    clipped = clipPolygon(clipped, Plane::through(p, inward / length));
  }
  return clipped.size() >= 3 ? geometry::polygonArea(clipped) : 0.0;
}

std::vector<PieceContact> findPieceContacts(std::span<const Piece> pieces, double tolerance,
                                            double min_area) {
  std::vector<BoxWithIndex> boxes;
  boxes.reserve(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const geometry::Box b = geometry::bounds(pieces[i].shape).enlarged(tolerance);
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
  for (std::size_t i = 0; i < pieces.size(); ++i) faces[i] = faceData(pieces[i]);

  std::vector<PieceContact> contacts;
  for (const auto& [i, j] : pairs) {
    for (std::size_t fa = 0; fa < faces[i].size(); ++fa) {
      const FaceData& a = faces[i][fa];
      for (std::size_t fb = 0; fb < faces[j].size(); ++fb) {
        const FaceData& b = faces[j][fb];
        // Opposite normals (within ~2.6 degrees; the plane test below decides).
        if (a.normal.dot(b.normal) > -0.999) continue;
        if (!inPlane(a, b, tolerance) || !inPlane(b, a, tolerance)) continue;
        const double area = faceOverlapArea(a.points, b.points, a.normal);
        if (area > min_area) {
          contacts.push_back({i, static_cast<int>(fa), j, static_cast<int>(fb), area});
        }
      }
    }
  }
  return contacts;
}

}  // namespace rockmass::blocks
