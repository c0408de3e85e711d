// rockmass strength: cut the scene into blocks as `rockmass dda` does and find the critical
// strength reduction factor of analysis.strength_reduction (docs/stability.md); writes
// summary.json.
#include <memory>

#include "app/command.h"
#include "app/stability.h"
#include "scene_model/scene_blocks.h"

namespace rockmass::app {

Command addStrengthCommand(CLI::App& app) {
  auto options = std::make_shared<StabilityOptions>();
  CLI::App* cli = app.add_subcommand(
      "strength",
      "Strength reduction: divide the joints' friction and cohesion by SRF and find the "
      "critical SRF by bisection (analysis.strength_reduction)");
  addCommonOptions(*cli, options->common);
  addCutterOption(*cli, options->cutter);
  return {cli, [options] {
            return runStabilityCommand(*options, StabilityAnalysis::StrengthReduction);
          }};
}

}  // namespace rockmass::app
