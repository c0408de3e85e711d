#pragma once
/// Atomic output: write to a temporary name in the same folder, then rename, so a failed
/// or interrupted run never leaves a half-written file that looks whole.
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace rockmass::io {

/// Writes `content` to `path` atomically (temporary file, flush, rename). Creates no
/// folders. Throws std::runtime_error naming the path when anything fails; the temporary
/// file is removed then.
void writeFileAtomically(const std::filesystem::path& path, std::string_view content);

/// Creates `path` atomically with a writer that needs a file name (a library that opens the
/// file itself): calls `write(temporary)`, which must create the whole file at `temporary`
/// (a hidden name beside `path`) and throw on failure, then renames it onto `path`. Creates
/// no folders. Throws std::runtime_error "cannot write <path>: <reason>" when `write` throws
/// a std::exception or the rename fails; the temporary file is removed then.
void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path& temporary)>& write);

/// A file written as it goes (the history of a long run, which would not fit in memory),
/// under a temporary name beside `path` until commit() renames it onto `path`: a run that
/// stops early leaves no file that looks whole. Destroyed uncommitted, it removes the
/// temporary file.
class StreamedFile {
 public:
  /// Creates the temporary file (std::runtime_error naming `path` when it cannot).
  explicit StreamedFile(std::filesystem::path path);
  ~StreamedFile();
  StreamedFile(const StreamedFile&) = delete;
  StreamedFile& operator=(const StreamedFile&) = delete;

  /// Appends `text` (buffered).
  void write(std::string_view text);
  /// Flushes, closes, checks and renames the file onto its path (std::runtime_error naming
  /// the path when anything fails; the temporary file is removed then).
  void commit();

 private:
  std::filesystem::path path_;
  std::filesystem::path temporary_;
  std::unique_ptr<std::ofstream> stream_;
};

/// Every path this process wrote through writeAtomically or writeFileAtomically, in the
/// order written (a file written twice appears twice): what an interrupted run completed.
std::vector<std::filesystem::path> filesWritten();

/// Shortest text that reads back to the same double (std::to_chars).
std::string formatDouble(double value);

/// `field` as a CSV field (RFC 4180): quoted, with doubled quotes, when it holds a comma,
/// quote or newline; unchanged otherwise.
std::string csvField(const std::string& field);

}  // namespace rockmass::io
