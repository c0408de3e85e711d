// The fast cutter against volumes known in closed form, degenerate inputs, and the
// invariants every cut must keep: closed convex outward pieces, volume conservation, and
// disc faces that lie inside their disc.
#include "blocks/fast_cutter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <tuple>

#include "blocks/convex_split.h"
#include "blocks/piece_contacts.h"
#include "blocks/union_find.h"
#include "geometry/disc.h"
#include "geometry/orientation.h"
#include "scenarios/disc_scenes.h"
#include "tests/blocks/block_test_support.h"

namespace rockmass::blocks {
namespace {

using geometry::Disc;
using geometry::FractureNetwork;
using geometry::Vec3;
using test::circle;
using test::cubeNetwork;
using test::expectValidPiece;
using test::totalVolume;

/// A rectangle in the plane z = z0 (a FAB-like polygon disc).
Disc rectangleZ(double x0, double x1, double y0, double y1, double z0) {
  return geometry::discFromPolygon({{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}});
}

/// A rectangle in the plane x = x0.
Disc rectangleX(double x0, double y0, double y1, double z0, double z1) {
  return geometry::discFromPolygon({{x0, y0, z0}, {x0, y1, z0}, {x0, y1, z1}, {x0, y0, z1}});
}

/// Every piece valid, volumes sum to the domain, no inconsistent contact.
void expectSoundModel(const BlockModel& model, const FastCutReport& report) {
  // Tolerance: the cutter snaps at 1e-11 x diagonal; round-off of constructed points is far
  // below; 1e-9 x diagonal leaves room for a piece's long thin faces.
  const double tolerance = 1e-9 * model.domain.diagonal();
  for (const Block& b : model.blocks) {
    for (const Piece& piece : b.pieces) expectValidPiece(piece, tolerance);
  }
  // Volume conservation, 1e-9 relative (issue 3): splitting shares each cap between the two
  // halves, so only round-off separates the sum from the domain volume.
  EXPECT_NEAR(totalVolume(model), model.domain_volume, 1e-9 * model.domain_volume);
  EXPECT_EQ(report.inconsistent_contacts, 0);
  for (std::size_t i = 0; i < model.blocks.size(); ++i) EXPECT_EQ(model.blocks[i].id, int(i) + 1);
}

struct Cut {
  BlockModel model;
  FastCutReport report;
};

Cut cut(const FractureNetwork& network, int segments = 24, FastCutOptions options = {}) {
  Cut c;
  c.model = cutFast(boxCutInput(network, segments), options, &c.report);
  return c;
}

/// The edge-plane strategy (every face wholly inside or outside its disc).
FastCutOptions edgePlanes() {
  FastCutOptions options;
  options.strategy = FastStrategy::EdgePlanes;
  return options;
}

TEST(FastCutter, ThreePersistentOrthogonalPlanes) {
  // Planes x = 3, y = 4, z = 6 through a 10 m cube: 8 boxes with volumes a b c for
  // a in {3, 7}, b in {4, 6}, c in {6, 4}.
  const FractureNetwork network =
      cubeNetwork({circle({3, 5, 5}, Vec3::UnitX(), 100), circle({5, 4, 5}, Vec3::UnitY(), 100),
                   circle({5, 5, 6}, Vec3::UnitZ(), 100)});
  const Cut c = cut(network);
  expectSoundModel(c.model, c.report);
  std::vector<double> expected;
  for (double a : {3.0, 7.0})
    for (double b : {4.0, 6.0})
      for (double h : {6.0, 4.0}) expected.push_back(a * b * h);
  std::sort(expected.begin(), expected.end());
  ASSERT_EQ(c.model.blocks.size(), 8u);
  const std::vector<double> got = test::sortedVolumes(c.model);
  for (std::size_t i = 0; i < 8; ++i) EXPECT_NEAR(got[i], expected[i], 1e-10);  // round-off
  // Each box touches 3 others across a disc face: 12 adjacencies.
  EXPECT_EQ(c.model.adjacency.size(), 12u);
  for (const Adjacency& a : c.model.adjacency) EXPECT_EQ(a.source.kind, FaceKind::Disc);
}

TEST(FastCutter, SmallDiscLeavesOneBlockWithACrack) {
  // A disc of radius 2 in the middle of the cube crosses nothing: one block of 1000 m3,
  // whose inside carries the crack on both sides: disc faces of total area 2 x the
  // 24-gon's area.
  // (EdgePlanes: the crack is peeled out of the cube, so its faces exist.)
  const FractureNetwork network = cubeNetwork({circle({5, 5, 5}, Vec3(1, 2, 3), 2.0)});
  const Cut c = cut(network, 24, edgePlanes());
  expectSoundModel(c.model, c.report);
  ASSERT_EQ(c.model.blocks.size(), 1u);
  EXPECT_NEAR(c.model.blocks[0].mass.volume, 1000.0, 1e-9);
  double crack = 0.0;
  for (const Piece& p : c.model.blocks[0].pieces) {
    for (std::size_t f = 0; f < p.shape.faces.size(); ++f) {
      if (p.face_sources[f].kind != FaceKind::Disc) continue;
      std::vector<Vec3> pts;
      for (int v : p.shape.faces[f]) pts.push_back(p.shape.vertices[v]);
      crack += geometry::polygonArea(pts);
    }
  }
  const double polygon = geometry::polygonArea(network.discs[0].outline(24));
  EXPECT_NEAR(crack, 2.0 * polygon, 1e-9 * polygon);  // round-off of the split sections
  EXPECT_TRUE(c.model.adjacency.empty());
}

TEST(FastCutter, FullPlanesSmallDiscLeavesOneBlock) {
  // FullPlanes, like the exact cutter, splits the cube by the disc's whole plane; neither
  // half-face is wholly covered by the disc, so both stay fictitious and the halves glue:
  // one block of 1000 m3, no disc face, no adjacency.
  const FractureNetwork network = cubeNetwork({circle({5, 5, 5}, Vec3(1, 2, 3), 2.0)});
  const Cut c = cut(network);
  expectSoundModel(c.model, c.report);
  ASSERT_EQ(c.model.blocks.size(), 1u);
  EXPECT_NEAR(c.model.blocks[0].mass.volume, 1000.0, 1e-9);  // round-off only
  EXPECT_EQ(c.model.blocks[0].pieces.size(), 2u);            // one full-plane split
  for (const Piece& p : c.model.blocks[0].pieces) {
    for (const FaceSource& s : p.face_sources) EXPECT_NE(s.kind, FaceKind::Disc);
  }
  EXPECT_TRUE(c.model.adjacency.empty());
}

TEST(FastCutter, TwoDiscsTogetherSeparateTheBox) {
  // A horizontal rectangle z = 5 over x < 6 and a vertical one x = 6 below z = 5 meet along
  // their edges: together they cut off the box x < 6, z < 5 (300 m3); the rest is one
  // L-shaped, non-convex block (700 m3). Neither disc alone separates anything.
  const FractureNetwork network =
      cubeNetwork({rectangleZ(-1, 6, -1, 11, 5), rectangleX(6, -1, 11, -1, 5)});
  const Cut c = cut(network);
  expectSoundModel(c.model, c.report);
  ASSERT_EQ(c.model.blocks.size(), 2u);
  const std::vector<double> v = test::sortedVolumes(c.model);
  EXPECT_NEAR(v[0], 300.0, 1e-9);
  EXPECT_NEAR(v[1], 700.0, 1e-9);
  // They touch across 6 x 10 of the first disc and 5 x 10 of the second: one adjacency
  // entry per disc.
  ASSERT_EQ(c.model.adjacency.size(), 2u);
  EXPECT_NEAR(c.model.adjacency[0].area, 60.0, 1e-9);
  EXPECT_EQ(c.model.adjacency[0].source, (FaceSource{FaceKind::Disc, 1}));
  EXPECT_NEAR(c.model.adjacency[1].area, 50.0, 1e-9);
  EXPECT_EQ(c.model.adjacency[1].source, (FaceSource{FaceKind::Disc, 2}));

  const Cut one = cut(cubeNetwork({rectangleZ(-1, 6, -1, 11, 5)}));
  EXPECT_EQ(one.model.blocks.size(), 1u);
}

TEST(FastCutter, WedgeFromACorner) {
  // The plane x + y + z = 27 cuts the corner (10, 10, 10) off: a right tetrahedron with
  // legs 3, volume 27 / 6. The disc (radius 3 about (9, 9, 9)) covers the whole triangular
  // section (its 24-gon's inradius 2.97 exceeds the 2.45 m to the triangle's corners).
  const FractureNetwork network = cubeNetwork({circle({9, 9, 9}, Vec3(1, 1, 1), 3.0)});
  const Cut c = cut(network);
  expectSoundModel(c.model, c.report);
  ASSERT_EQ(c.model.blocks.size(), 2u);
  const std::vector<double> v = test::sortedVolumes(c.model);
  EXPECT_NEAR(v[0], 4.5, 1e-10);
  EXPECT_NEAR(v[1], 995.5, 1e-9);
}

TEST(FastCutter, DiscOnADomainFaceCutsNothing) {
  // Coplanar with the top and bottom faces: the rock stays one block, and no face is a crack.
  const FractureNetwork network =
      cubeNetwork({circle({5, 5, 10}, Vec3::UnitZ(), 100), rectangleZ(2, 8, 2, 8, 0)});
  const Cut c = cut(network);
  expectSoundModel(c.model, c.report);
  ASSERT_EQ(c.model.blocks.size(), 1u);
  EXPECT_EQ(c.model.blocks[0].pieces.size(), 1u);
  for (const FaceSource& s : c.model.blocks[0].pieces[0].face_sources) {
    EXPECT_EQ(s.kind, FaceKind::Boundary);
  }
}

TEST(FastCutter, DiscsThroughDomainVerticesAndEdges) {
  // x = y holds two opposite edges of the cube: two prisms of 500 m3. x + y + z = 10 holds
  // three vertices: it cuts off the corner tetrahedron of volume 1000 / 6 from one prism.
  const FractureNetwork network =
      cubeNetwork({circle({5, 5, 5}, Vec3(1, -1, 0), 100),
                   circle({10.0 / 3, 10.0 / 3, 10.0 / 3}, Vec3(1, 1, 1), 100)});
  const Cut c = cut(network);
  expectSoundModel(c.model, c.report);
  ASSERT_EQ(c.model.blocks.size(), 4u);
  // The tetrahedron is halved by x = y; the rest of each prism is 500 - 1000 / 12.
  const std::vector<double> v = test::sortedVolumes(c.model);
  EXPECT_NEAR(v[0], 1000.0 / 12, 1e-10);
  EXPECT_NEAR(v[1], 1000.0 / 12, 1e-10);
  EXPECT_NEAR(v[2], 500.0 - 1000.0 / 12, 1e-9);
  EXPECT_NEAR(v[3], 500.0 - 1000.0 / 12, 1e-9);
}

TEST(FastCutter, TwoCoplanarOverlappingDiscs) {
  // Two rectangles in z = 5, x in [-1, 7] and [3, 11]: neither separates alone, together
  // they cover the section and cut the cube in two halves. The overlap is cut twice in one
  // plane; each crack face keeps the first disc that made it.
  const FractureNetwork network =
      cubeNetwork({rectangleZ(-1, 7, -1, 11, 5), rectangleZ(3, 11, -1, 11, 5)});
  const Cut c = cut(network, 24, edgePlanes());
  expectSoundModel(c.model, c.report);
  ASSERT_EQ(c.model.blocks.size(), 2u);
  EXPECT_NEAR(c.model.blocks[0].mass.volume, 500.0, 1e-9);
  EXPECT_NEAR(c.model.blocks[1].mass.volume, 500.0, 1e-9);
  double area[3] = {0, 0, 0};
  for (const Adjacency& a : c.model.adjacency) area[a.source.id] += a.area;
  EXPECT_NEAR(area[1], 70.0, 1e-9);  // x in [0, 7]
  EXPECT_NEAR(area[2], 30.0, 1e-9);  // x in [7, 10]
}

TEST(FastCutter, FullPlanesTwoCoplanarOverlappingDiscs) {
  // FullPlanes: the two rectangles form one group; the section z = 5 (100 m2) is covered by
  // their union only, so the peeled coverage test (not the one-polygon fast path) decides
  // it is wholly covered: two halves of 500 m3 touching over 100 m2, labelled with the disc
  // holding the face's centre (5, 5): the first.
  const FractureNetwork network =
      cubeNetwork({rectangleZ(-1, 7, -1, 11, 5), rectangleZ(3, 11, -1, 11, 5)});
  const Cut c = cut(network);
  expectSoundModel(c.model, c.report);
  ASSERT_EQ(c.model.blocks.size(), 2u);
  EXPECT_NEAR(c.model.blocks[0].mass.volume, 500.0, 1e-9);
  EXPECT_NEAR(c.model.blocks[1].mass.volume, 500.0, 1e-9);
  ASSERT_EQ(c.model.adjacency.size(), 1u);
  EXPECT_NEAR(c.model.adjacency[0].area, 100.0, 1e-9);  // the whole section, round-off
  EXPECT_EQ(c.model.adjacency[0].source, (FaceSource{FaceKind::Disc, 1}));
}

TEST(FastCutter, TwoDiscsOneNanometreApart) {
  // Parallel planes z = 5 and z = 5 + 1e-9: three blocks, the middle one 10 x 10 x 1e-9.
  // The snapping tolerance (1e-11 x 17.3 m) is 6x below the gap, so the sliver survives.
  const FractureNetwork network = cubeNetwork(
      {circle({5, 5, 5}, Vec3::UnitZ(), 100), circle({5, 5, 5 + 1e-9}, Vec3::UnitZ(), 100)});
  const Cut c = cut(network);
  expectSoundModel(c.model, c.report);
  ASSERT_EQ(c.model.blocks.size(), 3u);
  const std::vector<double> v = test::sortedVolumes(c.model);
  // Coordinates near 5 m carry ~1e-15 m of round-off: 1e-6 relative of the 1e-9 m gap.
  EXPECT_NEAR(v[0], 1e-7, 1e-12);
  EXPECT_NEAR(v[1], 500.0 - 1e-7, 1e-9);
  EXPECT_NEAR(v[2], 500.0, 1e-9);
}

TEST(FastCutter, DiscTangentToExistingEdges) {
  // z = 5 (whole), then y + z = 5: its plane holds the edge y = 0, z = 5 of the upper half
  // (tangent: no cut there) and cuts from the lower half the prism y + z < 5 (125 m3).
  // Then a rectangle x = 5 over z in [5, 11], whose lower edge lies on the first cut:
  // it halves the upper half.
  const FractureNetwork network =
      cubeNetwork({circle({5, 5, 5}, Vec3::UnitZ(), 100), circle({5, 0, 5}, Vec3(0, 1, 1), 100),
                   rectangleX(5, -1, 11, 5, 11)});
  const Cut c = cut(network);
  expectSoundModel(c.model, c.report);
  ASSERT_EQ(c.model.blocks.size(), 4u);
  const std::vector<double> v = test::sortedVolumes(c.model);
  EXPECT_NEAR(v[0], 125.0, 1e-9);
  EXPECT_NEAR(v[1], 250.0, 1e-9);
  EXPECT_NEAR(v[2], 250.0, 1e-9);
  EXPECT_NEAR(v[3], 375.0, 1e-9);
}

TEST(FastCutter, SliversOfAspectOneToThousand) {
  // z = 5 and z = 5.01 make a 10 x 10 x 0.01 slab (aspect 1:1000); x = 5 and a plane
  // at a grazing 0.1 degree to the slab cross it.
  const Vec3 grazing(0, std::sin(0.1 * geometry::kPi / 180), std::cos(0.1 * geometry::kPi / 180));
  const FractureNetwork network =
      cubeNetwork({circle({5, 5, 5}, Vec3::UnitZ(), 100), circle({5, 5, 5.01}, Vec3::UnitZ(), 100),
                   circle({5, 5, 5}, Vec3::UnitX(), 100), circle({5, 5, 5.005}, grazing, 100)});
  const Cut c = cut(network);
  expectSoundModel(c.model, c.report);
  // The grazing plane z = 5.005 - (y - 5) tan(0.1 deg) leaves the slab at |y - 5| = 2.86 m:
  // below y = 2.14 the slab lies under it, above y = 7.86 over it, so it splits each slab
  // half (x < 5, x > 5) into two connected blocks: 4 thin blocks.
  double slab = 0.0;
  int thin = 0;
  for (const Block& b : c.model.blocks) {
    if (b.bounds.min.z() >= 5.0 - 1e-9 && b.bounds.max.z() <= 5.01 + 1e-9) {
      slab += b.mass.volume;
      ++thin;
    }
  }
  EXPECT_EQ(thin, 4);
  EXPECT_NEAR(slab, 1.0, 1e-9);  // 10 x 10 x 0.01, round-off only
}

TEST(FastCutter, RandomScenesConserveVolumeAndKeepProvenance) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    DiscSceneSpec spec;
    spec.discs = 25;
    spec.seed = seed;
    const FractureNetwork network = randomDiscNetwork(spec);
    const Cut c = cut(network, 12);
    expectSoundModel(c.model, c.report);
    // The cutter finds contacts among faces of one cutting plane only; a brute-force search
    // over all pairs of pieces (same tolerances) must glue the very same blocks.
    std::vector<Piece> all;
    for (const Block& b : c.model.blocks) all.insert(all.end(), b.pieces.begin(), b.pieces.end());
    const CutTolerances tol = cutTolerances(network.domain);
    std::vector<int> parent(all.size());
    for (std::size_t i = 0; i < all.size(); ++i) parent[i] = static_cast<int>(i);
    const auto root = [&](int i) {
      while (parent[i] != i) i = parent[i];
      return i;
    };
    for (const PieceContact& k : findPieceContacts(all, tol.distance, tol.area)) {
      if (all[k.piece_a].face_sources[k.face_a].kind == FaceKind::Fictitious &&
          all[k.piece_b].face_sources[k.face_b].kind == FaceKind::Fictitious) {
        parent[root(k.piece_a)] = root(k.piece_b);
      }
    }
    std::size_t roots = 0;
    for (std::size_t i = 0; i < all.size(); ++i) roots += root(static_cast<int>(i)) == int(i);
    EXPECT_EQ(roots, c.model.blocks.size());
    // Provenance: every disc face lies in its disc's plane and inside its polygon
    // (within 1e-9 x diagonal, the validity tolerance above).
    const double tolerance = 1e-9 * network.domain.diagonal();
    for (const Block& b : c.model.blocks) {
      for (const Piece& p : b.pieces) {
        for (std::size_t f = 0; f < p.shape.faces.size(); ++f) {
          if (p.face_sources[f].kind != FaceKind::Disc) continue;
          const Disc& d = network.discs[p.face_sources[f].id - 1];
          const std::vector<Vec3> outline = d.outline(12);
          for (int v : p.shape.faces[f]) {
            const Vec3& x = p.shape.vertices[v];
            EXPECT_NEAR(d.normal.dot(x - d.center), 0.0, tolerance);
            for (std::size_t k = 0; k < outline.size(); ++k) {
              const Vec3 inward = d.normal.cross(outline[(k + 1) % outline.size()] - outline[k]);
              EXPECT_GE(inward.normalized().dot(x - outline[k]), -tolerance);
            }
          }
        }
      }
    }
  }
}

TEST(FastCutter, ContactSearchWithDecisionsGluesTheSameClusters) {
  // findContactsByPlane with a decision skips pairs of pieces glued already: the clusters
  // and every contact between different clusters must be exactly those of the full search.
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    DiscSceneSpec spec;
    spec.discs = 25;
    spec.seed = seed;
    const FractureNetwork network = randomDiscNetwork(spec);
    const Cut c = cut(network, 12);
    std::vector<Piece> all;
    for (const Block& b : c.model.blocks) all.insert(all.end(), b.pieces.begin(), b.pieces.end());
    const CutTolerances tol = cutTolerances(network.domain);
    // Plane ids: faces that touch share one (union over the brute-force contacts).
    std::vector<std::size_t> first(all.size() + 1, 0);
    for (std::size_t i = 0; i < all.size(); ++i)
      first[i + 1] = first[i] + all[i].shape.faces.size();
    UnionFind face_planes(first.back());
    for (const PieceContact& k : findPieceContacts(all, tol.distance, tol.area)) {
      face_planes.unite(static_cast<int>(first[k.piece_a] + k.face_a),
                        static_cast<int>(first[k.piece_b] + k.face_b));
    }
    std::vector<std::vector<int>> planes(all.size());
    for (std::size_t i = 0; i < all.size(); ++i) {
      for (std::size_t f = 0; f < all[i].shape.faces.size(); ++f) {
        planes[i].push_back(face_planes.find(static_cast<int>(first[i] + f)));
      }
    }
    const ContactDecision decide = [&](const PieceContact& k, bool) {
      const FaceSource& a = all[k.piece_a].face_sources[k.face_a];
      return a.kind == FaceKind::Fictitious ? all[k.piece_b].face_sources[k.face_b] : a;
    };
    const std::vector<PieceContact> full = findContactsByPlane(all, planes, tol.distance, tol.area);
    std::vector<FaceSource> sources;
    const std::vector<PieceContact> decided =
        findContactsByPlane(all, planes, tol.distance, tol.area, decide, &sources);
    ASSERT_EQ(sources.size(), decided.size());
    // Blocks of several pieces here: pairs glued through mirrored faces first have other
    // contacts, which the search with decisions skips.
    EXPECT_LT(decided.size(), full.size());
    const auto clustersOf = [&](const std::vector<PieceContact>& contacts) {
      UnionFind clusters(all.size());
      for (const PieceContact& k : contacts) {
        if (decide(k, false).kind == FaceKind::Fictitious) clusters.unite(k.piece_a, k.piece_b);
      }
      std::vector<int> root(all.size());
      for (std::size_t i = 0; i < all.size(); ++i) root[i] = clusters.find(static_cast<int>(i));
      return root;
    };
    const std::vector<int> root = clustersOf(full);
    EXPECT_EQ(clustersOf(decided), root);
    for (std::size_t k = 0; k < decided.size(); ++k)
      EXPECT_EQ(sources[k], decide(decided[k], false));
    const auto between = [&](const std::vector<PieceContact>& contacts) {
      std::vector<std::tuple<int, int, int, int, double>> out;
      for (const PieceContact& k : contacts) {
        if (root[k.piece_a] != root[k.piece_b]) {
          out.emplace_back(k.piece_a, k.face_a, k.piece_b, k.face_b, k.area);
        }
      }
      return out;
    };
    EXPECT_EQ(between(decided), between(full));
  }
}

TEST(FastCutter, TrackedContactsGiveTheSameBlocksAndAdjacencyAsThePlaneSearch) {
  // FullPlanes follows which faces may touch through the splits (track_contacts) instead of
  // searching every plane geometrically. Small regions (8 polygons) so that many contacts
  // cross region faces, which the tracked cut still finds by a search in the kd planes.
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    DiscSceneSpec spec;
    spec.discs = 40;
    spec.seed = seed;
    const FractureNetwork network = randomDiscNetwork(spec);
    FastCutOptions tracked;
    tracked.max_discs_per_region = 8;
    FastCutOptions searched = tracked;
    searched.track_contacts = false;
    FastCutReport report;
    const BlockModel a = cutFast(boxCutInput(network, 12), tracked, &report);
    const BlockModel b = cutFast(boxCutInput(network, 12), searched);
    EXPECT_GT(report.regions, 4);  // the scene really has region faces to glue across
    EXPECT_EQ(report.inconsistent_contacts, 0);
    ASSERT_EQ(a.blocks.size(), b.blocks.size());
    EXPECT_GT(a.blocks.size(), 3u);
    for (std::size_t i = 0; i < a.blocks.size(); ++i) {
      // The same splits make the same pieces: volumes are bitwise equal.
      EXPECT_EQ(a.blocks[i].mass.volume, b.blocks[i].mass.volume);
      EXPECT_EQ(a.blocks[i].pieces.size(), b.blocks[i].pieces.size());
    }
    ASSERT_EQ(a.adjacency.size(), b.adjacency.size());
    EXPECT_GT(a.adjacency.size(), a.blocks.size());
    for (std::size_t k = 0; k < a.adjacency.size(); ++k) {
      const Adjacency& x = a.adjacency[k];
      const Adjacency& y = b.adjacency[k];
      EXPECT_EQ(x.block_a, y.block_a);
      EXPECT_EQ(x.block_b, y.block_b);
      EXPECT_EQ(x.source, y.source);
      // The same contacts; each overlap polygon may be clipped from the other face, so the
      // areas agree to round-off (1e-12 relative, far above 1e-16 per clip).
      EXPECT_NEAR(x.area, y.area, 1e-12 * std::max(1.0, y.area));
    }
  }
}

TEST(FastCutter, Deterministic) {
  DiscSceneSpec spec;
  spec.discs = 30;
  const FractureNetwork network = randomDiscNetwork(spec);
  const Cut a = cut(network);
  const Cut b = cut(network);
  ASSERT_EQ(a.model.blocks.size(), b.model.blocks.size());
  for (std::size_t i = 0; i < a.model.blocks.size(); ++i) {
    EXPECT_EQ(a.model.blocks[i].mass.volume, b.model.blocks[i].mass.volume);
    EXPECT_EQ(a.model.blocks[i].pieces.size(), b.model.blocks[i].pieces.size());
  }
}

}  // namespace
}  // namespace rockmass::blocks
