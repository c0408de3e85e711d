#pragma once
/// summary.json: what ran, counts, key results, active effects, timings, seed, version.
/// Keys used by scripts are listed in the shared scene-format.md; timings are the only
/// part that changes between two runs of the same scene and seed.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "geometry/fracture_network.h"

namespace rockmass::io {

/// Seconds per stage (keys dfn, cut, rqd, dda, overload, strength_reduction, write),
/// in the order the stages ran.
using Timings = std::vector<std::pair<std::string, double>>;

/// What every summary says about the run itself.
/// The uplift on one structure: the water pressure in its interface with the rock
/// (loads.pore_pressure, or loads.water with uplift) summed as the model starts.
struct StructureUplift {
  std::string structure;                          ///< its name
  geometry::Vec3 force = geometry::Vec3::Zero();  ///< resultant on the structure (N)
};

/// The state of one bolt at one time, for bolts.csv and the summary.
struct BoltSample {
  std::string name;
  double force = 0.0;                            ///< axial force (N, > 0 tension)
  std::string state;                             ///< intact | yielded | broken
  double broken_at = -1.0;                       ///< time of the rupture (s), -1 when intact
  geometry::Vec3 head = geometry::Vec3::Zero();  ///< where it was set (m)
  geometry::Vec3 end = geometry::Vec3::Zero();
};

struct RunInfo {
  std::string command;               ///< sub-command, e.g. "dfn"
  std::string scene;                 ///< scene file as given on the command line
  std::string name;                  ///< scene name
  std::uint64_t seed = 0;            ///< seed used (after --seed)
  std::vector<std::string> stages;   ///< stages that ran, in order
  std::vector<std::string> effects;  ///< physics terms that were active
  Timings timings;                   ///< seconds per stage
};

/// rockmass version string (the CMake project version).
const char* version();

/// summary.json of the dfn stage: per set count, P32 and P10 in the domain with their
/// targets, mean orientation and Fisher kappa estimate.
std::string formatDfnSummary(const RunInfo& run, const geometry::FractureNetwork& network,
                             const std::vector<geometry::SetStatistics>& stats);

}  // namespace rockmass::io
