// Where one strain field per block is too coarse (docs/dda3d.md, "Blocks that bend"): a
// deformable block has one uniform strain, so it shows the mean stress of a block that is
// bent, not the bending. A side of a block (its contacts facing one way) whose contact
// resultant lies outside the middle third of the contact (the eccentricity e over the
// side's half-extent h along it above 1/3) loads the block with a bending stress, 3 e / h
// times the mean, larger than the mean itself: the block's reported stress and strain are
// then off by more than 100 % at that side. A column in uniform compression has e = 0; a
// dam's base has the eccentricity of its resultant (the middle-third rule of dam design).
#pragma once

#include <vector>

#include "dda3d/simulation.h"

namespace rockmass::dda3d {

/// e / h above which an interface bends its block more than its mean stress (the middle
/// third rule).
inline constexpr double kMiddleThird = 1.0 / 3.0;

/// Per block: the largest e / h over its sides (0 for a block with no side of three contact
/// points or more, or none closed). A side: the block's contact points whose outward
/// directions lie within 20 deg of each other, open or closed (together they span it). e:
/// distance from their centroid to the point of the closed ones' normal force resultant, in
/// the side's plane; h: the points' largest distance from that centroid along e.
std::vector<double> interfaceEccentricity(const Simulation& sim);

}  // namespace rockmass::dda3d
