#include "io/fab.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "io/atomic_file.h"
#include "io/input_error.h"
#include "tests/support/test_support.h"

namespace rockmass::io {
namespace {

using geometry::Vec3;

/// The message of the InputError that parsing `text` as "f.fab" throws, or "no error".
std::string parseError(const std::string& text) {
  try {
    parseFab(text, "f.fab");
  } catch (const InputError& error) {
    return error.what();
  }
  return "no error";
}

/// Two fractures whose coordinates have no short exact decimal form in binary, or are
/// extreme (1e11 m, near the 1e12 m a FAB vertex may reach; the last vertex 2^-7 m off the
/// plane of the others, within the planarity tolerance), so any loss of precision in writing
/// or reading changes them.
FabFile awkwardFab() {
  FabFile fab;
  fab.set_names = {"J1", "fault \"F1\""};
  fab.property_names = {"Semi-major axis (m)", "Aperture"};
  fab.fractures.push_back(
      {1,
       1,
       {Vec3(0.1, 1.0 / 3.0, -1e-300), Vec3(123456.789, 0.2, 7.0), Vec3(1.0, 2.0, 3.0)},
       {1.0 / 3.0, 1e-300}});
  fab.fractures.push_back({9007199254740993LL,
                           12,
                           {Vec3(-0.0, 0.0, 1e11), Vec3(1e-7, 0.0, 1e11),
                            Vec3(1e-7, 2.0 / 3.0, 1e11), Vec3(0.0, 2.0 / 3.0, 1e11 + 0.0078125)},
                           {7.0, -0.0}});
  return fab;
}

TEST(FabFormat, WritesTheFormatBlockAndNewellNormal) {
  // As FracMan writes a FAB file: PROPERTIES, SETS with names, the property values after the
  // set on the header line, an empty TESSFRACTURE section (pyfracman needs the property
  // table, porepy the tessellated section).
  FabFile fab;
  fab.set_names = {"J1", "J2"};
  fab.property_names = {"Semi-major axis (m)"};
  fab.fractures.push_back(
      {4, 2, {Vec3(0, 0, 0.5), Vec3(2, 0, 0.5), Vec3(2, 1.5, 0.5), Vec3(0, 1.5, 0.5)}, {2.5}});
  EXPECT_EQ(formatFab(fab),
            "BEGIN FORMAT\n"
            "    Format = Ascii\n"
            "    Length_Unit = Meter\n"
            "    XAxis = East\n"
            "    Scale = 1.0\n"
            "    No_Fractures = 1\n"
            "    No_TessFractures = 0\n"
            "    No_Nodes = 4\n"
            "    No_Properties = 1\n"
            "END FORMAT\n"
            "\n"
            "BEGIN PROPERTIES\n"
            "    Prop1 = (Real*4) \"Semi-major axis (m)\"\n"
            "END PROPERTIES\n"
            "\n"
            "BEGIN SETS\n"
            "    Set1 = \"J1\"\n"
            "    Set2 = \"J2\"\n"
            "END SETS\n"
            "\n"
            "BEGIN FRACTURE\n"
            "4 4 2 2.5\n"
            "1 0 0 0.5\n"
            "2 2 0 0.5\n"
            "3 2 1.5 0.5\n"
            "4 0 1.5 0.5\n"
            "0 0 0 1\n"
            "END FRACTURE\n"
            "\n"
            "BEGIN TESSFRACTURE\n"
            "END TESSFRACTURE\n");
}

TEST(FabRoundTrip, WriteReadWriteIsByteIdentical) {
  const FabFile fab = awkwardFab();
  const std::string text = formatFab(fab);
  const FabFile parsed = parseFab(text, "awkward.fab");
  ASSERT_EQ(parsed.fractures.size(), fab.fractures.size());
  for (std::size_t i = 0; i < fab.fractures.size(); ++i) {
    EXPECT_EQ(parsed.fractures[i].id, fab.fractures[i].id);
    EXPECT_EQ(parsed.fractures[i].set, fab.fractures[i].set);
    EXPECT_EQ(parsed.fractures[i].vertices, fab.fractures[i].vertices);  // exact, not near
    EXPECT_EQ(parsed.fractures[i].properties, fab.fractures[i].properties);
  }
  // A double quote in a name is written as a single quote (it would end the FAB string).
  EXPECT_EQ(parsed.set_names, (std::vector<std::string>{"J1", "fault 'F1'"}));
  EXPECT_EQ(parsed.property_names, fab.property_names);
  EXPECT_EQ(formatFab(parsed), text);
}

TEST(FabRoundTrip, EmptyFileHasAnEmptyFractureSection) {
  const std::string text = formatFab(FabFile{});
  EXPECT_NE(text.find("No_Fractures = 0\n"), std::string::npos);
  EXPECT_TRUE(parseFab(text, "empty.fab").fractures.empty());
}

TEST(FabParse, MinimalExampleOfSceneFormat) {
  // The minimal form of docs/scene-format.md, "FAB files" (Scale = 100 is ignored).
  const FabFile fab = parseFab(test::kSceneFormatFab, "minimal.fab");
  ASSERT_EQ(fab.fractures.size(), 1u);
  EXPECT_EQ(fab.fractures[0].id, 1);
  EXPECT_EQ(fab.fractures[0].set, 1);
  const std::vector<Vec3> expected = {Vec3(-1, -1, 5), Vec3(11, -1, 5), Vec3(11, 11, 5),
                                      Vec3(-1, 11, 5)};
  EXPECT_EQ(fab.fractures[0].vertices, expected);
}

TEST(FabParse, SkipsOptionalSectionsAndExtraProperties) {
  // What FracMan writes around the fractures: properties and sets, tessellated fractures,
  // rock blocks; keys in any case, tabs, CRLF, property values after the set id, dummy
  // normals, and no final newline.
  const std::string text =
      "BEGIN FORMAT\r\n"
      "\tformat = ascii\r\n"
      "  LENGTH_UNIT=meter\r\n"
      "  no_fractures\t=\t2\r\n"
      "  No_TessFractures = 1\r\n"
      "  No_Properties = 2\r\n"
      "END FORMAT\r\n"
      "\r\n"
      "BEGIN PROPERTIES\n"
      "  Prop1 = (Real*4) \"Transmissivity\"\n"
      "  Prop2 = (Real*4) \"Aperture\"\n"
      "END PROPERTIES\n"
      "BEGIN SETS\n"
      "  Set = 1 \"J1\"\n"
      "END SETS\n"
      "begin fracture\n"
      "  7   3   2   1.5e-7   0.001\n"
      "  1\t0 0 0\n"
      "  2\t1 0 0\n"
      "  3\t0 1 +2.5\n"
      "  0 -1 -1 -1\n"
      "8 3 1 2e-7 0.002\n"
      "1 5 5 5\n"
      "2 6 5 5\n"
      "3 5 6 5\n"
      "0 -1 -1 -1\n"
      "End Fracture\n"
      "BEGIN TESSFRACTURE\n"
      "1 3 1\n"
      "1 0 0 0\n"
      "END TESSFRACTURE\n"
      "BEGIN ROCKBLOCK\n"
      "1 8 1\n"
      "END ROCKBLOCK";
  const FabFile fab = parseFab(text, "fracman.fab");
  ASSERT_EQ(fab.fractures.size(), 2u);
  EXPECT_EQ(fab.fractures[0].id, 7);
  EXPECT_EQ(fab.fractures[0].set, 2);
  const std::vector<Vec3> first = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 2.5)};
  EXPECT_EQ(fab.fractures[0].vertices, first);
  EXPECT_EQ(fab.fractures[1].id, 8);
  EXPECT_EQ(fab.fractures[1].set, 1);
  EXPECT_EQ(fab.fractures[1].vertices.size(), 3u);
  // The property names and each fracture's values are read; "Set = 1 \"J1\"" is not
  // FracMan's "Set1 = \"J1\"" and names nothing.
  EXPECT_EQ(fab.property_names, (std::vector<std::string>{"Transmissivity", "Aperture"}));
  EXPECT_EQ(fab.fractures[0].properties, (std::vector<double>{1.5e-7, 0.001}));
  EXPECT_EQ(fab.fractures[1].properties, (std::vector<double>{2e-7, 0.002}));
  EXPECT_TRUE(fab.set_names.empty());
}

TEST(FabParse, SetNamesAndPropertiesThatDoNotMatch) {
  // Set names by their index (Set3 before Set1 leaves Set2 unnamed); a fracture with fewer
  // values than properties keeps none; a word that is no number ends the values.
  const std::string text =
      "BEGIN PROPERTIES\n"
      "  Prop1 = (Real*4) \"A\"\n"
      "  Prop2 = (Real*4) \"B\"\n"
      "END PROPERTIES\n"
      "BEGIN SETS\n"
      "  Set3 = \"third\"\n"
      "  Set1 = \"first\"\n"
      "  Set999999999 = \"too far\"\n"
      "END SETS\n"
      "BEGIN FRACTURE\n"
      "1 3 1 0.5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n0 0 0 1\n"
      "2 3 1 0.5 x\n1 0 0 0\n2 1 0 0\n3 0 1 0\n0 0 0 1\n"
      "3 3 1 0.5 0.25\n1 0 0 0\n2 1 0 0\n3 0 1 0\n0 0 0 1\n"
      "END FRACTURE\n";
  const FabFile fab = parseFab(text, "names.fab");
  EXPECT_EQ(fab.set_names, (std::vector<std::string>{"first", "", "third"}));
  ASSERT_EQ(fab.fractures.size(), 3u);
  EXPECT_TRUE(fab.fractures[0].properties.empty());
  EXPECT_TRUE(fab.fractures[1].properties.empty());
  EXPECT_EQ(fab.fractures[2].properties, (std::vector<double>{0.5, 0.25}));
}

/// A FAB text and the exact message it must be rejected with.
struct BadFab {
  const char* what;
  std::string text;
  std::string message;
};

TEST(FabErrors, GarbledAndTruncatedFilesAreLocated) {
  const std::string format_block =  // lines 1-4
      "BEGIN FORMAT\n"
      "  Format = Ascii\n"
      "  No_Fractures = 2\n"
      "END FORMAT\n";
  const std::string first_fracture =  // lines 6-10, after "BEGIN FRACTURE" on line 5
      "1 3 1\n"
      "1 0 0 0\n"
      "2 1 0 0\n"
      "3 0 1 0\n"
      "0 0 0 1\n";
  const std::string head = format_block + "BEGIN FRACTURE\n" + first_fracture;
  const std::vector<BadFab> cases = {
      {"vertex lines end at END FRACTURE", head + "3 4 1\n1 0 0 1\n2 1 0 1\nEND FRACTURE\n",
       "f.fab:14: expected 4 vertex lines for fracture 3, found 'END FRACTURE'"},
      {"a vertex line is missing",
       head + "3 4 1\n1 0 0 1\n2 1 0 1\n3 1 1 1\n0 0 0 1\nEND FRACTURE\n",
       "f.fab:15: expected 4 vertex lines for fracture 3, found '0 0 0 1'"},
      {"one vertex line too many",
       head + "3 3 1\n1 0 0 1\n2 1 0 1\n3 1 1 1\n4 0 1 1\nEND FRACTURE\n",
       "f.fab:15: expected the normal line '0 nx ny nz' after the 3 vertices of fracture 3, got "
       "'4 0 1 1'"},
      {"a coordinate is not a number", head + "3 3 1\n1 0 0 1\n2 x1 0 1\n",
       "f.fab:13: expected a number, got 'x1'"},
      {"a coordinate is not finite", head + "3 3 1\n1 0 0 1\n2 1 nan 1\n",
       "f.fab:13: vertex 2 of fracture 3 has a non-finite coordinate 'nan'"},
      {"a coordinate overflows", head + "3 3 1\n1 0 0 1\n2 1 1e999 1\n",
       "f.fab:13: expected a number, got '1e999'"},
      // The geometry of each polygon (../shared/repro/bad-input r5-r8), at its header line.
      {"a coordinate beyond 1e12 m", head + "3 3 1\n1 0 0 1\n2 1 1e308 1\n",
       "f.fab:13: vertex 2 of fracture 3 has a coordinate '1e308' beyond 1e12 m"},
      {"collinear vertices", head + "3 3 1\n1 0 0 1\n2 1 0 1\n3 2 0 1\n0 0 0 1\nEND FRACTURE\n",
       "f.fab:11: fracture 3 has no area: its vertices are collinear or coincide"},
      {"a bow-tie", head + "3 4 1\n1 0 0 1\n2 1 1 1\n3 1 0 1\n4 0 1 1\n0 0 0 1\nEND FRACTURE\n",
       "f.fab:11: fracture 3 crosses itself: its lobes turn opposite ways and cancel (no net "
       "area)"},
      {"a twisted quadrilateral",
       head + "3 4 1\n1 0 0 0\n2 1 0 0\n3 1 1 0.5\n4 0 1 0\n0 0 0 1\nEND FRACTURE\n",
       // (the distance from the Newell plane through the vertices' mean offset)
       "f.fab:11: fracture 3 is not planar: vertex 1 lies 0.11785113019775793 m off its plane "
       "(at most 0.01 of its size, 0.015 m)"},
      {"the vertex count is not an integer", head + "3 four 1\n",
       "f.fab:11: expected an integer, got 'four'"},
      {"a polygon of 2 vertices", head + "3 2 1\n1 0 0 1\n2 1 0 1\n0 0 0 1\nEND FRACTURE\n",
       "f.fab:11: fracture 3 has 2 vertices; a polygon needs at least 3"},
      {"a header line is cut short", head + "3 3\n",
       "f.fab:11: expected a fracture header 'id "
       "nvertices set', got '3 3'"},
      {"a vertex line is cut short", head + "3 3 1\n1 0 0 1\n2 1 0\n",
       "f.fab:13: expected a vertex line 'k x y z' for fracture 3, got '2 1 0'"},
      {"the file ends inside the fractures", head + "\n\n",
       "f.fab:12: file ends inside BEGIN FRACTURE (missing END FRACTURE)"},
      {"the file ends inside the format block", "BEGIN FORMAT\n  Format = Ascii\n",
       "f.fab:2: file ends inside BEGIN FORMAT (missing END FORMAT)"},
      {"the file ends inside an optional section", "BEGIN PROPERTIES\n  Prop1 = x\n",
       "f.fab:2: file ends inside BEGIN PROPERTIES (missing END PROPERTIES)"},
      {"No_Fractures does not match", head + "END FRACTURE\n",
       "f.fab:3: header says No_Fractures = 2 but the file has 1"},
      {"No_Fractures is not a number", "BEGIN FORMAT\n  No_Fractures = many\nEND FORMAT\n",
       "f.fab:2: expected an integer, got 'many'"},
      {"a format line without '='", "BEGIN FORMAT\n  Format Ascii\nEND FORMAT\n",
       "f.fab:2: expected 'key = value' in BEGIN FORMAT, got 'Format Ascii'"},
      {"a binary file", "BEGIN FORMAT\n  Format = Binary\nEND FORMAT\n",
       "f.fab:2: Format = Binary is not supported (only Ascii)"},
      {"coordinates in feet", "BEGIN FORMAT\n  Length_Unit = Foot\nEND FORMAT\n",
       "f.fab:2: Length_Unit = Foot is not supported (coordinates must be in metres: Meter)"},
      {"text outside any section", format_block + "hello\n",
       "f.fab:5: expected 'BEGIN <section>', got 'hello'"},
      {"an empty file", "", "f.fab: no BEGIN FRACTURE section"},
      {"only a format block", format_block, "f.fab: no BEGIN FRACTURE section"},
  };
  for (const BadFab& bad : cases) {
    EXPECT_EQ(parseError(bad.text), bad.message) << bad.what;
  }
}

TEST(FabRead, ReadsAWrittenFile) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("rockmass_fab_read_" + std::to_string(::getpid()) + ".fab");
  const FabFile fab = awkwardFab();
  writeFileAtomically(path, formatFab(fab));
  const FabFile read = readFab(path);
  std::filesystem::remove(path);
  EXPECT_EQ(formatFab(read), formatFab(fab));
}

TEST(FabRead, MissingFileIsAnInputError) {
  const std::filesystem::path path = "/nonexistent-rockmass-folder/joints.fab";
  try {
    readFab(path);
    FAIL() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()),
              "/nonexistent-rockmass-folder/joints.fab: cannot read the FAB file");
  }
}

TEST(FabRead, FolderIsAnInputError) {
  const std::filesystem::path folder = std::filesystem::temp_directory_path();
  EXPECT_THROW(readFab(folder), InputError);
}

}  // namespace
}  // namespace rockmass::io
