#include "io/vdb_file.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>

#include "io/atomic_file.h"

namespace rockmass::io {
namespace {

/// Where OpenVDB's file header keeps the UUID text: after the magic number (8 bytes), the
/// file format version and the library's major and minor versions (4 bytes each) and the
/// "has grid offsets" flag (1 byte); 36 characters (8-4-4-4-12 hex digits).
constexpr std::streamoff kUuidOffset = 21;
constexpr std::size_t kUuidLength = 36;

void requireValid(const VdbScalarGrid& grid) {
  const std::string what = "VDB grid '" + grid.name + "': ";
  if (!(std::isfinite(grid.voxel_size) && grid.voxel_size > 0.0)) {
    throw std::invalid_argument(what + "the voxel size must be finite and > 0 m");
  }
  if (grid.dims[0] < 1 || grid.dims[1] < 1 || grid.dims[2] < 1) {
    throw std::invalid_argument(what + "needs at least one voxel along each axis");
  }
  const auto count = static_cast<std::size_t>(grid.dims[0]) *
                     static_cast<std::size_t>(grid.dims[1]) *
                     static_cast<std::size_t>(grid.dims[2]);
  if (grid.values.size() != count) {
    throw std::invalid_argument(what + std::to_string(grid.values.size()) + " values for " +
                                std::to_string(count) + " voxels");
  }
}

openvdb::FloatGrid::Ptr toOpenVdb(const VdbScalarGrid& in) {
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(in.background);
  grid->setName(in.name);
  openvdb::math::Transform::Ptr transform =
      openvdb::math::Transform::createLinearTransform(in.voxel_size);
  transform->postTranslate(openvdb::Vec3d(in.first_voxel_center.x(), in.first_voxel_center.y(),
                                          in.first_voxel_center.z()));
  grid->setTransform(transform);
  grid->setGridClass(openvdb::GRID_UNKNOWN);
  grid->setSaveFloatAsHalf(false);
  grid->insertMeta("units", openvdb::StringMetadata(in.units));
  grid->insertMeta("description", openvdb::StringMetadata(in.description));
  for (const auto& [key, value] : in.numbers) grid->insertMeta(key, openvdb::DoubleMetadata(value));
  openvdb::FloatGrid::Accessor accessor = grid->getAccessor();
  std::size_t index = 0;
  for (int k = 0; k < in.dims[2]; ++k) {
    for (int j = 0; j < in.dims[1]; ++j) {
      for (int i = 0; i < in.dims[0]; ++i) {
        accessor.setValueOn(openvdb::Coord(i, j, k), in.values[index++]);
      }
    }
  }
  return grid;
}

/// 64-bit FNV-1a of `bytes`, starting from `basis`.
std::uint64_t fnv1a(const std::string& bytes, std::uint64_t basis) {
  std::uint64_t hash = basis;
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

/// Replaces the random UUID in the header of the VDB file `file` by 128 bits of hash of
/// everything after it, so that the same content gives the same bytes. Leaves a file whose
/// header does not hold a UUID where expected untouched.
void makeUuidDeterministic(const std::filesystem::path& file) {
  std::fstream stream(file, std::ios::in | std::ios::out | std::ios::binary);
  std::string content{std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
  if (content.size() < kUuidOffset + kUuidLength) return;
  const std::string uuid = content.substr(kUuidOffset, kUuidLength);
  if (uuid[8] != '-' || uuid[13] != '-' || uuid[18] != '-' || uuid[23] != '-') return;
  const std::string rest = content.substr(kUuidOffset + kUuidLength);
  const std::uint64_t high = fnv1a(rest, 0xcbf29ce484222325ULL);
  const std::uint64_t low = fnv1a(rest, high);
  char text[kUuidLength + 1];
  std::snprintf(text, sizeof text, "%08x-%04x-%04x-%04x-%012llx", static_cast<unsigned>(high >> 32),
                static_cast<unsigned>((high >> 16) & 0xffff), static_cast<unsigned>(high & 0xffff),
                static_cast<unsigned>(low >> 48),
                static_cast<unsigned long long>(low & 0xffffffffffffULL));
  stream.clear();
  stream.seekp(kUuidOffset);
  stream.write(text, static_cast<std::streamsize>(kUuidLength));
  stream.close();
  if (!stream) throw std::runtime_error("rewriting the header of " + file.string() + " failed");
}

}  // namespace

void writeVdb(const std::filesystem::path& path, const std::vector<VdbScalarGrid>& grids) {
  std::set<std::string> names;
  for (const VdbScalarGrid& grid : grids) {
    requireValid(grid);
    if (!names.insert(grid.name).second) {
      throw std::invalid_argument("two VDB grids are named '" + grid.name + "'");
    }
  }
  openvdb::initialize();
  openvdb::GridPtrVec vdb_grids;
  for (const VdbScalarGrid& grid : grids) vdb_grids.push_back(toOpenVdb(grid));
  writeAtomically(path, [&](const std::filesystem::path& temporary) {
    openvdb::io::File file(temporary.string());
    file.write(vdb_grids);
    file.close();
    makeUuidDeterministic(temporary);
  });
}

}  // namespace rockmass::io
