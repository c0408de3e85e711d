#include "blocks/piece_soundness.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "blocks/union_find.h"
#include "geometry/disc.h"
#include "geometry/polyhedron.h"

namespace rockmass::blocks {
namespace {

using geometry::Vec3;

/// A merge that changes the piece's volume by more than this fraction does not remove a
/// tiny feature but flattens a thin piece (two discs 1e-9 m apart, issue 3's degenerate
/// case, must give a slab block): it is refused. Merges on the Xiangjiaba quick model
/// change a piece's volume by 1e-6 to 1.3e-4 of it.
constexpr double kMaxMergeVolumeChange = 1e-2;

/// Removes cyclically repeated neighbours (a, a) and spikes (a, b, a -> a) until none is
/// left.
void simplifyRing(std::vector<int>& ring) {
  bool changed = true;
  while (changed && ring.size() >= 2) {
    changed = false;
    for (std::size_t k = 0; k < ring.size() && ring.size() >= 2; ++k) {
      const std::size_t next = (k + 1) % ring.size();
      if (ring[k] == ring[next]) {
        ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(next));
        changed = true;
        break;
      }
      if (ring.size() >= 3) {
        const std::size_t after = (k + 2) % ring.size();
        if (ring[k] == ring[after]) {  // spike k -> next -> k: drop next and the return
          const std::size_t first = std::min(next, after);
          const std::size_t second = std::max(next, after);
          ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(second));
          ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(first));
          changed = true;
          break;
        }
      }
    }
  }
}

/// Splits a ring in which a vertex occurs twice (a pinch) into simple rings.
void splitPinches(std::vector<int> ring, std::vector<std::vector<int>>& out) {
  simplifyRing(ring);
  if (ring.size() < 3) return;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    for (std::size_t j = i + 1; j < ring.size(); ++j) {
      if (ring[i] != ring[j]) continue;
      std::vector<int> first(ring.begin() + static_cast<std::ptrdiff_t>(i),
                             ring.begin() + static_cast<std::ptrdiff_t>(j));
      std::vector<int> second(ring.begin() + static_cast<std::ptrdiff_t>(j), ring.end());
      second.insert(second.end(), ring.begin(), ring.begin() + static_cast<std::ptrdiff_t>(i));
      splitPinches(std::move(first), out);
      splitPinches(std::move(second), out);
      return;
    }
  }
  out.push_back(std::move(ring));
}

/// True when every directed edge occurs once and its reverse once (a closed, consistently
/// oriented surface).
bool closedSurface(const std::vector<std::vector<int>>& faces) {
  std::map<std::pair<int, int>, int> count;
  for (const std::vector<int>& ring : faces) {
    for (std::size_t k = 0; k < ring.size(); ++k) {
      ++count[{ring[k], ring[(k + 1) % ring.size()]}];
    }
  }
  for (const auto& [edge, n] : count) {
    if (n != 1) return false;
    const auto reverse = count.find({edge.second, edge.first});
    if (reverse == count.end() || reverse->second != 1) return false;
  }
  return !faces.empty();
}

}  // namespace

SoundnessTolerances soundnessTolerances(const geometry::Box& domain) {
  SoundnessTolerances t;
  t.distance = 1e-7 * domain.diagonal();
  t.area = t.distance * t.distance;
  t.volume = 1e-15 * domain.volume();
  return t;
}

SoundnessReport& SoundnessReport::operator+=(const SoundnessReport& other) {
  folded_pieces += other.folded_pieces;
  folded_volume += other.folded_volume;
  merged_vertices += other.merged_vertices;
  removed_faces += other.removed_faces;
  unrepaired += other.unrepaired;
  volume_change += other.volume_change;
  return *this;
}

bool hasCloseVertices(const Piece& piece, const SoundnessTolerances& tolerances) {
  const std::vector<Vec3>& vertices = piece.shape.vertices;
  const double limit = tolerances.distance * tolerances.distance;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if ((vertices[i] - vertices[j]).squaredNorm() < limit) return true;
    }
  }
  return false;
}

std::optional<SoundPiece> soundPiece(const Piece& piece, const SoundnessTolerances& tolerances,
                                     SoundPieceReport* report) {
  SoundPieceReport local;
  const std::vector<Vec3>& vertices = piece.shape.vertices;
  const std::size_t n = vertices.size();
  // Clusters of vertices closer than the distance tolerance; each maps to its first vertex.
  UnionFind clusters(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if ((vertices[i] - vertices[j]).squaredNorm() < tolerances.distance * tolerances.distance) {
        clusters.unite(static_cast<int>(i), static_cast<int>(j));
      }
    }
  }
  // Per root: the centre of its cluster's bounding box. Unlike the mean, it does not move
  // when a cutter has already snapped two of the cluster's vertices into one.
  std::vector<int> target(n);
  std::vector<Vec3> low = vertices;
  std::vector<Vec3> high = vertices;
  for (std::size_t i = 0; i < n; ++i) {
    target[i] = clusters.find(static_cast<int>(i));
    const auto root = static_cast<std::size_t>(target[i]);
    if (root != i) {
      ++local.merged_vertices;
      low[root] = low[root].cwiseMin(vertices[i]);
      high[root] = high[root].cwiseMax(vertices[i]);
    }
  }
  std::vector<Vec3> position(n);
  for (std::size_t i = 0; i < n; ++i) position[i] = 0.5 * (low[i] + high[i]);

  // Faces after the merge: collapsed ones dropped, spikes and pinches resolved.
  std::vector<std::vector<int>> faces;
  std::vector<int> origin;
  for (std::size_t f = 0; f < piece.shape.faces.size(); ++f) {
    std::vector<int> ring;
    for (const int v : piece.shape.faces[f]) ring.push_back(target[static_cast<std::size_t>(v)]);
    std::vector<std::vector<int>> parts;
    if (local.merged_vertices > 0) {
      splitPinches(std::move(ring), parts);
    } else {
      parts.push_back(std::move(ring));
    }
    if (parts.empty()) ++local.removed_faces;
    for (std::vector<int>& part : parts) {
      faces.push_back(std::move(part));
      origin.push_back(static_cast<int>(f));
    }
  }

  SoundPiece out;
  if (local.merged_vertices > 0 && closedSurface(faces)) {
    std::vector<int> renumber(n, -1);
    for (std::vector<int>& ring : faces) {
      for (int& v : ring) {
        if (renumber[static_cast<std::size_t>(v)] < 0) {
          renumber[static_cast<std::size_t>(v)] = static_cast<int>(out.piece.shape.vertices.size());
          out.piece.shape.vertices.push_back(position[static_cast<std::size_t>(v)]);
        }
        v = renumber[static_cast<std::size_t>(v)];
      }
    }
    // A face with a merged corner is planar only within the distance tolerance, and its
    // fan triangulation (massProperties) then depends on the corner it starts from: start
    // every face at its lowest corner (x, then y, then z, each compared with a tolerance far
    // below the distance between two corners), so that both cutters fan it alike.
    const double tie = 1e-3 * tolerances.distance;
    const auto lower = [&](int a, int b) {
      const Vec3& p = out.piece.shape.vertices[static_cast<std::size_t>(a)];
      const Vec3& q = out.piece.shape.vertices[static_cast<std::size_t>(b)];
      for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(p[axis] - q[axis]) > tie) return p[axis] < q[axis];
      }
      return false;
    };
    for (std::vector<int>& ring : faces) {
      std::rotate(ring.begin(), std::min_element(ring.begin(), ring.end(), lower), ring.end());
    }
    out.piece.shape.faces = std::move(faces);
    out.face_origin = std::move(origin);
  }
  const double volume = geometry::massProperties(piece.shape).volume;
  if (!out.piece.shape.faces.empty() &&
      std::abs(geometry::massProperties(out.piece.shape).volume - volume) >
          kMaxMergeVolumeChange * std::abs(volume)) {
    out = SoundPiece{};  // the merge would flatten a thin piece: refused
  }
  if (out.piece.shape.faces.empty()) {
    // Nothing to merge, or a merge that would not close or would flatten the piece: the
    // piece as it is.
    local.unrepaired = local.merged_vertices > 0;
    local.merged_vertices = 0;
    local.removed_faces = 0;
    out.piece.shape = piece.shape;
    out.face_origin.resize(piece.shape.faces.size());
    for (std::size_t f = 0; f < out.face_origin.size(); ++f) {
      out.face_origin[f] = static_cast<int>(f);
    }
  }
  for (const int f : out.face_origin) {
    out.piece.face_sources.push_back(piece.face_sources[static_cast<std::size_t>(f)]);
  }
  if (report != nullptr) *report = local;
  if (!(geometry::massProperties(out.piece.shape).volume >= tolerances.volume)) return std::nullopt;
  return out;
}

void addToReport(const Piece& piece, const std::optional<SoundPiece>& sound,
                 const SoundPieceReport& piece_report, SoundnessReport& report) {
  const double before = geometry::massProperties(piece.shape).volume;
  if (!sound) {
    ++report.folded_pieces;
    report.folded_volume += before;
    return;
  }
  report.merged_vertices += piece_report.merged_vertices;
  report.removed_faces += piece_report.removed_faces;
  report.unrepaired += piece_report.unrepaired ? 1 : 0;
  if (piece_report.merged_vertices > 0) {
    report.volume_change += std::abs(geometry::massProperties(sound->piece.shape).volume - before);
  }
}

}  // namespace rockmass::blocks
