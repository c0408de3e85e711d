// rockmass: the command-line program. Sub-commands (one file each, see command.h) wire the
// modules together; every exception becomes an exit code and a message (0 success, 2 bad
// input, 1 anything else).
#include <exception>
#include <iostream>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/command.h"
#include "io/input_error.h"
#include "io/summary.h"

int main(int argc, char** argv) {
  CLI::App app{"rockmass: fractured rock workbench (DFN, blocks, RQD, 3D DDA)"};
  app.set_version_flag("--version", rockmass::io::version());
  app.require_subcommand(1);
  // One sub-command per line.
  // clang-format off
  const std::vector<rockmass::app::Command> commands = {
      rockmass::app::addDfnCommand(app),
      rockmass::app::addBlocksCommand(app),
      rockmass::app::addRqdCommand(app),
      rockmass::app::addDdaCommand(app),
      rockmass::app::addOverloadCommand(app),
      rockmass::app::addStrengthCommand(app),
      rockmass::app::addRunCommand(app),
  };
  // clang-format on

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  try {
    for (const rockmass::app::Command& command : commands) {
      if (command.cli->parsed()) return command.run();
    }
  } catch (const rockmass::io::InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 1;
}
