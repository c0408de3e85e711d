#pragma once
/// A plane section through the block model (Figure 5 of the Xiangjiaba paper): the 2D
/// polygons of the blocks' convex pieces, with the provenance of every edge, and the traces
/// of the fractures, faults and interlayers, written as section.csv (data) and section.svg
/// (a drawing an engineer can open in any browser).
#include <cstdint>
#include <string>
#include <vector>

#include "blocks/block_model.h"
#include "geometry/fracture_network.h"
#include "geometry/plane_section.h"
#include "io/scene.h"

namespace rockmass::io {

/// The section of one convex piece of a block.
struct SectionPolygon {
  int block = 0;                          ///< block id (as in blocks.csv)
  int material = 0;                       ///< material index
  int piece = 0;                          ///< piece index within the block
  std::vector<geometry::Vec2> points;     ///< (u, v) corners, counter-clockwise (m)
  std::vector<blocks::FaceSource> edges;  ///< per edge points[k] -> points[k + 1]
};

/// The trace of one fracture segment in the plane.
struct SectionTrace {
  std::int64_t disc = 0;  ///< disc id (as in fractures.csv)
  int set = 0;            ///< set index of the network
  int part = 0;           ///< segment index of this disc's trace (0 for a convex fracture)
  geometry::Vec2 a = geometry::Vec2::Zero();  ///< (u, v) end points (m)
  geometry::Vec2 b = geometry::Vec2::Zero();
};

/// A plane section of a block model and its network.
struct Section {
  geometry::SectionPlane plane;          ///< the cutting plane
  std::string label;                     ///< e.g. "y=10"
  std::vector<SectionPolygon> polygons;  ///< by block id, then piece
  std::vector<SectionTrace> traces;      ///< by disc id, then part
};

/// Cuts every piece of `model` and every disc of `network` (clipped to the network's
/// domain; ellipses as the `disc_segments`-gons the cutters use, 0 for exact ellipses)
/// with `plane`. Pieces the plane only touches are left out, except that where the plane
/// lies on faces of pieces, the pieces above it (on the normal's side) give those faces
/// (sectionPolyhedron with FaceInPlane::Above): the polygons always tile the section of the
/// domain, even on a disc plane or on a face between two kd regions of the cutters.
Section sectionOf(const blocks::BlockModel& model, const geometry::FractureNetwork& network,
                  const geometry::SectionPlane& plane, const std::string& label, int disc_segments);

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
