#include "io/vtu.h"

#include <tbb/parallel_for.h>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <optional>
#include <stdexcept>

namespace rockmass::io {
namespace {

static_assert(std::endian::native == std::endian::little,
              "VTU files are written little-endian; add byte swapping for this platform");

/// Uncompressed bytes per zlib block: VTK's own writer's default (vtkXMLWriter::BlockSize).
constexpr std::size_t kBlockSize = std::size_t{1} << 15;

/// `bytes` as VTK's zlib compressor writes them (vtkZLibDataCompressor): the blocks of
/// kBlockSize bytes each compressed on its own, preceded by the UInt64 header [block
/// count, block size, size of the last block when partial (else 0), compressed size of each
/// block]; the header is base64-encoded on its own, then the compressed blocks together.
/// Blocks are compressed in parallel; each block's bytes depend on the block alone, so the
/// file does not depend on the thread count.
std::string compressedText(const std::string& bytes) {
  const std::size_t n = bytes.size();
  const std::size_t blocks = (n + kBlockSize - 1) / kBlockSize;
  std::vector<std::string> packed(blocks);
  tbb::parallel_for(std::size_t{0}, blocks, [&](std::size_t b) {
    const std::size_t begin = b * kBlockSize;
    const std::size_t size = std::min(kBlockSize, n - begin);
    uLongf packed_size = compressBound(static_cast<uLong>(size));
    std::string& block = packed[b];
    block.resize(packed_size);
    // Level 6, zlib's default and VTK's (sizes and times: docs/blocks.md, "Outputs").
    if (compress2(reinterpret_cast<Bytef*>(block.data()), &packed_size,
                  reinterpret_cast<const Bytef*>(bytes.data() + begin), static_cast<uLong>(size),
                  Z_DEFAULT_COMPRESSION) != Z_OK) {
      throw std::runtime_error("zlib could not compress a VTU array block");
    }
    block.resize(packed_size);
  });
  std::vector<std::uint64_t> header{blocks, kBlockSize, n % kBlockSize};
  std::string data;
  std::size_t total = 0;
  for (const std::string& block : packed) total += block.size();
  data.reserve(total);
  for (const std::string& block : packed) {
    header.push_back(block.size());
    data += block;
  }
  return base64Encode(std::string_view(reinterpret_cast<const char*>(header.data()),
                                       header.size() * sizeof(std::uint64_t))) +
         base64Encode(data);
}

/// Appends one inline binary <DataArray>, zlib-compressed (compressedText); `tuples`, when
/// given, as NumberOfTuples (FieldData arrays need it).
void appendArray(std::string& out, const VtuArray& array, std::optional<std::size_t> tuples = {}) {
  out += "        <DataArray type=\"" + array.type + "\" Name=\"" + array.name + "\"";
  if (tuples) out += " NumberOfTuples=\"" + std::to_string(*tuples) + "\"";
  // Scalars (and the cells' topology arrays) carry no NumberOfComponents, as VTK's own writer
  // does: meshio reads a topology array that has it as a 2D table and fails.
  if (array.components != 1) {
    out += " NumberOfComponents=\"" + std::to_string(array.components) + "\"";
  }
  for (std::size_t c = 0; c < array.component_names.size(); ++c) {
    out += " ComponentName" + std::to_string(c) + "=\"" + array.component_names[c] + "\"";
  }
  out += " format=\"binary\">\n          ";
  out += compressedText(array.bytes);
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
  out.field_data = piece.field_data;
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

std::size_t PointWelder::KeyHash::operator()(const Key& k) const {
  std::size_t h = 0;
  for (const double v : {k.x, k.y, k.z}) {
    h = h * 0x9E3779B97F4A7C15ull + std::hash<double>{}(v);
  }
  return h;
}

std::int64_t PointWelder::index(double x, double y, double z) {
  // + 0.0 turns -0 into 0 (the two compare equal, and must hash alike).
  const Key key{x + 0.0, y + 0.0, z + 0.0};
  const auto [it, added] = index_.try_emplace(key, static_cast<std::int64_t>(points_.size() / 3));
  if (added) points_.insert(points_.end(), {key.x, key.y, key.z});
  return it->second;
}

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
      "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n"
      "  <UnstructuredGrid>\n";
  if (!piece.field_data.empty()) {
    out += "    <FieldData>\n";
    for (const VtuArray& array : piece.field_data) {
      appendArray(
          out, array,
          array.bytes.size() / static_cast<std::size_t>(array.value_size * array.components));
    }
    out += "    </FieldData>\n";
  }
  out += "    <Piece NumberOfPoints=\"" + std::to_string(piece.points.size() / 3) +
         "\" NumberOfCells=\"" + std::to_string(piece.types.size()) + "\">\n";
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
