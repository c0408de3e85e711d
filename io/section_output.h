#pragma once
/// A plane section through the block model (blocks/block_section.h) written as section.csv
/// (data) and section.svg (a drawing an engineer can open in any browser).
#include <cstdint>
#include <string>
#include <vector>

#include "blocks/block_section.h"
#include "geometry/fracture_network.h"
#include "geometry/plane_section.h"
#include "io/scene.h"

namespace rockmass::io {

using blocks::Section;
using blocks::SectionPolygon;
using blocks::SectionTrace;

/// section.csv, one row per polygon corner or trace end point:
/// `kind,id,label,part,vertex,u,v,x,y,z,source` where
/// - kind: block | joint | fault | interlayer | fab (the disc's origin);
/// - id: block id or disc id; label: material name (blocks) or set name (traces);
/// - part: piece index in the block, or segment index of the trace;
/// - vertex: corner index (counter-clockwise in u, v) or 0 / 1 for the two trace ends;
/// - u, v: in-plane coordinates (m); x, y, z: the same point in 3D (m);
/// - source: blocks: what made the edge from this corner to the next, `disc:<id>`,
///   `boundary:<face>` (0..5: x_min, x_max, y_min, y_max, z_min, z_max),
///   `structure:<index>` or `fictitious` (an internal cut inside a block); traces:
///   `cutting` or `not_cutting` (a disc below min_cut_size, counted for RQD only).
std::string formatSectionCsv(const Section& section, const geometry::FractureNetwork& network,
                             const std::vector<Material>& materials);

/// section.svg: the pieces filled by material, the block outlines (every edge that is not
/// fictitious), the traces (joints thin, non-cutting joints light, faults red, interlayers
/// brown and thick), a legend, a scale bar and the plane's label. u to the right, v up.
std::string formatSectionSvg(const Section& section, const geometry::FractureNetwork& network,
                             const std::vector<Material>& materials);

}  // namespace rockmass::io
