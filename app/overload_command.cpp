// rockmass overload: cut the scene into blocks as `rockmass dda` does and find K_s by the
// overload method of analysis.overload (docs/stability.md); writes overload.csv and
// summary.json.
#include <memory>

#include "app/command.h"
#include "app/stability.h"
#include "scene_model/scene_blocks.h"

namespace rockmass::app {

Command addOverloadCommand(CLI::App& app) {
  auto options = std::make_shared<StabilityOptions>();
  CLI::App* cli = app.add_subcommand(
      "overload",
      "Overload method: run the DDA to equilibrium for each factor K of analysis.overload and "
      "report K_s, where the model stops coming to rest");
  addCommonOptions(*cli, options->common);
  addCutterOption(*cli, options->cutter);
  return {cli, [options] { return runStabilityCommand(*options, StabilityAnalysis::Overload); }};
}

}  // namespace rockmass::app
