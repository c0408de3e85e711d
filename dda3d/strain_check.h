// Where one strain field per block is too coarse (docs/dda3d.md, "Blocks that bend"): a
// deformable block has one uniform strain, so it shows the mean stress of a block that is
// bent, not the bending. An interface whose contact resultant lies outside the middle third
// of the contact (the eccentricity e over the contact's half-extent h along it above 1/3)
// loads its block with a bending stress, 3 e / h times the mean, larger than the mean
// itself: the block's reported stress and strain are then off by more than 100 % at its
// faces. A column in uniform compression has e = 0.
#pragma once

#include <vector>

#include "dda3d/simulation.h"

namespace rockmass::dda3d {

/// e / h above which an interface bends its block more than its mean stress (the middle
/// third rule).
inline constexpr double kMiddleThird = 1.0 / 3.0;

/// Per block: the largest e / h over its interfaces with the other blocks (0 for a block
/// with no interface of three contact points or more, or none closed). e: distance from the
/// centroid of the interface's contact points (open or closed: together they span it) to
/// the point of the closed ones' normal force resultant, in the interface plane; h: the
/// points' largest distance from that centroid along e.
std::vector<double> interfaceEccentricity(const Simulation& sim);

}  // namespace rockmass::dda3d
