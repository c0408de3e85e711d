#include "io/vtu.h"

#include <bit>

namespace rockmass::io {
namespace {

static_assert(std::endian::native == std::endian::little,
              "VTU files are written little-endian; add byte swapping for this platform");

/// Appends one inline binary <DataArray>. The UInt64 byte count that precedes the values
/// is base64-encoded on its own, then the values: VTK's reader decodes the two separately.
void appendArray(std::string& out, const VtuArray& array) {
  const std::uint64_t size = array.bytes.size();
  out += "        <DataArray type=\"" + array.type + "\" Name=\"" + array.name +
         "\" NumberOfComponents=\"" + std::to_string(array.components) +
         "\" format=\"binary\">\n          ";
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

std::string formatVtu(const VtuPiece& piece) {
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
  if (!piece.faceoffsets.empty()) {
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
