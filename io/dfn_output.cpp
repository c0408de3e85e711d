#include "io/dfn_output.h"

#include <cstddef>
#include <string_view>
#include <vector>

#include "geometry/orientation.h"
#include "io/atomic_file.h"

namespace rockmass::io {
namespace {

using geometry::Disc;
using geometry::FractureNetwork;
using geometry::Vec3;

/// `field` as a CSV field: quoted (with doubled quotes) when it holds a comma, quote or newline.
std::string csvField(const std::string& field) {
  if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
  std::string quoted = "\"";
  for (char c : field) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + '"';
}

/// Appends ",x,y,z" in shortest round-trip form.
void appendCsvVector(std::string& out, const Vec3& v) {
  for (int axis = 0; axis < 3; ++axis) out += ',' + formatDouble(v[axis]);
}

/// Appends one ASCII VTK <DataArray> whose values are `body` (already formatted lines).
void appendDataArray(std::string& out, std::string_view type, std::string_view name, int components,
                     const std::string& body) {
  out += "        <DataArray type=\"";
  out += type;
  out += "\" Name=\"";
  out += name;
  out += "\" NumberOfComponents=\"" + std::to_string(components) + "\" format=\"ascii\">\n";
  out += body;
  out += "        </DataArray>\n";
}

/// One line of values for a DataArray body, indented to sit under its tag.
std::string dataLine(const std::string& values) {
  return "          " + values + '\n';
}

}  // namespace

/// Outline of every disc as a FAB polygon, id = disc id, set = set index + 1.
FabFile toFab(const FractureNetwork& network, int segments) {
  FabFile fab;
  fab.fractures.reserve(network.discs.size());
  for (const Disc& disc : network.discs) {
    fab.fractures.push_back({disc.id, disc.set + 1, disc.outline(segments)});
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

/// VTK XML UnstructuredGrid (ASCII): one VTK_POLYGON cell per disc outline, with cell data
/// id (disc id), set (set index) and cuts (0/1).
std::string formatFracturesVtu(const FractureNetwork& network, int segments) {
  constexpr int kVtkPolygon = 7;
  std::string points, connectivity, offsets, types, ids, sets, cuts;
  std::size_t point_count = 0;
  for (const Disc& disc : network.discs) {
    const std::vector<Vec3> outline = disc.outline(segments);
    std::string cell;
    for (const Vec3& p : outline) {
      points +=
          dataLine(formatDouble(p.x()) + ' ' + formatDouble(p.y()) + ' ' + formatDouble(p.z()));
      if (!cell.empty()) cell += ' ';
      cell += std::to_string(point_count++);
    }
    connectivity += dataLine(cell);
    offsets += dataLine(std::to_string(point_count));
    types += dataLine(std::to_string(kVtkPolygon));
    ids += dataLine(std::to_string(disc.id));
    sets += dataLine(std::to_string(disc.set));
    cuts += dataLine(disc.cuts ? "1" : "0");
  }
  std::string out =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n"
      "  <UnstructuredGrid>\n"
      "    <Piece NumberOfPoints=\"" +
      std::to_string(point_count) + "\" NumberOfCells=\"" + std::to_string(network.discs.size()) +
      "\">\n"
      "      <CellData Scalars=\"id\">\n";
  appendDataArray(out, "Int64", "id", 1, ids);
  appendDataArray(out, "Int32", "set", 1, sets);
  appendDataArray(out, "UInt8", "cuts", 1, cuts);
  out += "      </CellData>\n      <Points>\n";
  appendDataArray(out, "Float64", "Points", 3, points);
  out += "      </Points>\n      <Cells>\n";
  appendDataArray(out, "Int64", "connectivity", 1, connectivity);
  appendDataArray(out, "Int64", "offsets", 1, offsets);
  appendDataArray(out, "UInt8", "types", 1, types);
  out +=
      "      </Cells>\n"
      "    </Piece>\n"
      "  </UnstructuredGrid>\n"
      "</VTKFile>\n";
  return out;
}

}  // namespace rockmass::io
