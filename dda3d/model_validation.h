// The checks a DDA model and its settings must pass before a Simulation is built: indices,
// materials, pieces, supports and settings, each failure an std::invalid_argument that names
// the item.
#pragma once

#include "dda3d/model.h"
#include "dda3d/simulation_settings.h"

namespace rockmass::dda3d {

/// Throws std::invalid_argument naming the first item of `model` or `settings` that a
/// Simulation cannot run with. A model without joints must have been given its default one
/// (DdaJoint{}) first, as the Simulation does.
void validateModel(const DdaModel& model, const DdaSettings& settings);

}  // namespace rockmass::dda3d
