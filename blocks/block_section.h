#pragma once
/// A plane section through the block model (Figure 5 of the Xiangjiaba paper): the 2D
/// polygons of the blocks' convex pieces, with the provenance of every edge, and the traces
/// of the fractures, faults and interlayers (written by io/section_output.h).
#include <cstdint>
#include <string>
#include <vector>

#include "blocks/block_model.h"
#include "geometry/fracture_network.h"
#include "geometry/plane_section.h"

namespace rockmass::blocks {

/// The section of one convex piece of a block.
struct SectionPolygon {
  int block = 0;                       ///< block id (as in blocks.csv)
  int material = 0;                    ///< material index
  int piece = 0;                       ///< piece index within the block
  std::vector<geometry::Vec2> points;  ///< (u, v) corners, counter-clockwise (m)
  std::vector<FaceSource> edges;       ///< per edge points[k] -> points[k + 1]
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
Section sectionOf(const BlockModel& model, const geometry::FractureNetwork& network,
                  const geometry::SectionPlane& plane, const std::string& label, int disc_segments);

}  // namespace rockmass::blocks
