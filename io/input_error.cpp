#include "io/input_error.h"

#include <algorithm>
#include <numeric>
#include <vector>

namespace rockmass::io {
namespace {

/// Levenshtein distance: insertions, deletions and substitutions that turn a into b.
std::size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace

std::string suggestion(std::string_view word, const std::vector<std::string>& candidates) {
  const std::string* best = nullptr;
  std::size_t best_distance = 3;
  for (const std::string& candidate : candidates) {
    const std::size_t distance = editDistance(word, candidate);
    if (distance < best_distance && distance < candidate.size()) {
      best = &candidate;
      best_distance = distance;
    }
  }
  return best ? " (did you mean '" + *best + "'?)" : "";
}

/// "file:line:column: message", dropping the column when it is 0 and the line when both are 0.
std::string locate(const std::filesystem::path& file, int line, int column,
                   const std::string& message) {
  std::string located = file.string();
  if (line > 0) {
    located += ':' + std::to_string(line);
    if (column > 0) located += ':' + std::to_string(column);
  }
  return located + ": " + message;
}

}  // namespace rockmass::io
