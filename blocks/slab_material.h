// Which material a block of rock has: the material of the slab (thick fault or interlayer)
// that holds most of its volume, or the rock material. ONE rule, shared by both cutters.
#pragma once

#include <vector>

#include "blocks/block_model.h"
#include "blocks/convex_split.h"
#include "geometry/fracture_network.h"

namespace rockmass::blocks {

/// The slabs of a network as convex regions, for point tests.
///
/// A slab is bounded by its lower and upper surface discs. Each lower surface is paired with
/// the upper surface whose centre is nearest (within 4 thicknesses: a surface whose partner
/// lies outside the domain has none), and the pair's region is the convex hull of their
/// `disc_segments`-gons (Disc::outline, the very polygons the cutters cut with): two caps and
/// the side quadrilaterals. The union of a slab's regions is the slab.
class SlabMaterials {
 public:
  /// `network` may be null (no slabs). `tolerance` (m): a point this close outside a region
  /// is in it.
  SlabMaterials(const geometry::FractureNetwork* network, int disc_segments, int rock_material,
                double tolerance);

  /// Material at `point` (m): the material of the first slab region holding it, else the
  /// rock material. A point exactly on a slab surface is ambiguous: use interior points.
  int at(const Vec3& point) const;

  /// Material of a rock block made of `pieces`: each convex piece counts with its volume for
  /// the material at its centroid (an interior point; pieces never straddle a slab surface
  /// that cuts them); the material with the largest volume wins (ties: the smaller index).
  int ofBlock(const std::vector<Piece>& pieces) const;
  /// The same for a block given by the shapes of its convex pieces.
  int ofBlock(const std::vector<const geometry::Polyhedron*>& shapes) const;

 private:
  struct Region {
    std::vector<Plane> planes;  ///< outward
    int material = -1;
  };
  std::vector<Region> regions_;
  int rock_material_ = -1;
  double tolerance_ = 0.0;
};

}  // namespace rockmass::blocks
