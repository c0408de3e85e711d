#include "dda3d/strain_check.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace rockmass::dda3d {

using geometry::Vec3;

namespace {

/// Contact directions within this angle of a side's first contact belong to that side.
const double kSideCosine = std::cos(20.0 * 3.14159265358979323846 / 180.0);

/// One contact point as its block sees it: where, which way out of the block, how hard.
struct Touch {
  Vec3 point;
  Vec3 outward;
  double force;  ///< N, > 0 for a closed, compressed contact, else 0
};

/// e / h of one side of a block: its points' centroid, the resultant of their forces.
double sideEccentricity(const std::vector<const Touch*>& side) {
  if (side.size() < 3) return 0.0;
  Vec3 normal = Vec3::Zero(), centre = Vec3::Zero(), resultant_at = Vec3::Zero();
  double force = 0.0;
  for (const Touch* t : side) {
    normal += t->outward;
    centre += t->point;
    resultant_at += t->force * t->point;
    force += t->force;
  }
  if (!(force > 0.0) || normal.norm() <= 0.0) return 0.0;
  normal.normalize();
  centre /= static_cast<double>(side.size());
  Vec3 offset = resultant_at / force - centre;
  offset -= normal * normal.dot(offset);  // in the side's plane
  const double e = offset.norm();
  if (e <= 0.0) return 0.0;
  const Vec3 along = offset / e;
  double h = 0.0;
  for (const Touch* t : side) h = std::max(h, std::abs(along.dot(t->point - centre)));
  return h > 0.0 ? e / h : 0.0;
}

}  // namespace

std::vector<double> interfaceEccentricity(const Simulation& sim) {
  // Each block's contact points, in contact order (deterministic).
  std::vector<std::vector<Touch>> touches(sim.blocks().size());
  for (const Contact& c : sim.contacts()) {
    const double force =
        c.state != ContactState::Open && c.normal_force > 0.0 ? c.normal_force : 0.0;
    // n points out of j: into i.
    touches[static_cast<std::size_t>(c.block_i)].push_back({c.point, -c.normal, force});
    touches[static_cast<std::size_t>(c.block_j)].push_back({c.point, c.normal, force});
  }
  std::vector<double> ratio(sim.blocks().size(), 0.0);
  for (std::size_t b = 0; b < touches.size(); ++b) {
    // Sides: the points whose outward directions lie within 20 deg of a side's first point.
    std::vector<std::vector<const Touch*>> sides;
    for (const Touch& t : touches[b]) {
      auto side = std::find_if(sides.begin(), sides.end(), [&](const auto& s) {
        return s.front()->outward.dot(t.outward) >= kSideCosine;
      });
      if (side == sides.end()) {
        sides.push_back({&t});
      } else {
        side->push_back(&t);
      }
    }
    for (const auto& side : sides) ratio[b] = std::max(ratio[b], sideEccentricity(side));
  }
  return ratio;
}

}  // namespace rockmass::dda3d
