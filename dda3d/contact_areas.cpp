// The contact area between pieces: the overlap of facing faces split among its corners
// (cornerWeights), or the sub-contact points of a face (facePointsToFace), and the samples'
// assignment to the contact entries (docs/dda3d.md, "Contact area").
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>
#include <unordered_map>

#include "dda3d/piece_view.h"
#include "dda3d/polygon2d.h"

namespace rockmass::dda3d::detection {

namespace {

/// Weights of the corners of a convex polygon of area `area` that carry its area: each corner
/// takes half of the two triangles it shares with the centroid (lumped, symmetric for
/// symmetric polygons), corrected by the least change that makes the weights integrate every
/// linear field over the polygon exactly (their sum is the area, their first moments the
/// polygon's), unless that would make a weight negative. Equal for a rectangle.
std::vector<double> cornerWeights(const std::vector<Point2>& polygon, double area) {
  const std::size_t n = polygon.size();
  const Point2 centroid = polygonCentroid(polygon, area);
  std::vector<double> weight(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const double half = 0.25 * cross2(polygon[k] - centroid, polygon[(k + 1) % n] - centroid);
    weight[k] += half;
    weight[(k + 1) % n] += half;
  }
  // Constraints C w = (A, A cx, A cy); least change: w += C^T (C C^T)^-1 (b - C w).
  Eigen::Matrix3d cct = Eigen::Matrix3d::Zero();
  Eigen::Vector3d residual(area, area * centroid.x(), area * centroid.y());
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d row(1.0, polygon[k].x(), polygon[k].y());
    cct += row * row.transpose();
    residual -= weight[k] * row;
  }
  const Eigen::Vector3d lambda = cct.ldlt().solve(residual);
  std::vector<double> exact(n);
  for (std::size_t k = 0; k < n; ++k) {
    exact[k] = weight[k] + lambda.dot(Eigen::Vector3d(1.0, polygon[k].x(), polygon[k].y()));
    if (!(exact[k] >= 0.0)) return weight;
  }
  return exact;
}

/// Fewest sub-contact points that carry a face pair; with fewer, the corners of the overlap
/// carry it (three points resist the tilt of the face both ways).
constexpr std::size_t kMinFacePoints = 3;

/// The sub-contact points of face `fa` of piece `a` against face `fb` of piece `b` facing it:
/// a FacePoint entry for each point whose foot lies in fb and whose gap is within the range,
/// with the point's area.
void facePointsToFace(const PieceView& a, std::size_t fa, const PieceView& b, std::size_t fb,
                      const Range& range, double tolerance, std::vector<Contact>& out) {
  const Plane& plane = b.planes[fb];
  for (int k = a.points->first[fa]; k < a.points->first[fa + 1]; ++k) {
    const FacePoint& point = a.points->points[static_cast<std::size_t>(k)];
    const double gap = plane.normal.dot(point.position) - plane.offset;
    if (gap > range.gap || gap < -range.depth) continue;
    const Vec3 foot = point.position - gap * plane.normal;
    if (!insideFace(*b.shape, b.shape->faces[fb], plane.normal, foot, tolerance)) continue;
    Contact c = pairContact(ContactKind::FacePoint, a, b);
    c.vertex = k;
    c.face = static_cast<int>(fb);
    c.point = point.position;
    c.normal = plane.normal;
    c.gap0 = gap;
    c.foot = foot;
    c.area = point.area;
    c.share = std::min(1.0, point.area / a.planes[fa].area);
    out.push_back(c);
  }
}

}  // namespace

/// The contact area between pieces a and b, as weighted points: for every face of a and face
/// of b that face each other (opposite normals within kAreaCosine, each piece on the other's
/// outer side), their overlap polygon in b's face plane, clipped to where a's face lies within
/// the gap and depth range of b's, split among its corners (cornerWeights). Where the smaller
/// of the two faces has sub-contact points (or only the larger one has, and at least
/// kMinFacePoints of them land on the smaller), those carry the contact instead (FacePoint
/// entries with their own areas, facePointsToFace) and the corners no area.
void overlapAreas(const PieceView& a, const PieceView& b, const Range& range, double tolerance,
                  std::vector<AreaSample>& out, std::vector<Contact>& contacts) {
  for (std::size_t fb = 0; fb < b.planes.size(); ++fb) {
    const Plane& pb = b.planes[fb];
    if (!b.topology->faceExterior(fb)) continue;
    if (pb.area <= 0.0 || pb.normal.dot(a.centroid) - pb.offset <= -tolerance) continue;
    for (std::size_t fa = 0; fa < a.planes.size(); ++fa) {
      const Plane& pa = a.planes[fa];
      const double facing = pa.normal.dot(pb.normal);
      if (facing > -kAreaCosine || pa.area <= 0.0 || !a.topology->faceExterior(fa)) continue;
      if (pa.normal.dot(b.centroid) - pa.offset <= -tolerance) continue;
      // Cheap reject before clipping: a's face wholly beyond the range from b's plane.
      const std::vector<int>& face_a = a.shape->faces[fa];
      double low = std::numeric_limits<double>::infinity(), high = -low;
      for (int v : face_a) {
        const double h = pb.normal.dot(a.shape->vertices[static_cast<std::size_t>(v)]) - pb.offset;
        low = std::min(low, h);
        high = std::max(high, h);
      }
      if (low > range.gap + tolerance || high < -range.depth - tolerance) continue;
      // Sub-contact points: those of the face that has them; of the smaller face when both
      // have (its points lie on the larger one, most of the larger's would miss it), the
      // lower block first when equal. The points of a face larger than the other that miss
      // it are no contact: the overlap is resolved by the grid.
      const int points_a = a.points ? a.points->count(fa) : 0;
      const int points_b = b.points ? b.points->count(fb) : 0;
      if (points_a > 0 || points_b > 0) {
        const bool a_smaller = pa.area < pb.area * (1.0 - 1e-9) ||
                               (pa.area <= pb.area * (1.0 + 1e-9) &&
                                std::pair{a.block, a.piece} < std::pair{b.block, b.piece});
        const std::size_t before = contacts.size();
        if (points_b == 0 || (points_a > 0 && a_smaller)) {
          facePointsToFace(a, fa, b, fb, range, tolerance, contacts);
        } else {
          facePointsToFace(b, fb, a, fa, range, tolerance, contacts);
        }
        // Fewer than kMinFacePoints on the other face (a small rock face under a structure's
        // grid, a sliver of overlap): the grid does not resolve the overlap, its corners do.
        if (contacts.size() - before >= kMinFacePoints) continue;
        contacts.resize(before);
      }
      const Vec3& n = pb.normal;
      const FaceFrame frame(*b.shape, b.shape->faces[fb], n);
      std::vector<Point2> polygon =
          facesOverlap(*a.shape, face_a, *b.shape, b.shape->faces[fb], frame);
      if (polygon.size() < 3) continue;
      // Height of a's face plane over b's along n at a point of b's plane: affine in x.
      const auto height = [&](const Point2& x) {
        return (pa.offset - pa.normal.dot(frame.at(x))) / -facing;
      };
      polygon = clipped(polygon, [&](const Point2& x) { return height(x) - range.gap; });
      if (polygon.size() < 3) continue;
      polygon = clipped(polygon, [&](const Point2& x) { return -range.depth - height(x); });
      if (polygon.size() < 3) continue;
      const double area = polygonArea(polygon);
      if (!(area > tolerance * tolerance)) continue;
      const std::vector<double> weight = cornerWeights(polygon, area);
      for (std::size_t k = 0; k < polygon.size(); ++k) {
        if (weight[k] == 0.0) continue;
        out.push_back({a.block, b.block, a.piece, b.piece, frame.at(polygon[k]), n, weight[k],
                       range.larger() + tolerance});
      }
    }
  }
}

/// Gives every entry its share of the contact area (Contact::area): each area sample goes to
/// the nearest entry between the same two blocks whose normal faces the same way (within
/// kAreaCosine) and whose point lies within the sample's distance of its plane. Entries
/// that take no sample (point contacts between faces that do not face each other) have no
/// area. Samples are taken in their found order within each pair of blocks, so the sums are
/// the same run to run.
void assignAreas(std::vector<Contact>& contacts, const std::vector<AreaSample>& samples) {
  // Key of a pair of pieces of two blocks, the lower block first: (block, block, piece, piece).
  using Key = std::array<int, 4>;
  const auto keyOf = [](int block_a, int piece_a, int block_b, int piece_b) {
    return block_a < block_b ? Key{block_a, block_b, piece_a, piece_b}
                             : Key{block_b, block_a, piece_b, piece_a};
  };
  // The keys are computed once and sorted as compact copies (in parallel; the index breaks
  // ties, so the order is the serial one): read through the contacts, every comparison was
  // a cache miss.
  std::vector<Key> contact_keys(contacts.size()), sample_keys(samples.size());
  tbb::parallel_for(std::size_t{0}, contacts.size(), [&](std::size_t k) {
    Contact& c = contacts[k];
    contact_keys[k] = keyOf(c.block_i, c.piece_i, c.block_j, c.piece_j);
    if (c.kind != ContactKind::FacePoint) c.area = 0.0;
  });
  tbb::parallel_for(std::size_t{0}, samples.size(), [&](std::size_t k) {
    const AreaSample& s = samples[k];
    sample_keys[k] = keyOf(s.block_a, s.piece_a, s.block_b, s.piece_b);
  });
  const auto contactKey = [&](std::size_t k) -> const Key& { return contact_keys[k]; };
  const auto sampleKey = [&](std::size_t k) -> const Key& { return sample_keys[k]; };
  const auto sameBlocks = [](const Key& x, const Key& y) { return x[0] == y[0] && x[1] == y[1]; };
  const auto sortedBy = [](const std::vector<Key>& keys) {
    std::vector<std::pair<Key, std::size_t>> sorted(keys.size());
    tbb::parallel_for(std::size_t{0}, keys.size(), [&](std::size_t k) {
      sorted[k] = {keys[k], k};
    });
    tbb::parallel_sort(sorted.begin(), sorted.end());
    std::vector<std::size_t> order(keys.size());
    tbb::parallel_for(std::size_t{0}, keys.size(),
                      [&](std::size_t k) { order[k] = sorted[k].second; });
    return order;
  };
  std::vector<std::size_t> by_pair = sortedBy(contact_keys);
  const std::vector<std::size_t> order = sortedBy(sample_keys);
  // Groups of samples of one pair of blocks (each touches its own entries only).
  std::vector<std::size_t> group_start;
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k == 0 || !sameBlocks(sampleKey(order[k]), sampleKey(order[k - 1]))) {
      group_start.push_back(k);
    }
  }
  group_start.push_back(order.size());
  using Iterator = std::vector<std::size_t>::iterator;
  // Whether entry c may take `sample`: it faces the sample's way and lies on its plane (within
  // its distance); the squared distance between them in `distance`.
  const auto takes = [](const Contact& c, const AreaSample& sample, double& distance) {
    const Vec3 normal = c.block_j == sample.block_b ? c.normal : Vec3(-c.normal);
    if (normal.dot(sample.normal) < kAreaCosine) return false;
    if (std::abs(sample.normal.dot(c.point - sample.point)) > sample.distance) return false;
    distance = (c.point - sample.point).squaredNorm();
    return true;
  };
  // The entry that takes `sample` among the candidates `visit` shows (their positions in
  // by_pair, FacePoints left out: they carry their own area): the nearest, or among those
  // about as near as it (within kAreaTieShare of the sample's distance) the earliest in
  // by_pair order. `visit(bound, f)` calls f on the candidates, and may skip those whose
  // squared distance is known to exceed `bound` (read after each call); it is called twice,
  // for the nearest distance, then for the earliest within the tie of it.
  const auto tiedNearest = [&](const AreaSample& sample, const auto& visit,
                               double& nearest_distance) {
    nearest_distance = std::numeric_limits<double>::infinity();
    visit(nearest_distance, [&](std::size_t position) {
      double distance = 0.0;
      if (takes(contacts[by_pair[position]], sample, distance)) {
        nearest_distance = std::min(nearest_distance, distance);
      }
    });
    Contact* nearest = nullptr;
    if (!(nearest_distance < std::numeric_limits<double>::infinity())) return nearest;
    // Never below the nearest's own squared distance, whatever the round-off of the root and
    // the square.
    const double within =
        std::max(nearest_distance,
                 std::pow(std::sqrt(nearest_distance) + kAreaTieShare * sample.distance, 2));
    std::size_t nearest_position = 0;
    visit(within, [&](std::size_t position) {
      Contact& c = contacts[by_pair[position]];
      double distance = 0.0;
      if (takes(c, sample, distance) && distance <= within &&
          (nearest == nullptr || position < nearest_position)) {
        nearest = &c;
        nearest_position = position;
      }
    });
    return nearest;
  };
  // The taker among [begin, end), scanned.
  const auto nearestIn = [&](const AreaSample& sample, Iterator begin, Iterator end,
                             double& nearest_distance) {
    const auto scan = [&](const double&, const auto& f) {
      for (auto it = begin; it != end; ++it) {
        if (contacts[*it].kind != ContactKind::FacePoint) {
          f(static_cast<std::size_t>(it - by_pair.begin()));
        }
      }
    };
    return tiedNearest(sample, scan, nearest_distance);
  };
  // The nearest of the whole pair of blocks is searched outward from the sample along x,
  // over the pair's entries sorted by x (a Xiangjiaba region step falls back for about
  // 180 000 of its 420 000 samples, and the linear scan over the pair's entries read 3.4e7
  // entries a step). Each pass stops where the x distance alone exceeds its bound (the
  // squared distance of any entry beyond is larger: a sum of non-negative terms rounds no
  // lower than one of them), so the result is that of the linear scan.
  struct ByX {
    double x;
    std::size_t position;  ///< in by_pair
    bool operator<(const ByX& o) const { return std::tie(x, position) < std::tie(o.x, o.position); }
  };
  const auto nearestByX = [&](const AreaSample& sample, const std::vector<ByX>& sorted,
                              double& nearest_distance) {
    const double x = sample.point.x();
    const auto middle = std::lower_bound(sorted.begin(), sorted.end(), ByX{x, 0});
    const auto outward = [&](const double& bound, const auto& f) {
      const auto beyond = [&](const ByX& e) {
        const double dx = e.x - x;
        return dx * dx > bound;
      };
      for (auto it = middle; it != sorted.end() && !beyond(*it); ++it) f(it->position);
      for (auto it = middle; it != sorted.begin();) {
        --it;
        if (beyond(*it)) break;
        f(it->position);
      }
    };
    return tiedNearest(sample, outward, nearest_distance);
  };
  // Pairs of blocks with fewer entries than this are scanned linearly.
  constexpr std::ptrdiff_t kSortedSearch = 32;
  const auto assignGroup = [&](std::size_t g) {
    const Key first = sampleKey(order[group_start[g]]);
    const Key low{first[0], first[1], std::numeric_limits<int>::min(),
                  std::numeric_limits<int>::min()};
    const Key high{first[0], first[1], std::numeric_limits<int>::max(),
                   std::numeric_limits<int>::max()};
    const auto below = [&](std::size_t k, const Key& value) { return contactKey(k) < value; };
    const Iterator begin = std::lower_bound(by_pair.begin(), by_pair.end(), low, below);
    const Iterator end =
        std::upper_bound(begin, by_pair.end(), high,
                         [&](const Key& value, std::size_t k) { return value < contactKey(k); });
    std::vector<ByX> sorted;  // the pair's entries by x, made at its first fallback
    for (std::size_t k = group_start[g]; k < group_start[g + 1]; ++k) {
      const AreaSample& sample = samples[order[k]];
      // The corner's entry is almost always one of the same two pieces (a vertex of either,
      // or a crossing of their edges): searched first, taken when it lies on the corner (within
      // the sample's distance); else (the entry was kept from another piece of the same block,
      // a duplicate dropped) every entry of the two blocks.
      const Key key = sampleKey(order[k]);
      const Iterator piece_begin = std::lower_bound(begin, end, key, below);
      Iterator piece_end = piece_begin;
      while (piece_end != end && contactKey(*piece_end) == key) ++piece_end;
      double distance = 0.0;
      Contact* nearest = nearestIn(sample, piece_begin, piece_end, distance);
      if (!nearest || distance > sample.distance * sample.distance) {
        if (end - begin < kSortedSearch) {
          nearest = nearestIn(sample, begin, end, distance);
        } else {
          if (sorted.empty()) {
            for (Iterator it = begin; it != end; ++it) {
              if (contacts[*it].kind == ContactKind::FacePoint) continue;  // own area
              sorted.push_back(
                  {contacts[*it].point.x(), static_cast<std::size_t>(it - by_pair.begin())});
            }
            std::sort(sorted.begin(), sorted.end());
          }
          nearest = nearestByX(sample, sorted, distance);
        }
      }
      if (nearest) nearest->area += sample.weight;
    }
  };
  // Groups touch disjoint entries (those of their own pair of blocks), each summed in order:
  // the same sums whatever the threads. Ranges of groups, not a task each: most groups hold
  // a handful of samples.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, group_start.size() - 1, 256),
                    [&](const tbb::blocked_range<std::size_t>& groups) {
                      for (std::size_t g = groups.begin(); g != groups.end(); ++g) assignGroup(g);
                    });
}

}  // namespace rockmass::dda3d::detection
