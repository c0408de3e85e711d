#pragma once
/// The summary.json parts of the stability analyses, for io's summary writers (internal to
/// io, like summary_json.h): `rockmass overload`/`strength` and the whole-run summary.
#include "io/stability_output.h"
#include "io/summary_json.h"

namespace rockmass::io {

/// {unbalanced_ratio, kinetic_ratio, settle_steps, max_steps}
SummaryJson equilibriumJson(const dda3d::EquilibriumSettings& settings);

/// {rule, path, scales, scale_uplift, last_stable, first_unstable, K_s, runs[]}
SummaryJson overloadJson(const dda3d::FactorSearchResult& overload,
                         const std::vector<std::string>& scales, bool scale_uplift);

/// {rule, path, last_stable, first_unstable, critical_srf, runs[]}
SummaryJson strengthReductionJson(const dda3d::FactorSearchResult& strength);

/// Adds equilibrium, overload and strength_reduction (those that ran) and safety_factor.
void appendStability(SummaryJson& j, const StabilitySummary& summary);

}  // namespace rockmass::io
