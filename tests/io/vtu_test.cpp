// The VTU writer's compressed arrays (io/vtu.h), read back by the tests' own decoder
// (tests/support/vtu_reading.h: the block header of VTK's vtkZLibDataCompressor format, zlib's
// uncompress). meshio and VTK read the same files in meshio_read_test.py.
#include "io/vtu.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "tests/support/vtu_reading.h"

namespace rockmass::io {
namespace {

using test::attribute;
using test::dataArray;

/// A piece of `n` points (a helix, so that the coordinates are not all alike) and one
/// polygon cell through them, with an integer point array.
VtuPiece helix(std::size_t n) {
  VtuPiece piece;
  std::vector<std::int32_t> index;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 0.01 * static_cast<double>(i);
    piece.points.insert(piece.points.end(), {std::cos(t), std::sin(t), 1e-3 * t});
    piece.connectivity.push_back(static_cast<std::int64_t>(i));
    index.push_back(static_cast<std::int32_t>(i));
  }
  piece.offsets.push_back(static_cast<std::int64_t>(n));
  piece.types.push_back(7);
  piece.point_data.push_back(makeVtuArray("index", index));
  return piece;
}

TEST(VtuCompression, ArraysOfManyBlocksReadBackExactly) {
  // 50 000 points: 1.2 MB of coordinates, 37 blocks of 32 KiB, the last one partial; the
  // connectivity 400 kB (13 blocks). Exact: the values are the bytes written.
  const VtuPiece piece = helix(50000);
  const std::string vtu = formatVtu(piece);
  EXPECT_EQ(attribute(vtu, "compressor"), "vtkZLibDataCompressor");
  EXPECT_EQ(dataArray(vtu, "Points"), piece.points);
  const std::vector<double> connectivity = dataArray(vtu, "connectivity");
  ASSERT_EQ(connectivity.size(), 50000u);
  for (std::size_t i = 0; i < connectivity.size(); ++i) {
    ASSERT_EQ(connectivity[i], static_cast<double>(i));
  }
  EXPECT_EQ(dataArray(vtu, "index").back(), 49999.0);
  EXPECT_EQ(dataArray(vtu, "offsets"), std::vector<double>{50000.0});
}

TEST(VtuCompression, AnArrayOfExactlyOneBlockHasNoPartialBlock) {
  // 4 096 doubles = 32 768 bytes: one full block, last-block size 0 in the header (VTK's
  // convention: 0 when the last block is full).
  VtuPiece piece;
  piece.points.assign(4096, 2.5);
  piece.offsets.push_back(0);
  piece.types.push_back(1);
  piece.cell_data.push_back(makeVtuArray("x", std::vector<double>(4096, 1.0)));
  const std::string vtu = formatVtu(piece);
  EXPECT_EQ(dataArray(vtu, "x"), std::vector<double>(4096, 1.0));
}

/// The length of the text of the DataArray called `name` in `xml`.
std::size_t arrayTextLength(const std::string& xml, const std::string& name) {
  const std::size_t begin = xml.find('>', xml.find("Name=\"" + name + "\"")) + 1;
  return xml.find("</DataArray>", begin) - begin;
}

TEST(VtuCompression, EmptyArraysAndIndexArraysCompress) {
  VtuPiece empty;
  const std::string none = formatVtu(empty);
  EXPECT_TRUE(dataArray(none, "offsets").empty());
  // An index counting up (the connectivity of 50 000 points, 400 kB of Int64) compresses: its text,
  // base64 included, is under a third of its raw bytes (measured: 101 548 characters, 3.9 times
  // less). The coordinates of a helix are nearly incompressible doubles (1.2 MB in 1.6 MB of text).
  const std::string vtu = formatVtu(helix(50000));
  EXPECT_LT(3 * arrayTextLength(vtu, "connectivity"), 50000u * 8u)
      << arrayTextLength(vtu, "connectivity");
}

}  // namespace
}  // namespace rockmass::io
