// rockmass sub-commands: what they share (options, scene loading, output folder) and how
// main() finds them. Each sub-command lives in its own file and exposes one add*Command().
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "geometry/fracture_network.h"
#include "geometry/interrupt.h"
#include "io/scene.h"

namespace rockmass::app {

using Clock = std::chrono::steady_clock;

/// Options every sub-command takes.
struct CommonOptions {
  std::string scene;                  ///< scene file
  std::string output;                 ///< output folder
  std::optional<std::uint64_t> seed;  ///< overrides the scene's seed
  /// --max-discs: geometry::GenerationLimits::max_discs
  double max_discs = geometry::GenerationLimits{}.max_discs;
  double max_blocks = 1e6;  ///< --max-blocks: io::Scene::max_blocks
  int threads = 0;          ///< --threads: worker threads (0: every core)
};

/// A registered sub-command: its CLI11 node and what runs when it was parsed.
struct Command {
  CLI::App* cli = nullptr;
  std::function<int()> run;  ///< returns the exit code; throws io::InputError on bad input
};

/// Seconds since `start`.
double secondsSince(Clock::time_point start);

/// Adds SCENE, -o OUTDIR and --seed to a sub-command.
void addCommonOptions(CLI::App& command, CommonOptions& options);

/// Reads the scene and applies command-line overrides. A mesh domain is read and checked
/// (io::readMeshDomain; scene.domain_surface, and dfn.domain becomes its bounding box) when
/// `mesh_domain_supported`, else it is an io::InputError (the command works on boxes only).
io::Scene loadScene(const CommonOptions& options, bool mesh_domain_supported = false);

/// The command-line overrides of loadScene applied to a scene read otherwise (an ensemble's
/// realizations): --seed, --max-discs, --max-blocks, and the mesh domain.
void applyCommonOptions(io::Scene& scene, const CommonOptions& options,
                        bool mesh_domain_supported = false);

/// How many threads the run may keep busy: --threads, else every core (TBB's limit).
std::size_t allowedThreads();

/// Creates the output folder (an error naming it when that is impossible) and removes a
/// stale interruption marker from it.
std::filesystem::path prepareOutput(const std::string& output);

/// The marker an interrupted command leaves in its output folder.
inline constexpr const char* kInterruptedMarker = "interrupted.json";

/// Reports an interruption: a message on stderr and, once an output folder was prepared,
/// `interrupted.json` in it (the signal, where the command stopped, and the files it had
/// completed, all written whole). Returns the exit code, 128 + the signal (130 for Ctrl-C).
int reportInterruption(const Interrupted& interruption, const std::string& command);

/// Generates the scene's fracture network; an impossible distribution becomes an
/// io::InputError that names the scene file.
geometry::FractureNetwork generateNetwork(const io::Scene& scene, const std::string& scene_path);

// One function per sub-command (each in <name>_command.cpp).
Command addDfnCommand(CLI::App& app);
Command addRqdCommand(CLI::App& app);
Command addBlocksCommand(CLI::App& app);
Command addDdaCommand(CLI::App& app);
Command addOverloadCommand(CLI::App& app);
Command addStrengthCommand(CLI::App& app);
Command addRunCommand(CLI::App& app);
Command addEnsembleCommand(CLI::App& app);

/// `text` quoted for the shell (single quotes; a quote inside closed, escaped and reopened).
std::string shellQuote(const std::string& text);

/// What a helper script printed and how it ended (runScript).
struct ScriptRun {
  bool started = false;            ///< the interpreter could be started
  bool succeeded = false;          ///< it exited with status 0
  std::vector<std::string> lines;  ///< its output (stdout and stderr), line by line
};

/// Runs `python script folder arguments...` (the figure and report scripts), echoing each
/// line it prints to stderr as "<prefix>: line" as it comes. `low_priority` runs it at nice 19
/// (coreutils' nice): beside a computation that keeps every core busy it takes the time
/// the computation leaves idle.
ScriptRun runScript(const std::string& python, const std::filesystem::path& script,
                    const std::filesystem::path& folder, const std::string& prefix,
                    const std::vector<std::string>& arguments = {}, bool low_priority = false);

/// Adds `--cutter exact|fast` (overriding analysis.blocks.cutter) to a sub-command.
void addCutterOption(CLI::App& command, std::string& cutter);

}  // namespace rockmass::app
