// The contact search on face tables (piece_contacts.h): faces grouped by plane id or named
// by candidate pairs, their pair tests, and the batches that decide contacts in a fixed order.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>
#include <tuple>

#include "blocks/convex_split.h"
#include "blocks/piece_contacts.h"
#include "blocks/union_find.h"
#include "geometry/disc.h"

namespace rockmass::blocks {

namespace {

using geometry::Vec3;
using BoxWithIndex = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

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

/// Fills face entry d (piece, face) from its `n` corners point(0) .. point(n - 1), writing
/// its points and edge normals from `begin` on: the Newell unit normal, the plane offset
/// through the corners' mean, the bounding box and every edge's inward unit normal.
template <class Point>
void fillFace(ContactFaces::Face& d, int piece, int face, std::uint32_t begin, std::size_t n,
              const Point& point, Vec3* points, Vec3* inward) {
  d.piece = piece;
  d.face = face;
  d.begin = begin;
  d.end = begin + static_cast<std::uint32_t>(n);
  Vec3 newell = Vec3::Zero(), mean = Vec3::Zero();
  d.box = {point(0), point(0)};
  std::uint32_t at = d.begin;
  for (std::size_t v = 0; v < n; ++v) {
    const Vec3& p = point(v);
    const Vec3& q = point(v + 1 == n ? 0 : v + 1);
    newell += p.cross(q);
    mean += p;
    d.box.min = d.box.min.cwiseMin(p);
    d.box.max = d.box.max.cwiseMax(p);
    points[at++] = p;
  }
  const double length = newell.norm();
  d.normal = length > 0.0 ? Vec3(newell / length) : Vec3(Vec3::Zero());
  d.offset = d.normal.dot(mean / static_cast<double>(n));
  const std::uint32_t count = d.end - d.begin;
  for (std::uint32_t v = 0; v < count; ++v) {
    const Vec3& p = points[d.begin + v];
    const Vec3& q = points[d.begin + (v + 1 == count ? 0 : v + 1)];
    const Vec3 in = d.normal.cross(q - p);
    const double edge = in.norm();
    inward[d.begin + v] = edge == 0.0 ? Vec3(Vec3::Zero()) : Vec3(in / edge);
  }
}

/// Fills table.faces[k] from face f of piece i (its points go to points[begin..]).
void fillFromPiece(ContactFaces& table, std::span<const Piece> pieces, int i, int f, std::size_t k,
                   std::uint32_t begin) {
  const geometry::Polyhedron& shape = pieces[i].shape;
  const std::vector<int>& loop = shape.faces[f];
  fillFace(
      table.faces[k], i, f, begin, loop.size(),
      [&](std::size_t v) -> const Vec3& { return shape.vertices[loop[v]]; }, table.points.data(),
      table.inward.data());
}

using PlaneFaces = ContactFaces;

/// A face with no slot in a table (left out).
constexpr std::uint32_t kNoSlot = std::numeric_limits<std::uint32_t>::max();

/// first_face[i]: the index of piece i's face 0 among all faces in piece order (and the
/// count of all faces at the end).
std::vector<std::size_t> firstFaces(std::span<const Piece> pieces) {
  std::vector<std::size_t> first_face(pieces.size() + 1, 0);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    first_face[i + 1] = first_face[i] + pieces[i].shape.faces.size();
  }
  return first_face;
}

/// The table of `first_point.size() - 1` faces: face f of piece i goes to slot
/// slot[first_face[i] + f] (none when kNoSlot), its points from first_point[slot]. Reads the
/// pieces in order (sequential in memory: a piece's faces were allocated together) and writes
/// each face to its slot; in slot order every face was a cache miss.
PlaneFaces faceTable(std::span<const Piece> pieces, const std::vector<std::size_t>& first_face,
                     const std::vector<std::uint32_t>& slot,
                     const std::vector<std::uint32_t>& first_point) {
  PlaneFaces table;
  table.faces.resize(first_point.size() - 1);
  table.points.resize(first_point.back());
  table.inward.resize(first_point.back());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pieces.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        for (std::size_t f = 0; f < pieces[i].shape.faces.size(); ++f) {
                          const std::uint32_t k = slot[first_face[i] + f];
                          if (k == kNoSlot) continue;
                          fillFromPiece(table, pieces, static_cast<int>(i), static_cast<int>(f), k,
                                        first_point[k]);
                        }
                      }
                    });
  return table;
}

/// The faces of all pieces with a plane id >= 0, in plane order (faces with a negative id are
/// left out), for findContactsByPlane.
/// `plane_of(i, f)`: the plane id of face f of piece i.
template <class PlaneOf>
PlaneFaces planeFaces(std::span<const Piece> pieces, const PlaneOf& plane_of) {
  // Faces in piece order: their plane ids and sizes.
  const std::vector<std::size_t> first_face = firstFaces(pieces);
  const std::size_t all = first_face.back();
  std::vector<int> plane(all);
  std::size_t count = 0;
  int lowest = std::numeric_limits<int>::max(), highest = std::numeric_limits<int>::min();
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    for (std::size_t f = 0; f < pieces[i].shape.faces.size(); ++f) {
      const int id = plane_of(i, f);
      plane[first_face[i] + f] = id;
      if (id < 0) continue;
      ++count;
      lowest = std::min(lowest, id);
      highest = std::max(highest, id);
    }
  }
  // slot[k]: where face k (piece order) goes in plane order, ties in piece and face order
  // (a counting sort by plane id when the ids are dense, else a stable sort).
  std::vector<std::uint32_t> slot(all, kNoSlot);
  if (count > 0 &&
      static_cast<long long>(highest) - lowest < 16LL * static_cast<long long>(count) + 4096) {
    std::vector<std::uint32_t> start(static_cast<std::size_t>(highest - lowest) + 2, 0);
    for (std::size_t k = 0; k < all; ++k) {
      if (plane[k] >= 0) ++start[plane[k] - lowest + 1];
    }
    for (std::size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
    for (std::size_t k = 0; k < all; ++k) {
      if (plane[k] >= 0) slot[k] = start[plane[k] - lowest]++;
    }
  } else if (count > 0) {
    std::vector<std::uint32_t> order;
    order.reserve(count);
    for (std::size_t k = 0; k < all; ++k) {
      if (plane[k] >= 0) order.push_back(static_cast<std::uint32_t>(k));
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return plane[a] < plane[b]; });
    for (std::size_t k = 0; k < count; ++k) slot[order[k]] = static_cast<std::uint32_t>(k);
  }
  std::vector<std::uint32_t> sorted_size(count), sorted_plane(count);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    for (std::size_t f = 0; f < pieces[i].shape.faces.size(); ++f) {
      const std::uint32_t k = slot[first_face[i] + f];
      if (k == kNoSlot) continue;
      sorted_size[k] = static_cast<std::uint32_t>(pieces[i].shape.faces[f].size());
      sorted_plane[k] = static_cast<std::uint32_t>(plane[first_face[i] + f] - lowest);
    }
  }
  std::vector<std::uint32_t> first_point(count + 1, 0);
  for (std::size_t k = 0; k < count; ++k) first_point[k + 1] = first_point[k] + sorted_size[k];

  PlaneFaces out = faceTable(pieces, first_face, slot, first_point);
  for (std::size_t b = 0; b < count;) {
    std::size_t e = b + 1;
    while (e < count && sorted_plane[e] == sorted_plane[b]) ++e;
    if (e - b >= 2) out.groups.emplace_back(b, e);
    b = e;
  }
  return out;
}

/// The candidate pairs of one plane group: faces along and against the group's first
/// normal whose boxes (grown by `tolerance`) meet, in CGAL's report order.
std::vector<std::pair<std::uint32_t, std::uint32_t>> candidatePairs(const PlaneFaces& table,
                                                                    std::size_t begin,
                                                                    std::size_t end,
                                                                    double tolerance) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> candidates;
  const Vec3 reference = table.faces[begin].normal;
  std::vector<BoxWithIndex> front, back;
  for (std::size_t k = begin; k < end; ++k) {
    const PlaneFaces::Face& d = table.faces[k];
    const geometry::Box b = d.box.enlarged(tolerance);
    const BoxWithIndex box(
        CGAL::Bbox_3(b.min.x(), b.min.y(), b.min.z(), b.max.x(), b.max.y(), b.max.z()),
        static_cast<int>(k));
    (d.normal.dot(reference) > 0.0 ? front : back).push_back(box);
  }
  if (front.empty() || back.empty()) return candidates;
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
  return candidates;
}

/// Union-find over the clusters one batch meets (ids are cluster roots, 0 .. ids - 1). The
/// slot of each root met is kept in a per-thread array of all ids (no hashing), which the
/// destructor clears again; a batch runs on one thread from start to end.
class LocalClusters {
 public:
  explicit LocalClusters(std::size_t ids) {
    thread_local std::vector<int> index;
    if (index.size() < ids) index.assign(ids, -1);
    index_ = &index;
  }
  LocalClusters(const LocalClusters&) = delete;
  LocalClusters& operator=(const LocalClusters&) = delete;
  ~LocalClusters() {
    for (int root : label_) (*index_)[static_cast<std::size_t>(root)] = -1;
  }
  int find(int root) {
    int i = (*index_)[static_cast<std::size_t>(root)];
    if (i < 0) return root;
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return label_[i];
  }
  void unite(int a, int b) {
    const int ia = slot(a), ib = slot(b);
    int ra = ia, rb = ib;
    while (parent_[ra] != ra) ra = parent_[ra];
    while (parent_[rb] != rb) rb = parent_[rb];
    if (ra != rb) parent_[rb] = ra;
  }

 private:
  int slot(int root) {
    int& at = (*index_)[static_cast<std::size_t>(root)];
    if (at < 0) {
      at = static_cast<int>(parent_.size());
      parent_.push_back(at);
      label_.push_back(root);
    }
    return at;
  }
  std::vector<int>* index_ = nullptr;
  std::vector<int> parent_, label_;
};

/// The pair tests of the contact search on one face table.
class PairTests {
 public:
  using Face = PlaneFaces::Face;
  PairTests(const PlaneFaces& table, double tolerance, double min_area, int piece_offset = 0)
      : table_(table),
        points_(table.points),
        tolerance_(tolerance),
        min_area_(min_area),
        piece_offset_(piece_offset) {}

  const Face& face(std::uint32_t k) const { return table_.faces[k]; }
  /// The piece of a face, counting the pieces of all tables.
  int piece(const Face& f) const { return f.piece + piece_offset_; }

  /// Different pieces, opposite normals (within ~2.6 degrees; the plane test decides).
  bool viable(const Face& a, const Face& b) const {
    return a.piece != b.piece && a.normal.dot(b.normal) <= -0.999;
  }
  /// Both sides of one cut: bitwise the same loop.
  bool mirrored(const Face& a, const Face& b) const {
    return sameLoop(points_, a.begin, a.end, b.begin, b.end);
  }
  /// The two faces lie in one plane: the smaller face's points near the larger face's plane
  /// (the plane of a tiny face is too uncertain to test a large one against; see coplanar).
  bool coplanarFaces(const Face& a, const Face& b) const {
    const bool a_larger =
        (a.box.max - a.box.min).squaredNorm() >= (b.box.max - b.box.min).squaredNorm();
    return a_larger ? inPlaneOf(a, b) : inPlaneOf(b, a);
  }
  void loopOf(const Face& f, std::vector<Vec3>& out) const {
    out.assign(points_.begin() + f.begin, points_.begin() + f.end);
  }
  PieceContact contactOf(const Face& a, const Face& b, double area) const {
    const int pa = piece(a), pb = piece(b);
    return pa < pb ? PieceContact{pa, a.face, pb, b.face, area}
                   : PieceContact{pb, b.face, pa, a.face, area};
  }
  /// The overlap of a candidate pair whose faces are not the same loop, into `overlap`
  /// (fewer than 3 points when they do not touch with area), and its area (m2). Separated
  /// faces share at most a strip thinner than the tolerance: never a real contact.
  double overlapOf(const Face& a, const Face& b, std::vector<Vec3>& loop_a,
                   std::vector<Vec3>& loop_b, std::vector<Vec3>& overlap) const {
    overlap.clear();
    if (separated(a, b) || separated(b, a) || !coplanarFaces(a, b)) return 0.0;
    loopOf(a, loop_a);
    loopOf(b, loop_b);
    faceOverlap(loop_a, loop_b, a.normal, overlap);
    return overlap.size() >= 3 ? geometry::polygonArea(overlap) : 0.0;
  }
  bool real(const std::vector<Vec3>& overlap, double area) const {
    return realContact(overlap, area, tolerance_, min_area_);
  }

 private:
  bool inPlaneOf(const Face& a, const Face& b) const {
    for (std::uint32_t k = b.begin; k < b.end; ++k) {
      if (std::abs(a.normal.dot(points_[k]) - a.offset) > tolerance_) return false;
    }
    return true;
  }
  /// True when an edge line of face e has every point of face x on its outer side or within
  /// the tolerance of it: the faces share at most a strip of that width, decided without
  /// constructing points (most candidate pairs only touch along an edge).
  bool separated(const Face& e, const Face& x) const {
    for (std::uint32_t k = e.begin; k < e.end; ++k) {
      const Vec3& unit = table_.inward[k];
      if (unit.x() == 0.0 && unit.y() == 0.0 && unit.z() == 0.0) continue;
      const Vec3& p = points_[k];
      bool outside = true;
      for (std::uint32_t j = x.begin; j < x.end && outside; ++j) {
        outside = unit.dot(points_[j] - p) <= tolerance_;
      }
      if (outside) return true;
    }
    return false;
  }
  const PlaneFaces& table_;
  const std::vector<Vec3>& points_;
  double tolerance_, min_area_;
  int piece_offset_ = 0;
};

using TablePairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

/// Finds and decides the contacts among candidate pairs of table faces given in `batches`
/// (`candidates(g)` gives batch g): first every mirrored pair (both sides of one cut), then,
/// per batch, the others whose pieces are not yet glued. Contacts and their sources go to
/// found[g] / decided[g]. Deterministic: the batches are fixed, not the threads.
template <class TestsOf, class Candidates>
void decideBatches(const TestsOf& tests_of, std::size_t piece_count, std::size_t batches,
                   const Candidates& candidates, const ContactDecision& decide,
                   std::vector<std::vector<PieceContact>>& found,
                   std::vector<std::vector<FaceSource>>& decided) {
  // Pass 1: the mirrored pairs (cheap), decided; the other candidates wait.
  std::vector<TablePairs> waiting(batches);
  tbb::parallel_for(std::size_t{0}, batches, [&](std::size_t g) {
    const PairTests& tests = tests_of(g);
    std::vector<Vec3> loop;
    for (const auto& [ka, kb] : candidates(g)) {
      const PlaneFaces::Face& a = tests.face(ka);
      const PlaneFaces::Face& b = tests.face(kb);
      if (!tests.viable(a, b)) continue;
      if (!tests.mirrored(a, b)) {
        waiting[g].emplace_back(ka, kb);
        continue;
      }
      if (!tests.coplanarFaces(a, b)) continue;
      tests.loopOf(a, loop);
      const double area = geometry::polygonArea(loop);
      if (!tests.real(loop, area)) continue;
      found[g].push_back(tests.contactOf(a, b, area));
      decided[g].push_back(decide(found[g].back(), true));
    }
  });
  UnionFind clusters(piece_count);
  for (std::size_t g = 0; g < batches; ++g) {
    for (std::size_t k = 0; k < found[g].size(); ++k) {
      if (decided[g][k].kind == FaceKind::Fictitious) {
        clusters.unite(found[g][k].piece_a, found[g][k].piece_b);
      }
    }
  }
  std::vector<int> root(piece_count);
  for (std::size_t i = 0; i < piece_count; ++i) root[i] = clusters.find(static_cast<int>(i));
  // Pass 2: the others, skipping pairs already glued (by pass 1, or earlier in the batch).
  tbb::parallel_for(std::size_t{0}, batches, [&](std::size_t g) {
    const PairTests& tests = tests_of(g);
    LocalClusters local(piece_count);
    std::vector<Vec3> loop_a, loop_b, overlap;
    for (const auto& [ka, kb] : waiting[g]) {
      const PlaneFaces::Face& a = tests.face(ka);
      const PlaneFaces::Face& b = tests.face(kb);
      const int ra = local.find(root[tests.piece(a)]), rb = local.find(root[tests.piece(b)]);
      if (ra == rb) continue;
      const double area = tests.overlapOf(a, b, loop_a, loop_b, overlap);
      if (!tests.real(overlap, area)) continue;
      found[g].push_back(tests.contactOf(a, b, area));
      decided[g].push_back(decide(found[g].back(), false));
      if (decided[g].back().kind == FaceKind::Fictitious) local.unite(ra, rb);
    }
  });
}

/// The contacts of all batches in (piece_a, piece_b, face_a, face_b) order, their decided
/// sources (when `decide`) in the same order into `sources`.
std::vector<PieceContact> sortedContacts(const std::vector<std::vector<PieceContact>>& found,
                                         const std::vector<std::vector<FaceSource>>& decided,
                                         bool with_sources, std::vector<FaceSource>* sources) {
  std::vector<PieceContact> contacts;
  std::vector<FaceSource> contact_sources;
  for (std::size_t g = 0; g < found.size(); ++g) {
    contacts.insert(contacts.end(), found[g].begin(), found[g].end());
    contact_sources.insert(contact_sources.end(), decided[g].begin(), decided[g].end());
  }
  std::vector<std::uint32_t> order(contacts.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t i, std::uint32_t j) {
    const PieceContact& x = contacts[i];
    const PieceContact& y = contacts[j];
    return std::tie(x.piece_a, x.piece_b, x.face_a, x.face_b, i) <
           std::tie(y.piece_a, y.piece_b, y.face_a, y.face_b, j);
  });
  std::vector<PieceContact> sorted;
  sorted.reserve(contacts.size());
  for (std::uint32_t k : order) sorted.push_back(contacts[k]);
  if (sources != nullptr) {
    sources->clear();
    if (with_sources) {
      sources->reserve(order.size());
      for (std::uint32_t k : order) sources->push_back(contact_sources[k]);
    }
  }
  return sorted;
}

}  // namespace

namespace {

template <class PlaneOf>
std::vector<PieceContact> contactsByPlane(std::span<const Piece> pieces, const PlaneOf& plane_of,
                                          double tolerance, double min_area,
                                          const ContactDecision& decide,
                                          std::vector<FaceSource>* sources) {
  const PlaneFaces table = planeFaces(pieces, plane_of);
  const PairTests tests(table, tolerance, min_area);
  const std::size_t group_count = table.groups.size();
  std::vector<std::vector<PieceContact>> found(group_count);
  std::vector<std::vector<FaceSource>> decided(group_count);
  if (!decide) {
    tbb::parallel_for(std::size_t{0}, group_count, [&](std::size_t g) {
      const auto [begin, end] = table.groups[g];
      std::vector<Vec3> loop_a, loop_b, overlap;
      for (const auto& [ka, kb] : candidatePairs(table, begin, end, tolerance)) {
        const PlaneFaces::Face& a = table.faces[ka];
        const PlaneFaces::Face& b = table.faces[kb];
        if (!tests.viable(a, b)) continue;
        double area = 0.0;
        if (tests.mirrored(a, b)) {
          // The common case: both sides of one cut, neither split further since. Shared
          // points are bitwise equal (the splitter computes each crossing point once).
          if (!tests.coplanarFaces(a, b)) continue;
          tests.loopOf(a, overlap);
          area = geometry::polygonArea(overlap);
        } else {
          area = tests.overlapOf(a, b, loop_a, loop_b, overlap);
        }
        if (tests.real(overlap, area)) found[g].push_back(tests.contactOf(a, b, area));
      }
    });
  } else {
    return decidePlaneContacts(table, pieces.size(), tolerance, min_area, decide, sources);
  }
  return sortedContacts(found, decided, static_cast<bool>(decide), sources);
}

}  // namespace

std::vector<PieceContact> decidePlaneContacts(const ContactFaces& table, std::size_t piece_count,
                                              double tolerance, double min_area,
                                              const ContactDecision& decide,
                                              std::vector<FaceSource>* sources) {
  const PairTests tests(table, tolerance, min_area);
  const std::size_t group_count = table.groups.size();
  std::vector<std::vector<PieceContact>> found(group_count);
  std::vector<std::vector<FaceSource>> decided(group_count);
  decideBatches([&](std::size_t) -> const PairTests& { return tests; }, piece_count, group_count,
                [&](std::size_t g) {
                  return candidatePairs(table, table.groups[g].first, table.groups[g].second,
                                        tolerance);
                },
                decide, found, decided);
  return sortedContacts(found, decided, true, sources);
}

std::vector<PieceContact> findContactsByPlane(std::span<const Piece> pieces,
                                              const std::vector<std::vector<int>>& planes,
                                              double tolerance, double min_area,
                                              const ContactDecision& decide,
                                              std::vector<FaceSource>* sources) {
  return contactsByPlane(
      pieces, [&](std::size_t i, std::size_t f) { return planes[i][f]; }, tolerance, min_area,
      decide, sources);
}

std::vector<PieceContact> findContactsByPlane(std::span<const Piece> pieces,
                                              std::span<const int> face_planes, double tolerance,
                                              double min_area, const ContactDecision& decide,
                                              std::vector<FaceSource>* sources) {
  const std::vector<std::size_t> first_face = firstFaces(pieces);
  return contactsByPlane(
      pieces, [&](std::size_t i, std::size_t f) { return face_planes[first_face[i] + f]; },
      tolerance, min_area, decide, sources);
}

std::vector<PieceContact> decideCandidateContacts(std::span<const Piece> pieces,
                                                  std::span<const FacePair> candidates,
                                                  double tolerance, double min_area,
                                                  const ContactDecision& decide,
                                                  std::vector<FaceSource>* sources) {
  // Table slots for the faces the candidates name, in first-use order.
  const std::vector<std::size_t> first_face = firstFaces(pieces);
  std::vector<std::uint32_t> slot(first_face.back(), kNoSlot);
  std::vector<FaceRef> refs;
  std::vector<std::uint32_t> first_point{0};
  TablePairs pairs;
  pairs.reserve(candidates.size());
  const auto slotOf = [&](const FaceRef& r) {
    std::uint32_t& k = slot[first_face[r.piece] + r.face];
    if (k == kNoSlot) {
      k = static_cast<std::uint32_t>(refs.size());
      refs.push_back(r);
      first_point.push_back(first_point.back() +
                            static_cast<std::uint32_t>(pieces[r.piece].shape.faces[r.face].size()));
    }
    return k;
  };
  for (const FacePair& c : candidates) pairs.emplace_back(slotOf(c.first), slotOf(c.second));
  const PlaneFaces table = faceTable(pieces, first_face, slot, first_point);
  return decideTableContacts(table, pieces.size(), pairs, tolerance, min_area, decide, sources);
}

std::uint32_t ContactFaces::add(int piece, int face, std::span<const Vec3> vertices,
                                std::span<const int> loop) {
  const auto k = static_cast<std::uint32_t>(faces.size());
  const auto begin = static_cast<std::uint32_t>(points.size());
  faces.emplace_back();
  points.resize(points.size() + loop.size());
  inward.resize(inward.size() + loop.size());
  fillFace(
      faces.back(), piece, face, begin, loop.size(),
      [&](std::size_t v) -> const Vec3& { return vertices[loop[v]]; }, points.data(),
      inward.data());
  return k;
}

void ContactFaces::set(std::uint32_t k, int piece, int face, std::uint32_t begin,
                       std::span<const Vec3> vertices, std::span<const int> loop) {
  fillFace(
      faces[k], piece, face, begin, loop.size(),
      [&](std::size_t v) -> const Vec3& { return vertices[loop[v]]; }, points.data(),
      inward.data());
}

void ContactFaces::append(const ContactFaces& other, int piece_offset) {
  const auto shift = static_cast<std::uint32_t>(points.size());
  for (Face d : other.faces) {
    d.piece += piece_offset;
    d.begin += shift;
    d.end += shift;
    faces.push_back(d);
  }
  points.insert(points.end(), other.points.begin(), other.points.end());
  inward.insert(inward.end(), other.inward.begin(), other.inward.end());
}

std::vector<PieceContact> decideTableContacts(
    const ContactFaces& table, std::size_t piece_count,
    std::span<const std::pair<std::uint32_t, std::uint32_t>> pairs, double tolerance,
    double min_area, const ContactDecision& decide, std::vector<FaceSource>* sources) {
  const PairTests tests(table, tolerance, min_area);
  // Fixed batches of candidates (not one per thread), so the result does not depend on the
  // thread count.
  constexpr std::size_t kBatch = 4096;
  const std::size_t batches = (pairs.size() + kBatch - 1) / kBatch;
  std::vector<std::vector<PieceContact>> found(batches);
  std::vector<std::vector<FaceSource>> decided(batches);
  decideBatches([&](std::size_t) -> const PairTests& { return tests; }, piece_count, batches,
                [&](std::size_t g) {
                  return pairs.subspan(g * kBatch,
                                       std::min(pairs.size(), (g + 1) * kBatch) - g * kBatch);
                },
                decide, found, decided);
  return sortedContacts(found, decided, true, sources);
}

std::optional<double> mirroredContactArea(std::span<const Vec3> a, std::span<const Vec3> b,
                                          double tolerance, double min_area) {
  // The numbers fillFace gives the two faces (Newell unit normals, a's offset through the
  // mean of its corners) and the tests PairTests makes of a mirrored pair: viable (opposite
  // normals), coplanarFaces (equal boxes: b's corners near a's plane), real.
  const auto newell = [](std::span<const Vec3> points) {
    Vec3 sum = Vec3::Zero();
    for (std::size_t v = 0; v < points.size(); ++v) {
      sum += points[v].cross(points[v + 1 == points.size() ? 0 : v + 1]);
    }
    const double length = sum.norm();
    return length > 0.0 ? Vec3(sum / length) : Vec3(Vec3::Zero());
  };
  const Vec3 normal_a = newell(a);
  if (normal_a.dot(newell(b)) > -0.999) return std::nullopt;
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : a) mean += p;
  const double offset = normal_a.dot(mean / static_cast<double>(a.size()));
  for (const Vec3& p : b) {
    if (std::abs(normal_a.dot(p) - offset) > tolerance) return std::nullopt;
  }
  thread_local std::vector<Vec3> loop;
  loop.assign(a.begin(), a.end());
  const double area = geometry::polygonArea(loop);
  if (!realContact(loop, area, tolerance, min_area)) return std::nullopt;
  return area;
}

std::vector<PieceContact> decideTableContacts(std::span<const ContactTablePart> parts,
                                              std::size_t piece_count, double tolerance,
                                              double min_area, const ContactDecision& decide,
                                              std::vector<FaceSource>* sources) {
  constexpr std::size_t kBatch = 4096;
  std::vector<PairTests> tests;
  tests.reserve(parts.size());
  // Batch g: part part_of[g], its pairs from first_pair[g] on (kBatch at most); a part's
  // first batch starts with its mirrored contacts, decided here.
  std::vector<std::size_t> part_of, first_pair, first_batch;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    tests.emplace_back(*parts[p].table, tolerance, min_area, parts[p].piece_offset);
    first_batch.push_back(part_of.size());
    for (std::size_t k = 0; k < std::max<std::size_t>(parts[p].pairs.size(), 1); k += kBatch) {
      part_of.push_back(p);
      first_pair.push_back(k);
    }
  }
  const std::size_t batches = part_of.size();
  std::vector<std::vector<PieceContact>> found(batches);
  std::vector<std::vector<FaceSource>> decided(batches);
  tbb::parallel_for(std::size_t{0}, parts.size(), [&](std::size_t p) {
    std::vector<PieceContact>& list = found[first_batch[p]];
    std::vector<FaceSource>& sources_of = decided[first_batch[p]];
    list.reserve(parts[p].mirrored.size());
    sources_of.reserve(parts[p].mirrored.size());
    for (PieceContact c : parts[p].mirrored) {
      c.piece_a += parts[p].piece_offset;
      c.piece_b += parts[p].piece_offset;
      list.push_back(c);
      sources_of.push_back(decide(c, true));
    }
  });
  decideBatches(
      [&](std::size_t g) -> const PairTests& { return tests[part_of[g]]; }, piece_count, batches,
      [&](std::size_t g) {
        const auto& pairs = parts[part_of[g]].pairs;
        return pairs.empty()
                   ? pairs
                   : pairs.subspan(first_pair[g], std::min(pairs.size() - first_pair[g], kBatch));
      },
      decide, found, decided);
  return sortedContacts(found, decided, true, sources);
}

}  // namespace rockmass::blocks
