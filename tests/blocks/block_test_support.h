// Checks and measures shared by the block tests (blocks_tests).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "blocks/block_model.h"
#include "blocks/convex_split.h"
#include "geometry/fracture_network.h"
#include "geometry/polyhedron.h"

namespace rockmass::blocks::test {

/// A cube network [0, side]^3 with the given discs (ids assigned 1..N here).
inline geometry::FractureNetwork cubeNetwork(std::vector<geometry::Disc> discs,
                                             double side = 10.0) {
  geometry::FractureNetwork network;
  network.domain = {geometry::Vec3::Zero(), geometry::Vec3::Constant(side)};
  for (std::size_t i = 0; i < discs.size(); ++i) discs[i].id = static_cast<std::int64_t>(i) + 1;
  network.discs = std::move(discs);
  return network;
}

/// A circular disc of radius r (m); the default crosses a 10 m cube whole.
inline geometry::Disc circle(const geometry::Vec3& center, const geometry::Vec3& normal,
                             double r = 100.0) {
  geometry::Disc d;
  d.center = center;
  d.normal = normal.normalized();
  d.major = d.normal.unitOrthogonal();
  d.a = d.b = r;
  return d;
}

/// Block volumes, sorted ascending (m3).
inline std::vector<double> sortedVolumes(const BlockModel& model) {
  std::vector<double> v;
  for (const Block& b : model.blocks) v.push_back(b.mass.volume);
  std::sort(v.begin(), v.end());
  return v;
}

/// Sum of the block volumes (m3).
inline double totalVolume(const BlockModel& model) {
  double sum = 0.0;
  for (const Block& b : model.blocks) sum += b.mass.volume;
  return sum;
}

/// Checks one piece: every directed edge used once and its reverse once (closed, 2-manifold),
/// Euler V - E + F = 2 (a sphere), planar faces, and every vertex on the inner side of every
/// face plane (convex, outward), all within `tolerance` (m); positive volume.
inline void expectValidPiece(const Piece& piece, double tolerance) {
  const geometry::Polyhedron& p = piece.shape;
  ASSERT_EQ(piece.face_sources.size(), p.faces.size());
  std::map<std::pair<int, int>, int> edges;
  for (const std::vector<int>& face : p.faces) {
    ASSERT_GE(face.size(), 3u);
    for (std::size_t k = 0; k < face.size(); ++k) ++edges[{face[k], face[(k + 1) % face.size()]}];
  }
  for (const auto& [edge, count] : edges) {
    ASSERT_EQ(count, 1) << "edge used twice the same way";
    ASSERT_EQ(edges.count({edge.second, edge.first}), 1u) << "open edge";
  }
  const long v = static_cast<long>(p.vertices.size());
  const long e = static_cast<long>(edges.size()) / 2;
  const long f = static_cast<long>(p.faces.size());
  EXPECT_EQ(v - e + f, 2);
  for (std::size_t k = 0; k < p.faces.size(); ++k) {
    const geometry::Vec3 n = geometry::faceNormal(p, static_cast<int>(k));
    const Plane plane = Plane::through(p.vertices[p.faces[k][0]], n);
    for (int i : p.faces[k]) EXPECT_NEAR(plane.distance(p.vertices[i]), 0.0, tolerance);
    for (const geometry::Vec3& x : p.vertices) EXPECT_LE(plane.distance(x), tolerance);
  }
  EXPECT_GT(geometry::massProperties(p).volume, 0.0);
}

}  // namespace rockmass::blocks::test
