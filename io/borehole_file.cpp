#include "io/borehole_file.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>

#include "io/atomic_file.h"
#include "io/input_error.h"

namespace rockmass::io {
namespace {

/// A CSV file read row by row, with the position for messages.
class CsvReader {
 public:
  /// Opens `file` and checks its header against `header` (comma-separated names).
  CsvReader(const std::filesystem::path& file, std::string_view header)
      : file_(file), in_(file, std::ios::binary) {
    if (!in_) throw InputError(locate(file_, 0, 0, "cannot open the file"));
    std::vector<std::string> row;
    if (!next(row)) fail("expected the header row '" + std::string(header) + "', got nothing");
    std::string joined;
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (i > 0) joined += ',';
      joined += row[i];
    }
    if (joined != header) {
      fail("expected the header row '" + std::string(header) + "', got '" + joined + "'");
    }
  }

  /// The next non-blank row split at commas, fields trimmed; false at the end of the file.
  bool next(std::vector<std::string>& fields) {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.find_first_not_of(" \t") == std::string::npos) continue;
      fields.clear();
      std::size_t start = 0;
      while (true) {
        const std::size_t comma = line.find(',', start);
        fields.push_back(trim(line.substr(start, comma - start)));
        if (comma == std::string::npos) break;
        start = comma + 1;
      }
      return true;
    }
    return false;
  }

  /// Fails unless the current row has `count` fields named in `header`.
  void requireFields(const std::vector<std::string>& fields, std::size_t count,
                     std::string_view header) const {
    if (fields.size() != count) {
      fail("expected " + std::to_string(count) + " comma-separated fields (" + std::string(header) +
           "), got " + std::to_string(fields.size()));
    }
  }

  /// The number in `text` (field `name`), or a located error.
  double number(const std::string& text, std::string_view name) const {
    std::string_view view = text;
    if (view.starts_with('+')) view.remove_prefix(1);
    double value = 0.0;
    const auto [end, error] = std::from_chars(view.data(), view.data() + view.size(), value);
    if (text.empty() || error != std::errc() || end != view.data() + view.size() ||
        !std::isfinite(value)) {
      fail(std::string(name) + ": expected a number, got '" + text + "'");
    }
    return value;
  }

  /// Throws "file:line: what" at the current row.
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(locate(file_, line_, 0, what));
  }

 private:
  static std::string trim(const std::string& text) {
    const std::size_t first = text.find_first_not_of(" \t");
    if (first == std::string::npos) return "";
    return text.substr(first, text.find_last_not_of(" \t") - first + 1);
  }

  std::filesystem::path file_;
  std::ifstream in_;
  int line_ = 0;
};

constexpr std::string_view kCollarHeader = "id,x,y,z,azimuth,plunge,length";
constexpr std::string_view kLogHeader = "id,from,to,rqd";

/// "(x, y, z)" for messages, to 6 significant digits (a human reads it; rounding of the
/// hole's direction must not show as 5.000000000000002).
std::string point(const geometry::Vec3& p) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.6g, %.6g, %.6g)", p.x(), p.y(), p.z());
  return buffer;
}

}  // namespace

std::vector<rqd::Borehole> readBoreholes(const std::filesystem::path& file,
                                         const geometry::Box& domain) {
  CsvReader csv(file, kCollarHeader);
  std::vector<rqd::Borehole> holes;
  std::set<std::string> ids;
  std::vector<std::string> f;
  // Rounding of the hole's end (one ulp of the coordinates) must not push it out.
  const double slack = 1e-9 * std::max(1.0, domain.diagonal());
  while (csv.next(f)) {
    csv.requireFields(f, 7, kCollarHeader);
    rqd::Borehole hole;
    hole.id = f[0];
    if (hole.id.empty()) csv.fail("id: expected a hole name, got nothing");
    if (!ids.insert(hole.id).second) csv.fail("id: hole '" + hole.id + "' is listed twice");
    hole.collar = {csv.number(f[1], "x"), csv.number(f[2], "y"), csv.number(f[3], "z")};
    hole.azimuth = csv.number(f[4], "azimuth");
    hole.plunge = csv.number(f[5], "plunge");
    hole.length = csv.number(f[6], "length");
    if (!(hole.azimuth >= 0.0 && hole.azimuth <= 360.0)) {
      csv.fail("azimuth: expected degrees in [0, 360], got " + f[4]);
    }
    if (!(hole.plunge >= -90.0 && hole.plunge <= 90.0)) {
      csv.fail("plunge: expected degrees in [-90, 90] (positive downward), got " + f[5]);
    }
    if (!(hole.length > 0.0)) csv.fail("length: expected a number > 0 (m), got " + f[6]);
    const geometry::Box box = domain.enlarged(slack);
    for (const auto& [what, p] : {std::pair{"collar", hole.collar}, {"bottom", hole.end()}}) {
      if (!box.contains(p)) {
        csv.fail("hole '" + hole.id + "' leaves the domain: its " + what + " " + point(p) +
                 " lies outside the box " + point(domain.min) + " - " + point(domain.max));
      }
    }
    holes.push_back(std::move(hole));
  }
  if (holes.empty()) throw InputError(locate(file, 0, 0, "expected at least one borehole row"));
  return holes;
}

std::vector<rqd::LoggedInterval> readMeasuredLog(const std::filesystem::path& file,
                                                 const std::vector<rqd::Borehole>& holes) {
  CsvReader csv(file, kLogHeader);
  std::vector<rqd::LoggedInterval> log;
  std::vector<std::string> f;
  while (csv.next(f)) {
    csv.requireFields(f, 4, kLogHeader);
    int hole = -1;
    for (std::size_t i = 0; i < holes.size(); ++i) {
      if (holes[i].id == f[0]) hole = static_cast<int>(i);
    }
    if (hole < 0) csv.fail("id: unknown borehole '" + f[0] + "'");
    rqd::LoggedInterval entry;
    entry.hole = hole;
    entry.interval = {csv.number(f[1], "from"), csv.number(f[2], "to")};
    entry.rqd = csv.number(f[3], "rqd");
    const double length = holes[static_cast<std::size_t>(hole)].length;
    if (!(entry.interval.from >= 0.0 && entry.interval.from < entry.interval.to &&
          entry.interval.to <= length)) {
      csv.fail("from, to: expected 0 <= from < to <= " + formatDouble(length) +
               " (the length of hole '" + f[0] + "'), got " + f[1] + ", " + f[2]);
    }
    if (!(entry.rqd >= 0.0 && entry.rqd <= 100.0)) {
      csv.fail("rqd: expected a percentage in [0, 100], got " + f[3]);
    }
    log.push_back(entry);
  }
  if (log.empty()) throw InputError(locate(file, 0, 0, "expected at least one measured interval"));
  return log;
}

}  // namespace rockmass::io
