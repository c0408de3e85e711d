#include "io/rqd_vdb.h"

#include <cmath>

#include "io/atomic_file.h"

namespace rockmass::io {
namespace {

/// An empty grid placed on the volume's cells.
VdbScalarGrid onCells(const rqd::CellGrid& cells, std::string name) {
  VdbScalarGrid grid;
  grid.name = std::move(name);
  grid.first_voxel_center = cells.cellCenter(0, 0, 0);
  grid.voxel_size = cells.cell_size;
  grid.dims = cells.dims;
  return grid;
}

std::vector<float> toFloat(const std::vector<double>& values) {
  return {values.begin(), values.end()};
}

}  // namespace

std::string rqdGridName(double threshold) {
  // In millimetres, the integer part zero-padded to 5 digits: the names sort as the
  // thresholds do (ParaView and the OpenVDB tools list grids by name; "rqd_10m" came before
  // "rqd_1m"), up to 99.999 m.
  // In whole micrometres: 0.3 m is 300 mm, not 299.99999999999997, and 1.3 mm keeps its
  // fraction ".3", not ".30000000000000004".
  const long long um = std::llround(threshold * 1e6);
  std::string digits = std::to_string(um / 1000);
  if (digits.size() < 5) digits.insert(0, 5 - digits.size(), '0');
  std::string fraction;
  if (um % 1000 != 0) {
    fraction = std::to_string(1000 + um % 1000).substr(1);  // three digits
    fraction = '.' + fraction.substr(0, fraction.find_last_not_of('0') + 1);
  }
  return "rqd_" + digits + fraction + "mm";
}

std::vector<VdbScalarGrid> rqdVdbGrids(const rqd::RqdVolume& volume) {
  std::vector<VdbScalarGrid> grids;
  for (std::size_t t = 0; t < volume.thresholds.size(); ++t) {
    const double threshold = volume.thresholds[t];
    VdbScalarGrid grid = onCells(volume.grid, rqdGridName(threshold));
    grid.values = toFloat(volume.mean_rqd[t]);
    grid.units = "percent";
    grid.description = "mean RQD(t = " + formatDouble(threshold) + " m) of " +
                       std::to_string(volume.direction_count) + " scanline axes of " +
                       formatDouble(volume.scanline_length) +
                       " m centred on each cell centre, clipped to the rock domain";
    grid.numbers = {{"threshold_m", threshold},
                    {"scanline_length_m", volume.scanline_length},
                    {"direction_count", volume.direction_count}};
    grids.push_back(std::move(grid));
  }
  VdbScalarGrid p32 = onCells(volume.grid, "p32");
  p32.values = toFloat(volume.p32);
  p32.units = "m2/m3";
  p32.description = "fracture area (one face) inside each cell per cell volume";
  grids.push_back(std::move(p32));
  return grids;
}

void writeRqdVdb(const std::filesystem::path& path, const rqd::RqdVolume& volume) {
  writeVdb(path, rqdVdbGrids(volume));
}

}  // namespace rockmass::io
