// What every benchmark program shares: a console reporter that also records each benchmark's
// times and counters, so that main() can print comparisons as ratios measured in the same run.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

namespace rockmass::bench {

/// One benchmark's result, per iteration, in the benchmark's time unit.
struct Record {
  double real_time = 0.0;                  ///< wall time
  double cpu_time = 0.0;                   ///< CPU time of the benchmark's thread
  std::map<std::string, double> counters;  ///< final counter values
};

/// Console output plus a Record per benchmark name.
class RecordingReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      Record& r = records[run.benchmark_name()];
      r.real_time = run.GetAdjustedRealTime();
      r.cpu_time = run.GetAdjustedCPUTime();
      for (const auto& [name, counter] : run.counters) r.counters[name] = counter.value;
    }
  }

  /// The record named `prefix`, or the first whose name continues it with run options
  /// (".../iterations:1/real_time"); nullptr when none ran.
  const Record* find(const std::string& prefix) const {
    for (const auto& [name, record] : records) {
      if (name == prefix || name.rfind(prefix + "/", 0) == 0) return &record;
    }
    return nullptr;
  }
  /// Wall time per benchmark name.
  std::map<std::string, double> realTimes() const {
    std::map<std::string, double> t;
    for (const auto& [name, record] : records) t[name] = record.real_time;
    return t;
  }
  /// CPU time per benchmark name (fairer than wall time on a machine shared with other jobs,
  /// for single-threaded benchmarks).
  std::map<std::string, double> cpuTimes() const {
    std::map<std::string, double> t;
    for (const auto& [name, record] : records) t[name] = record.cpu_time;
    return t;
  }
  /// The value of counter `counter` per benchmark name, for the benchmarks that set it.
  std::map<std::string, double> counterValues(const std::string& counter) const {
    std::map<std::string, double> values;
    for (const auto& [name, record] : records) {
      const auto it = record.counters.find(counter);
      if (it != record.counters.end()) values[name] = it->second;
    }
    return values;
  }

  std::map<std::string, Record> records;  ///< by benchmark name, as Google Benchmark gives it
};

/// Removes --NAME=VALUE from argv; returns VALUE, or `fallback` when absent.
inline std::string takeFlag(int& argc, char** argv, const std::string& name,
                            const std::string& fallback) {
  std::string value = fallback;
  const std::string flag = "--" + name + "=";
  int out = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind(flag, 0) == 0) {
      value = arg.substr(flag.size());
    } else {
      argv[out++] = argv[i];
    }
  }
  argc = out;
  return value;
}

}  // namespace rockmass::bench
