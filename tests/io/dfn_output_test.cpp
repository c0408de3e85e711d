#include "io/dfn_output.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "geometry/disc.h"
#include "io/atomic_file.h"
#include "tests/support/vtu_reading.h"

namespace rockmass::io {
namespace {

using geometry::Disc;
using geometry::FractureNetwork;
using geometry::Vec3;
using test::attribute;
using test::dataArray;

constexpr int kSegments = 12;

/// Three discs: a horizontal ellipse (J1), a vertical circle that does not cut (a fault
/// whose set name needs CSV quoting), and a polygon-form disc from a FAB file.
FractureNetwork smallNetwork() {
  FractureNetwork network;
  network.sets.push_back({.name = "J1"});
  network.sets.push_back({.name = "F1, \"west\"", .origin = geometry::DiscOrigin::Fault});
  network.sets.push_back({.name = "mapped", .origin = geometry::DiscOrigin::FabFile});

  Disc horizontal;
  horizontal.id = 1;
  horizontal.set = 0;
  horizontal.center = Vec3(1, 2, 3);
  horizontal.normal = Vec3::UnitZ();
  horizontal.major = Vec3::UnitX();
  horizontal.a = 2.0;
  horizontal.b = 1.0;
  network.discs.push_back(horizontal);

  Disc vertical;
  vertical.id = 2;
  vertical.set = 1;
  vertical.origin = geometry::DiscOrigin::Fault;
  vertical.center = Vec3(0, -5, 2.5);
  vertical.normal = Vec3::UnitX();
  vertical.major = Vec3::UnitY();
  vertical.a = 3.0;
  vertical.b = 3.0;
  vertical.cuts = false;
  network.discs.push_back(vertical);

  Disc polygon = geometry::discFromPolygon(
      {Vec3(0, 0, -1), Vec3(4, 0, -1), Vec3(4, 2, -0.5), Vec3(0, 2, -0.5)});
  polygon.id = 3;
  polygon.set = 2;
  polygon.origin = geometry::DiscOrigin::FabFile;
  network.discs.push_back(polygon);
  return network;
}

/// The lines of `text` (which ends with "\n").
std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> result;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);) result.push_back(line);
  return result;
}

/// How often `needle` occurs in `text`.
std::size_t occurrences(const std::string& text, const std::string& needle) {
  std::size_t count = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos;
       at = text.find(needle, at + 1)) {
    ++count;
  }
  return count;
}

TEST(DfnOutputCsv, HeaderAndOneLinePerDisc) {
  const FractureNetwork network = smallNetwork();
  const std::vector<std::string> csv = lines(formatFracturesCsv(network));
  ASSERT_EQ(csv.size(), 4u);
  EXPECT_EQ(csv[0], "id,set,cx,cy,cz,dip_direction,dip,a,b,major_x,major_y,major_z");
  // Horizontal: dip 0 and, by convention, dip direction 0.
  EXPECT_EQ(csv[1], "1,J1,1,2,3,0,0,2,1,1,0,0");
  // Normal +x: the plane strikes north-south and dips 90 degrees towards the east (90).
  // The angles come from inverse trigonometry, so they are compared to 1e-12 degrees.
  const std::string quoted_name = "\"F1, \"\"west\"\"\"";
  ASSERT_EQ(csv[2].rfind("2," + quoted_name + ",0,-5,2.5,", 0), 0u) << csv[2];
  std::istringstream rest(csv[2].substr(("2," + quoted_name + ",0,-5,2.5,").size()));
  double dip_direction = 0, dip = 0;
  char comma = 0;
  rest >> dip_direction >> comma >> dip;
  EXPECT_NEAR(dip_direction, 90.0, 1e-12);
  EXPECT_NEAR(dip, 90.0, 1e-12);
  EXPECT_TRUE(csv[2].ends_with(",3,3,0,1,0")) << csv[2];
  EXPECT_TRUE(csv[3].starts_with("3,mapped,")) << csv[3];
}

TEST(DfnOutputFab, OutlinesWithDiscIdsAndSetsFromOne) {
  const FractureNetwork network = smallNetwork();
  const FabFile fab = toFab(network, kSegments);
  ASSERT_EQ(fab.fractures.size(), 3u);
  for (std::size_t i = 0; i < fab.fractures.size(); ++i) {
    EXPECT_EQ(fab.fractures[i].id, network.discs[i].id);
    EXPECT_EQ(fab.fractures[i].set, network.discs[i].set + 1);
  }
  EXPECT_EQ(fab.fractures[0].vertices.size(), static_cast<std::size_t>(kSegments));
  // The second disc does not cut blocks: an octagon is enough for viewing it.
  EXPECT_EQ(fab.fractures[1].vertices.size(), static_cast<std::size_t>(kRqdOnlySegments));
  EXPECT_EQ(fab.fractures[2].vertices, network.discs[2].polygon);  // exactly as given

  const FabFile parsed = parseFab(formatFab(fab), "fractures.fab");
  ASSERT_EQ(parsed.fractures.size(), fab.fractures.size());
  for (std::size_t i = 0; i < fab.fractures.size(); ++i) {
    EXPECT_EQ(parsed.fractures[i].id, fab.fractures[i].id);
    EXPECT_EQ(parsed.fractures[i].set, fab.fractures[i].set);
    EXPECT_EQ(parsed.fractures[i].vertices, fab.fractures[i].vertices);
  }
}

TEST(DfnOutputVtu, PolygonCellsWithCellData) {
  const FractureNetwork network = smallNetwork();
  const std::string vtu = formatFracturesVtu(network, kSegments);
  EXPECT_TRUE(
      vtu.starts_with("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" "
                      "version=\"1.0\" byte_order=\"LittleEndian\" "
                      "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n"));
  EXPECT_TRUE(vtu.ends_with("</VTKFile>\n"));
  EXPECT_EQ(occurrences(vtu, "<DataArray "), 7u);
  EXPECT_EQ(occurrences(vtu, "</DataArray>"), 7u);

  std::vector<double> expected_points;
  std::vector<double> expected_offsets;
  std::size_t point_count = 0;
  for (const Disc& disc : network.discs) {
    for (const Vec3& p : outputOutline(disc, kSegments)) {
      expected_points.insert(expected_points.end(), {p.x(), p.y(), p.z()});
      ++point_count;
    }
    expected_offsets.push_back(static_cast<double>(point_count));
  }
  EXPECT_EQ(point_count, kSegments + kRqdOnlySegments + 4u);
  EXPECT_EQ(attribute(vtu, "NumberOfPoints"), std::to_string(point_count));
  EXPECT_EQ(attribute(vtu, "NumberOfCells"), "3");
  EXPECT_EQ(dataArray(vtu, "Points"), expected_points);  // exact: binary doubles

  std::vector<double> expected_connectivity;
  for (std::size_t i = 0; i < point_count; ++i) {
    expected_connectivity.push_back(static_cast<double>(i));
  }
  EXPECT_EQ(dataArray(vtu, "connectivity"), expected_connectivity);
  ASSERT_EQ(dataArray(vtu, "offsets"), expected_offsets);
  EXPECT_EQ(dataArray(vtu, "offsets").back(), static_cast<double>(point_count));
  EXPECT_EQ(dataArray(vtu, "types"), std::vector<double>(3, 7.0));  // VTK_POLYGON
  EXPECT_EQ(dataArray(vtu, "id"), (std::vector<double>{1, 2, 3}));
  // Numbered as in fractures.fab, from 1 (summary.json's sets[set - 1]).
  EXPECT_EQ(dataArray(vtu, "set"), (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(dataArray(vtu, "cuts"), (std::vector<double>{1, 0, 1}));
}

TEST(DfnOutputVtu, EmptyNetworkHasNoPointsOrCells) {
  const std::string vtu = formatFracturesVtu(FractureNetwork{}, kSegments);
  EXPECT_EQ(attribute(vtu, "NumberOfPoints"), "0");
  EXPECT_EQ(attribute(vtu, "NumberOfCells"), "0");
  EXPECT_TRUE(dataArray(vtu, "offsets").empty());
}

TEST(DfnOutputVtu, IsWellFormedXml) {
  if (std::system("python3 -c 'import xml.dom.minidom' >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "python3 with xml.dom.minidom is not available";
  }
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("rockmass_fractures_" + std::to_string(::getpid()) + ".vtu");
  writeFileAtomically(path, formatFracturesVtu(smallNetwork(), kSegments));
  const std::string command =
      "python3 -c 'import xml.dom.minidom,sys; "
      "xml.dom.minidom.parse(sys.argv[1])' '" +
      path.string() + "'";
  const int status = std::system(command.c_str());
  std::filesystem::remove(path);
  EXPECT_EQ(status, 0);
}

}  // namespace
}  // namespace rockmass::io
