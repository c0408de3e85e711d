#include "io/run_summary.h"

#include <set>
#include <stdexcept>

#include "io/summary_json.h"

namespace rockmass::io {

std::string formatRunSummary(const RunInfo& run, const std::vector<StageSummary>& stages,
                             const RunReport& report) {
  SummaryJson j = summaryHeader(run);
  const std::set<std::string> header = {"rockmass_version", "command", "scene",  "name", "seed",
                                        "stages",           "effects", "timings"};
  SummaryJson extra_timings = SummaryJson::object();
  for (const StageSummary& stage : stages) {
    SummaryJson part;
    try {
      part = SummaryJson::parse(stage.json);
    } catch (const nlohmann::json::exception& e) {
      throw std::runtime_error("run summary: the " + stage.stage + " summary is not JSON (" +
                               e.what() + ")");
    }
    for (auto it = part.begin(); it != part.end(); ++it) {
      if (header.count(it.key())) continue;
      if (!j.contains(it.key())) {
        j[it.key()] = it.value();
      } else if (j[it.key()] != it.value()) {
        j[stage.stage][it.key()] = it.value();
      }
    }
    if (part.contains("timings")) {
      for (auto it = part["timings"].begin(); it != part["timings"].end(); ++it) {
        extra_timings[it.key()] = it.value();
      }
    }
  }
  SummaryJson r;
  r["quick"] = report.quick;
  r["domain"] = {{"min", {report.domain.min.x(), report.domain.min.y(), report.domain.min.z()}},
                 {"max", {report.domain.max.x(), report.domain.max.y(), report.domain.max.z()}}};
  r["cutter"] = report.cutter.empty() ? SummaryJson(nullptr) : SummaryJson(report.cutter);
  r["section"] = report.section.empty() ? SummaryJson(nullptr) : SummaryJson(report.section);
  SummaryJson unavailable = SummaryJson::object();
  for (const auto& [stage, reason] : report.unavailable) unavailable[stage] = reason;
  r["unavailable"] = unavailable;
  r["files"] = report.files;
  r["figures"] = report.figures;
  r["warnings"] = report.warnings;
  j["run"] = r;

  SummaryJson timings = SummaryJson::object();
  for (const auto& [stage, seconds] : run.timings) timings[stage] = seconds;
  for (auto it = extra_timings.begin(); it != extra_timings.end(); ++it) {
    if (!timings.contains(it.key())) timings[it.key()] = it.value();
  }
  j["timings"] = timings;
  return j.dump(2) + "\n";
}

}  // namespace rockmass::io
