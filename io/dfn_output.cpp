#include "io/dfn_output.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "geometry/orientation.h"
#include "io/atomic_file.h"
#include "io/vtu.h"

namespace rockmass::io {
namespace {

using geometry::Disc;
using geometry::FractureNetwork;
using geometry::Vec3;

/// Appends ",x,y,z" in shortest round-trip form.
void appendCsvVector(std::string& out, const Vec3& v) {
  for (int axis = 0; axis < 3; ++axis) out += ',' + formatDouble(v[axis]);
}

}  // namespace

std::vector<Vec3> outputOutline(const Disc& disc, int segments) {
  return disc.outline(disc.cuts ? segments : std::min(segments, kRqdOnlySegments));
}

FabFile toFab(const FractureNetwork& network, int segments) {
  FabFile fab;
  for (const auto& set : network.sets) fab.set_names.push_back(set.name);
  // The ellipse the outline stands for (fractures.csv has it too).
  fab.property_names = {"Semi-major axis (m)", "Semi-minor axis (m)"};
  fab.fractures.reserve(network.discs.size());
  for (const Disc& disc : network.discs) {
    fab.fractures.push_back(
        {disc.id, disc.set + 1, outputOutline(disc, segments), {disc.a, disc.b}});
  }
  return fab;
}

/// One CSV line per disc: id, set name, centre, orientation, semi-axes, major axis.
std::string formatFracturesCsv(const FractureNetwork& network) {
  std::string out = "id,set,cx,cy,cz,dip_direction,dip,a,b,major_x,major_y,major_z\n";
  for (const Disc& disc : network.discs) {
    const geometry::PlaneOrientation orientation = geometry::orientationFromNormal(disc.normal);
    out += std::to_string(disc.id) + ',' + csvField(network.sets.at(disc.set).name);
    appendCsvVector(out, disc.center);
    out += ',' + formatDouble(orientation.dip_direction) + ',' + formatDouble(orientation.dip);
    out += ',' + formatDouble(disc.a) + ',' + formatDouble(disc.b);
    appendCsvVector(out, disc.major);
    out += '\n';
  }
  return out;
}

std::string formatFracturesVtu(const FractureNetwork& network, int segments) {
  constexpr std::uint8_t kVtkPolygon = 7;
  VtuPiece piece;
  std::vector<std::int64_t> ids;
  std::vector<std::int32_t> sets;
  std::vector<std::uint8_t> cuts;
  for (const Disc& disc : network.discs) {
    for (const Vec3& p : outputOutline(disc, segments)) {
      piece.connectivity.push_back(static_cast<std::int64_t>(piece.points.size() / 3));
      piece.points.insert(piece.points.end(), {p.x(), p.y(), p.z()});
    }
    piece.offsets.push_back(static_cast<std::int64_t>(piece.connectivity.size()));
    piece.types.push_back(kVtkPolygon);
    ids.push_back(disc.id);
    sets.push_back(disc.set + 1);  // the set number of the FAB file: summary.json sets[set - 1]
    cuts.push_back(disc.cuts ? 1 : 0);
  }
  piece.cell_data = {makeVtuArray("id", ids), makeVtuArray("set", sets),
                     makeVtuArray("cuts", cuts)};
  return formatVtu(piece);
}

}  // namespace rockmass::io
