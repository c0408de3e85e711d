// rockmass: the command-line program. Sub-commands (one file each, see command.h) wire the
// modules together; every exception becomes an exit code and a message (0 success, 2 bad
// input, 1 anything else).
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <ctime>
#include <exception>
#include <iostream>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/command.h"
#include "app/version.h"
#include "io/input_error.h"
#include "io/summary.h"

int main(int argc, char** argv) {
  CLI::App app{"rockmass: fractured rock workbench (DFN, blocks, RQD, 3D DDA)"};
  app.set_version_flag("--version", rockmass::app::versionText());
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
      rockmass::app::addEnsembleCommand(app),
  };
  // clang-format on

  // A mistyped command or option is named, with the closest valid one.
  std::vector<std::string> names;
  for (const rockmass::app::Command& command : commands) names.push_back(command.cli->get_name());
  if (argc > 1 && argv[1][0] != '-' &&
      std::find(names.begin(), names.end(), argv[1]) == names.end()) {
    std::string list;
    for (const std::string& name : names) list += (list.empty() ? "" : ", ") + name;
    std::cerr << "error: unknown command '" << argv[1] << "'; expected one of: " << list
              << rockmass::io::suggestion(argv[1], names) << "\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ExtrasError& e) {
    app.exit(e);
    for (const rockmass::app::Command& command : commands) {
      if (!command.cli->parsed()) continue;
      std::vector<std::string> options;
      for (const CLI::Option* option : command.cli->get_options()) {
        for (const std::string& name : option->get_lnames()) options.push_back("--" + name);
      }
      for (int i = 2; i < argc; ++i) {
        const std::string word = argv[i];
        if (word.rfind("--", 0) == 0 &&
            std::find(options.begin(), options.end(), word) == options.end()) {
          std::cerr << "error: unknown option '" << word << "' for rockmass "
                    << command.cli->get_name() << rockmass::io::suggestion(word, options) << "\n";
        }
      }
    }
    return 2;
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  // Ctrl-C (and SIGTERM) asks the running stage to stop at its next safe point. A second
  // signal a second or more later ends the program at once; one sooner is the same request
  // delivered twice (GNU timeout signals the process and then its process group).
  struct sigaction action {};
  action.sa_handler = [](int signal) {
    static std::atomic<long long> first_ns{0};
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    const long long ns = now.tv_sec * 1'000'000'000LL + now.tv_nsec;
    if (!rockmass::interruptRequested()) {
      first_ns.store(ns);
      rockmass::requestInterrupt(signal);
      static const char message[] =
          "\nrockmass: stopping at the next safe point (Ctrl-C again to stop at once)\n";
      [[maybe_unused]] const auto written = write(STDERR_FILENO, message, sizeof message - 1);
      return;
    }
    if (ns - first_ns.load() < 1'000'000'000LL) return;
    static const char message[] = "\nrockmass: stopped at once\n";
    [[maybe_unused]] const auto written = write(STDERR_FILENO, message, sizeof message - 1);
    _exit(128 + signal);
  };
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);

  std::string command_name;
  try {
    for (const rockmass::app::Command& command : commands) {
      if (!command.cli->parsed()) continue;
      command_name = command.cli->get_name();
      const int code = command.run();
      // A request that came after the last safe point still ends as an interruption.
      rockmass::throwIfInterrupted("the last step of " + command_name);
      return code;
    }
  } catch (const rockmass::Interrupted& e) {
    return rockmass::app::reportInterruption(e, command_name);
  } catch (const rockmass::io::InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 1;
}
