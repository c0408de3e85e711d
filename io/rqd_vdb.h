#pragma once
/// The RQD and P32 volumes as an OpenVDB file (`rqd.vdb`).
#include <filesystem>
#include <string>
#include <vector>

#include "io/vdb_file.h"
#include "rqd/rqd_volume.h"

namespace rockmass::io {

/// Name of the grid of mean RQD at threshold t (m): t in millimetres (to the micrometre),
/// its integer part zero-padded to 5 digits, so that the names sort as the thresholds:
/// "rqd_00100mm" (0.1 m), "rqd_01000mm" (1 m), "rqd_01500mm", "rqd_10000mm", "rqd_00062.5mm".
std::string rqdGridName(double threshold);

/// The grids of `rqd.vdb`: one per threshold (rqdGridName, units "percent", metadata
/// "threshold_m", "scanline_length_m", "direction_count"), then "p32" (units "m2/m3"). Voxel
/// (i, j, k) is cell (i, j, k) of the volume's grid, centred at its cell centre.
std::vector<VdbScalarGrid> rqdVdbGrids(const rqd::RqdVolume& volume);

/// Writes rqdVdbGrids(volume) to `path` with writeVdb (atomic, byte-identical for the same
/// volume). Throws std::runtime_error naming the path when writing fails.
void writeRqdVdb(const std::filesystem::path& path, const rqd::RqdVolume& volume);

}  // namespace rockmass::io
