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
  /// The values of the file's properties (FabFile::property_names), in their order; empty
  /// when the file's header lines do not carry one value per property.
  std::vector<double> properties;
};

/// The content of a FAB file that rockmass reads and writes.
struct FabFile {
  /// The SETS section: the name of set k + 1 (FracMan's "Set<k+1> = \"name\""); empty
  /// names where the file names fewer sets.
  std::vector<std::string> set_names;
  /// The PROPERTIES section: the name of each property ("Prop<k+1> = (Real*4) \"name\"").
  std::vector<std::string> property_names;
  std::vector<FabFracture> fractures;
};

/// Writes `fab` as FAB text as FracMan writes it: FORMAT, PROPERTIES (each a Real*4), SETS,
/// FRACTURE (header "id nvertices set values...", vertex lines, normal line) and an empty
/// TESSFRACTURE section. Numbers are written in their shortest round-trip form, and the
/// normal line of each fracture is the polygon's Newell normal, so write -> read -> write
/// gives the same bytes.
std::string formatFab(const FabFile& fab);

/// Parses FAB text. The set names (SETS) and property names (PROPERTIES) are read, with each
/// fracture's property values when its header line carries one per property; TESSFRACTURE
/// and ROCKBLOCK are skipped, Scale is ignored, the normal line is ignored (it may be a
/// dummy).
/// Throws InputError located at file:line for truncated or garbled input.
FabFile parseFab(const std::string& text, const std::filesystem::path& file);

/// Reads a FAB file from disk (InputError if it cannot be read or parsed).
FabFile readFab(const std::filesystem::path& file);

}  // namespace rockmass::io
