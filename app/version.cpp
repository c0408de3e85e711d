// `rockmass --version`: the program's version, the commit it was built from and the
// versions of the libraries it was compiled against (their headers' version macros).
#include "app/version.h"

#include <CGAL/version.h>
#include <assimp/version.h>
#include <cholmod.h>
#include <embree3/rtcore_config.h>
#include <oneapi/tbb/version.h>
#include <openvdb/version.h>
#include <zlib.h>
#include <CLI/Version.hpp>
#include <nlohmann/json.hpp>

#ifdef ROCKMASS_WITH_MPI
#include <mpi.h>
#endif

#include <Eigen/Core>
#include <string>

#include "dda3d/linear_solver.h"
#include "io/summary.h"

namespace rockmass::app {
namespace {

#define ROCKMASS_TEXT(x) #x
#define ROCKMASS_EXPANDED_TEXT(x) ROCKMASS_TEXT(x)

std::string dotted(int major, int minor, int patch) {
  return std::to_string(major) + '.' + std::to_string(minor) + '.' + std::to_string(patch);
}

}  // namespace

std::string versionText() {
  std::string text =
      std::string("rockmass ") + io::version() + " (commit " + ROCKMASS_COMMIT + ")\n";
  const std::pair<const char*, std::string> libraries[] = {
      {"CGAL", ROCKMASS_EXPANDED_TEXT(CGAL_VERSION)},
      {"CHOLMOD (SuiteSparse)",
       dotted(CHOLMOD_MAIN_VERSION, CHOLMOD_SUB_VERSION, CHOLMOD_SUBSUB_VERSION)},
      {"CLI11", CLI11_VERSION},
      {"Eigen", dotted(EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION)},
      {"Embree", RTC_VERSION_STRING},
      {"nlohmann-json", dotted(NLOHMANN_JSON_VERSION_MAJOR, NLOHMANN_JSON_VERSION_MINOR,
                               NLOHMANN_JSON_VERSION_PATCH)},
      {"OpenVDB", OPENVDB_LIBRARY_VERSION_STRING},
      {"assimp",
       dotted(static_cast<int>(aiGetVersionMajor()), static_cast<int>(aiGetVersionMinor()),
              static_cast<int>(aiGetVersionPatch()))},
      {"oneTBB", TBB_VERSION_STRING},
      {"zlib", ZLIB_VERSION},
  };
  for (const auto& [name, version] : libraries) {
    text += "  " + std::string(name) + ' ' + version + '\n';
  }
  // The BLAS that CHOLMOD's supernodes run on: its round-off is the factorization's
  // (docs/dda3d.md, "BLAS").
  for (const auto& [name, soname] : {std::pair<const char*, const char*>{"BLAS", "libblas.so.3"},
                                     {"LAPACK", "liblapack.so.3"}}) {
    const std::string file = dda3d::loadedLibrary(soname);
    text += std::string("  ") + name + ' ' + (file.empty() ? std::string("(none loaded)") : file) +
            '\n';
  }
#ifdef ROCKMASS_WITH_MPI
  // The MPI standard the headers declare (the ensemble command's ranks; docs/ensemble.md).
  text += "  MPI " + std::to_string(MPI_VERSION) + '.' + std::to_string(MPI_SUBVERSION) + '\n';
#else
  text += "  (built without MPI: ensembles run on local processes)\n";
#endif
  return text;
}

}  // namespace rockmass::app
