// rockmass dfn: the discrete fracture network and its files.
#include <cstdio>
#include <memory>
#include <vector>

#include "app/command.h"
#include "io/atomic_file.h"
#include "io/dfn_output.h"
#include "io/summary.h"

namespace rockmass::app {

namespace {

namespace fs = std::filesystem;

int runDfn(const CommonOptions& options) {
  const io::Scene scene = loadScene(options, /*mesh_domain_supported=*/true);
  const fs::path out = prepareOutput(options.output);

  auto start = Clock::now();
  const geometry::FractureNetwork network = generateNetwork(scene, options.scene);
  const std::vector<geometry::SetStatistics> stats = geometry::measureSets(network);
  const double dfn_seconds = secondsSince(start);
  std::fprintf(stderr, "dfn: %zu discs in %zu sets (%.2f s)\n", network.discs.size(),
               network.sets.size(), dfn_seconds);

  start = Clock::now();
  const int segments = scene.analysis.blocks ? scene.analysis.blocks->disc_segments : 24;
  io::writeFileAtomically(out / "fractures.fab", io::formatFab(io::toFab(network, segments)));
  io::writeFileAtomically(out / "fractures.csv", io::formatFracturesCsv(network));
  io::writeFileAtomically(out / "fractures.vtu", io::formatFracturesVtu(network, segments));
  io::RunInfo run;
  run.command = "dfn";
  run.scene = options.scene;
  run.name = scene.name;
  run.seed = scene.seed;
  run.stages = {"dfn"};
  run.timings = {{"dfn", dfn_seconds}, {"write", secondsSince(start)}};
  io::writeFileAtomically(out / "summary.json", io::formatDfnSummary(run, network, stats));
  std::fprintf(stderr, "dfn: wrote %s\n", out.string().c_str());
  return 0;
}

}  // namespace

Command addDfnCommand(CLI::App& app) {
  auto options = std::make_shared<CommonOptions>();
  CLI::App* cli = app.add_subcommand("dfn", "Generate the discrete fracture network of a scene");
  addCommonOptions(*cli, *options);
  return {cli, [options] { return runDfn(*options); }};
}

}  // namespace rockmass::app
