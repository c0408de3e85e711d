// Contact detection on blocks of many convex pieces (the glued blocks of a cut rock mass):
// which piece faces lie on a block's surface, that only those carry contacts, and that the
// broad-phase pairs kept between steps give the same contacts as a broad phase every step,
// and that entries kept between steps follow their blocks as the detection places them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>
#include <vector>

#include "dda3d/contact_detection.h"
#include "geometry/polyhedron.h"
#include "geometry/random.h"
#include "tests/dda3d/cut_pieces.h"

namespace rockmass::dda3d {
namespace {

using geometry::Polyhedron;
using geometry::Vec3;
using testing::blocksOf;
using testing::cutCube;
using testing::kNoPrevious;

double faceArea(const Polyhedron& p, std::size_t f) {
  Vec3 newell = Vec3::Zero();
  const std::vector<int>& face = p.faces[f];
  for (std::size_t k = 0; k < face.size(); ++k) {
    newell += p.vertices[static_cast<std::size_t>(face[k])].cross(
        p.vertices[static_cast<std::size_t>(face[(k + 1) % face.size()])]);
  }
  return 0.5 * newell.norm();
}

/// True when every vertex of face f of p lies on one face of the unit cube.
bool onUnitCubeSurface(const Polyhedron& p, std::size_t f) {
  for (int axis = 0; axis < 3; ++axis) {
    for (double side : {0.0, 1.0}) {
      bool all = true;
      for (int v : p.faces[f]) {
        if (std::abs(p.vertices[static_cast<std::size_t>(v)][axis] - side) > 1e-9) all = false;
      }
      if (all) return true;
    }
  }
  return false;
}

// A cube cut into convex pieces by random planes, as one block: its exterior faces are
// exactly the piece faces on the cube's surface, and their areas sum to the cube's 6 m2
// (exact geometry: the cuts' round-off is 1e-9 m on a 1 m cube).
TEST(ExteriorFaces, ACutCubesSurfaceIsItsSixSides) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const std::vector<Polyhedron> pieces = cutCube(seed, 7);
    ASSERT_GT(pieces.size(), 6u) << "seed " << seed;
    std::vector<PieceTopology> topology;
    for (const Polyhedron& p : pieces) topology.push_back(pieceTopology(p));
    markExterior(pieces, topology);
    double exterior_area = 0.0;
    int interior_faces = 0;
    for (std::size_t p = 0; p < pieces.size(); ++p) {
      bool any = false;
      for (std::size_t f = 0; f < pieces[p].faces.size(); ++f) {
        const bool surface = onUnitCubeSurface(pieces[p], f);
        EXPECT_EQ(topology[p].faceExterior(f), surface) << "seed " << seed << " piece " << p;
        if (topology[p].faceExterior(f)) exterior_area += faceArea(pieces[p], f);
        interior_faces += !topology[p].faceExterior(f);
        any |= surface;
      }
      EXPECT_EQ(topology[p].exterior, any);
      // A vertex or edge is exterior when a face of the surface holds it.
      for (std::size_t v = 0; v < pieces[p].vertices.size(); ++v) {
        bool held = false;
        for (int f : topology[p].vertex_faces[v]) held |= onUnitCubeSurface(pieces[p], f);
        EXPECT_EQ(topology[p].vertexExterior(v), held);
      }
    }
    EXPECT_NEAR(exterior_area, 6.0, 1e-8) << "seed " << seed;
    EXPECT_GT(interior_faces, 6) << "seed " << seed;
  }
}

// Unit cubes in a 3 x 3 x 3 stack, one block: the middle cube is inside (no exterior face,
// no part in contact detection), the 54 unit squares of the outside are the exterior faces.
// A face only partly covered stays exterior: a 1 m cube beside a 2 x 2 m face.
TEST(ExteriorFaces, AStackOfCubesAndAPartlyCoveredFace) {
  std::vector<Polyhedron> pieces;
  for (int x = 0; x < 3; ++x) {
    for (int y = 0; y < 3; ++y) {
      for (int z = 0; z < 3; ++z) {
        pieces.push_back(geometry::boxPolyhedron({Vec3(x, y, z), Vec3(x + 1, y + 1, z + 1)}));
      }
    }
  }
  std::vector<PieceTopology> topology;
  for (const Polyhedron& p : pieces) topology.push_back(pieceTopology(p));
  markExterior(pieces, topology);
  int exterior_faces = 0, inside = 0;
  for (const PieceTopology& t : topology) {
    for (std::size_t f = 0; f < 6; ++f) exterior_faces += t.faceExterior(f);
    inside += !t.exterior;
  }
  EXPECT_EQ(exterior_faces, 54);
  EXPECT_EQ(inside, 1);
  EXPECT_FALSE(topology[13].exterior);  // (1, 1, 1)

  const std::vector<Polyhedron> pair{geometry::boxPolyhedron({Vec3(0, 0, 0), Vec3(1, 1, 1)}),
                                     geometry::boxPolyhedron({Vec3(1, 0, 0), Vec3(3, 2, 2)})};
  std::vector<PieceTopology> pair_topology{pieceTopology(pair[0]), pieceTopology(pair[1])};
  markExterior(pair, pair_topology);
  int small_interior = 0, large_interior = 0;
  for (std::size_t f = 0; f < 6; ++f) {
    small_interior += !pair_topology[0].faceExterior(f);
    large_interior += !pair_topology[1].faceExterior(f);
  }
  EXPECT_EQ(small_interior, 1);  // its x = 1 face, wholly against the large box
  EXPECT_EQ(large_interior, 0);  // its x = 1 face is covered by a quarter only
}

// Two cut cubes, each one block of many pieces, the upper one narrowed to 0.8 x 0.8 m in
// plan (so that no side is flush with the lower one's) and pressed 1e-6 m into the lower:
// every contact entry acts across the horizontal interface (normal +-z) and their areas sum
// to the 0.64 m2 of it. Faces inside a block take no part: a vertex of the upper block near the
// line where two lower pieces meet was matched to the vertical face between them, a spring
// pushing sideways inside the block.
TEST(ExteriorFaces, OnlyTheSurfaceOfAGluedBlockCarriesContacts) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    std::vector<Polyhedron> upper = cutCube(seed, 6), lower = cutCube(seed + 500, 6);
    for (Polyhedron& p : upper) {
      for (Vec3& v : p.vertices) {
        v = Vec3(0.1 + 0.8 * v.x(), 0.1 + 0.8 * v.y(), v.z() + 1.0 - 1e-6);
      }
    }
    const std::vector<BlockState> blocks = blocksOf({upper, lower});
    const std::vector<Contact> contacts = findContacts(blocks, {1e-4, 1e-4}, 1e-3, kNoPrevious);
    ASSERT_GT(contacts.size(), 4u) << "seed " << seed;
    double area = 0.0;
    for (const Contact& c : contacts) {
      EXPECT_NEAR(std::abs(c.normal.z()), 1.0, 1e-9)
          << "seed " << seed << " blocks " << c.block_i << "/" << c.block_j << " point "
          << c.point.transpose() << " kind " << static_cast<int>(c.kind);
      EXPECT_GT(c.gap0, -1e-6 - 1e-9);
      area += c.area;
    }
    EXPECT_NEAR(area, 0.64, 1e-6) << "seed " << seed;
  }
}

// One point of block i found against two pieces of block j, shallow behind the first's top
// (1e-5 m) and 0.1 m deep behind the second's side, keeps only the shallow entry: the face
// it came through. The pieces overlap, standing for a point at the line where two pieces
// meet (inside both within round-off), as a corner resting on a slope of the Xiangjiaba
// quick box was, read 3.7 mm deep behind the region's side plane by the other piece.
TEST(NarrowPhase, APointIsNotHeldDeeperThanItsShallowestEntry) {
  const Polyhedron first = geometry::boxPolyhedron({Vec3(0, 0, 0), Vec3(1, 1, 1)});
  const Polyhedron second = geometry::boxPolyhedron({Vec3(0.4, 0, 0), Vec3(2, 1, 1.5)});
  // A's corner (0.5, 0.5, 1 - 1e-5) has edges along -x, +y and +z: none dives into either face.
  const Polyhedron a =
      geometry::boxPolyhedron({Vec3(-0.5, 0.5, 1.0 - 1e-5), Vec3(0.5, 1.5, 2.0 - 1e-5)});
  const std::vector<BlockState> blocks = blocksOf({{a}, {first, second}});
  const std::vector<Contact> contacts = findContacts(blocks, {0.01, 0.01}, 0.2, kNoPrevious);
  int at_corner = 0;
  for (const Contact& c : contacts) {
    if (c.block_i != 0 || c.kind != ContactKind::VertexFace ||
        (c.point - Vec3(0.5, 0.5, 1.0 - 1e-5)).norm() > 1e-12) {
      continue;
    }
    ++at_corner;
    EXPECT_NEAR(c.normal.z(), 1.0, 1e-12);
    EXPECT_NEAR(c.gap0, -1e-5, 1e-12);
  }
  EXPECT_EQ(at_corner, 1);
}

/// The unit cube cut by 6 random planes (`seed`): pairs of neighbouring pieces glued into
/// blocks, the rest blocks of their own, each block pulled 1 % away from the cube's centre so
/// that gaps open and close as they drift.
std::vector<BlockState> gluedCutCubePulledApart(std::uint64_t seed) {
  std::vector<std::vector<Polyhedron>> groups;
  const std::vector<Polyhedron> pieces = cutCube(seed, 6);
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    if (p % 3 == 0 && p + 1 < pieces.size()) {
      groups.push_back({pieces[p], pieces[p + 1]});
      ++p;
    } else {
      groups.push_back({pieces[p]});
    }
  }
  for (std::vector<Polyhedron>& group : groups) {
    Vec3 centre = Vec3::Zero();
    int n = 0;
    for (const Polyhedron& p : group) {
      for (const Vec3& v : p.vertices) centre += v, ++n;
    }
    centre /= n;
    for (Polyhedron& p : group) {
      for (Vec3& v : p.vertices) v += 0.01 * (centre - Vec3::Constant(0.5));
    }
  }
  return blocksOf(groups);
}

/// Moves `block` rigidly by `shift` and a small turn `turn` (rad, first order) about its
/// centroid; returns the farthest any vertex moved (m).
double moveRigidly(BlockState& block, const Vec3& shift, const Vec3& turn) {
  const Vec3 centre = block.centroid;
  double farthest = 0.0;
  for (Polyhedron& p : block.pieces) {
    for (Vec3& v : p.vertices) {
      const Vec3 next = centre + shift + (v - centre) + turn.cross(v - centre);
      farthest = std::max(farthest, (next - v).norm());
      v = next;
    }
  }
  block.updateMassProperties();
  return farthest;
}

// The broad-phase pairs kept between steps (CandidatePairs) give exactly the contacts of a
// broad phase run every step, while the blocks drift by random steps of up to 3 mm and turn
// by up to 2 mrad, over 40 steps: the pairs are found again only when a block has moved
// farther than its margin, and a pair that comes into reach is never missed.
TEST(CandidatePairs, KeptPairsGiveTheContactsOfAFreshBroadPhase) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    std::vector<BlockState> blocks = gluedCutCubePulledApart(seed);
    const std::vector<double> reach(blocks.size(), 0.004);
    CandidatePairs kept(0.01);
    geometry::Rng rng = geometry::makeRng(seed, 7);
    const auto uniform = [&rng] { return static_cast<double>(rng() % 2000001) / 1e6 - 1.0; };
    int compared = 0;
    for (int step = 0; step < 40; ++step) {
      const std::vector<Contact> fresh = findContacts(blocks, reach, 0.02, kNoPrevious);
      const std::vector<Contact> reused = findContacts(blocks, reach, 0.02, kNoPrevious, &kept);
      ASSERT_EQ(fresh.size(), reused.size()) << "seed " << seed << " step " << step;
      for (std::size_t k = 0; k < fresh.size(); ++k) {
        EXPECT_EQ(fresh[k].block_i, reused[k].block_i);
        EXPECT_EQ(fresh[k].piece_i, reused[k].piece_i);
        EXPECT_EQ(fresh[k].block_j, reused[k].block_j);
        EXPECT_EQ(fresh[k].piece_j, reused[k].piece_j);
        EXPECT_EQ(fresh[k].point, reused[k].point);
        EXPECT_EQ(fresh[k].gap0, reused[k].gap0);
        EXPECT_EQ(fresh[k].area, reused[k].area);
      }
      compared += static_cast<int>(fresh.size());
      // Each block moves rigidly: a translation of up to 3 mm a side and a turn of up to
      // 2 mrad about its centroid; CandidatePairs learns a bound on how far it moved.
      for (std::size_t b = 0; b < blocks.size(); ++b) {
        const Vec3 shift = 0.003 * Vec3(uniform(), uniform(), uniform());
        const Vec3 turn = 0.002 * Vec3(uniform(), uniform(), uniform());
        kept.moved(b, moveRigidly(blocks[b], shift, turn));
      }
    }
    EXPECT_GT(compared, 500) << "seed " << seed;
    // Found again as the blocks drifted past the margin, but not every step.
    EXPECT_GT(kept.builds(), 2) << "seed " << seed;
    EXPECT_LT(kept.builds(), 30) << "seed " << seed;
  }
}

/// An entry's identity: its kind, pieces, and vertex and face, or edges.
std::tuple<int, int, int, int, int, int, int> entryKey(const Contact& c) {
  const bool edges = c.kind == ContactKind::EdgeEdge;
  return {static_cast<int>(c.kind),    c.block_i, c.piece_i,
          edges ? c.edge_i : c.vertex, c.block_j, c.piece_j,
          edges ? c.edge_j : c.face};
}

// Kept entries (DdaSettings::detection.search_margin) follow their blocks: refreshContacts
// must give each entry the point, normal and gap the narrow phase computes for the same
// vertex and face (or edges) at the blocks' new place, to the bit (the same formulas), and
// report the deepest penetration among them. The blocks of a cut cube, pulled 1 % apart,
// drift rigidly by up to 20 um and 20 urad a side a step (a resting block moves 1e-6 m a
// step on the Xiangjiaba foundation): nearly every entry is found again by the detection.
TEST(KeptContacts, FollowTheirBlocksAsTheDetectionPlacesThem) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    std::vector<BlockState> blocks = gluedCutCubePulledApart(seed);
    const std::vector<double> reach(blocks.size(), 0.004);
    std::vector<Contact> kept = findContacts(blocks, reach, 0.02, kNoPrevious);
    ASSERT_GT(kept.size(), 100u) << "seed " << seed;
    geometry::Rng rng = geometry::makeRng(seed, 11);
    const auto uniform = [&rng] { return static_cast<double>(rng() % 2000001) / 1e6 - 1.0; };
    int compared = 0, edges = 0;
    for (int step = 0; step < 10; ++step) {
      for (BlockState& block : blocks) {
        const Vec3 shift = 2e-5 * Vec3(uniform(), uniform(), uniform());
        const Vec3 turn = 2e-5 * Vec3(uniform(), uniform(), uniform());
        moveRigidly(block, shift, turn);
      }
      const double deepest = refreshContacts(blocks, kept);
      double expected_deepest = 0.0;
      for (const Contact& c : kept) expected_deepest = std::max(expected_deepest, -c.gap0);
      EXPECT_EQ(deepest, expected_deepest);
      const std::vector<Contact> fresh = findContacts(blocks, reach, 0.02, kNoPrevious);
      std::map<std::tuple<int, int, int, int, int, int, int>, const Contact*> found;
      for (const Contact& c : fresh) found[entryKey(c)] = &c;
      int matched = 0;
      for (const Contact& c : kept) {
        const auto it = found.find(entryKey(c));
        if (it == found.end()) continue;
        const Contact& f = *it->second;
        ++matched;
        edges += c.kind == ContactKind::EdgeEdge;
        EXPECT_EQ(c.point, f.point) << "seed " << seed << " step " << step;
        EXPECT_EQ(c.normal, f.normal) << "seed " << seed << " step " << step;
        EXPECT_EQ(c.gap0, f.gap0) << "seed " << seed << " step " << step;
        EXPECT_EQ(c.foot, f.foot) << "seed " << seed << " step " << step;
      }
      // Small motions: nearly every kept entry is one the detection finds again.
      EXPECT_GT(matched, 0.9 * static_cast<double>(kept.size())) << "seed " << seed;
      compared += matched;
    }
    EXPECT_GT(compared, 1000) << "seed " << seed;
    EXPECT_GT(edges, 0) << "seed " << seed;
  }
}

}  // namespace
}  // namespace rockmass::dda3d
