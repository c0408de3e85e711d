// Block surfaces (blocks/block_surface.h) and their mesh files through assimp
// (io/block_mesh.h): every surface is closed and outward and encloses the block's volume;
// every format reads back with assimp with the same blocks and volumes.
#include "io/block_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <sstream>
#include <utility>

#include "blocks/fast_cutter.h"
#include "blocks/surface_check.h"
#include "geometry/disc.h"
#include "geometry/polyhedron.h"
#include "io/atomic_file.h"
#include "scenarios/disc_scenes.h"
#include "tests/support/test_support.h"

namespace rockmass::io {
namespace {

using blocks::BlockModel;
using blocks::TriangleSurface;
using geometry::Vec3;

/// Number of directed edges that are not matched by exactly one opposite directed edge
/// (0 for a closed, consistently oriented, conforming triangle surface).
int unmatchedEdges(const TriangleSurface& s) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : s.triangles) {
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  int bad = 0;
  for (const auto& [edge, count] : directed) {
    const auto it = directed.find({edge.second, edge.first});
    if (count != 1 || it == directed.end() || it->second != 1) ++bad;
  }
  return bad;
}

/// Volume enclosed by a triangle surface (divergence theorem, geometry::massProperties).
double volume(const TriangleSurface& s) {
  return geometry::massProperties(blocks::toPolyhedron(s)).volume;
}

/// Total triangle area (m2).
double area(const TriangleSurface& s) {
  double a = 0.0;
  for (const auto& t : s.triangles) {
    const Vec3& p = s.vertices[static_cast<std::size_t>(t[0])];
    a += 0.5 * (s.vertices[static_cast<std::size_t>(t[1])] - p)
                   .cross(s.vertices[static_cast<std::size_t>(t[2])] - p)
                   .norm();
  }
  return a;
}

/// A fast-cut random scene: 12 discs of radius 3..7 m in a 10 m cube, so many cracks end
/// inside the rock (multi-piece, non-convex blocks with internal crack faces).
BlockModel randomModel(std::uint64_t seed, geometry::FractureNetwork& network) {
  blocks::DiscSceneSpec spec;
  spec.discs = 12;
  spec.seed = seed;
  network = blocks::randomDiscNetwork(spec);
  return blocks::cutFast(blocks::boxCutInput(network));
}

TEST(BlockSurface, ClosedOutwardAndEnclosesTheBlockVolume) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    geometry::FractureNetwork network;
    const BlockModel model = randomModel(seed, network);
    int multi_piece = 0;
    for (const blocks::Block& block : model.blocks) {
      if (block.pieces.size() > 1) ++multi_piece;
      const TriangleSurface s = blocks::blockSurface(block);
      // Every edge is used once in each direction: closed, oriented, no T-junction and no
      // sheet left inside the block. (Seeds 1, 4 and 5 each had a block with a millimetre
      // sheet inside, two faces of one plane put in two plane groups; docs/blocks.md.)
      EXPECT_EQ(unmatchedEdges(s), 0) << "seed " << seed << " block " << block.id;
      EXPECT_TRUE(blocks::isClosedSurface(blocks::toPolyhedron(s)))
          << "seed " << seed << " block " << block.id;
      // Same volume up to double round-off of the clipped points: the surface is made of the
      // pieces' own faces, so 1e-10 relative is 1e4x above round-off and far below any
      // missing or doubled face (which would change the volume by a whole face's prism).
      EXPECT_NEAR(volume(s), block.mass.volume, 1e-10 * block.mass.volume)
          << "seed " << seed << " block " << block.id;
    }
    // The scenes must exercise the gluing, or the test proves nothing about it.
    EXPECT_GT(multi_piece, 0) << "seed " << seed;
  }
}

TEST(BlockSurface, ACrackEndingInsideTheBlockLeavesNoInternalFace) {
  // A 4 m square crack in the middle of a 10 m cube: one block of 1 + pieces; its surface is
  // the cube's 6 faces only, 12 triangles' worth of area 600 m2 (the crack's 2 x 16 m2 gone).
  geometry::FractureNetwork network;
  network.domain = {Vec3::Zero(), Vec3::Constant(10.0)};
  network.discs = {geometry::discFromPolygon({{3, 3, 5}, {7, 3, 5}, {7, 7, 5}, {3, 7, 5}})};
  network.discs[0].id = 1;
  const BlockModel model = blocks::cutFast(blocks::boxCutInput(network));
  ASSERT_EQ(model.blocks.size(), 1u);
  ASSERT_GT(model.blocks[0].pieces.size(), 1u);
  const TriangleSurface s = blocks::blockSurface(model.blocks[0]);
  EXPECT_EQ(unmatchedEdges(s), 0);
  EXPECT_NEAR(area(s), 600.0, 1e-9);  // the cube's faces, no crack face (round-off only)
  EXPECT_NEAR(volume(s), 1000.0, 1e-9);
}

/// `surface` as a soup: every triangle with its own copies of its points (as STL stores it).
geometry::Polyhedron soup(const TriangleSurface& surface) {
  geometry::Polyhedron out;
  for (const auto& t : surface.triangles) {
    const int first = static_cast<int>(out.vertices.size());
    for (int k = 0; k < 3; ++k) out.vertices.push_back(surface.vertices[t[k]]);
    out.faces.push_back({first, first + 1, first + 2});
  }
  return out;
}

TEST(BlockSurface, TheClosedCheckSeesAGapAndAcceptsATouchingCorner) {
  // A 10 m cube block: its skin as a soup is closed once points merge; without one triangle
  // it has a gap.
  geometry::FractureNetwork network;
  network.domain = {Vec3::Zero(), Vec3::Constant(10.0)};
  const BlockModel cube = blocks::cutFast(blocks::boxCutInput(network));
  ASSERT_EQ(cube.blocks.size(), 1u);
  const TriangleSurface s = blocks::blockSurface(cube.blocks[0]);
  EXPECT_TRUE(blocks::isClosedSurface(soup(s)));
  geometry::Polyhedron open = soup(s);
  open.faces.pop_back();
  EXPECT_FALSE(blocks::isClosedSurface(open));
  // Two unit cubes touching at one corner (a block glued elsewhere can touch itself so):
  // closed, the corner is split into one copy per cube.
  geometry::Polyhedron two = geometry::boxPolyhedron({Vec3::Zero(), Vec3::Ones()});
  const geometry::Polyhedron other = geometry::boxPolyhedron({Vec3::Ones(), Vec3::Constant(2)});
  const int offset = static_cast<int>(two.vertices.size());
  two.vertices.insert(two.vertices.end(), other.vertices.begin(), other.vertices.end());
  for (std::vector<int> face : other.faces) {
    for (int& v : face) v += offset;
    two.faces.push_back(face);
  }
  EXPECT_TRUE(blocks::isClosedSurface(two));
}

/// A block of convex `boxes` (one piece each; faces real, from no disc).
blocks::Block blockOfBoxes(const std::vector<geometry::Box>& boxes) {
  blocks::Block block;
  block.id = 1;
  block.bounds = boxes.front();
  for (const geometry::Box& box : boxes) {
    blocks::Piece piece;
    piece.shape = geometry::boxPolyhedron(box);
    piece.face_sources.assign(piece.shape.faces.size(), blocks::FaceSource{});
    block.pieces.push_back(piece);
    block.mass += geometry::massProperties(piece.shape);
    block.bounds = {block.bounds.min.cwiseMin(box.min), block.bounds.max.cwiseMax(box.max)};
  }
  return block;
}

/// For each undirected edge, the number of triangles on it, and whether every vertex's
/// triangles form one fan (connected across the vertex's edges): a 2-manifold surface has
/// two triangles on every edge and one fan at every vertex.
bool isTwoManifold(const TriangleSurface& s) {
  std::map<std::pair<int, int>, int> edges;
  for (const auto& t : s.triangles) {
    for (int k = 0; k < 3; ++k) {
      ++edges[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
    }
  }
  for (const auto& [edge, count] : edges) {
    if (count != 2) return false;
  }
  for (std::size_t v = 0; v < s.vertices.size(); ++v) {
    // The triangles at v, joined when they share an edge at v.
    std::vector<std::size_t> fan;
    for (std::size_t t = 0; t < s.triangles.size(); ++t) {
      if (std::find(s.triangles[t].begin(), s.triangles[t].end(), static_cast<int>(v)) !=
          s.triangles[t].end()) {
        fan.push_back(t);
      }
    }
    if (fan.empty()) continue;
    std::vector<bool> reached(fan.size(), false);
    std::vector<std::size_t> stack{0};
    reached[0] = true;
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      for (std::size_t j = 0; j < fan.size(); ++j) {
        if (reached[j]) continue;
        int shared = 0;
        for (int a : s.triangles[fan[i]]) {
          for (int b : s.triangles[fan[j]]) shared += a == b;
        }
        if (shared == 2) {
          reached[j] = true;
          stack.push_back(j);
        }
      }
    }
    if (std::find(reached.begin(), reached.end(), false) != reached.end()) return false;
  }
  return true;
}

TEST(BlockSurface, ABlockTouchingItselfAlongAnEdgeIsSplitIntoAManifold) {
  // Two unit cubes of one block sharing the edge x = 1, y = 1 (0 <= z <= 1): four triangles
  // met on that edge (mesh tools saw such blocks as not watertight: 261 blocks, 1 028 edges
  // of the full Xiangjiaba model). Split, every edge has two triangles and every vertex one
  // fan; the edge's two ends get a copy each; the volume and closedness stay.
  const blocks::Block block =
      blockOfBoxes({{Vec3::Zero(), Vec3::Ones()}, {Vec3(1, 1, 0), Vec3(2, 2, 1)}});
  const TriangleSurface s = blocks::blockSurface(block);
  EXPECT_TRUE(isTwoManifold(s));
  EXPECT_EQ(unmatchedEdges(s), 0);
  EXPECT_EQ(s.vertices.size(), 16u);  // 8 corners per cube, the shared edge's 2 copied
  EXPECT_NEAR(volume(s), 2.0, 1e-12);
  // (Not isClosedSurface: it merges equal points first, which makes the edge four-fold again.)
  // The triangles fall into two parts that share no vertex, each a unit cube (volume 1):
  // the wrong pairing around the edge would join a face of one cube to a face of the other.
  std::vector<int> part(s.triangles.size(), -1);
  int parts = 0;
  for (std::size_t seed = 0; seed < s.triangles.size(); ++seed) {
    if (part[seed] >= 0) continue;
    std::vector<std::size_t> stack{seed};
    part[seed] = parts;
    while (!stack.empty()) {
      const std::size_t t = stack.back();
      stack.pop_back();
      for (std::size_t u = 0; u < s.triangles.size(); ++u) {
        if (part[u] >= 0) continue;
        for (int a : s.triangles[t]) {
          if (std::find(s.triangles[u].begin(), s.triangles[u].end(), a) != s.triangles[u].end()) {
            part[u] = parts;
            stack.push_back(u);
            break;
          }
        }
      }
    }
    ++parts;
  }
  ASSERT_EQ(parts, 2);
  for (int p = 0; p < 2; ++p) {
    TriangleSurface cube;
    cube.vertices = s.vertices;
    for (std::size_t t = 0; t < s.triangles.size(); ++t) {
      if (part[t] == p) cube.triangles.push_back(s.triangles[t]);
    }
    EXPECT_NEAR(volume(cube), 1.0, 1e-12) << "part " << p;
  }
}

TEST(BlockSurface, ABlockTouchingItselfAtACornerGetsTwoCopiesOfTheCorner) {
  const blocks::Block block =
      blockOfBoxes({{Vec3::Zero(), Vec3::Ones()}, {Vec3::Ones(), Vec3::Constant(2.0)}});
  const TriangleSurface s = blocks::blockSurface(block);
  EXPECT_TRUE(isTwoManifold(s));
  EXPECT_EQ(s.vertices.size(), 16u);
  EXPECT_NEAR(volume(s), 2.0, 1e-12);
}

TEST(BlockSurface, RandomBlocksAreTwoManifold) {
  // The random scenes' blocks (non-convex ones among them): every skin is a 2-manifold.
  for (int seed = 1; seed <= 5; ++seed) {
    geometry::FractureNetwork network;
    const BlockModel model = randomModel(seed, network);
    for (const blocks::Block& b : model.blocks) {
      EXPECT_TRUE(isTwoManifold(blocks::blockSurface(b))) << "seed " << seed << " block " << b.id;
    }
  }
}

/// Round trip of one format: the file assimp reads back has the blocks' triangles and volumes.
void checkRoundTrip(MeshFormat format) {
  geometry::FractureNetwork network;
  const BlockModel model = randomModel(3, network);
  std::vector<TriangleSurface> surfaces;
  for (const blocks::Block& b : model.blocks) surfaces.push_back(blocks::blockSurface(b));
  const std::string bytes = formatBlockMesh(model, format, surfaces);
  // Deterministic: the same model gives the same bytes.
  EXPECT_EQ(bytes, formatBlockMesh(model, format, surfaces));

  test::TempDir dir("block_mesh_" + meshExtension(format));
  const auto path = dir.path() / ("blocks." + meshExtension(format));
  writeFileAtomically(path, bytes);
  const std::vector<ImportedMesh> meshes = readMeshFile(path);

  // Read-back surfaces per block: by name where the format keeps one mesh per block (OBJ
  // groups, glTF nodes, STL solids), else (PLY: one mesh, whose face property assimp does not
  // read) by the ranges of triangles written in block order; plyFaceBlocks checks the
  // property itself.
  std::vector<TriangleSurface> read;
  if (format == MeshFormat::Obj || format == MeshFormat::Glb || format == MeshFormat::Stl) {
    ASSERT_EQ(meshes.size(), model.blocks.size());
    for (std::size_t i = 0; i < meshes.size(); ++i) {
      EXPECT_EQ(meshes[i].name, "block_" + std::to_string(model.blocks[i].id));
      read.push_back(meshes[i].surface);
    }
  } else {
    ASSERT_EQ(meshes.size(), 1u);
    const TriangleSurface& all = meshes[0].surface;
    std::size_t next = 0;
    for (const TriangleSurface& s : surfaces) {
      TriangleSurface part;
      part.vertices = all.vertices;
      for (std::size_t t = 0; t < s.triangles.size() && next < all.triangles.size(); ++t) {
        part.triangles.push_back(all.triangles[next++]);
      }
      read.push_back(std::move(part));
    }
    EXPECT_EQ(next, all.triangles.size());
  }
  ASSERT_EQ(read.size(), model.blocks.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].triangles.size(), surfaces[i].triangles.size());
    // The skin read back is closed (CGAL::is_closed once duplicate points are merged: STL
    // and PLY files give each triangle or block its own copies).
    EXPECT_TRUE(blocks::isClosedSurface(blocks::toPolyhedron(read[i])))
        << meshExtension(format) << " block " << model.blocks[i].id;
    // Every format stores float coordinates: each is off by at most half an ulp,
    // 2^-24 |x| <= 6e-7 m here (|x| <= 10 m). Moving a surface by h changes the volume by at
    // most h times its area; 2x margin for the rounding of two points per triangle.
    const double tolerance = 2.0 * area(surfaces[i]) * 10.0 * std::ldexp(1.0, -24);
    EXPECT_NEAR(volume(read[i]), model.blocks[i].mass.volume, tolerance)
        << meshExtension(format) << " block " << model.blocks[i].id;
  }
}

/// The face property `block` of a binary PLY file, read by the PLY format's description
/// (header lines, then little-endian vertex and face records) independently of assimp.
std::vector<std::int32_t> plyFaceBlocks(const std::string& bytes) {
  const std::size_t end = bytes.find("end_header\n");
  EXPECT_NE(end, std::string::npos);
  std::istringstream header(bytes.substr(0, end));
  std::string line;
  std::size_t vertices = 0, faces = 0;
  std::vector<std::string> face_properties;
  std::string element;
  while (std::getline(header, line)) {
    std::istringstream words(line);
    std::string word;
    words >> word;
    if (word == "format") {
      words >> word;
      EXPECT_EQ(word, "binary_little_endian");
    } else if (word == "element") {
      std::size_t count = 0;
      words >> element >> count;
      (element == "vertex" ? vertices : faces) = count;
    } else if (word == "property" && element == "face") {
      face_properties.push_back(line);
    }
  }
  EXPECT_EQ(face_properties, (std::vector<std::string>{"property list uchar int vertex_indices",
                                                       "property int block"}));
  std::vector<std::int32_t> blocks;
  std::size_t at = end + 11 + 12 * vertices;  // three floats per vertex
  for (std::size_t f = 0; f < faces; ++f) {
    EXPECT_EQ(bytes[at], 3);
    std::int32_t block = 0;
    std::memcpy(&block, bytes.data() + at + 13, sizeof block);
    blocks.push_back(block);
    at += 17;
  }
  EXPECT_EQ(at, bytes.size());
  return blocks;
}

TEST(BlockMesh, PlyFacesCarryTheirBlockId) {
  geometry::FractureNetwork network;
  const BlockModel model = randomModel(3, network);
  std::vector<TriangleSurface> surfaces;
  std::vector<std::int32_t> expected;
  for (const blocks::Block& b : model.blocks) {
    surfaces.push_back(blocks::blockSurface(b));
    expected.insert(expected.end(), surfaces.back().triangles.size(), b.id);
  }
  ASSERT_GT(model.blocks.size(), 2u);
  EXPECT_EQ(plyFaceBlocks(formatBlockMesh(model, MeshFormat::Ply, surfaces)), expected);
}

TEST(BlockMesh, ObjRoundTrip) {
  checkRoundTrip(MeshFormat::Obj);
}
TEST(BlockMesh, PlyRoundTrip) {
  checkRoundTrip(MeshFormat::Ply);
}
TEST(BlockMesh, StlRoundTrip) {
  checkRoundTrip(MeshFormat::Stl);
}
TEST(BlockMesh, GlbRoundTrip) {
  checkRoundTrip(MeshFormat::Glb);
}

TEST(BlockMesh, FormatNames) {
  for (const char* name : {"obj", "ply", "stl", "glb"}) {
    const auto format = parseMeshFormat(name);
    ASSERT_TRUE(format.has_value());
    EXPECT_EQ(meshExtension(*format), name);
  }
  EXPECT_FALSE(parseMeshFormat("fbx").has_value());
}

}  // namespace
}  // namespace rockmass::io
