#pragma once
/// Files of the `dfn` stage: fractures.fab, fractures.csv, fractures.vtu.
#include <string>
#include <vector>

#include "geometry/fracture_network.h"
#include "io/fab.h"

namespace rockmass::io {

/// Vertices written for the ellipse of a disc that does not cut blocks (it counts for RQD
/// only, where its exact ellipse is used; fractures.csv keeps its exact axes). Small discs
/// are the vast majority of a field DFN, so this keeps the files a fraction of the size.
constexpr int kRqdOnlySegments = 8;

/// The polygon written for `disc`: its exact polygon, the `segments`-gon the cutter uses
/// for a disc that cuts, or a min(segments, kRqdOnlySegments)-gon for an RQD-only disc.
std::vector<geometry::Vec3> outputOutline(const geometry::Disc& disc, int segments);

/// The network as FAB polygons (outputOutline). Fracture ids are disc ids, set ids are
/// set index + 1.
FabFile toFab(const geometry::FractureNetwork& network, int segments);

/// fractures.csv: id,set,cx,cy,cz,dip_direction,dip,a,b,major_x,major_y,major_z
/// (set is the set name).
std::string formatFracturesCsv(const geometry::FractureNetwork& network);

/// fractures.vtu: VTK XML unstructured grid (binary arrays) of the outputOutline polygons,
/// with cell data id (disc id), set (set index) and cuts (0/1).
std::string formatFracturesVtu(const geometry::FractureNetwork& network, int segments);

}  // namespace rockmass::io
