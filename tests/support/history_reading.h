#pragma once
/// Reading the `history.csv` of `rockmass dda` (docs/dda-io.md) in the CLI tests.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/test_support.h"

namespace rockmass::test {

/// One row of history.csv: a monitor's displacement and velocity at a time.
struct HistoryRow {
  double time = 0.0;
  std::string monitor;
  double ux = 0.0, uy = 0.0, uz = 0.0;
  double vx = 0.0, vy = 0.0, vz = 0.0;
  double speed() const { return std::sqrt(vx * vx + vy * vy + vz * vz); }
};

/// The rows of `file`, after checking its header.
inline std::vector<HistoryRow> readHistory(const std::filesystem::path& file) {
  std::istringstream in(readFile(file));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "time,monitor,ux,uy,uz,vx,vy,vz,u");
  std::vector<HistoryRow> rows;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    HistoryRow row;
    std::string field;
    const auto number = [&]() {
      std::getline(fields, field, ',');
      return std::stod(field);
    };
    row.time = number();
    std::getline(fields, row.monitor, ',');
    row.ux = number();
    row.uy = number();
    row.uz = number();
    row.vx = number();
    row.vy = number();
    row.vz = number();
    rows.push_back(row);
  }
  return rows;
}

}  // namespace rockmass::test
