#include "io/summary.h"

#include <cmath>

#include "geometry/orientation.h"
#include "io/summary_json.h"

namespace rockmass::io {
namespace {

using Json = SummaryJson;

/// A number, or null where JSON has none (infinite kappa of identical normals).
Json number(double value) {
  return finiteOrNull(value);
}

/// [x, y, z]
Json vector3(const geometry::Vec3& v) {
  return Json::array({v.x(), v.y(), v.z()});
}

/// Scene-facing name of a set's origin.
const char* originName(geometry::DiscOrigin origin) {
  switch (origin) {
    case geometry::DiscOrigin::JointSet:
      return "joint_set";
    case geometry::DiscOrigin::Fault:
      return "fault";
    case geometry::DiscOrigin::Interlayer:
      return "interlayer";
    case geometry::DiscOrigin::FabFile:
      return "fab_file";
  }
  return "unknown";
}

}  // namespace

/// The fields every summary starts with.
SummaryJson summaryHeader(const RunInfo& run) {
  SummaryJson j;
  j["rockmass_version"] = version();
  j["command"] = run.command;
  j["scene"] = run.scene;
  j["name"] = run.name;
  j["seed"] = run.seed;
  j["stages"] = run.stages;
  j["effects"] = run.effects;
  return j;
}

void appendTimings(SummaryJson& j, const Timings& timings) {
  SummaryJson t = SummaryJson::object();
  for (const auto& [stage, seconds] : timings) t[stage] = seconds;
  j["timings"] = t;
}

SummaryJson finiteOrNull(double value) {
  return std::isfinite(value) ? SummaryJson(value) : SummaryJson(nullptr);
}

const char* version() {
  return ROCKMASS_VERSION;
}

std::string formatDfnSummary(const RunInfo& run, const geometry::FractureNetwork& network,
                             const std::vector<geometry::SetStatistics>& stats) {
  Json j = summaryHeader(run);
  j["domain"] = {{"min", vector3(network.domain.min)},
                 {"max", vector3(network.domain.max)},
                 {"volume", network.domain.volume()}};
  std::int64_t cutting = 0;
  for (const geometry::Disc& d : network.discs) cutting += d.cuts;
  j["discs"] = network.discs.size();
  j["cutting_discs"] = cutting;
  Json sets = Json::array();
  for (std::size_t i = 0; i < network.sets.size(); ++i) {
    const geometry::SetInfo& info = network.sets[i];
    const geometry::SetStatistics& s = stats[i];
    const geometry::PlaneOrientation mean = geometry::orientationFromNormal(s.mean_normal);
    Json set;
    set["name"] = info.name;
    set["origin"] = originName(info.origin);
    set["count"] = s.count;
    set["p32"] = s.p32;
    set["p10"] = s.p10;
    set["mean_spacing"] = number(1.0 / s.p10);
    if (info.origin == geometry::DiscOrigin::JointSet) {
      set["p32_target"] = info.target_p32;
      set["p10_target"] = info.target_p10;
      set["size_scale"] = info.size_scale;
      set["margin"] = info.margin;
    }
    set["generated"] = info.generated;
    set["mean_orientation"] = {{"dip_direction", mean.dip_direction}, {"dip", mean.dip}};
    set["fisher_kappa"] = s.count >= 2 ? number(s.kappa) : Json(nullptr);
    sets.push_back(set);
  }
  j["sets"] = sets;
  appendTimings(j, run.timings);
  return j.dump(2) + "\n";
}

SummaryJson upliftJson(const std::vector<StructureUplift>& uplift) {
  SummaryJson list = SummaryJson::array();
  for (const StructureUplift& u : uplift) {
    list.push_back({{"structure", u.structure},
                    {"force", {u.force.x(), u.force.y(), u.force.z()}},
                    {"vertical", u.force.z()}});
  }
  return list;
}

SummaryJson gluedBlocksJson(const blocks::MergeReport& glued) {
  return {{"min_volume", glued.min_volume},
          {"blocks_before", glued.blocks_before},
          {"blocks_after", glued.blocks_after},
          {"merged", glued.merged},
          {"merged_volume", glued.merged_volume},
          {"left_small", glued.left_small},
          {"merged_across_materials", glued.merged_across},
          {"merged_across_materials_volume", glued.merged_across_volume}};
}

}  // namespace rockmass::io
