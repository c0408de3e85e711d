#pragma once
/// Running the rockmass binary from the CLI tests (ROCKMASS_BINARY is set by
/// rockmass_add_test_program).
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "tests/support/test_support.h"

namespace rockmass::test {

/// Runs `rockmass <arguments>`; returns its exit code (-1 when it did not exit normally) and,
/// when `output` is given, stores its stdout and stderr there. `environment`: assignments
/// (NAME=value ...) for this run only.
inline int runRockmass(const std::string& arguments, std::string* output = nullptr,
                       const std::string& environment = "") {
  const std::string command = (environment.empty() ? "" : "env " + environment + " ") +
                              std::string(ROCKMASS_BINARY) + " " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return -1;
  char buffer[4096];
  std::string text;
  while (std::fgets(buffer, sizeof buffer, pipe)) text += buffer;
  const int status = pclose(pipe);
  if (output) *output = text;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// Writes `scene_text` as `<dir>/<name>.yaml` and runs `rockmass <command>` on it with the
/// output folder `<dir>/<name>`; returns the exit code, stdout and stderr in `output`.
inline int runOnScene(const std::string& command, const std::filesystem::path& dir,
                      const std::string& name, const std::string& scene_text,
                      std::string* output = nullptr) {
  const std::filesystem::path scene = writeFile(dir / (name + ".yaml"), scene_text);
  return runRockmass(command + " " + scene.string() + " -o " + (dir / name).string(), output);
}

/// The exit code and the output of one run of the binary.
struct CliResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs `rockmass <arguments>` and captures its exit code and output.
inline CliResult runCli(const std::string& arguments) {
  CliResult result;
  result.exit_code = runRockmass(arguments, &result.output);
  return result;
}

}  // namespace rockmass::test
