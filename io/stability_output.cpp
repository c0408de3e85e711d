#include "io/stability_output.h"

#include <algorithm>
#include <numeric>

#include "io/atomic_file.h"
#include "io/stability_json.h"

namespace rockmass::io {

namespace {

using Json = SummaryJson;

/// The rule that decides K_s / the critical SRF, as stated in the summary.
constexpr const char* kSearchRule =
    "a run is at rest when settle_steps steps in a row are accepted on every check with "
    "unbalanced ratio (step displacement / (g dt^2 / 2)) and kinetic ratio (kinetic energy / "
    "work of the loads) at most their tolerances, each of them searching its contacts "
    "(not keeping an earlier search's), within max_steps; the first factor "
    "(ascending) at which the run is not at rest marks the loss of stability; the critical "
    "factor is the middle of [last factor at rest, first factor not at rest], bisected to the "
    "tolerance; a static run whose unbalanced ratio is at least failure_ratio in failure_steps "
    "steps in a row is not at rest and stops there (failing), and so is one whose fastest watched "
    "block moves the same way in steady_steps steps in a row, none calm, their unbalanced "
    "ratios within steady_spread of the largest (failing, steady), and so is one in which a "
    "watched block drifts in drift_steps steps in a row, none calm: its step displacements "
    "adding up to at least 0.9 of their path, its second half's steps along them at least as "
    "long as its first half's, its mean ratio at least unbalanced_ratio (failing, drifting); "
    "the ratios are of the blocks "
    "that equilibrium.watch names (all: every movable block; monitors: the blocks that carry "
    "a monitor)";

/// `value` or null.
Json optionalJson(const std::optional<double>& value) {
  return value ? Json(*value) : Json(nullptr);
}

/// A block that moved most in a run's last step, or null.
Json movedBlockJson(const dda3d::MovedBlock& moved) {
  if (moved.block < 0) return Json(nullptr);
  return {{"block", moved.block},
          {"volume", moved.volume},
          {"centroid", {moved.centroid.x(), moved.centroid.y(), moved.centroid.z()}}};
}

/// One entry per run, in the order they ran.
Json runsJson(const dda3d::FactorSearchResult& result) {
  Json runs = Json::array();
  for (const dda3d::FactorRun& r : result.runs) {
    runs.push_back(
        {{"factor", r.factor},
         {"bisection", r.bisection},
         {"at_rest", r.equilibrium.reached},
         {"steps", r.equilibrium.steps},
         {"time", r.equilibrium.time},
         {"unbalanced_ratio", finiteOrNull(r.equilibrium.unbalanced_ratio)},
         {"kinetic_ratio", finiteOrNull(r.equilibrium.kinetic_ratio)},
         {"failing", r.equilibrium.failing},
         {"steady", r.equilibrium.steady},
         {"drifting", r.equilibrium.drifting},
         {"stalled", r.equilibrium.stalled.empty() ? Json(nullptr) : Json(r.equilibrium.stalled)},
         {"all_blocks_ratio", finiteOrNull(r.equilibrium.all_blocks_ratio)},
         {"min_time_step", r.equilibrium.min_time_step},
         {"redone",
          {{"open_close", r.equilibrium.redone_open_close},
           {"displacement", r.equilibrium.redone_displacement},
           {"penetration", r.equilibrium.redone_penetration}}},
         {"contact_searches", r.equilibrium.contact_searches},
         {"partial_contact_searches", r.equilibrium.partial_contact_searches},
         {"fastest_block", movedBlockJson(r.equilibrium.fastest)},
         {"fastest_watched_block", movedBlockJson(r.equilibrium.watched)}});
    if (!r.bolts.empty()) {
      int broken = 0, yielded = 0;
      double largest = 0.0;
      for (const dda3d::BoltState& b : r.bolts) {
        broken += b.broken;
        yielded += b.yielded && !b.broken;
        largest = std::max(largest, b.force);
      }
      runs.back()["bolts"] = {{"broken", broken}, {"yielded", yielded}, {"largest_force", largest}};
    }
  }
  return runs;
}

}  // namespace

std::string formatOverloadCsv(const std::vector<std::string>& monitor_names,
                              const dda3d::FactorSearchResult& overload) {
  std::vector<std::size_t> order(overload.runs.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return overload.runs[a].factor < overload.runs[b].factor;
  });
  std::string out = "factor,monitor,ux,uy,uz,u,at_rest,steps\n";
  for (std::size_t k : order) {
    const dda3d::FactorRun& run = overload.runs[k];
    for (std::size_t m = 0; m < run.monitors.size(); ++m) {
      const geometry::Vec3& u = run.monitors[m].displacement;
      out += formatDouble(run.factor) + ',' + csvField(monitor_names.at(m)) + ',' +
             formatDouble(u.x()) + ',' + formatDouble(u.y()) + ',' + formatDouble(u.z()) + ',' +
             formatDouble(u.norm()) + ',' + (run.equilibrium.reached ? "1" : "0") + ',' +
             std::to_string(run.equilibrium.steps) + '\n';
    }
  }
  return out;
}

Json equilibriumJson(const dda3d::EquilibriumSettings& settings) {
  return {{"unbalanced_ratio", settings.unbalanced_ratio},
          {"kinetic_ratio", settings.kinetic_ratio},
          {"settle_steps", settings.settle_steps},
          {"max_steps", settings.max_steps},
          {"failure_ratio", settings.failure_ratio},
          {"failure_steps", settings.failure_steps},
          {"steady_steps", settings.steady_steps},
          {"steady_spread", settings.steady_spread},
          {"drift_steps", settings.drift_steps},
          {"watch", settings.watch == dda3d::EquilibriumWatch::All ? "all" : "monitors"}};
}

namespace {

/// analysis.*.path of a search: "incremental" or "restart".
const char* pathName(const dda3d::FactorSearchResult& search) {
  return search.incremental ? "incremental" : "restart";
}

}  // namespace

Json overloadJson(const dda3d::FactorSearchResult& overload, const std::vector<std::string>& scales,
                  bool scale_uplift) {
  return {{"rule", kSearchRule},
          {"path", pathName(overload)},
          {"scales", scales},
          {"scale_uplift", scale_uplift},
          {"last_stable", optionalJson(overload.last_stable)},
          {"first_unstable", optionalJson(overload.first_unstable)},
          {"K_s", optionalJson(overload.critical)},
          {"runs", runsJson(overload)}};
}

Json strengthReductionJson(const dda3d::FactorSearchResult& strength) {
  return {{"rule", kSearchRule},
          {"path", pathName(strength)},
          {"last_stable", optionalJson(strength.last_stable)},
          {"first_unstable", optionalJson(strength.first_unstable)},
          {"critical_srf", optionalJson(strength.critical)},
          {"runs", runsJson(strength)}};
}

void appendStability(Json& j, const StabilitySummary& summary) {
  j["equilibrium"] = equilibriumJson(summary.equilibrium);
  if (summary.overload) {
    j["overload"] = overloadJson(*summary.overload, summary.overload_scales, summary.scale_uplift);
  }
  if (summary.strength_reduction) {
    j["strength_reduction"] = strengthReductionJson(*summary.strength_reduction);
  }
  const dda3d::FactorSearchResult* decisive =
      summary.overload ? summary.overload : summary.strength_reduction;
  j["safety_factor"] = decisive ? optionalJson(decisive->critical) : Json(nullptr);
}

std::string formatStabilitySummary(const RunInfo& run, const StabilitySummary& summary) {
  Json j = summaryHeader(run);
  j["blocks"] = summary.blocks;
  j["fixed_blocks"] = summary.fixed_blocks;
  if (summary.glued) j["glued_blocks"] = gluedBlocksJson(*summary.glued);
  j["pressures"] = summary.pressures;
  if (!summary.uplift.empty()) j["uplift"] = upliftJson(summary.uplift);
  appendStability(j, summary);
  appendTimings(j, run.timings);
  return j.dump(2) + "\n";
}

}  // namespace rockmass::io
