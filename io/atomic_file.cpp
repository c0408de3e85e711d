#include "io/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <string>
#include <system_error>

namespace rockmass::io {
namespace {

/// The temporary name used while `path` is written: ".<filename>.tmp.<pid>" beside it.
std::filesystem::path temporaryPathFor(const std::filesystem::path& path) {
  std::string name = ".";
  name += path.filename().string();
  name += ".tmp." + std::to_string(::getpid());
  return path.parent_path() / name;
}

/// `what` followed by strerror(errno) when the failed operation set errno.
std::string withErrno(std::string what) {
  const int error = errno;
  if (error != 0) what += std::string(": ") + std::strerror(error);
  return what;
}

/// Flushes and closes `stream`, written to `temporary` (errno cleared by the caller before its
/// last write); returns an empty string on success, otherwise why it failed.
std::string flushAndClose(std::ofstream& stream, const std::filesystem::path& temporary) {
  stream.flush();
  if (!stream) return withErrno("writing " + temporary.string() + " failed");
  errno = 0;
  stream.close();
  if (!stream) return withErrno("closing " + temporary.string() + " failed");
  return {};
}

/// Writes `content` to `temporary` and closes it; returns an empty string on success,
/// otherwise why it failed.
std::string writeAndClose(const std::filesystem::path& temporary, std::string_view content) {
  errno = 0;
  std::ofstream stream(temporary, std::ios::binary | std::ios::trunc);
  if (!stream.is_open()) return withErrno("cannot create " + temporary.string());
  errno = 0;
  stream.write(content.data(), static_cast<std::streamsize>(content.size()));
  return flushAndClose(stream, temporary);
}

std::mutex written_mutex;
std::vector<std::filesystem::path> written;  ///< guarded by written_mutex

/// The end of every atomic write: with no `reason` to fail, renames `temporary` onto `path`
/// and records it (filesWritten); otherwise, or when the rename fails, removes `temporary`
/// and throws "cannot write <path>: <reason>".
void finishAtomically(const std::filesystem::path& temporary, const std::filesystem::path& path,
                      std::string reason) {
  if (reason.empty()) {
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error) reason = "renaming " + temporary.string() + " failed: " + error.message();
  }
  if (reason.empty()) {
    const std::lock_guard<std::mutex> lock(written_mutex);
    written.push_back(path);
    return;
  }
  std::error_code ignored;
  std::filesystem::remove(temporary, ignored);
  throw std::runtime_error("cannot write " + path.string() + ": " + reason);
}

}  // namespace

std::vector<std::filesystem::path> filesWritten() {
  const std::lock_guard<std::mutex> lock(written_mutex);
  return written;
}

void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path& temporary)>& write) {
  const std::filesystem::path temporary = temporaryPathFor(path);
  std::string reason;
  try {
    write(temporary);
  } catch (const std::exception& error) {
    reason = error.what();
    if (reason.empty()) reason = "the writer failed";
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
  finishAtomically(temporary, path, std::move(reason));
}

StreamedFile::StreamedFile(std::filesystem::path path)
    : path_(std::move(path)), temporary_(temporaryPathFor(path_)) {
  errno = 0;
  stream_ = std::make_unique<std::ofstream>(temporary_, std::ios::binary | std::ios::trunc);
  if (!stream_->is_open()) {
    throw std::runtime_error("cannot write " + path_.string() + ": " +
                             withErrno("cannot create " + temporary_.string()));
  }
}

StreamedFile::~StreamedFile() {
  if (!stream_) return;
  stream_.reset();
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

void StreamedFile::write(std::string_view text) {
  if (!stream_) throw std::logic_error("StreamedFile::write after commit: " + path_.string());
  stream_->write(text.data(), static_cast<std::streamsize>(text.size()));
}

void StreamedFile::commit() {
  if (!stream_) throw std::logic_error("StreamedFile::commit twice: " + path_.string());
  errno = 0;
  std::string reason = flushAndClose(*stream_, temporary_);
  stream_.reset();
  finishAtomically(temporary_, path_, std::move(reason));
}

/// Writes to a temporary file beside `path`, checks the stream, then renames it onto `path`.
void writeFileAtomically(const std::filesystem::path& path, std::string_view content) {
  writeAtomically(path, [&](const std::filesystem::path& temporary) {
    const std::string reason = writeAndClose(temporary, content);
    if (!reason.empty()) throw std::runtime_error(reason);
  });
}

/// Shortest round-trip text of `value` (std::to_chars); "nan", "inf" or "-inf" otherwise.
std::string formatDouble(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[32];
  const std::to_chars_result result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

/// Quoted (with doubled quotes) only when the field holds a comma, quote or newline.
std::string csvField(const std::string& field) {
  if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
  std::string quoted = "\"";
  for (char c : field) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + '"';
}

}  // namespace rockmass::io
