// rockmass ensemble: many realizations of a scene (the paper's analogue simulation), each with
// its own seed and sample of the scene's uncertain inputs, each run as `rockmass run` runs a
// scene into OUT/r<i>/, then the aggregate (ensemble.json and CSVs). Realizations are spread
// over local processes (--jobs) or MPI ranks with dynamic load balancing; a realization whose
// marker says it is complete is not run again (docs/ensemble.md).
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>
#include <nlohmann/json.hpp>

#ifdef ROCKMASS_WITH_MPI
#include <mpi.h>
#endif

#include "app/command.h"
#include "app/run.h"
#include "ensemble/aggregate.h"
#include "ensemble/sampling.h"
#include "io/atomic_file.h"
#include "io/input_error.h"

namespace rockmass::app {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

struct EnsembleOptions {
  RunOptions run;                   ///< what every realization runs (output: OUT/r<i>)
  int realizations = 0;             ///< --realizations N
  std::optional<int> only;          ///< --only I: realization I alone
  int jobs = 1;                     ///< --jobs J: local processes
  bool no_figures = false;          ///< skip the ensemble's figures
  std::vector<std::string> stages;  ///< --stages: the analyses kept (empty: the scene's)
};

/// The scene's analyses reduced to `stages` (the DFN always runs; a stage the scene does not
/// name is an error: nothing would compute it).
void keepStages(io::Scene& scene, const std::vector<std::string>& stages, const std::string& file) {
  if (stages.empty()) return;
  io::Analysis& a = scene.analysis;
  const auto keep = [&](const char* name, bool present) {
    const bool wanted = std::find(stages.begin(), stages.end(), name) != stages.end();
    if (wanted && !present) {
      throw io::InputError("--stages " + std::string(name) + ": " + file + " has no analysis." +
                           name + " section");
    }
    return wanted;
  };
  const bool blocks = keep("blocks", a.blocks.has_value());
  const bool rqd = keep("rqd", a.rqd.has_value());
  const bool overload = keep("overload", a.overload.has_value());
  const bool strength = keep("strength_reduction", a.strength_reduction.has_value());
  // The stability analyses run on analysis.dda's model: it stays with either of them.
  const bool dda = keep("dda", a.dda.has_value()) || overload || strength;
  if (!blocks) a.blocks.reset();
  if (!rqd) a.rqd.reset();
  if (!dda) a.dda.reset();
  if (!overload) a.overload.reset();
  if (!strength) a.strength_reduction.reset();
}

/// Who runs realizations on this thread ("rank 1"), named in the progress lines; empty on a
/// single process.
thread_local std::string worker_label;

/// What a realization is: its index, seed and sampled inputs (its marker without the status).
Json identityOf(const io::Scene& base, int index) {
  Json j;
  j["index"] = index;
  j["seed"] = ensemble::realizationSeed(base.seed, index);
  Json inputs = Json::array();
  if (base.uncertainty) {
    const std::vector<double> values = ensemble::sampleInputs(*base.uncertainty, base.seed, index);
    for (std::size_t k = 0; k < values.size(); ++k) {
      inputs.push_back({{"key", base.uncertainty->inputs[k].key}, {"value", values[k]}});
    }
  }
  j["inputs"] = inputs;
  return j;
}

/// The scene of realization `index`: the scene file with the realization's inputs and seed,
/// the command line's overrides applied as to the base scene.
io::Scene realizationScene(const EnsembleOptions& o, const io::Scene& base, int index) {
  const std::uint64_t seed = ensemble::realizationSeed(base.seed, index);
  CommonOptions common = o.run.common;
  common.seed.reset();
  io::Scene scene;
  if (base.uncertainty) {
    scene = io::parseSampledScene(
        o.run.common.scene, ensemble::sampleInputs(*base.uncertainty, base.seed, index), seed);
    applyCommonOptions(scene, common);
  } else {
    scene = base;
    scene.seed = seed;
  }
  keepStages(scene, o.stages, o.run.common.scene);
  return scene;
}

/// True when OUT/r<i> holds the realization complete (or failed: run and recorded); an
/// InputError when it holds another scene's realization.
bool isDone(const fs::path& folder, const Json& identity) {
  std::ifstream in(folder / ensemble::kRealizationMarker);
  if (!in) return false;
  const Json marker = Json::parse(in, nullptr, false);
  if (marker.is_discarded()) return false;
  Json same = marker;
  same.erase("status");
  same.erase("error");
  if (same != identity) {
    throw io::InputError(
        folder.string() + "/" + ensemble::kRealizationMarker + ": realization " +
        std::to_string(identity["index"].get<int>()) +
        " was made from another scene, seed or sample; give a new output folder (-o) or "
        "remove this one");
  }
  return true;
}

/// Runs realization `index` into OUT/r<index> unless it is done; records it in its marker.
void runRealization(const EnsembleOptions& o, const io::Scene& base, int index) {
  const fs::path out = o.run.common.output;
  const fs::path folder = ensemble::realizationFolder(out, index);
  const Json identity = identityOf(base, index);
  if (isDone(folder, identity)) {
    std::fprintf(stderr, "ensemble: realization %d already complete in %s\n", index,
                 folder.string().c_str());
    return;
  }
  std::error_code error;
  fs::remove_all(folder, error);  // a half-written realization starts again
  std::fprintf(stderr, "ensemble: %srealization %d of %d (seed %llu)\n",
               worker_label.empty() ? "" : (worker_label + ": ").c_str(), index, o.realizations,
               static_cast<unsigned long long>(identity["seed"].get<std::uint64_t>()));
  RunOptions run = o.run;
  run.common.output = folder.string();
  run.no_figures = true;
  Json marker = identity;
  try {
    runScene(run, realizationScene(o, base, index));
    marker["status"] = "complete";
  } catch (const Interrupted&) {
    throw;
  } catch (const io::InputError&) {
    throw;
  } catch (const std::exception& e) {
    // A realization that cannot be computed (a DDA that cannot progress) is recorded, not run
    // again: the aggregate counts it as failed.
    std::fprintf(stderr, "ensemble: realization %d failed: %s\n", index, e.what());
    marker["status"] = "failed";
    marker["error"] = e.what();
  }
  io::writeFileAtomically(folder / ensemble::kRealizationMarker, marker.dump(2) + "\n");
}

/// Every realization of the list on this process, one after the other.
void runSerial(const EnsembleOptions& o, const io::Scene& base, const std::vector<int>& list) {
  for (int index : list) runRealization(o, base, index);
}

/// The list on `jobs` local processes (fork), each taking the next realization as it finishes
/// one: a slow realization holds one process, not a share of the list.
void runForked(const EnsembleOptions& o, const io::Scene& base, const std::vector<int>& list) {
  const int cores = std::max(1, tbb::info::default_concurrency());
  const int threads = o.run.common.threads > 0 ? o.run.common.threads : std::max(1, cores / o.jobs);
  std::map<pid_t, int> running;
  std::size_t next = 0;
  int failures = 0;
  std::fflush(nullptr);
  while (next < list.size() || !running.empty()) {
    while (next < list.size() && static_cast<int>(running.size()) < o.jobs &&
           !interruptRequested()) {
      const int index = list[next++];
      const pid_t pid = fork();
      if (pid < 0) throw std::runtime_error("ensemble: cannot start a process (fork failed)");
      if (pid == 0) {
        int code = 0;
        try {
          tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(threads));
          runRealization(o, base, index);
        } catch (const Interrupted&) {
          code = 130;
        } catch (const std::exception& e) {
          std::fprintf(stderr, "error: realization %d: %s\n", index, e.what());
          code = 1;
        }
        std::fflush(nullptr);
        _exit(code);
      }
      running[pid] = index;
    }
    int status = 0;
    const pid_t done = waitpid(-1, &status, 0);
    if (done < 0) {
      if (errno == EINTR) continue;
      break;
    }
    const auto found = running.find(done);
    if (found == running.end()) continue;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      ++failures;
      std::fprintf(stderr, "ensemble: the process of realization %d ended with %s %d\n",
                   found->second, WIFEXITED(status) ? "code" : "signal",
                   WIFEXITED(status) ? WEXITSTATUS(status) : WTERMSIG(status));
    }
    running.erase(found);
  }
  throwIfInterrupted("the ensemble");
  if (failures > 0) {
    throw std::runtime_error(std::to_string(failures) +
                             " realization processes did not end normally; rerun the same "
                             "command to run what is missing");
  }
}

#ifdef ROCKMASS_WITH_MPI
/// True when the process was started by an MPI launcher (mpirun, srun).
bool underMpiLauncher() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"}) {
    if (std::getenv(name)) return true;
  }
  return false;
}

constexpr int kRequestTag = 1;
constexpr int kAssignTag = 2;

/// The list over the ranks: rank 0 hands out the next realization to whichever rank asks
/// (dynamic load balancing) and runs realizations itself on a second thread; every rank
/// writes its realizations' folders. Returns true on rank 0.
bool runMpi(const EnsembleOptions& o, const io::Scene& base, const std::vector<int>& list, int rank,
            int size) {
  if (rank == 0) {
    std::atomic<std::size_t> next{0};
    std::exception_ptr local_error;
    std::atomic<bool> local_failed{false};
    std::thread local([&] {
      worker_label = "rank 0";
      try {
        for (std::size_t k; (k = next++) < list.size();) runRealization(o, base, list[k]);
      } catch (...) {
        local_error = std::current_exception();
        local_failed = true;
      }
    });
    int active = size - 1;
    while (active > 0) {
      int flag = 0;
      MPI_Status status;
      MPI_Iprobe(MPI_ANY_SOURCE, kRequestTag, MPI_COMM_WORLD, &flag, &status);
      if (!flag) {
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
        continue;
      }
      int request = 0;
      MPI_Recv(&request, 1, MPI_INT, status.MPI_SOURCE, kRequestTag, MPI_COMM_WORLD,
               MPI_STATUS_IGNORE);
      const std::size_t k = next++;
      const int reply = k < list.size() && !local_failed ? list[k] : -1;
      if (reply < 0) --active;
      MPI_Send(&reply, 1, MPI_INT, status.MPI_SOURCE, kAssignTag, MPI_COMM_WORLD);
    }
    local.join();
    if (local_error) std::rethrow_exception(local_error);
  } else {
    worker_label = "rank " + std::to_string(rank);
    for (;;) {
      const int request = 0;
      MPI_Send(&request, 1, MPI_INT, 0, kRequestTag, MPI_COMM_WORLD);
      int index = -1;
      MPI_Recv(&index, 1, MPI_INT, 0, kAssignTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      if (index < 0) break;
      try {
        runRealization(o, base, index);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "error: rank %d, realization %d: %s\n", rank, index, e.what());
        MPI_Abort(MPI_COMM_WORLD, 1);
      }
    }
  }
  MPI_Barrier(MPI_COMM_WORLD);
  return rank == 0;
}
#endif

/// The ensemble's figures (scripts/figures/ensemble_figures.py); a warning when they fail.
void drawFigures(const EnsembleOptions& o) {
  const fs::path script = fs::path(o.run.figure_scripts) / "ensemble_figures.py";
  if (!runScript(o.run.python, script, o.run.common.output, "ensemble").succeeded) {
    std::fprintf(stderr, "ensemble: warning: the figures were not drawn (%s %s)\n",
                 o.run.python.c_str(), script.string().c_str());
  }
}

int runEnsemble(EnsembleOptions& o) {
  const io::Scene base = loadScene(o.run.common);
  const int n = o.realizations;
  if (o.only && *o.only >= n) {
    throw io::InputError("--only " + std::to_string(*o.only) + ": expected a realization in [0, " +
                         std::to_string(n - 1) + "] (--realizations " + std::to_string(n) + ")");
  }
  if (base.uncertainty && base.uncertainty->latin_hypercube && n > base.uncertainty->size) {
    throw io::InputError(io::locate(base, base.uncertainty->size_location,
                                    "the Latin hypercube has " +
                                        std::to_string(base.uncertainty->size) +
                                        " strata per input; --realizations " + std::to_string(n) +
                                        " asks for more (raise size)"));
  }
  std::vector<int> list;
  if (o.only) {
    list.push_back(*o.only);
  } else {
    for (int i = 0; i < n; ++i) list.push_back(i);
  }
  // Every realization's scene is read before any work: a sampled value its key cannot take
  // stops the ensemble here, naming the realization, the key and its line.
  for (int index : list) {
    try {
      realizationScene(o, base, index);
    } catch (const io::InputError& e) {
      throw io::InputError("realization " + std::to_string(index) + ": " + e.what());
    }
  }
  const fs::path out = prepareOutput(o.run.common.output);
  bool aggregate = !o.only;
#ifdef ROCKMASS_WITH_MPI
  if (underMpiLauncher()) {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (size > 1) {
      if (rank == 0) {
        std::fprintf(stderr, "ensemble: %zu realizations over %d MPI ranks\n", list.size(), size);
      }
      aggregate = runMpi(o, base, list, rank, size) && aggregate;
    } else if (o.jobs > 1 && list.size() > 1) {
      runForked(o, base, list);
    } else {
      runSerial(o, base, list);
    }
    MPI_Finalize();
  } else
#endif
      if (o.jobs > 1 && list.size() > 1) {
    runForked(o, base, list);
  } else {
    runSerial(o, base, list);
  }
  if (!aggregate) return 0;
  const Json j = ensemble::writeAggregate(out, base, n);
  std::fprintf(stderr, "ensemble: %d of %d realizations complete (%zu failed); wrote %s\n",
               j["complete"].get<int>(), n, j["failed"].size(),
               (out / "ensemble.json").string().c_str());
  if (!o.no_figures) drawFigures(o);
  return j["failed"].empty() && j["missing"].empty() ? 0 : 1;
}

}  // namespace

Command addEnsembleCommand(CLI::App& app) {
  auto options = std::make_shared<EnsembleOptions>();
  CLI::App* cli = app.add_subcommand(
      "ensemble",
      "Run N realizations of the scene (each its own seed and sample of the scene's "
      "uncertainty inputs) into OUT/r<i>, then aggregate them (ensemble.json)");
  addCommonOptions(*cli, options->run.common);
  cli->add_option("--realizations", options->realizations, "Number of realizations N (>= 1)")
      ->required()
      ->check(CLI::Range(1, 1000000));
  cli->add_option("--only", options->only, "Run realization I (0-based) alone, no aggregate")
      ->check(CLI::NonNegativeNumber);
  cli->add_option("--jobs", options->jobs,
                  "Local processes running realizations at once (default 1; each uses the "
                  "cores / jobs threads unless --threads)")
      ->check(CLI::Range(1, 4096));
  cli->add_flag("--quick", options->run.quick, "Each realization as `run --quick`");
  cli->add_option("--stages", options->stages,
                  "Analyses each realization runs, of those the scene names (default all): "
                  "blocks, rqd, dda, overload, strength_reduction (dfn always)")
      ->delimiter(',')
      ->check(CLI::IsMember({"blocks", "rqd", "dda", "overload", "strength_reduction"}));
  addCutterOption(*cli, options->run.cutter);
  cli->add_option("--solver", options->run.solver, "DDA linear solver: auto, cholmod, eigen, pcg")
      ->check(CLI::IsMember({"auto", "cholmod", "eigen", "pcg"}));
  cli->add_flag("--no-figures", options->no_figures, "Do not draw the ensemble's figures");
  cli->add_option("--figure-scripts", options->run.figure_scripts,
                  "Folder of the figure scripts (default: the source tree's scripts/figures)");
  cli->add_option("--python", options->run.python,
                  "Python interpreter with matplotlib for the figures (default /usr/bin/python3)");
  return {cli, [options] { return runEnsemble(*options); }};
}

}  // namespace rockmass::app
