#include "blocks/piece_contacts.h"

#include <CGAL/box_intersection_d.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <tuple>

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

/// True when points[b_begin, b_end) is the loop points[a_begin, a_end) run backwards (the
/// same face seen from its other side), with bitwise equal points.
bool sameLoop(const std::vector<Vec3>& points, std::uint32_t a_begin, std::uint32_t a_end,
              std::uint32_t b_begin, std::uint32_t b_end) {
  const std::uint32_t n = a_end - a_begin;
  if (b_end - b_begin != n) return false;
  std::uint32_t start = n;
  for (std::uint32_t k = 0; k < n; ++k) {
    if (points[b_begin + k] == points[a_begin]) {
      start = k;
      break;
    }
  }
  if (start == n) return false;
  for (std::uint32_t k = 0; k < n; ++k) {
    // a[k] pairs with b[start - k] (backwards).
    if (points[a_begin + k] != points[b_begin + (start + n - k) % n]) return false;
  }
  return true;
}

}  // namespace

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
          if (!inPlane(a, b, tolerance) || !inPlane(b, a, tolerance)) continue;
          const double area = faceOverlapArea(a.points, b.points, a.normal);
          if (area > min_area) found[chunk].push_back({i, fa, j, fb, area});
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

std::vector<PieceContact> findContactsByPlane(std::span<const Piece> pieces,
                                              const std::vector<std::vector<int>>& planes,
                                              double tolerance, double min_area) {
  // One flat table of faces in piece order (sequential memory access; built in parallel),
  // their points in one array: no allocation per face.
  std::vector<std::size_t> first_face(pieces.size() + 1, 0);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    first_face[i + 1] = first_face[i] + pieces[i].shape.faces.size();
  }
  const std::size_t face_count = first_face.back();
  struct Face {
    int plane, piece, face;
    std::uint32_t begin, end;  ///< range in `points`
    Vec3 normal;
    double offset;
    geometry::Box box;
  };
  std::vector<std::size_t> first_point(pieces.size() + 1, 0);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    std::size_t n = 0;
    for (const std::vector<int>& face : pieces[i].shape.faces) n += face.size();
    first_point[i + 1] = first_point[i] + n;
  }
  std::vector<Face> faces(face_count);
  std::vector<Vec3> points(first_point.back());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pieces.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const geometry::Polyhedron& shape = pieces[i].shape;
                        std::size_t at = first_point[i];
                        for (std::size_t f = 0; f < shape.faces.size(); ++f) {
                          Face& d = faces[first_face[i] + f];
                          d.plane = planes[i][f];
                          d.piece = static_cast<int>(i);
                          d.face = static_cast<int>(f);
                          d.begin = static_cast<std::uint32_t>(at);
                          Vec3 newell = Vec3::Zero(), mean = Vec3::Zero();
                          const std::vector<int>& loop = shape.faces[f];
                          d.box = {shape.vertices[loop[0]], shape.vertices[loop[0]]};
                          for (std::size_t k = 0; k < loop.size(); ++k) {
                            const Vec3& p = shape.vertices[loop[k]];
                            const Vec3& q = shape.vertices[loop[k + 1 == loop.size() ? 0 : k + 1]];
                            newell += p.cross(q);
                            mean += p;
                            d.box.min = d.box.min.cwiseMin(p);
                            d.box.max = d.box.max.cwiseMax(p);
                            points[at++] = p;
                          }
                          d.end = static_cast<std::uint32_t>(at);
                          const double length = newell.norm();
                          d.normal = length > 0.0 ? Vec3(newell / length) : Vec3(Vec3::Zero());
                          d.offset = d.normal.dot(mean / static_cast<double>(loop.size()));
                        }
                      }
                    });
  // Faces grouped by plane (ties in piece and face order: deterministic).
  std::vector<std::uint32_t> order(face_count);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return faces[a].plane != faces[b].plane ? faces[a].plane < faces[b].plane : a < b;
  });
  std::vector<std::pair<std::size_t, std::size_t>> groups;  // [begin, end) in order
  for (std::size_t b = 0; b < order.size();) {
    std::size_t e = b + 1;
    while (e < order.size() && faces[order[e]].plane == faces[order[b]].plane) ++e;
    if (e - b >= 2) groups.emplace_back(b, e);
    b = e;
  }
  const auto inPlaneOf = [&](const Face& a, const Face& b) {
    for (std::uint32_t k = b.begin; k < b.end; ++k) {
      if (std::abs(a.normal.dot(points[k]) - a.offset) > tolerance) return false;
    }
    return true;
  };
  // True when an edge line of face e has every point of face x on its outer side or within
  // `tolerance` of it: the faces share at most a strip of that width (area below min_area),
  // decided without constructing points (most candidate pairs only touch along an edge).
  const auto separated = [&](const Face& e, const Face& x) {
    const std::uint32_t n = e.end - e.begin;
    for (std::uint32_t k = 0; k < n; ++k) {
      const Vec3& p = points[e.begin + k];
      const Vec3& q = points[e.begin + (k + 1 == n ? 0 : k + 1)];
      const Vec3 inward = e.normal.cross(q - p);
      const double length = inward.norm();
      if (length == 0.0) continue;
      const Vec3 unit = inward / length;
      bool outside = true;
      for (std::uint32_t j = x.begin; j < x.end && outside; ++j) {
        outside = unit.dot(points[j] - p) <= tolerance;
      }
      if (outside) return true;
    }
    return false;
  };
  const auto loopOf = [&](const Face& f, std::vector<Vec3>& out) {
    out.assign(points.begin() + f.begin, points.begin() + f.end);
  };
  std::vector<std::vector<PieceContact>> found(groups.size());
  tbb::parallel_for(std::size_t{0}, groups.size(), [&](std::size_t g) {
    const auto [begin, end] = groups[g];
    const Vec3 reference = faces[order[begin]].normal;
    std::vector<BoxWithIndex> front, back;  // faces along and against the reference normal
    for (std::size_t k = begin; k < end; ++k) {
      const Face& d = faces[order[k]];
      const geometry::Box b = d.box.enlarged(tolerance);
      const BoxWithIndex box(
          CGAL::Bbox_3(b.min.x(), b.min.y(), b.min.z(), b.max.x(), b.max.y(), b.max.z()),
          static_cast<int>(order[k]));
      (d.normal.dot(reference) > 0.0 ? front : back).push_back(box);
    }
    if (front.empty() || back.empty()) return;
    std::vector<std::pair<int, int>> candidates;
    const auto report = [&](const BoxWithIndex& a, const BoxWithIndex& b) {
      candidates.emplace_back(a.info(), b.info());
    };
    if (front.size() == 1 || back.size() == 1) {
      // One face against many: a plain loop beats the segment tree's set-up.
      for (const BoxWithIndex& a : front) {
        for (const BoxWithIndex& b : back) {
          if (CGAL::do_overlap(a.bbox(), b.bbox())) report(a, b);
        }
      }
    } else {
      CGAL::box_intersection_d(front.begin(), front.end(), back.begin(), back.end(), report);
    }
    std::vector<Vec3> loop_a, loop_b;
    for (const auto& [ka, kb] : candidates) {
      const Face& a = faces[ka];
      const Face& b = faces[kb];
      if (a.piece == b.piece) continue;
      if (a.normal.dot(b.normal) > -0.999) continue;
      if (!inPlaneOf(a, b) || !inPlaneOf(b, a)) continue;
      loopOf(a, loop_a);
      double area = 0.0;
      if (sameLoop(points, a.begin, a.end, b.begin, b.end)) {
        // The common case: both sides of one cut, neither split further since. Shared points
        // are bitwise equal (the splitter computes each crossing point once).
        area = geometry::polygonArea(loop_a);
      } else if (!separated(a, b) && !separated(b, a)) {
        loopOf(b, loop_b);
        area = faceOverlapArea(loop_a, loop_b, a.normal);
      }
      if (area <= min_area) continue;
      if (a.piece < b.piece) {
        found[g].push_back({a.piece, a.face, b.piece, b.face, area});
      } else {
        found[g].push_back({b.piece, b.face, a.piece, a.face, area});
      }
    }
  });
  std::vector<PieceContact> contacts;
  for (const std::vector<PieceContact>& list : found) {
    contacts.insert(contacts.end(), list.begin(), list.end());
  }
  std::sort(contacts.begin(), contacts.end(), [](const PieceContact& x, const PieceContact& y) {
    return std::tie(x.piece_a, x.piece_b, x.face_a, x.face_b) <
           std::tie(y.piece_a, y.piece_b, y.face_a, y.face_b);
  });
  return contacts;
}

}  // namespace rockmass::blocks
