#include "blocks/block_section.h"

#include <algorithm>

namespace rockmass::blocks {

Section sectionOf(const BlockModel& model, const geometry::FractureNetwork& network,
                  const geometry::SectionPlane& plane, const std::string& label,
                  int disc_segments) {
  Section section;
  section.plane = plane;
  section.label = label;
  const double tolerance = 1e-9 * std::max(1.0, model.domain.diagonal());
  for (const Block& block : model.blocks) {
    for (std::size_t p = 0; p < block.pieces.size(); ++p) {
      const Piece& piece = block.pieces[p];
      // A plane on the faces of pieces (a cut, or the exact cutter's region faces, which
      // lie at the domain's mid-planes) takes the pieces above it: the polygons tile the
      // section as the pieces tile the domain.
      const auto cut =
          geometry::sectionPolyhedron(piece.shape, plane, tolerance, geometry::FaceInPlane::Above);
      if (!cut) continue;
      SectionPolygon polygon;
      polygon.block = block.id;
      polygon.material = block.material;
      polygon.piece = static_cast<int>(p);
      polygon.points = cut->points;
      for (const int face : cut->edge_faces) {
        polygon.edges.push_back(face >= 0 &&
                                        static_cast<std::size_t>(face) < piece.face_sources.size()
                                    ? piece.face_sources[static_cast<std::size_t>(face)]
                                    : FaceSource{});
      }
      section.polygons.push_back(std::move(polygon));
    }
  }
  for (const geometry::Disc& disc : network.discs) {
    const auto traces = geometry::sectionTrace(disc, plane, network.domain, disc_segments);
    for (std::size_t k = 0; k < traces.size(); ++k) {
      section.traces.push_back(
          {disc.id, disc.set, static_cast<int>(k), traces[k].first, traces[k].second});
    }
  }
  return section;
}

}  // namespace rockmass::blocks
