// The section of a block model: a 10 m cube cut (fast cutter) by three known planes gives
// known polygons (areas exact to 1e-9), edge provenance and traces; section.csv reads back
// to the same polygons; section.svg is well-formed XML (parsed with expat).
#include "io/section_output.h"

#include <expat.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include "blocks/exact_cutter.h"
#include "blocks/fast_cutter.h"
#include "geometry/disc.h"
#include "geometry/polyhedron.h"
#include "scenarios/disc_scenes.h"

namespace rockmass::io {
namespace {

using geometry::Vec2;
using geometry::Vec3;

/// The cube [0, 10]^3 cut by: disc 1, z = 4 everywhere; disc 2, x = 6 below z = 4 only;
/// disc 3, x + z = 14 everywhere (it cuts the corner x > 4, z > 4 of the upper block).
/// In the plane y = 5 the pieces are [0,6]x[0,4] (24 m2), [6,10]x[0,4] (16), the triangle
/// (10,4)-(10,10)-(4,10) (18) and the rest of the upper half (42).
struct CutCube {
  geometry::FractureNetwork network;
  blocks::BlockModel model;
  CutCube() {
    network.domain = {Vec3::Zero(), Vec3::Constant(10)};
    network.sets = {{"planes", geometry::DiscOrigin::Fault}};
    std::vector<geometry::Disc> discs = {
        geometry::discFromPolygon({{-1, -1, 4}, {11, -1, 4}, {11, 11, 4}, {-1, 11, 4}}),
        geometry::discFromPolygon({{6, -1, -1}, {6, 11, -1}, {6, 11, 4}, {6, -1, 4}}),
        geometry::discFromPolygon({{15, -1, -1}, {15, 11, -1}, {3, 11, 11}, {3, -1, 11}})};
    for (std::size_t i = 0; i < discs.size(); ++i) {
      discs[i].id = static_cast<std::int64_t>(i) + 1;
      discs[i].origin = geometry::DiscOrigin::Fault;
    }
    network.discs = discs;
    blocks::CutInput input;
    input.domain_box = network.domain;
    input.domain_pieces = {geometry::boxPolyhedron(network.domain)};
    input.network = &network;
    input.rock_material = 0;
    model = blocks::cutFast(input);
  }
};

const std::vector<Material> kMaterials = {{"rock", 2500.0, 1e10, 0.25}};

TEST(SectionOutput, CubeCutByThreePlanesGivesTheKnownPolygons) {
  const CutCube cube;
  const Section s =
      blocks::sectionOf(cube.model, cube.network, geometry::axisPlane(1, 5.0), "y=5", 0);
  std::vector<double> areas;
  std::set<int> blocks;
  for (const SectionPolygon& p : s.polygons) {
    areas.push_back(geometry::signedArea(p.points));
    blocks.insert(p.block);
    ASSERT_EQ(p.edges.size(), p.points.size());
  }
  std::sort(areas.begin(), areas.end());
  ASSERT_EQ(areas.size(), 4u);
  // Exact up to round-off of the cut coordinates (all are small integers).
  EXPECT_NEAR(areas[0], 16.0, 1e-9);
  EXPECT_NEAR(areas[1], 18.0, 1e-9);
  EXPECT_NEAR(areas[2], 24.0, 1e-9);
  EXPECT_NEAR(areas[3], 42.0, 1e-9);
  EXPECT_EQ(blocks.size(), 4u);  // every piece is its own block here (all cuts persistent)

  // The 24 m2 piece: its edges come from the x_min (0) and z_min (4) box faces and discs 1, 2.
  for (const SectionPolygon& p : s.polygons) {
    if (std::abs(geometry::signedArea(p.points) - 24.0) > 1e-6) continue;
    std::set<std::pair<int, int>> sources;
    for (const blocks::FaceSource& e : p.edges) {
      sources.insert({static_cast<int>(e.kind), e.id});
    }
    const std::set<std::pair<int, int>> expected = {
        {static_cast<int>(blocks::FaceKind::Boundary), 0},
        {static_cast<int>(blocks::FaceKind::Boundary), 4},
        {static_cast<int>(blocks::FaceKind::Disc), 1},
        {static_cast<int>(blocks::FaceKind::Disc), 2}};
    EXPECT_EQ(sources, expected);
  }

  // Traces: disc 1 across the whole section (10 m), disc 2 from z = 0 to 4 (the polygon
  // reaches below the box; clipped), disc 3 from (4, 10) to (10, 4): 6 sqrt(2) inside.
  ASSERT_EQ(s.traces.size(), 3u);
  std::map<std::int64_t, double> lengths;
  for (const SectionTrace& t : s.traces) lengths[t.disc] = (t.b - t.a).norm();
  EXPECT_NEAR(lengths[1], 10.0, 1e-12);
  EXPECT_NEAR(lengths[2], 4.0 + 0.0, 1e-12);
  EXPECT_NEAR(lengths[3], 6.0 * std::sqrt(2.0), 1e-12);
}

TEST(SectionOutput, CsvReadsBackToThePolygons) {
  const CutCube cube;
  const Section s =
      blocks::sectionOf(cube.model, cube.network, geometry::axisPlane(1, 5.0), "y=5", 0);
  std::istringstream in(formatSectionCsv(s, cube.network, kMaterials));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "kind,id,label,part,vertex,u,v,x,y,z,source");
  std::map<std::pair<int, int>, std::vector<Vec2>> polygons;
  int trace_rows = 0;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::stringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) f.push_back(field);
    ASSERT_EQ(f.size(), 11u) << line;
    EXPECT_EQ(std::stod(f[8]), 5.0);  // y of every point is the plane's
    if (f[0] == "block") {
      EXPECT_EQ(f[2], "rock");
      std::vector<Vec2>& polygon = polygons[std::make_pair(std::stoi(f[1]), std::stoi(f[3]))];
      EXPECT_EQ(static_cast<std::size_t>(std::stoi(f[4])), polygon.size());
      polygon.push_back({std::stod(f[5]), std::stod(f[6])});
      EXPECT_EQ(std::stod(f[5]), std::stod(f[7]));  // u = x
      EXPECT_EQ(std::stod(f[6]), std::stod(f[9]));  // v = z
    } else {
      EXPECT_EQ(f[0], "fault");
      EXPECT_EQ(f[2], "planes");
      EXPECT_EQ(f[10], "cutting");
      ++trace_rows;
    }
  }
  EXPECT_EQ(trace_rows, 6);  // 3 traces x 2 ends
  double total = 0.0;
  for (const auto& [key, points] : polygons) total += geometry::signedArea(points);
  EXPECT_NEAR(total, 100.0, 1e-9);  // the whole 10 x 10 section, from the written numbers
}

/// expat callbacks: counts elements by name.
void XMLCALL onStart(void* data, const XML_Char* name, const XML_Char**) {
  ++(*static_cast<std::map<std::string, int>*>(data))[name];
}

TEST(SectionOutput, SvgIsWellFormed) {
  const CutCube cube;
  const Section s =
      blocks::sectionOf(cube.model, cube.network, geometry::axisPlane(1, 5.0), "y=5", 0);
  const std::string svg = formatSectionSvg(s, cube.network, kMaterials);
  std::map<std::string, int> elements;
  XML_Parser parser = XML_ParserCreate(nullptr);
  XML_SetUserData(parser, &elements);
  XML_SetElementHandler(parser, onStart, nullptr);
  const XML_Status status = XML_Parse(parser, svg.data(), static_cast<int>(svg.size()), XML_TRUE);
  EXPECT_EQ(status, XML_STATUS_OK) << XML_ErrorString(XML_GetErrorCode(parser)) << " at line "
                                   << XML_GetCurrentLineNumber(parser);
  XML_ParserFree(parser);
  EXPECT_EQ(elements["svg"], 1);
  EXPECT_EQ(elements["polygon"], 4);  // one per piece section
  // Block outlines: 4 + 4 + 3 + 4 edges, none fictitious; + 3 traces + 4 legend lines +
  // the scale bar.
  EXPECT_EQ(elements["line"], 15 + 3 + 4 + 1);
}

/// Sum of the polygons' areas (m2).
double sectionArea(const Section& s) {
  double total = 0.0;
  for (const SectionPolygon& p : s.polygons) total += geometry::signedArea(p.points);
  return total;
}

TEST(SectionOutput, PlaneOnAFaceTakesThePiecesAboveIt) {
  // z = 4 is the plane of disc 1: the pieces below only touch it, the pieces above have a
  // face on it. The section is the one just above: the upper block's 10 x 10 face (disc 3's
  // piece starts at x = 10 there, a line); before, a plane on a face gave no polygon at all.
  const CutCube cube;
  const Section s =
      blocks::sectionOf(cube.model, cube.network, geometry::axisPlane(2, 4.0), "z=4", 0);
  ASSERT_FALSE(s.polygons.empty());
  // The domain's section is 100 m2; coordinates are small integers (round-off 1e-14).
  EXPECT_NEAR(sectionArea(s), 100.0, 1e-9);
  for (const SectionPolygon& p : s.polygons) {
    const blocks::Block& block = cube.model.blocks[static_cast<std::size_t>(p.block - 1)];
    EXPECT_GT(block.mass.centroid().z(), 4.0);  // a block above the plane
    // Its edges: the box's x_min, x_max, y_min, y_max faces, or a cut; never disc 1 itself.
    for (const blocks::FaceSource& e : p.edges)
      EXPECT_FALSE(e.kind == blocks::FaceKind::Disc && e.id == 1);
  }
  // Disc 1 lies in the plane (no trace); disc 2 ends on it (its edge touches: no trace);
  // disc 3 crosses it along x = 10, clipped to the box's edge: a point, so no trace either.
  for (const SectionTrace& t : s.traces) EXPECT_NE(t.disc, 1);
}

TEST(SectionOutput, SectionsOfAMultiBlockModelTileTheDomainSection) {
  // 40 random discs (radius 3-7 m) in the 10 m cube, cut by both cutters with at most 4
  // discs per kd region, so that region faces lie on the mid-planes x = 5 (the first split,
  // exactly halfway) and others: the Xiangjiaba quick run's section y = 10 was such a
  // mid-plane and gave 1 polygon instead of thousands. Whatever the plane, the polygons tile
  // the cube's 100 m2 section: their areas sum to it within 1e-9 relative (issue 6).
  const geometry::FractureNetwork network =
      blocks::randomDiscNetwork({.discs = 40, .side = 10.0, .seed = 7});
  const blocks::CutInput input = blocks::boxCutInput(network);
  blocks::ExactCutOptions exact_options;
  exact_options.max_discs_per_region = 4;
  blocks::FastCutOptions fast_options;
  fast_options.max_discs_per_region = 4;
  const blocks::BlockModel exact = blocks::cutExact(input, exact_options);
  const blocks::BlockModel fast = blocks::cutFast(input, fast_options);
  ASSERT_GT(exact.blocks.size(), 20u) << "a multi-block model";
  for (const auto& [axis, offset] :
       std::vector<std::pair<int, double>>{{0, 5.0}, {1, 5.0}, {2, 5.0}, {1, 3.7}, {0, 2.5}}) {
    for (const blocks::BlockModel* model : {&exact, &fast}) {
      const Section s =
          blocks::sectionOf(*model, network, geometry::axisPlane(axis, offset), "", 24);
      EXPECT_NEAR(sectionArea(s), 100.0, 1e-7) << "axis " << axis << " at " << offset;
      // Each polygon belongs to a block the plane crosses or bounds from below.
      EXPECT_GT(s.polygons.size(), 10u);
    }
  }
}

}  // namespace
}  // namespace rockmass::io
