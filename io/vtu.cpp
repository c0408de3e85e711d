#include "io/vtu.h"

#include <algorithm>
#include <bit>

namespace rockmass::io {
namespace {

static_assert(std::endian::native == std::endian::little,
              "VTU files are written little-endian; add byte swapping for this platform");

/// Appends one inline binary <DataArray>. The UInt64 byte count that precedes the values
/// is base64-encoded on its own, then the values: VTK's reader decodes the two separately.
void appendArray(std::string& out, const VtuArray& array) {
  const std::uint64_t size = array.bytes.size();
  out += "        <DataArray type=\"" + array.type + "\" Name=\"" + array.name + "\"";
  // Scalars (and the cells' topology arrays) carry no NumberOfComponents, as VTK's own writer
  // does: meshio reads a topology array that has it as a 2D table and fails.
  if (array.components != 1) {
    out += " NumberOfComponents=\"" + std::to_string(array.components) + "\"";
  }
  for (std::size_t c = 0; c < array.component_names.size(); ++c) {
    out += " ComponentName" + std::to_string(c) + "=\"" + array.component_names[c] + "\"";
  }
  out += " format=\"binary\">\n          ";
  out += base64Encode(std::string_view(reinterpret_cast<const char*>(&size), sizeof size));
  out += base64Encode(array.bytes);
  out += "\n        </DataArray>\n";
}

/// Appends a <CellData>/<PointData> section (nothing when there are no arrays).
void appendSection(std::string& out, const char* tag, const std::vector<VtuArray>& arrays) {
  if (arrays.empty()) return;
  out += std::string("      <") + tag + ">\n";
  for (const VtuArray& array : arrays) appendArray(out, array);
  out += std::string("      </") + tag + ">\n";
}

/// Where cell `c` starts in an array indexed by the cells' end offsets (connectivity, faces).
std::int64_t cellBegin(const std::vector<std::int64_t>& offsets, std::size_t c) {
  return c == 0 ? 0 : offsets[c - 1];
}

/// The number of points of cell `c`.
std::int64_t pointCount(const VtuPiece& piece, std::size_t c) {
  return piece.offsets[c] - cellBegin(piece.offsets, c);
}

/// The polyhedron cells of `piece` in ascending order of their point counts (stable), with
/// their cell data: meshio (7.0) files polyhedra in blocks by point count in the order it
/// meets them but files their cell data in ascending order of the count, so that any other
/// order pairs the cells with the wrong data (it refuses the file, or worse). VTK and
/// ParaView read any order. The blocks keep their relative order within a count, and every
/// cell keeps its data (its block id, ...).
VtuPiece polyhedraByPointCount(const VtuPiece& piece) {
  const std::size_t n = piece.types.size();
  std::vector<std::size_t> order(n);
  for (std::size_t c = 0; c < n; ++c) order[c] = c;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return pointCount(piece, a) < pointCount(piece, b);
  });
  VtuPiece out;
  out.points = piece.points;
  out.point_data = piece.point_data;
  for (const std::size_t c : order) {
    out.connectivity.insert(out.connectivity.end(),
                            piece.connectivity.begin() + cellBegin(piece.offsets, c),
                            piece.connectivity.begin() + piece.offsets[c]);
    out.offsets.push_back(static_cast<std::int64_t>(out.connectivity.size()));
    out.types.push_back(piece.types[c]);
    out.faces.insert(out.faces.end(), piece.faces.begin() + cellBegin(piece.faceoffsets, c),
                     piece.faces.begin() + piece.faceoffsets[c]);
    out.faceoffsets.push_back(static_cast<std::int64_t>(out.faces.size()));
  }
  for (const VtuArray& array : piece.cell_data) {
    VtuArray sorted = array;
    const std::size_t stride = n == 0 ? 0 : array.bytes.size() / n;
    for (std::size_t i = 0; i < n; ++i) {
      std::copy_n(array.bytes.begin() + static_cast<std::ptrdiff_t>(order[i] * stride), stride,
                  sorted.bytes.begin() + static_cast<std::ptrdiff_t>(i * stride));
    }
    out.cell_data.push_back(std::move(sorted));
  }
  return out;
}

/// True when every cell is a polyhedron and their point counts do not already ascend.
bool needsPointCountOrder(const VtuPiece& piece) {
  if (piece.faces.empty() || piece.types.empty()) return false;
  for (const std::uint8_t type : piece.types) {
    if (type != 42) return false;
  }
  for (std::size_t c = 1; c < piece.types.size(); ++c) {
    if (pointCount(piece, c) < pointCount(piece, c - 1)) return true;
  }
  return false;
}

}  // namespace

std::string base64Encode(std::string_view bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const std::uint32_t n = (std::uint32_t(std::uint8_t(bytes[i])) << 16) |
                            (std::uint32_t(std::uint8_t(bytes[i + 1])) << 8) |
                            std::uint8_t(bytes[i + 2]);
    out += kAlphabet[(n >> 18) & 63];
    out += kAlphabet[(n >> 12) & 63];
    out += kAlphabet[(n >> 6) & 63];
    out += kAlphabet[n & 63];
  }
  const std::size_t rest = bytes.size() - i;
  if (rest > 0) {
    std::uint32_t n = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    if (rest == 2) n |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    out += kAlphabet[(n >> 18) & 63];
    out += kAlphabet[(n >> 12) & 63];
    out += rest == 2 ? kAlphabet[(n >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string formatVtu(const VtuPiece& given) {
  // Polyhedra of mixed point counts: written in ascending order of the count (meshio).
  const bool reorder = needsPointCountOrder(given);
  const VtuPiece sorted = reorder ? polyhedraByPointCount(given) : VtuPiece{};
  const VtuPiece& piece = reorder ? sorted : given;
  std::string out =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n"
      "  <UnstructuredGrid>\n"
      "    <Piece NumberOfPoints=\"" +
      std::to_string(piece.points.size() / 3) + "\" NumberOfCells=\"" +
      std::to_string(piece.types.size()) + "\">\n";
  appendSection(out, "PointData", piece.point_data);
  appendSection(out, "CellData", piece.cell_data);
  out += "      <Points>\n";
  appendArray(out, makeVtuArray("Points", piece.points, 3));
  out += "      </Points>\n      <Cells>\n";
  appendArray(out, makeVtuArray("connectivity", piece.connectivity));
  appendArray(out, makeVtuArray("offsets", piece.offsets));
  appendArray(out, makeVtuArray("types", piece.types));
  if (!piece.faces.empty()) {
    appendArray(out, makeVtuArray("faces", piece.faces));
    appendArray(out, makeVtuArray("faceoffsets", piece.faceoffsets));
  }
  out +=
      "      </Cells>\n"
      "    </Piece>\n"
      "  </UnstructuredGrid>\n"
      "</VTKFile>\n";
  return out;
}

}  // namespace rockmass::io
