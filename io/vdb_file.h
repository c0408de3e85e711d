#pragma once
/// OpenVDB files of scalar fields on regular grids (OpenVDB stays inside io/vdb_file.cpp).
#include <array>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "geometry/vec.h"

namespace rockmass::io {

/// One scalar field on a dense block of cubic voxels, to be stored as an OpenVDB FloatGrid.
/// Voxel (i, j, k), 0 <= i < dims[0] etc., holds values[i + dims[0] (j + dims[1] k)] and is
/// centred at first_voxel_center + voxel_size (i, j, k) in world coordinates.
struct VdbScalarGrid {
  std::string name;                                            ///< grid name in the file (unique)
  geometry::Vec3 first_voxel_center = geometry::Vec3::Zero();  ///< centre of voxel 0 (m)
  double voxel_size = 1.0;                                     ///< voxel edge (m, > 0)
  std::array<int, 3> dims{0, 0, 0};                            ///< voxels along x, y, z (>= 1 each)
  std::vector<float> values;  ///< dims[0] dims[1] dims[2] values, x fastest
  std::string units;          ///< grid metadata "units", e.g. "m2/m3"
  std::string description;    ///< grid metadata "description"
  std::vector<std::pair<std::string, double>> numbers;  ///< more grid metadata (name, value)
  /// The value outside the grid's voxels (inactive): NaN by default, "no value", so that a
  /// tool sampling outside the grid does not read 0 (an RQD of 0 %).
  float background = std::numeric_limits<float>::quiet_NaN();
};

/// Writes `grids` to the OpenVDB file `path`, atomically (writeAtomically). Each grid is a
/// FloatGrid with a linear transform (uniform scale voxel_size, translation to
/// first_voxel_center), every voxel of its block active (zeros included; outside it the
/// `background` is inactive), class GRID_UNKNOWN (a plain scalar field: neither a level set
/// nor a fog volume, whose values would be read as densities in [0, 1]), 32-bit floats
/// (not half), and metadata "units", "description" and the `numbers`. The file's UUID,
/// random in OpenVDB, is replaced by a hash of the file's content, so that the same grids
/// give a byte-identical file. Throws std::invalid_argument for a grid whose value count does
/// not match its dims, a non-positive voxel size, or duplicate names; std::runtime_error
/// (naming the path) when writing fails.
void writeVdb(const std::filesystem::path& path, const std::vector<VdbScalarGrid>& grids);

}  // namespace rockmass::io
