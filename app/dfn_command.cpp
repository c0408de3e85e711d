// rockmass dfn: the discrete fracture network and its files.
#include <cstdio>
#include <memory>
#include <vector>

#include "app/command.h"
#include "app/stages.h"
#include "io/atomic_file.h"
#include "io/dfn_output.h"
#include "io/summary.h"

namespace rockmass::app {

namespace fs = std::filesystem;

DfnStage runDfnStage(const io::Scene& scene, const std::string& scene_path) {
  const auto start = Clock::now();
  DfnStage stage;
  stage.network = generateNetwork(scene, scene_path);
  stage.stats = geometry::measureSets(stage.network);
  stage.seconds = secondsSince(start);
  std::fprintf(stderr, "dfn: %zu discs in %zu sets (%.2f s)\n", stage.network.discs.size(),
               stage.network.sets.size(), stage.seconds);
  return stage;
}

void writeDfnFiles(const fs::path& out, const io::Scene& scene,
                   const geometry::FractureNetwork& network) {
  const int segments = scene.analysis.blocks ? scene.analysis.blocks->disc_segments : 24;
  io::writeFileAtomically(out / "fractures.fab", io::formatFab(io::toFab(network, segments)));
  io::writeFileAtomically(out / "fractures.csv", io::formatFracturesCsv(network));
  io::writeFileAtomically(out / "fractures.vtu", io::formatFracturesVtu(network, segments));
}

namespace {

int runDfn(const CommonOptions& options) {
  const io::Scene scene = loadScene(options, /*mesh_domain_supported=*/true);
  const fs::path out = prepareOutput(options.output);
  const DfnStage stage = runDfnStage(scene, options.scene);

  const auto start = Clock::now();
  writeDfnFiles(out, scene, stage.network);
  io::RunInfo run;
  run.command = "dfn";
  run.scene = options.scene;
  run.name = scene.name;
  run.seed = scene.seed;
  run.stages = {"dfn"};
  run.timings = {{"dfn", stage.seconds}, {"write", secondsSince(start)}};
  io::writeFileAtomically(out / "summary.json",
                          io::formatDfnSummary(run, stage.network, stage.stats));
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
