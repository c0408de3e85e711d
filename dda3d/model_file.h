// A DdaModel saved to a file and read back bit for bit: the benchmarks run the engine on a
// real model (the Xiangjiaba foundation region) without generating and cutting it again.
// Binary, little-endian as the machine writes it, zlib-compressed; a header names the format
// and its version.
#pragma once

#include <filesystem>

#include "dda3d/model.h"

namespace rockmass::dda3d {

/// Writes `model` to `path` (through a temporary name, renamed when complete). Throws
/// std::runtime_error when the file cannot be written.
void saveModel(const DdaModel& model, const std::filesystem::path& path);

/// The model saved by saveModel. Throws std::runtime_error naming the file when it is not
/// such a file (another format or version, truncated, corrupt).
DdaModel loadModel(const std::filesystem::path& path);

}  // namespace rockmass::dda3d
