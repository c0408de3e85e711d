#include "dda3d/step_report.h"

#include <chrono>

namespace rockmass::dda3d {

namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

std::vector<std::string> ActiveTerms::names() const {
  std::vector<std::string> out;
  const std::pair<bool, const char*> all[] = {{elastic, "elastic"},
                                              {initial_stress, "initial_stress"},
                                              {inertia, "inertia"},
                                              {body_force, "body_force"},
                                              {point_loads, "point_loads"},
                                              {surface_pressure, "surface_pressure"},
                                              {block_pore_pressure, "block_pore_pressure"},
                                              {fixed_points, "fixed_points"},
                                              {rollers, "rollers"},
                                              {fixed_blocks, "fixed_blocks"},
                                              {contact_normal, "contact_normal"},
                                              {contact_shear, "contact_shear"},
                                              {friction, "friction"},
                                              {bolts, "bolts"}};
  for (const auto& [on, name] : all) {
    if (on) out.emplace_back(name);
  }
  return out;
}

ActiveTerms& ActiveTerms::operator|=(const ActiveTerms& o) {
  elastic |= o.elastic;
  initial_stress |= o.initial_stress;
  inertia |= o.inertia;
  body_force |= o.body_force;
  point_loads |= o.point_loads;
  surface_pressure |= o.surface_pressure;
  block_pore_pressure |= o.block_pore_pressure;
  fixed_points |= o.fixed_points;
  rollers |= o.rollers;
  fixed_blocks |= o.fixed_blocks;
  contact_normal |= o.contact_normal;
  contact_shear |= o.contact_shear;
  friction |= o.friction;
  bolts |= o.bolts;
  return *this;
}

const char* StepProfile::name(StepPhase p) {
  switch (p) {
    case StepPhase::DetectContacts:
      return "detect_contacts";
    case StepPhase::AssembleBlockTerms:
      return "assemble_block_terms";
    case StepPhase::AssembleContacts:
      return "assemble_contacts";
    case StepPhase::Factorize:
      return "factorize";
    case StepPhase::Solve:
      return "solve";
    case StepPhase::UpdateStates:
      return "update_states";
    case StepPhase::UpdateBlocks:
      return "update_blocks";
  }
  return "unknown";
}

PhaseTimer::PhaseTimer(StepProfile& profile, StepPhase phase)
    : profile_(profile), phase_(phase), start_(now()) {}

PhaseTimer::~PhaseTimer() {
  profile_[phase_] += now() - start_;
}

}  // namespace rockmass::dda3d
