#include "io/input_error.h"

namespace rockmass::io {

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
