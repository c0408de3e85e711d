#include "app/command.h"

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <system_error>
#include <vector>

#include <tbb/global_control.h>
#include <nlohmann/json.hpp>

#include "io/atomic_file.h"

#include "io/input_error.h"
#include "io/mesh_domain.h"

namespace rockmass::app {

namespace fs = std::filesystem;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void addCommonOptions(CLI::App& command, CommonOptions& options) {
  command.add_option("scene", options.scene, "Scene file (YAML)")->required();
  command.add_option("-o,--output", options.output, "Output folder (created if missing)")
      ->required();
  command.add_option("--seed", options.seed, "Seed overriding the scene's `seed`");
  command
      .add_option("--max-discs", options.max_discs,
                  "Largest expected number of joint-set discs to draw (a budget checked "
                  "before the work)")
      ->default_val(geometry::GenerationLimits{}.max_discs)
      ->check(CLI::PositiveNumber);
  command
      .add_option("--threads", options.threads,
                  "Worker threads (0: every core); the outputs are the same bytes whatever "
                  "the count")
      ->default_val(0)
      ->check(CLI::NonNegativeNumber);
  command
      .add_option("--max-blocks", options.max_blocks,
                  "Largest estimated number of blocks a cut may make (an upper estimate, "
                  "checked before the cut)")
      ->default_val(io::Scene{}.max_blocks)
      ->check(CLI::PositiveNumber);
}

io::Scene loadScene(const CommonOptions& options, bool mesh_domain_supported) {
  if (options.threads > 0) {
    // For the rest of the process: every parallel loop (TBB) runs on at most this many.
    static std::unique_ptr<tbb::global_control> limit;
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  static_cast<std::size_t>(options.threads));
  }
  io::Scene scene = io::loadScene(options.scene);
  applyCommonOptions(scene, options, mesh_domain_supported);
  return scene;
}

void applyCommonOptions(io::Scene& scene, const CommonOptions& options,
                        bool mesh_domain_supported) {
  if (options.seed) scene.seed = *options.seed;
  scene.generation_limits.max_discs = options.max_discs;
  scene.max_blocks = options.max_blocks;
  if (!scene.domain_mesh.empty() && mesh_domain_supported) {
    io::MeshDomain domain = io::readMeshDomain(scene.domain_mesh, options.scene);
    scene.domain_surface = std::move(domain.surface);
    scene.dfn.domain = domain.bounds;
  } else if (!scene.domain_mesh.empty()) {
    throw io::InputError(options.scene +
                         ": domain.mesh: mesh domains are not supported by this version yet; "
                         "give domain.box (mesh domains work with dfn and blocks)");
  }
}

namespace {
/// The folder prepareOutput made ready (for the interruption marker).
std::optional<fs::path>& preparedFolder() {
  static std::optional<fs::path> folder;
  return folder;
}
}  // namespace

fs::path prepareOutput(const std::string& output) {
  std::error_code error;
  fs::create_directories(output, error);
  if (error || !fs::is_directory(output)) {
    throw std::runtime_error(output + ": cannot create the output folder (" + error.message() +
                             ")");
  }
  // A marker left by an earlier interrupted run into this folder no longer describes it.
  fs::remove(fs::path(output) / kInterruptedMarker, error);
  preparedFolder() = fs::path(output);
  return fs::path(output);
}

int reportInterruption(const Interrupted& interruption, const std::string& command) {
  const int signal = interruption.signal() > 0 ? interruption.signal() : SIGINT;
  const char* name = signal == SIGTERM ? "SIGTERM" : signal == SIGINT ? "SIGINT" : "a signal";
  std::fprintf(stderr, "rockmass %s: interrupted by %s during %s; stopped there.\n",
               command.c_str(), name, interruption.where().c_str());
  if (const std::optional<fs::path>& folder = preparedFolder()) {
    std::vector<std::string> complete;
    for (const fs::path& path : io::filesWritten()) {
      std::string file = path.lexically_relative(*folder).generic_string();
      if (file.empty() || file.rfind("..", 0) == 0) file = path.generic_string();
      if (std::find(complete.begin(), complete.end(), file) == complete.end()) {
        complete.push_back(file);
      }
    }
    std::sort(complete.begin(), complete.end());
    nlohmann::ordered_json marker;
    marker["interrupted"] = true;
    marker["signal"] = name;
    marker["command"] = command;
    marker["during"] = interruption.where();
    marker["complete"] = complete;
    marker["note"] =
        "the files in `complete` were written whole by this run before it stopped; the "
        "command's other outputs (and summary.json, unless listed) were not written";
    try {
      io::writeFileAtomically(*folder / kInterruptedMarker, marker.dump(2) + "\n");
      std::fprintf(stderr, "rockmass %s: %zu files were complete; see %s\n", command.c_str(),
                   complete.size(), (*folder / kInterruptedMarker).string().c_str());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "rockmass %s: %s\n", command.c_str(), e.what());
    }
  }
  return 128 + signal;
}

geometry::FractureNetwork generateNetwork(const io::Scene& scene, const std::string& scene_path) {
  try {
    return geometry::generateNetwork(scene.dfn, scene.seed, scene.generation_limits);
  } catch (const geometry::DiscBudgetExceeded& e) {
    const std::size_t set = static_cast<std::size_t>(e.set());
    if (set < scene.joint_set_keys.size()) {
      const io::JointSetKeys& keys = scene.joint_set_keys[set];
      throw io::InputError(
          io::locate(scene, e.bySize() ? keys.trace_length : keys.intensity, e.what()));
    }
    throw io::InputError(scene_path + ": " + e.what());
  } catch (const std::invalid_argument& e) {
    throw io::InputError(scene_path + ": " + e.what());
  }
}

void addCutterOption(CLI::App& command, std::string& cutter) {
  command
      .add_option("--cutter", cutter,
                  "exact (exact-kernel splitting, CGAL Nef referee) or fast (floating-point "
                  "convex splitting); overrides analysis.blocks.cutter")
      ->check(CLI::IsMember({"exact", "fast"}));
}

std::string shellQuote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::size_t allowedThreads() {
  return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
}

ScriptRun runScript(const std::string& python, const fs::path& script, const fs::path& folder,
                    const std::string& prefix, const std::vector<std::string>& arguments,
                    bool low_priority) {
  // The script may keep as many processes busy as the run may threads (--threads).
  std::string command = "ROCKMASS_THREADS=" + std::to_string(allowedThreads()) + " " +
                        (low_priority ? "nice -n 19 " : "") + shellQuote(python) + " " +
                        shellQuote(script.string()) + " " + shellQuote(folder.string());
  for (const std::string& argument : arguments) command += " " + shellQuote(argument);
  command += " 2>&1";
  ScriptRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return run;
  run.started = true;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) {
    std::string line(buffer);
    while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
    std::fprintf(stderr, "%s: %s\n", prefix.c_str(), line.c_str());
    run.lines.push_back(std::move(line));
  }
  run.succeeded = pclose(pipe) == 0;
  return run;
}

}  // namespace rockmass::app
