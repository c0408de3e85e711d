// rockmass: the command-line program. Sub-commands wire the modules together; every
// exception becomes an exit code and a message (0 success, 2 bad input, 1 anything else).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "geometry/fracture_network.h"
#include "io/atomic_file.h"
#include "io/dfn_output.h"
#include "io/input_error.h"
#include "io/scene.h"
#include "io/summary.h"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// Options every sub-command takes.
struct CommonOptions {
  std::string scene;                  ///< scene file
  std::string output;                 ///< output folder
  std::optional<std::uint64_t> seed;  ///< overrides the scene's seed
};

/// Seconds since `start`.
double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Adds SCENE, -o OUTDIR and --seed to a sub-command.
void addCommonOptions(CLI::App& command, CommonOptions& options) {
  command.add_option("scene", options.scene, "Scene file (YAML)")->required();
  command.add_option("-o,--output", options.output, "Output folder (created if missing)")
      ->required();
  command.add_option("--seed", options.seed, "Seed overriding the scene's `seed`");
}

/// Reads the scene and applies command-line overrides.
rockmass::io::Scene loadScene(const CommonOptions& options) {
  rockmass::io::Scene scene = rockmass::io::loadScene(options.scene);
  if (options.seed) scene.seed = *options.seed;
  if (!scene.domain_mesh.empty()) {
    throw rockmass::io::InputError(
        options.scene +
        ": domain.mesh: mesh domains are not supported by this version yet; "
        "give domain.box");
  }
  return scene;
}

/// Creates the output folder (an error naming it when that is impossible).
fs::path prepareOutput(const std::string& output) {
  std::error_code error;
  fs::create_directories(output, error);
  if (error || !fs::is_directory(output)) {
    throw std::runtime_error(output + ": cannot create the output folder (" + error.message() +
                             ")");
  }
  return fs::path(output);
}

/// rockmass dfn: the discrete fracture network and its files.
int runDfn(const CommonOptions& options) {
  const rockmass::io::Scene scene = loadScene(options);
  const fs::path out = prepareOutput(options.output);

  auto start = Clock::now();
  rockmass::geometry::FractureNetwork network;
  try {
    network = rockmass::geometry::generateNetwork(scene.dfn, scene.seed);
  } catch (const std::invalid_argument& e) {
    throw rockmass::io::InputError(options.scene + ": " + e.what());
  }
  const std::vector<rockmass::geometry::SetStatistics> stats =
      rockmass::geometry::measureSets(network);
  const double dfn_seconds = secondsSince(start);
  std::fprintf(stderr, "dfn: %zu discs in %zu sets (%.2f s)\n", network.discs.size(),
               network.sets.size(), dfn_seconds);

  start = Clock::now();
  const int segments = scene.analysis.blocks ? scene.analysis.blocks->disc_segments : 24;
  rockmass::io::writeFileAtomically(
      out / "fractures.fab", rockmass::io::formatFab(rockmass::io::toFab(network, segments)));
  rockmass::io::writeFileAtomically(out / "fractures.csv",
                                    rockmass::io::formatFracturesCsv(network));
  rockmass::io::writeFileAtomically(out / "fractures.vtu",
                                    rockmass::io::formatFracturesVtu(network, segments));
  rockmass::io::RunInfo run;
  run.command = "dfn";
  run.scene = options.scene;
  run.name = scene.name;
  run.seed = scene.seed;
  run.stages = {"dfn"};
  run.timings = {{"dfn", dfn_seconds}, {"write", secondsSince(start)}};
  rockmass::io::writeFileAtomically(out / "summary.json",
                                    rockmass::io::formatDfnSummary(run, network, stats));
  std::fprintf(stderr, "dfn: wrote %s\n", out.string().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"rockmass: fractured rock workbench (DFN, blocks, RQD, 3D DDA)"};
  app.set_version_flag("--version", rockmass::io::version());
  app.require_subcommand(1);
  CommonOptions options;
  CLI::App* dfn = app.add_subcommand("dfn", "Generate the discrete fracture network of a scene");
  addCommonOptions(*dfn, options);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  try {
    if (dfn->parsed()) return runDfn(options);
  } catch (const rockmass::io::InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 1;
}
