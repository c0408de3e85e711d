// Which faces of a block's convex pieces lie on the block's surface (markExterior).
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "blocks/union_find.h"
#include "dda3d/block_state.h"
#include "dda3d/piece_view.h"
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
  // earliest copy (the union-find's root is the smallest id).
  blocks::UnionFind corner(copies.size());
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
      corner.unite(static_cast<int>(a.serial), static_cast<int>(b.serial));
    }
  }
  std::vector<int> number(copies.size(), -1);
  int corners = 0;
  for (std::size_t k = 0; k < copies.size(); ++k) {
    const auto r = static_cast<std::size_t>(corner.find(static_cast<int>(k)));
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
  std::vector<std::vector<detection::Plane>> planes(pieces.size());
  std::vector<std::vector<double>> covered(pieces.size());
  double size = 0.0;
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    boxes.push_back(geometry::bounds(pieces[p]));
    size = std::max(size, boxes.back().diagonal());
    planes[p] = detection::facePlanes(pieces[p]);
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
        const detection::Plane& pa = planes[a][fa];
        if (!(pa.area > 0.0)) continue;
        for (std::size_t fb = 0; fb < planes[b].size(); ++fb) {
          const detection::Plane& pb = planes[b][fb];
          if (!(pb.area > 0.0) || pa.normal.dot(pb.normal) > -1.0 + kOppositeSlack) continue;
          bool coplanar = true;
          for (int v : pieces[a].faces[fa]) {
            const double h =
                pb.normal.dot(pieces[a].vertices[static_cast<std::size_t>(v)]) - pb.offset;
            if (std::abs(h) > tolerance) coplanar = false;
          }
          if (!coplanar) continue;
          const std::vector<Point2> overlap = detection::facesOverlap(
              pieces[a], pieces[a].faces[fa], pieces[b], pieces[b].faces[fb],
              detection::FaceFrame(pieces[b], pieces[b].faces[fb], pb.normal));
          const double area = overlap.size() >= 3 ? std::max(0.0, polygonArea(overlap)) : 0.0;
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
    for (std::size_t e = 0; e < t.edges.size(); ++e) {
      for (int f : t.edgeFaces(e)) {
        if (t.exterior_faces[static_cast<std::size_t>(f)]) t.exterior_edges[e] = 1;
      }
    }
  }
}

}  // namespace rockmass::dda3d
