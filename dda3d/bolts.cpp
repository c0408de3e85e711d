// The bolts of a simulation (dda3d/model.h DdaBolt): their springs in each step's equations
// and their state after each accepted step (yield, rupture).
#include "dda3d/block_terms.h"
#include "dda3d/simulation.h"

namespace rockmass::dda3d {

using geometry::Vec3;

void Simulation::addBoltTerms() {
  for (std::size_t k = 0; k < bolt_a_.size(); ++k) {
    const MaterialPoint& a = bolt_a_[k];
    const MaterialPoint& b = bolt_b_[k];
    const Vec3 axis = b.current - a.current;
    const double length = axis.norm();
    if (length <= 0.0) continue;
    const Vec3 n = axis / length;
    const DdaBolt& bolt = model_.bolts[k];
    if (bolt_state_[k].broken) continue;
    const double free_length = bolt_state_[k].free_length;
    const int i = movableIndex(a.block);
    const int j = b.block >= 0 ? movableIndex(b.block) : -1;
    const BlockVector ea =
        -displacementMatrix(a.current, blocks_[static_cast<std::size_t>(a.block)].centroid)
             .transpose() *
        n;
    const BlockVector eb =
        j >= 0 ? BlockVector(displacementMatrix(b.current,
                                                blocks_[static_cast<std::size_t>(b.block)].centroid)
                                 .transpose() *
                             n)
               : BlockVector(BlockVector::Zero());
    system_->addSpring(i, ea, j, eb, bolt.stiffness, length - free_length);
  }
}

void Simulation::updateBolts() {
  for (std::size_t k = 0; k < bolt_state_.size(); ++k) {
    BoltState& state = bolt_state_[k];
    if (state.broken) continue;
    const DdaBolt& bolt = model_.bolts[k];
    const double length = (bolt_b_[k].current - bolt_a_[k].current).norm();
    state.force = bolt.stiffness * (length - state.free_length);
    if (state.force >= bolt.rupture_force) {
      state.broken = true;
      state.broken_at = time_;
      state.force = 0.0;
    } else if (state.force > bolt.yield_force) {
      state.yielded = true;
      state.free_length = length - bolt.yield_force / bolt.stiffness;
      state.force = bolt.yield_force;
    }
  }
}

}  // namespace rockmass::dda3d
