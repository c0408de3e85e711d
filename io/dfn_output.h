#pragma once
/// Files of the `dfn` stage: fractures.fab, fractures.csv, fractures.vtu.
#include <string>

#include "geometry/fracture_network.h"
#include "io/fab.h"

namespace rockmass::io {

/// The network as FAB polygons: ellipses become `segments`-gons, polygons stay as they are.
/// Fracture ids are disc ids, set ids are set index + 1.
FabFile toFab(const geometry::FractureNetwork& network, int segments);

/// fractures.csv: id,set,cx,cy,cz,dip_direction,dip,a,b,major_x,major_y,major_z
/// (set is the set name).
std::string formatFracturesCsv(const geometry::FractureNetwork& network);

/// fractures.vtu: VTK XML unstructured grid (ASCII) of polygons (`segments`-gons for
/// ellipses) with cell data id, set, cuts.
std::string formatFracturesVtu(const geometry::FractureNetwork& network, int segments);

}  // namespace rockmass::io
