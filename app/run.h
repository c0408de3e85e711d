// `rockmass run` as a function of its options and an in-memory scene, so that an ensemble runs
// each realization's sampled scene exactly as `run` runs a scene file (app/ensemble_command.cpp).
#pragma once

#include <string>

#include "app/command.h"
#include "io/scene.h"

namespace rockmass::app {

/// Options of `rockmass run` beyond the common ones.
struct RunOptions {
  CommonOptions common;
  bool quick = false;           ///< the smaller test run (see quickScene)
  std::string cutter;           ///< "", "exact" or "fast" ("": the scene's choice)
  std::string section;          ///< "", "none" or AXIS=VALUE, e.g. y=10
  std::string solver = "auto";  ///< DDA linear solver
  bool no_figures = false;      ///< skip the matplotlib figures
  std::string figure_scripts = ROCKMASS_FIGURE_SCRIPTS;  ///< folder of the figure scripts
  std::string python = "/usr/bin/python3";               ///< interpreter of the figures
};

/// Runs every stage `scene` names into options.common.output (options.common.scene is the
/// file it came from: named in summary.json and in messages). Returns the exit code.
int runScene(const RunOptions& options, io::Scene scene);

}  // namespace rockmass::app
