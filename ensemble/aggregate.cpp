#include "ensemble/aggregate.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>
#include <tuple>

#include "io/atomic_file.h"

namespace rockmass::ensemble {

namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A JSON number as a double, NaN for null or a missing key.
double numberAt(const Json& j, const Json::json_pointer& at) {
  if (!j.contains(at)) return kNaN;
  const Json& v = j.at(at);
  return v.is_number() ? v.get<double>() : kNaN;
}

std::string numberText(double v) {
  return std::isfinite(v) ? io::formatDouble(v) : "";
}

/// The file's lines (none when it does not exist).
std::vector<std::string> linesOf(const fs::path& file) {
  std::vector<std::string> lines;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// Comma-separated fields of a line without quotes (our CSVs' numeric rows).
std::vector<std::string> fieldsOf(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string field; std::getline(in, field, ',');) fields.push_back(field);
  return fields;
}

/// One realization's numbers, by name in the order first met.
struct Table {
  std::vector<std::string> names;
  std::map<std::string, std::vector<double>> columns;  // one entry per realization
  void set(const std::string& name, std::size_t row, std::size_t rows, double value) {
    auto [it, added] = columns.try_emplace(name, std::vector<double>(rows, kNaN));
    if (added) names.push_back(name);
    it->second[row] = value;
  }
};

/// Running mean and its 95 % half-width after 1, 2, ... of the known values.
std::vector<std::pair<double, double>> runningMean(const std::vector<double>& values) {
  std::vector<std::pair<double, double>> out;
  std::vector<double> seen;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    seen.push_back(v);
    const Stats s = statsOf(seen);
    out.emplace_back(s.mean, s.ci95);
  }
  return out;
}

/// Average ranks (1-based) of values, ties sharing their mean rank.
std::vector<double> ranksOf(const std::vector<double>& v) {
  std::vector<std::size_t> order(v.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](auto a, auto b) { return v[a] < v[b]; });
  std::vector<double> ranks(v.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && v[order[j + 1]] == v[order[i]]) ++j;
    const double rank = 0.5 * static_cast<double>(i + j) + 1.0;
    for (std::size_t k = i; k <= j; ++k) ranks[order[k]] = rank;
    i = j + 1;
  }
  return ranks;
}

}  // namespace

fs::path realizationFolder(const fs::path& out, int index) {
  std::string name = "r";
  name += std::to_string(index);
  return out / name;
}

Stats statsOf(std::vector<double> values) {
  values.erase(
      std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }),
      values.end());
  Stats s;
  s.n = static_cast<int>(values.size());
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  const double n = static_cast<double>(values.size());
  s.mean = std::accumulate(values.begin(), values.end(), 0.0) / n;
  double squares = 0.0;
  for (double v : values) squares += (v - s.mean) * (v - s.mean);
  s.std = values.size() > 1 ? std::sqrt(squares / (n - 1.0)) : 0.0;
  const auto percentile = [&](double q) {
    const double at = q * (n - 1.0);
    const auto low = static_cast<std::size_t>(std::floor(at));
    const std::size_t high = std::min(low + 1, values.size() - 1);
    return values[low] + (at - static_cast<double>(low)) * (values[high] - values[low]);
  };
  s.min = values.front();
  s.max = values.back();
  s.p05 = percentile(0.05);
  s.p50 = percentile(0.5);
  s.p95 = percentile(0.95);
  s.ci95 = values.size() > 1 ? 1.959963984540054 * s.std / std::sqrt(n) : 0.0;
  return s;
}

Json toJson(const Stats& s) {
  if (s.n == 0) return {{"n", 0}};
  return {{"n", s.n},     {"mean", s.mean}, {"std", s.std}, {"ci95", s.ci95}, {"min", s.min},
          {"p05", s.p05}, {"p50", s.p50},   {"p95", s.p95}, {"max", s.max}};
}

Probability probabilityBelow(const std::vector<double>& values, double target,
                             const std::vector<double>& last_stable,
                             const std::vector<double>& first_unstable) {
  Probability p;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double v = values[i];
    if (std::isfinite(v)) {
      ++p.known;
      p.below += v < target;
      continue;
    }
    const double low = i < last_stable.size() ? last_stable[i] : kNaN;
    const double high = i < first_unstable.size() ? first_unstable[i] : kNaN;
    if (std::isfinite(high) && high <= target) {
      ++p.known;
      ++p.below;
    } else if (std::isfinite(low) && low >= target) {
      ++p.known;
    } else {
      ++p.undetermined;
    }
  }
  if (p.known > 0) {
    p.p = static_cast<double>(p.below) / p.known;
    p.standard_error = std::sqrt(p.p * (1.0 - p.p) / p.known);
  }
  return p;
}

double spearman(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> a, b;
  for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
    if (std::isfinite(x[i]) && std::isfinite(y[i])) {
      a.push_back(x[i]);
      b.push_back(y[i]);
    }
  }
  if (a.size() < 3) return kNaN;
  const std::vector<double> ra = ranksOf(a), rb = ranksOf(b);
  const double n = static_cast<double>(ra.size());
  const double mean = (n + 1.0) / 2.0;
  double sab = 0.0, saa = 0.0, sbb = 0.0;
  for (std::size_t i = 0; i < ra.size(); ++i) {
    sab += (ra[i] - mean) * (rb[i] - mean);
    saa += (ra[i] - mean) * (ra[i] - mean);
    sbb += (rb[i] - mean) * (rb[i] - mean);
  }
  if (saa <= 0.0 || sbb <= 0.0) return kNaN;
  return sab / std::sqrt(saa * sbb);
}

Json writeAggregate(const fs::path& out, const io::Scene& scene, int count) {
  const auto rows = static_cast<std::size_t>(count);
  std::vector<int> complete, missing, failed;
  Table table;  // scalar measures, one column each
  std::vector<std::uint64_t> seeds(rows, 0);
  // RQD of every ball direction and threshold: key "ball,dx,dy,dz,threshold" in first-met order.
  std::vector<std::string> ball_keys;
  std::map<std::string, std::vector<double>> ball_rqd;
  // Borehole RQD: key "hole,threshold".
  std::vector<std::string> hole_keys;
  std::map<std::string, std::vector<double>> hole_rqd;
  const std::vector<io::UncertainInput> inputs =
      scene.uncertainty ? scene.uncertainty->inputs : std::vector<io::UncertainInput>{};

  for (int i = 0; i < count; ++i) {
    const fs::path folder = realizationFolder(out, i);
    const auto r = static_cast<std::size_t>(i);
    std::ifstream marker_in(folder / kRealizationMarker);
    if (!marker_in) {
      missing.push_back(i);
      continue;
    }
    const Json marker = Json::parse(marker_in, nullptr, false);
    if (marker.is_discarded() || marker.value("status", "") != "complete") {
      failed.push_back(i);
      continue;
    }
    std::ifstream summary_in(folder / "summary.json");
    const Json s = Json::parse(summary_in, nullptr, false);
    if (s.is_discarded()) {
      failed.push_back(i);
      continue;
    }
    complete.push_back(i);
    seeds[r] = marker.value("seed", std::uint64_t{0});
    const Json& values = marker["inputs"];
    for (std::size_t k = 0; k < inputs.size() && k < values.size(); ++k) {
      table.set("input:" + inputs[k].key, r, rows, values[k].value("value", kNaN));
    }
    // DFN
    table.set("discs", r, rows, numberAt(s, "/discs"_json_pointer));
    if (s.contains("sets")) {
      for (const Json& set : s["sets"]) {
        table.set("p32:" + set.value("name", std::string{}), r, rows, set.value("p32", kNaN));
      }
    }
    // Blocks (the rock's, without structures, when the summary has them)
    if (s.contains("blocks")) {
      const std::string base = s.contains("rock") ? "/rock" : "";
      table.set("blocks", r, rows, numberAt(s, "/blocks"_json_pointer));
      table.set("block_volume_mean", r, rows,
                numberAt(s, Json::json_pointer(base + "/volume_stats/mean")));
      table.set("block_volume_max", r, rows,
                numberAt(s, Json::json_pointer(base + "/volume_stats/max")));
      table.set("weibull_shape", r, rows, numberAt(s, Json::json_pointer(base + "/weibull/shape")));
      table.set("weibull_scale", r, rows, numberAt(s, Json::json_pointer(base + "/weibull/scale")));
    }
    // RQD balls: each ball's mean over its directions, per threshold; and every direction.
    if (s.contains("balls")) {
      for (const Json& ball : s["balls"]) {
        for (const Json& t : ball["thresholds"]) {
          table.set("rqd_ball:" + ball.value("name", std::string{}) + ":" +
                        io::formatDouble(t.value("threshold", kNaN)),
                    r, rows, t.value("mean", kNaN));
        }
      }
      const std::vector<std::string> lines = linesOf(folder / "rqd_balls.csv");
      for (std::size_t l = 1; l < lines.size(); ++l) {
        std::vector<std::string> f = fieldsOf(lines[l]);
        if (f.size() != 6) continue;
        const std::string key = f[0] + "," + f[1] + "," + f[2] + "," + f[3] + "," + f[4];
        auto [it, added] = ball_rqd.try_emplace(key, std::vector<double>(rows, kNaN));
        if (added) ball_keys.push_back(key);
        it->second[r] = std::strtod(f[5].c_str(), nullptr);
      }
    }
    // Boreholes
    if (s.contains("/boreholes/holes"_json_pointer)) {
      for (const Json& hole : s["boreholes"]["holes"]) {
        for (const Json& t : hole["rqd"]) {
          const std::string key =
              hole.value("id", std::string{}) + "," + io::formatDouble(t.value("threshold", kNaN));
          auto [it, added] = hole_rqd.try_emplace(key, std::vector<double>(rows, kNaN));
          if (added) hole_keys.push_back(key);
          it->second[r] = t.value("rqd", kNaN);
        }
      }
      if (s.contains("/boreholes/measured"_json_pointer)) {
        for (const auto& [name, value] : s["boreholes"]["measured"].items()) {
          if (value.is_number()) table.set("measured_log:" + name, r, rows, value.get<double>());
        }
      }
    }
    // The factors, and the bracket of their searches (a factor outside the factors tried is
    // not a number, but its bracket may still decide P(factor < target)).
    for (const auto& [section, name] : {std::pair<std::string, std::string>{"overload", "K_s"},
                                        {"strength_reduction", "critical_srf"}}) {
      if (!s.contains(section)) continue;
      const std::string at = "/" + section + "/";
      table.set(name, r, rows, numberAt(s, Json::json_pointer(at + name)));
      table.set(name + "_last_stable", r, rows,
                numberAt(s, Json::json_pointer(at + "last_stable")));
      table.set(name + "_first_unstable", r, rows,
                numberAt(s, Json::json_pointer(at + "first_unstable")));
    }
  }

  Json j;
  j["scene"] = scene.file.string();
  j["name"] = scene.name;
  j["seed"] = scene.seed;
  j["realizations"] = count;
  j["complete"] = complete.size();
  j["missing"] = missing;
  j["failed"] = failed;
  j["sampling"] = !scene.uncertainty                   ? "seed only"
                  : scene.uncertainty->latin_hypercube ? "latin_hypercube"
                                                       : "monte_carlo";
  Json input_list = Json::array();
  for (const io::UncertainInput& input : inputs) {
    Json e{{"key", input.key}, {"distribution", input.distribution}, {"scene_value", input.value}};
    if (input.distribution == "list") {
      e["values"] = input.values;
    } else if (input.distribution == "uniform" || input.distribution == "triangular") {
      e["min"] = input.min;
      e["max"] = input.max;
      if (input.distribution == "triangular") e["mode"] = input.mode;
    } else {
      e["mean"] = input.mean;
      e["std"] = input.std;
      if (std::isfinite(input.min)) e["min"] = input.min;
      if (std::isfinite(input.max)) e["max"] = input.max;
    }
    e["sample"] = toJson(statsOf(table.columns["input:" + input.key]));
    input_list.push_back(e);
  }
  j["inputs"] = input_list;
  Json measures = Json::object();
  for (const std::string& name : table.names) {
    if (name.rfind("input:", 0) == 0) continue;
    measures[name] = toJson(statsOf(table.columns[name]));
  }
  j["measures"] = measures;

  // Probability of failure and sensitivity of each factor.
  Json stability = Json::object();
  const auto factor = [&](const std::string& name, const std::optional<double>& target) {
    if (!table.columns.count(name)) return;
    const std::vector<double>& v = table.columns[name];
    Json f;
    f["stats"] = toJson(statsOf(v));
    if (target) {
      const Probability p = probabilityBelow(v, *target, table.columns[name + "_last_stable"],
                                             table.columns[name + "_first_unstable"]);
      f["target"] = *target;
      f["probability_below"] = p.p;
      f["standard_error"] = p.standard_error;
      f["below"] = p.below;
      f["known"] = p.known;
      f["undetermined"] = p.undetermined;
    }
    Json sensitivity = Json::array();
    for (const io::UncertainInput& input : inputs) {
      const double rho = spearman(table.columns["input:" + input.key], v);
      sensitivity.push_back(
          {{"key", input.key}, {"spearman", std::isfinite(rho) ? Json(rho) : Json(nullptr)}});
    }
    std::stable_sort(sensitivity.begin(), sensitivity.end(), [](const Json& a, const Json& b) {
      const double x = a["spearman"].is_number() ? std::abs(a["spearman"].get<double>()) : -1.0;
      const double y = b["spearman"].is_number() ? std::abs(b["spearman"].get<double>()) : -1.0;
      return x > y;
    });
    f["sensitivity"] = sensitivity;
    stability[name] = f;
  };
  const std::optional<io::Uncertainty>& u = scene.uncertainty;
  factor("K_s", u ? u->overload_target : std::nullopt);
  factor("critical_srf", u ? u->strength_target : std::nullopt);
  j["stability"] = stability;
  j["files"] = {"ensemble.json", "ensemble_realizations.csv", "ensemble_convergence.csv"};

  // ensemble_realizations.csv: one row per complete realization.
  {
    std::string csv = "realization,seed";
    for (const std::string& name : table.names) csv.append(",").append(io::csvField(name));
    csv += "\n";
    for (int i : complete) {
      const auto r = static_cast<std::size_t>(i);
      csv.append(std::to_string(i)).append(",").append(std::to_string(seeds[r]));
      for (const std::string& name : table.names) {
        csv.append(",").append(numberText(table.columns[name][r]));
      }
      csv += "\n";
    }
    io::writeFileAtomically(out / "ensemble_realizations.csv", csv);
  }
  // ensemble_convergence.csv: the running mean of every measure with its 95 % half-width.
  {
    std::string csv = "measure,n,mean,ci95\n";
    for (const std::string& name : table.names) {
      if (name.rfind("rqd_ball:", 0) == 0) continue;  // per ball in ensemble.json
      const auto running = runningMean(table.columns[name]);
      for (std::size_t n = 0; n < running.size(); ++n) {
        csv += io::csvField(name) + "," + std::to_string(n + 1) + "," +
               io::formatDouble(running[n].first) + "," + io::formatDouble(running[n].second) +
               "\n";
      }
    }
    io::writeFileAtomically(out / "ensemble_convergence.csv", csv);
  }
  const auto bands = [&](const std::string& file, const std::string& header,
                         const std::vector<std::string>& keys,
                         std::map<std::string, std::vector<double>>& values) {
    std::string csv = header + ",n,mean,ci95,p05,p50,p95\n";
    for (const std::string& key : keys) {
      const Stats s = statsOf(values[key]);
      csv += key + "," + std::to_string(s.n) + "," + io::formatDouble(s.mean) + "," +
             io::formatDouble(s.ci95) + "," + io::formatDouble(s.p05) + "," +
             io::formatDouble(s.p50) + "," + io::formatDouble(s.p95) + "\n";
    }
    io::writeFileAtomically(out / file, csv);
    j["files"].push_back(file);
  };
  if (!ball_keys.empty()) {
    bands("ensemble_rqd_balls.csv", "ball,dir_x,dir_y,dir_z,threshold", ball_keys, ball_rqd);
  }
  if (!hole_keys.empty()) {
    bands("ensemble_boreholes.csv", "hole,threshold", hole_keys, hole_rqd);
  }
  io::writeFileAtomically(out / "ensemble.json", j.dump(2) + "\n");
  return j;
}

}  // namespace rockmass::ensemble
