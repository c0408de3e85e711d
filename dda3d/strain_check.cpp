#include "dda3d/strain_check.h"

#include <algorithm>
#include <map>
#include <utility>

#include "dda3d/contact_detection.h"

namespace rockmass::dda3d {

using geometry::Vec3;

std::vector<double> interfaceEccentricity(const Simulation& sim) {
  std::vector<double> ratio(sim.blocks().size(), 0.0);
  // The contact points of each pair of blocks (an ordered map: deterministic), open or
  // closed: together they span the interface; the closed ones carry its force.
  std::map<std::pair<int, int>, std::vector<const Contact*>> interfaces;
  for (const Contact& c : sim.contacts()) {
    interfaces[std::minmax(c.block_i, c.block_j)].push_back(&c);
  }
  for (const auto& [pair, contacts] : interfaces) {
    if (contacts.size() < 3) continue;
    Vec3 normal = Vec3::Zero(), centre = Vec3::Zero(), resultant_at = Vec3::Zero();
    double force = 0.0;
    for (const Contact* c : contacts) {
      // Normals of the two directions of the pair (out of i's or j's face) point opposite
      // ways: oriented from the lower block index to the higher before summing.
      normal += c->block_j == pair.first ? c->normal : Vec3(-c->normal);
      centre += c->point;
      if (c->state == ContactState::Open || !(c->normal_force > 0.0)) continue;
      resultant_at += c->normal_force * c->point;
      force += c->normal_force;
    }
    if (normal.norm() <= 0.0 || !(force > 0.0)) continue;
    normal.normalize();
    centre /= static_cast<double>(contacts.size());
    Vec3 offset = resultant_at / force - centre;
    offset -= normal * normal.dot(offset);  // in the interface plane
    const double e = offset.norm();
    if (e <= 0.0) continue;
    const Vec3 along = offset / e;
    double h = 0.0;
    for (const Contact* c : contacts) h = std::max(h, std::abs(along.dot(c->point - centre)));
    if (h <= 0.0) continue;
    for (const int b : {pair.first, pair.second}) {
      double& r = ratio[static_cast<std::size_t>(b)];
      r = std::max(r, e / h);
    }
  }
  return ratio;
}

}  // namespace rockmass::dda3d
