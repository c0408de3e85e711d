#pragma once
/// The text of `rockmass --version`.
#include <string>

namespace rockmass::app {

/// "rockmass <version> (commit <git describe>)" and one line per library with the version
/// its headers give (CGAL, CHOLMOD, CLI11, Eigen, Embree, nlohmann-json, OpenVDB, assimp,
/// oneTBB, zlib).
std::string versionText();

}  // namespace rockmass::app
