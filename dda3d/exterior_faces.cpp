// Which faces of a block's convex pieces lie on the block's surface (markExterior).
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "dda3d/block_state.h"
#include "dda3d/contact_detection.h"
#include "dda3d/polygon2d.h"
#include "geometry/box.h"

namespace rockmass::dda3d {

using geometry::Polyhedron;
using geometry::Vec3;

namespace {

/// Two faces cover each other only when their normals are opposite within this (1 - cos):
/// faces of one cut plane split between two pieces are opposite to round-off.
constexpr double kOppositeSlack = 1e-6;
/// A face counts as covered when the faces over it cover all but this share of its area.
constexpr double kUncoveredShare = 1e-6;

struct FacePlane {
  Vec3 normal = Vec3::Zero();
  double offset = 0.0;
  double area = 0.0;
};

FacePlane planeOf(const Polyhedron& piece, const std::vector<int>& face) {
  Vec3 newell = Vec3::Zero();
  for (std::size_t k = 0; k < face.size(); ++k) {
    newell += piece.vertices[static_cast<std::size_t>(face[k])].cross(
        piece.vertices[static_cast<std::size_t>(face[(k + 1) % face.size()])]);
  }
  const double twice = newell.norm();
  if (!(twice > 0.0)) return {};
  const Vec3 n = newell / twice;
  return {n, n.dot(piece.vertices[static_cast<std::size_t>(face[0])]), 0.5 * twice};
}

/// Area of face `fb` of `b` that face `fa` of `a` covers, both in one plane facing each other.
double coveredArea(const Polyhedron& a, const std::vector<int>& face_a, const Polyhedron& b,
                   const std::vector<int>& face_b, const Vec3& n) {
  Vec3 t1, t2;
  tangents(n, t1, t2);
  const Vec3 origin = b.vertices[static_cast<std::size_t>(face_b[0])];
  const auto flat = [&](const Vec3& x) {
    return Point2((x - origin).dot(t1), (x - origin).dot(t2));
  };
  // b's face counter-clockwise about n; a's face, seen from the other side, reversed.
  std::vector<Point2> polygon;
  for (auto v = face_a.rbegin(); v != face_a.rend(); ++v) {
    polygon.push_back(flat(a.vertices[static_cast<std::size_t>(*v)]));
  }
  for (std::size_t k = 0; k < face_b.size() && polygon.size() >= 3; ++k) {
    const Point2 p = flat(b.vertices[static_cast<std::size_t>(face_b[k])]);
    const Point2 q = flat(b.vertices[static_cast<std::size_t>(face_b[(k + 1) % face_b.size()])]);
    const Point2 edge = q - p;
    polygon = clipped(polygon, [&](const Point2& x) { return -cross2(edge, x - p); });
  }
  return polygon.size() >= 3 ? std::max(0.0, polygonArea(polygon)) : 0.0;
}

/// PieceTopology::block_vertex of every piece: vertices closer than 1e-9 of the block's
/// size (the cutter's round-off on a corner shared by pieces) are one corner, numbered in
/// the order of their first copy (piece, then vertex).
void numberCorners(const std::vector<Polyhedron>& pieces, std::vector<PieceTopology>& topology) {
  struct Copy {
    Vec3 at;
    std::size_t piece, vertex, serial;
  };
  std::vector<Copy> copies;
  geometry::Box all{Vec3::Constant(std::numeric_limits<double>::infinity()),
                    Vec3::Constant(-std::numeric_limits<double>::infinity())};
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    for (std::size_t v = 0; v < pieces[p].vertices.size(); ++v) {
      copies.push_back({pieces[p].vertices[v], p, v, copies.size()});
      all.min = all.min.cwiseMin(pieces[p].vertices[v]);
      all.max = all.max.cwiseMax(pieces[p].vertices[v]);
    }
  }
  const double tolerance = copies.empty() ? 0.0 : 1e-9 * all.diagonal();
  // Union of copies within the tolerance (a sweep along x), each group named by its
  // earliest copy.
  std::vector<std::size_t> root(copies.size());
  for (std::size_t k = 0; k < root.size(); ++k) root[k] = k;
  const auto find = [&](std::size_t k) {
    while (root[k] != k) k = root[k] = root[root[k]];
    return k;
  };
  std::vector<std::size_t> by_x(copies.size());
  for (std::size_t k = 0; k < by_x.size(); ++k) by_x[k] = k;
  std::sort(by_x.begin(), by_x.end(), [&](std::size_t a, std::size_t b) {
    return std::pair{copies[a].at.x(), a} < std::pair{copies[b].at.x(), b};
  });
  for (std::size_t i = 0; i < by_x.size(); ++i) {
    for (std::size_t j = i + 1; j < by_x.size(); ++j) {
      const Copy& a = copies[by_x[i]];
      const Copy& b = copies[by_x[j]];
      if (b.at.x() - a.at.x() > tolerance) break;
      if ((a.at - b.at).cwiseAbs().maxCoeff() > tolerance) continue;
      const std::size_t ra = find(a.serial), rb = find(b.serial);
      if (ra != rb) root[std::max(ra, rb)] = std::min(ra, rb);
    }
  }
  std::vector<int> number(copies.size(), -1);
  int corners = 0;
  for (std::size_t k = 0; k < copies.size(); ++k) {
    const std::size_t r = find(k);
    if (number[r] < 0) number[r] = corners++;
    number[k] = number[r];
  }
  for (std::size_t p = 0; p < pieces.size(); ++p)
    topology[p].block_vertex.assign(pieces[p].vertices.size(), -1);
  for (const Copy& c : copies) topology[c.piece].block_vertex[c.vertex] = number[c.serial];
}

}  // namespace

void markExterior(const std::vector<Polyhedron>& pieces, std::vector<PieceTopology>& topology) {
  for (PieceTopology& t : topology) {
    t.exterior_faces.clear();
    t.exterior_vertices.clear();
    t.exterior_edges.clear();
    t.exterior = true;
  }
  numberCorners(pieces, topology);
  if (pieces.size() < 2) return;
  std::vector<geometry::Box> boxes;
  std::vector<std::vector<FacePlane>> planes(pieces.size());
  std::vector<std::vector<double>> covered(pieces.size());
  double size = 0.0;
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    boxes.push_back(geometry::bounds(pieces[p]));
    size = std::max(size, boxes.back().diagonal());
    for (const std::vector<int>& face : pieces[p].faces)
      planes[p].push_back(planeOf(pieces[p], face));
    covered[p].assign(pieces[p].faces.size(), 0.0);
  }
  const double tolerance = 1e-9 * size;
  // Pieces in order of their boxes' lower x: a sweep finds the pairs whose boxes touch.
  std::vector<std::size_t> order(pieces.size());
  for (std::size_t p = 0; p < order.size(); ++p) order[p] = p;
  std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    return std::pair{boxes[x].min.x(), x} < std::pair{boxes[y].min.x(), y};
  });
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::size_t a = order[i];
    const geometry::Box grown_a = boxes[a].enlarged(tolerance);
    for (std::size_t j = i + 1; j < order.size(); ++j) {
      const std::size_t b = order[j];
      if (boxes[b].min.x() > grown_a.max.x()) break;
      if (!((boxes[b].min.array() <= grown_a.max.array()).all() &&
            (grown_a.min.array() <= boxes[b].max.array()).all())) {
        continue;
      }
      for (std::size_t fa = 0; fa < planes[a].size(); ++fa) {
        const FacePlane& pa = planes[a][fa];
        if (!(pa.area > 0.0)) continue;
        for (std::size_t fb = 0; fb < planes[b].size(); ++fb) {
          const FacePlane& pb = planes[b][fb];
          if (!(pb.area > 0.0) || pa.normal.dot(pb.normal) > -1.0 + kOppositeSlack) continue;
          bool coplanar = true;
          for (int v : pieces[a].faces[fa]) {
            const double h =
                pb.normal.dot(pieces[a].vertices[static_cast<std::size_t>(v)]) - pb.offset;
            if (std::abs(h) > tolerance) coplanar = false;
          }
          if (!coplanar) continue;
          const double area = coveredArea(pieces[a], pieces[a].faces[fa], pieces[b],
                                          pieces[b].faces[fb], pb.normal);
          covered[a][fa] += area;
          covered[b][fb] += area;
        }
      }
    }
  }
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    PieceTopology& t = topology[p];
    t.exterior_faces.assign(pieces[p].faces.size(), 1);
    t.exterior = false;
    for (std::size_t f = 0; f < planes[p].size(); ++f) {
      t.exterior_faces[f] = covered[p][f] < planes[p][f].area * (1.0 - kUncoveredShare) ? 1 : 0;
      if (t.exterior_faces[f]) t.exterior = true;
    }
    t.exterior_vertices.assign(pieces[p].vertices.size(), 0);
    for (std::size_t v = 0; v < t.vertex_faces.size(); ++v) {
      for (int f : t.vertex_faces[v]) {
        if (t.exterior_faces[static_cast<std::size_t>(f)]) t.exterior_vertices[v] = 1;
      }
    }
    t.exterior_edges.assign(t.edges.size(), 0);
    for (std::size_t f = 0; f < pieces[p].faces.size(); ++f) {
      if (!t.exterior_faces[f]) continue;
      const std::vector<int>& face = pieces[p].faces[f];
      for (std::size_t k = 0; k < face.size(); ++k) {
        const int x = face[k], y = face[(k + 1) % face.size()];
        for (std::size_t e = 0; e < t.edges.size(); ++e) {
          if (t.edges[e] == std::array<int, 2>{std::min(x, y), std::max(x, y)}) {
            t.exterior_edges[e] = 1;
          }
        }
      }
    }
  }
}

}  // namespace rockmass::dda3d
