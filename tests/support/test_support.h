#pragma once
/// Helpers shared by the test programs: temporary folders, whole-file I/O, and the sample
/// inputs of the shared scene-format document.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rockmass::test {

/// A fresh folder under the system temporary directory (named after `name` and the process
/// id), removed with everything in it when the object goes.
class TempDir {
 public:
  explicit TempDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("rockmass_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  /// The folder.
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// The whole content of a file ("" when it cannot be read).
inline std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

/// Writes `text` to `path` (replacing it) and returns the path.
inline std::filesystem::path writeFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

/// The minimal FAB example of scene-format.md: one 12 x 12 m square at z = 5 in set 1.
inline const std::string kSceneFormatFab =
    "BEGIN FORMAT\n"
    "    Format = Ascii\n"
    "    Length_Unit = Meter\n"
    "    XAxis = East\n"
    "    Scale = 100.0\n"
    "    No_Fractures = 1\n"
    "    No_TessFractures = 0\n"
    "    No_Nodes = 4\n"
    "    No_Properties = 0\n"
    "END FORMAT\n"
    "\n"
    "BEGIN FRACTURE\n"
    "1 4 1\n"
    "1 -1 -1 5\n"
    "2 11 -1 5\n"
    "3 11 11 5\n"
    "4 -1 11 5\n"
    "0 0 0 1\n"
    "END FRACTURE\n";

}  // namespace rockmass::test
