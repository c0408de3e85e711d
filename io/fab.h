#pragma once
/// FracMan FAB files (ASCII): discrete fractures as planar polygons.
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/vec.h"

namespace rockmass::io {

/// One fracture of a FAB file.
struct FabFracture {
  long long id = 0;                      ///< fracture id in the file
  int set = 0;                           ///< set id in the file
  std::vector<geometry::Vec3> vertices;  ///< polygon, as given (m)
};

/// The content of a FAB file that rockmass reads and writes.
struct FabFile {
  std::vector<FabFracture> fractures;
};

/// Writes `fab` as FAB text. Numbers are written in their shortest round-trip form, and the
/// normal line of each fracture is the polygon's Newell normal, so write -> read -> write
/// gives the same bytes.
std::string formatFab(const FabFile& fab);

/// Parses FAB text. Optional sections (PROPERTIES, SETS, TESSFRACTURE, ROCKBLOCK) are
/// skipped, Scale is ignored, the normal line is ignored (it may be a dummy).
/// Throws InputError located at file:line for truncated or garbled input.
FabFile parseFab(const std::string& text, const std::filesystem::path& file);

/// Reads a FAB file from disk (InputError if it cannot be read or parsed).
FabFile readFab(const std::filesystem::path& file);

}  // namespace rockmass::io
