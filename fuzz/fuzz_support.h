#pragma once
// What the fuzz targets share: the input as a file (the readers take paths, so that relative
// files and messages work as for users), and the rule that bad input is an io::InputError
// (exit 2) and nothing else.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/input_error.h"

namespace rockmass::fuzz {

/// A per-process file that holds the current input, named with `extension`.
inline std::filesystem::path inputFile(const char* extension) {
  return std::filesystem::temp_directory_path() /
         ("rockmass_fuzz_" + std::to_string(::getpid()) + extension);
}

/// Writes the input, runs `read` on its path; an io::InputError is the expected refusal, any
/// other exception aborts (a finding: the program would exit 1 on bad input, not 2).
template <typename Read>
int readInput(const std::uint8_t* data, std::size_t size, const char* extension, Read read) {
  const std::filesystem::path path = inputFile(extension);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    read(path);
  } catch (const io::InputError&) {
    // Refused with a located message: exit 2, as it should be.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "not an InputError: %s\n", e.what());
    std::abort();
  }
  return 0;
}

}  // namespace rockmass::fuzz
