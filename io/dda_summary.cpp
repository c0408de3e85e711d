#include "io/dda_summary.h"

#include <algorithm>

#include "io/atomic_file.h"
#include "io/summary_json.h"

namespace rockmass::io {
namespace {

using Json = SummaryJson;

/// One array with `value(step)` for every step.
template <class Value>
Json perStep(const std::vector<DdaStepRecord>& steps, Value value) {
  Json array = Json::array();
  for (const DdaStepRecord& s : steps) array.push_back(value(s));
  return array;
}

/// The phase names in first-seen order.
std::vector<std::string> phaseNames(const std::vector<DdaStepRecord>& steps) {
  std::vector<std::string> names;
  for (const DdaStepRecord& s : steps) {
    for (const auto& [name, seconds] : s.phase_seconds) {
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    }
  }
  return names;
}

/// Seconds of phase `name` in step `s` (0 when it did not run).
double phaseSeconds(const DdaStepRecord& s, const std::string& name) {
  double total = 0.0;
  for (const auto& [phase, seconds] : s.phase_seconds) {
    if (phase == name) total += seconds;
  }
  return total;
}

}  // namespace

void keepStepRecord(std::vector<DdaStepRecord>& steps, int& stride, DdaStepRecord record,
                    std::size_t limit) {
  if (record.step % stride != 0) return;
  steps.push_back(std::move(record));
  while (steps.size() > limit) {
    stride *= 2;
    std::erase_if(steps, [&](const DdaStepRecord& r) { return r.step % stride != 0; });
  }
}

std::string stepsCsvHeader() {
  return "step,time,time_step,contacts,open,sliding,locked,iterations,retries,max_displacement,"
         "max_penetration\n";
}

std::string formatStepsRow(const DdaStepRecord& r) {
  std::string out = std::to_string(r.step);
  for (const double x : {r.time, r.time_step}) out += ',' + formatDouble(x);
  for (const int n :
       {r.contacts, r.open, r.sliding, r.locked, r.open_close_iterations, r.retries}) {
    out += ',' + std::to_string(n);
  }
  for (const double x : {r.max_displacement, r.max_penetration}) out += ',' + formatDouble(x);
  out += '\n';
  return out;
}

std::string formatDdaSummary(const RunInfo& run, const DdaRunSummary& dda) {
  Json j = summaryHeader(run);
  j["blocks"] = dda.blocks;
  j["fixed_blocks"] = dda.fixed_blocks;
  j["pieces"] = dda.pieces;
  j["unknowns"] = dda.unknowns;
  if (dda.glued) j["glued_blocks"] = gluedBlocksJson(*dda.glued);
  if (!dda.uplift.empty()) j["uplift"] = upliftJson(dda.uplift);
  if (!dda.bolts.empty()) {
    Json bolts = Json::array();
    int broken = 0;
    for (const BoltSample& b : dda.bolts) {
      Json entry = {{"name", b.name},
                    {"head", {b.head.x(), b.head.y(), b.head.z()}},
                    {"end", {b.end.x(), b.end.y(), b.end.z()}},
                    {"force", b.force},
                    {"state", b.state}};
      if (b.broken_at >= 0.0) entry["broken_at"] = b.broken_at;
      broken += b.state == "broken";
      bolts.push_back(entry);
    }
    j["bolts_broken"] = broken;
    j["bolts"] = bolts;
  }
  if (dda.settled) {
    j["settled"] = {{"steps", dda.settled->steps},
                    {"at_rest", dda.settled->at_rest},
                    {"unbalanced_ratio", dda.settled->unbalanced_ratio},
                    {"without", dda.settled->without}};
  }
  if (dda.damage) {
    const auto& d = *dda.damage;
    j["damage"] = {{"maps", d.maps},        {"intact", d.intact}, {"bond_broken", d.bond_broken},
                   {"sliding", d.sliding},  {"opened", d.opened}, {"max_opening", d.max_opening},
                   {"max_slip", d.max_slip}};
  }
  if (dda.deformable) {
    Json coarse = Json::array();
    for (const auto& b : dda.coarse_strain) {
      coarse.push_back(
          {{"block", b.block}, {"volume", b.volume}, {"eccentricity", b.eccentricity}});
    }
    j["coarse_strain"] = coarse;
  }
  j["mode"] = dda.dynamic ? "dynamic" : "static";
  j["kinematics"] = dda.deformable ? "deformable" : "rigid";
  j["solver"] = dda.solver;
  j["time_integration"] = {{"scheme", dda.time_integration}};
  if (dda.time_integration == "bossak")
    j["time_integration"]["spectral_radius"] = dda.spectral_radius;
  j["steps_requested"] = dda.steps_requested;
  j["steps_taken"] =
      dda.steps_taken >= 0 ? static_cast<std::size_t>(dda.steps_taken) : dda.steps.size();
  j["late_contacts"] = dda.late_contacts;
  j["contact_searches"] = dda.contact_searches;
  j["partial_contact_searches"] = dda.partial_contact_searches;
  j["time_step"] = dda.time_step;
  j["duration"] = dda.duration;
  j["penalty"] = dda.penalty;
  Json monitors = Json::array();
  for (const DdaMonitorResult& m : dda.monitors) {
    monitors.push_back({{"name", m.name},
                        {"block", m.block},
                        {"ux", m.displacement.x()},
                        {"uy", m.displacement.y()},
                        {"uz", m.displacement.z()},
                        {"u", m.displacement.norm()},
                        {"point", {m.point.x(), m.point.y(), m.point.z()}}});
  }
  j["monitors"] = monitors;
  const auto& s = dda.steps;
  j["steps_stride"] = dda.step_stride;
  j["steps"] = {
      {"step", perStep(s, [](const DdaStepRecord& r) { return r.step; })},
      {"time", perStep(s, [](const DdaStepRecord& r) { return r.time; })},
      {"time_step", perStep(s, [](const DdaStepRecord& r) { return r.time_step; })},
      {"contacts", perStep(s, [](const DdaStepRecord& r) { return r.contacts; })},
      {"open", perStep(s, [](const DdaStepRecord& r) { return r.open; })},
      {"sliding", perStep(s, [](const DdaStepRecord& r) { return r.sliding; })},
      {"locked", perStep(s, [](const DdaStepRecord& r) { return r.locked; })},
      {"iterations", perStep(s, [](const DdaStepRecord& r) { return r.open_close_iterations; })},
      {"retries", perStep(s, [](const DdaStepRecord& r) { return r.retries; })},
      {"max_displacement", perStep(s, [](const DdaStepRecord& r) { return r.max_displacement; })},
      {"max_penetration", perStep(s, [](const DdaStepRecord& r) { return r.max_penetration; })},
  };
  appendTimings(j, run.timings);
  Json totals = Json::object(), per_step = Json::object();
  for (const std::string& name : phaseNames(s)) {
    double total = 0.0;
    Json values = Json::array();
    for (const DdaStepRecord& r : s) {
      values.push_back(phaseSeconds(r, name));
      total += values.back().get<double>();
    }
    totals[name] = total;
    per_step[name] = values;
  }
  for (const auto& [name, seconds] : dda.phase_totals) totals[name] = seconds;
  j["timings"]["dda_phases"] = totals;
  j["timings"]["dda_steps"] = per_step;
  return j.dump(2) + "\n";
}

}  // namespace rockmass::io
