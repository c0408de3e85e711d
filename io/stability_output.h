#pragma once
/// Outputs of the stability analyses (docs/stability.md): overload.csv (the K-displacement
/// curve) and the summary.json of `rockmass overload` / `rockmass strength`.
#include <optional>
#include <string>
#include <vector>

#include "blocks/block_merge.h"
#include "dda3d/stability.h"
#include "io/summary.h"

namespace rockmass::io {

/// overload.csv: `factor,monitor,ux,uy,uz,u,at_rest,steps`, one row per run and monitor,
/// by increasing factor (the sweep's and the bisection's runs together); ux..uz is the
/// monitor's displacement (m) at the end of the run, u its length, at_rest 1 when the run
/// reached equilibrium, steps the steps it took. The first six columns are the shared
/// contract's.
std::string formatOverloadCsv(const std::vector<std::string>& monitor_names,
                              const dda3d::FactorSearchResult& overload);

/// What a stability summary reports besides the run header.
struct StabilitySummary {
  int blocks = 0;                          ///< block count
  int fixed_blocks = 0;                    ///< blocks held by supports.fixed
  int pressures = 0;                       ///< wet faces (water and uplift pressure entries)
  dda3d::EquilibriumSettings equilibrium;  ///< the criterion used
  const dda3d::FactorSearchResult* overload = nullptr;  ///< when the overload method ran
  std::vector<std::string> overload_scales;             ///< analysis.overload.scales
  bool scale_uplift = false;                            ///< analysis.overload.scale_uplift
  const dda3d::FactorSearchResult* strength_reduction = nullptr;  ///< when it ran
  /// The small blocks glued before the runs (analysis.dda.min_block_volume > 0).
  std::optional<blocks::MergeReport> glued;
  /// The uplift on each structure (empty when no water acts in an interface).
  std::vector<StructureUplift> uplift;
};

/// summary.json of `overload` / `strength`: the header, blocks, fixed_blocks, glued_blocks
/// (when blocks were glued), pressures,
/// equilibrium{...}, overload{rule, path, scales, scale_uplift, factors_at_rest, last_stable,
/// first_unstable, K_s, runs[]} and/or strength_reduction{rule, path, last_stable,
/// first_unstable, critical_srf, runs[]}, safety_factor (K_s when the overload ran, else
/// the critical SRF; null when the factors did not bracket it), then timings.
std::string formatStabilitySummary(const RunInfo& run, const StabilitySummary& summary);

}  // namespace rockmass::io
