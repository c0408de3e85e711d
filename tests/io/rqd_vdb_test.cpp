// rqd.vdb: written by io::writeRqdVdb, read back with OpenVDB itself (not through our code):
// grid names, transform, metadata and every voxel value, and byte-identical rewrites.
#include "io/rqd_vdb.h"

#include <gtest/gtest.h>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <cmath>

#include <stdexcept>

#include "../support/test_support.h"

namespace rockmass::io {
namespace {

using geometry::Vec3;

/// A small volume with distinct, non-round values in every cell (no real RQD computation:
/// this tests the file, not the numbers).
rqd::RqdVolume sampleVolume() {
  rqd::RqdVolume volume;
  volume.grid = rqd::cellGridIn(geometry::Box{{100, -20, -35}, {112.5, -10, -30}}, 2.5);
  volume.thresholds = {0.1, 1.0, 10.0};
  volume.scanline_length = 20.0;
  volume.direction_count = 200;
  const auto cells = static_cast<std::size_t>(volume.grid.cellCount());
  for (std::size_t t = 0; t < volume.thresholds.size(); ++t) {
    std::vector<double> values(cells);
    for (std::size_t c = 0; c < cells; ++c) values[c] = 100.0 / (1.0 + 0.37 * c + t);
    volume.mean_rqd.push_back(values);
  }
  volume.p32.resize(cells);
  for (std::size_t c = 0; c < cells; ++c) volume.p32[c] = c % 3 == 0 ? 0.0 : 0.123 * c;
  return volume;
}

class RqdVdbTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { openvdb::initialize(); }
  test::TempDir dir{"rqd_vdb"};
};

TEST_F(RqdVdbTest, ReadsBackWithOpenVdb) {
  const rqd::RqdVolume volume = sampleVolume();
  ASSERT_EQ(volume.grid.dims, (std::array<int, 3>{5, 4, 2}));
  const auto path = dir.path() / "rqd.vdb";
  writeRqdVdb(path, volume);

  openvdb::io::File file(path.string());
  file.open();
  EXPECT_EQ(file.getGrids()->size(), 4u);
  const std::vector<std::string> names{"rqd_00100mm", "rqd_01000mm", "rqd_10000mm", "p32"};
  for (std::size_t g = 0; g < names.size(); ++g) {
    ASSERT_TRUE(file.hasGrid(names[g])) << names[g];
    const auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(names[g]));
    ASSERT_TRUE(grid) << names[g] << " is not a FloatGrid";
    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_UNKNOWN);
    EXPECT_EQ(grid->metaValue<std::string>("units"), g < 3 ? "percent" : "m2/m3");
    EXPECT_DOUBLE_EQ(grid->voxelSize()[0], 2.5);
    EXPECT_TRUE(grid->hasUniformVoxels());
    // Every cell is an active voxel, including those whose value is 0; outside the grid the
    // value is NaN, no value (with 0 there, a tool sampling outside read RQD 0 %).
    EXPECT_EQ(grid->activeVoxelCount(), static_cast<openvdb::Index64>(volume.grid.cellCount()));
    EXPECT_TRUE(std::isnan(grid->background())) << names[g];
    EXPECT_TRUE(std::isnan(grid->getConstAccessor().getValue(openvdb::Coord(-1, 0, 0))));
    EXPECT_TRUE(std::isnan(grid->getConstAccessor().getValue(openvdb::Coord(5, 3, 1))));
    const std::vector<double>& values = g < 3 ? volume.mean_rqd[g] : volume.p32;
    if (g < 3) {
      EXPECT_EQ(grid->metaValue<double>("threshold_m"), volume.thresholds[g]);
      EXPECT_EQ(grid->metaValue<double>("scanline_length_m"), 20.0);
      EXPECT_EQ(grid->metaValue<double>("direction_count"), 200.0);
    }
    const openvdb::FloatGrid::ConstAccessor accessor = grid->getConstAccessor();
    for (std::int64_t cell = 0; cell < volume.grid.cellCount(); ++cell) {
      const auto [i, j, k] = volume.grid.coordinates(cell);
      const openvdb::Coord ijk(i, j, k);
      // Stored as 32-bit floats (not half): the float of each value, exactly.
      ASSERT_EQ(accessor.getValue(ijk), static_cast<float>(values[static_cast<std::size_t>(cell)]));
      ASSERT_TRUE(accessor.isValueOn(ijk));
      // Voxel centres sit at the cell centres (exact: 2.5 m steps from a whole-metre origin).
      const openvdb::Vec3d world = grid->indexToWorld(ijk);
      const Vec3 center = volume.grid.cellCenter(i, j, k);
      ASSERT_EQ(world, openvdb::Vec3d(center.x(), center.y(), center.z()));
    }
  }
}

TEST_F(RqdVdbTest, SameVolumeGivesTheSameBytesAndNoTemporaryIsLeft) {
  // OpenVDB puts a random UUID in each file; writeVdb replaces it by a content hash.
  writeRqdVdb(dir.path() / "a.vdb", sampleVolume());
  writeRqdVdb(dir.path() / "b.vdb", sampleVolume());
  const std::string a = test::readFile(dir.path() / "a.vdb");
  ASSERT_GT(a.size(), 100u);
  EXPECT_EQ(a, test::readFile(dir.path() / "b.vdb"));
  rqd::RqdVolume changed = sampleVolume();
  changed.p32[1] += 1.0;
  writeRqdVdb(dir.path() / "c.vdb", changed);
  const std::string c = test::readFile(dir.path() / "c.vdb");
  EXPECT_NE(a.substr(21, 36), c.substr(21, 36));  // a different content, a different UUID
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path()))
    ++files;
  EXPECT_EQ(files, 3);
}

TEST_F(RqdVdbTest, UnwritablePathThrowsNamingIt) {
  const auto path = dir.path() / "missing" / "rqd.vdb";
  try {
    writeRqdVdb(path, sampleVolume());
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(path.string()), std::string::npos) << error.what();
  }
}

TEST(VdbFile, RejectsGridsThatDoNotFitTheirShape) {
  VdbScalarGrid grid;
  grid.name = "g";
  grid.dims = {2, 2, 2};
  grid.values.assign(7, 1.0f);
  EXPECT_THROW(writeVdb("unused.vdb", {grid}), std::invalid_argument);
  grid.values.assign(8, 1.0f);
  EXPECT_THROW(writeVdb("unused.vdb", {grid, grid}), std::invalid_argument);  // same name
  grid.voxel_size = 0.0;
  EXPECT_THROW(writeVdb("unused.vdb", {grid}), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists("unused.vdb"));
}

TEST(RqdGridName, NamesSortAsTheThresholds) {
  EXPECT_EQ(rqdGridName(0.1), "rqd_00100mm");
  EXPECT_EQ(rqdGridName(0.3), "rqd_00300mm");  // 0.3 x 1000 is 299.99999999999997
  EXPECT_EQ(rqdGridName(1.0), "rqd_01000mm");
  EXPECT_EQ(rqdGridName(2.5), "rqd_02500mm");
  EXPECT_EQ(rqdGridName(10.0), "rqd_10000mm");
  EXPECT_EQ(rqdGridName(0.0625), "rqd_00062.5mm");
  EXPECT_EQ(rqdGridName(0.0013), "rqd_00001.3mm");  // 1.3 - 1 is 0.30000000000000004
  // In name order as in threshold order (the paper's thresholds and more).
  const std::vector<double> thresholds{0.0625, 0.1, 0.3, 1.0, 1.5, 2.0, 3.0, 7.0, 10.0, 25.0};
  for (std::size_t k = 1; k < thresholds.size(); ++k) {
    EXPECT_LT(rqdGridName(thresholds[k - 1]), rqdGridName(thresholds[k])) << thresholds[k];
  }
}

}  // namespace
}  // namespace rockmass::io
