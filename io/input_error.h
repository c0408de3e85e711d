#pragma once
/// Bad input: a malformed scene, an impossible distribution, a truncated FAB file...
/// The message locates the problem ("file:line:column: key: what was expected"); the
/// program turns it into exit code 2.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace rockmass::io {

/// An error in what the user gave us. what() is the full, located message.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// " (did you mean 'x'?)" for the closest of `candidates` within 2 edits of `word` (and
/// closer than its own length, so one-letter names suggest nothing), else "".
std::string suggestion(std::string_view word, const std::vector<std::string>& candidates);

/// "file:line:column: message" with 1-based line and column (column omitted when 0).
std::string locate(const std::filesystem::path& file, int line, int column,
                   const std::string& message);

}  // namespace rockmass::io
