// Which material a point of the rock has: the material of the slab (thick fault or
// interlayer) it lies in, or the rock material. Shared by both cutters.
#pragma once

#include "geometry/fracture_network.h"

namespace rockmass::blocks {

/// Material at `point` (m): the slab's material when the point lies between the lower and
/// upper surfaces of a slab of `network`, else `rock_material`. "Between" means that along
/// the line through the point in the direction of the slab set's mean normal, the nearest
/// slab surface on one side is a lower surface and the nearest on the other side an upper
/// surface. Use a point strictly inside a block (its pieces' centroids): a point exactly on a
/// slab surface is ambiguous. The first slab that contains the point wins.
int materialAt(const geometry::FractureNetwork& network, const geometry::Vec3& point,
               int rock_material);

}  // namespace rockmass::blocks
