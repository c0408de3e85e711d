// The DDA on the model users run: the Xiangjiaba foundation region (examples/xiangjiaba/
// scene.yaml, analysis.dda: the dam and the rock of x 40..200, z -30..0, 1 081 glued blocks of
// 25 608 convex pieces), static and rigid as the scene runs it.
//
// The model is built once from the scene (DFN, cut, glue: scene_model, as `rockmass dda`
// builds it) and saved (dda3d::saveModel) to --region_model=PATH (default
// xiangjiaba_region.model beside this program); later runs read it instead of cutting again.
// Delete the file after changing the scene or the cutter.
//
// BM_Region/<variant>: --region_steps=N steps (default 6) timed after --region_warmup=W
// untimed ones (default 2: the first steps close the contacts), each variant a fresh
// Simulation of the same model:
//   as_run        the engine as every run uses it (contacts kept between searches while the
//                 blocks move less than DdaSettings::detection.search_margin, kept pairs,
//                 every piece face searched)
//   hull_corners  as_run with a face on a face carried by the corners of its hull, the pieces'
//                 vertices inside it and along its edges dropped (detection.hull_corners on)
//   every_step    contacts searched every step (detection.search_margin 0)
//   fresh_pairs   every_step with the broad phase every step (detection.keep_pairs off)
//   surface_only  every_step with only the blocks' surface faces (detection.surface_only on)
//   deformable    as_run with 12-unknown blocks (--region_deformable=1 only)
// Counters: block-steps per second (all blocks of the model, over the steps' wall time),
// contacts, open-close iterations per step, how many times the broad phase ran and how many
// steps searched their contacts in all 8 steps, seconds per step of each phase
// (Simulation::timings) and of what lies between them ("other"). After the
// run, a table of each phase's time per step and its ratio to as_run's.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/bench_support.h"
#include "blocks/block_merge.h"
#include "dda3d/model_file.h"
#include "dda3d/simulation.h"
#include "geometry/fracture_network.h"
#include "io/scene.h"
#include "scene_model/dda_model.h"
#include "scene_model/scene_blocks.h"
#include "scene_model/stability_settings.h"

namespace {

using namespace rockmass;

struct Region {
  dda3d::DdaModel model;
  dda3d::DdaSettings settings;
};

int warm_up = 2;
int timed_steps = 6;

/// The model of the scene's DDA region: read from `model_path` when it exists and is of this
/// version of the format, else built from the scene and saved there. The settings are always the
/// scene's (cheap to read).
Region loadRegion(const std::filesystem::path& scene_path,
                  const std::filesystem::path& model_path) {
  const io::Scene scene = io::loadScene(scene_path);
  Region region;
  region.settings = scene_model::ddaSettings(*scene.analysis.dda);
  const auto start = std::chrono::steady_clock::now();
  const auto seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  if (std::filesystem::exists(model_path)) {
    try {
      region.model = dda3d::loadModel(model_path);
      std::fprintf(stderr, "region model read from %s in %.2f s\n", model_path.string().c_str(),
                   seconds());
      return region;
    } catch (const std::runtime_error& e) {
      // A model saved by another version of the format (or damaged): built afresh below.
      std::fprintf(stderr, "%s: rebuilding it\n", e.what());
    }
  }
  std::fprintf(stderr, "building the region model from %s (DFN, cut, glue)...\n",
               scene_path.string().c_str());
  const geometry::FractureNetwork network =
      geometry::generateNetwork(scene.dfn, scene.seed, scene.generation_limits);
  const io::Scene dda_scene = scene_model::ddaScene(scene);
  const scene_model::SceneBlocks cut =
      scene_model::cutSceneBlocks(dda_scene, network, "fast", scene_path.string());
  std::optional<blocks::MergeReport> glued;
  const blocks::BlockModel dda_blocks = scene_model::ddaBlocks(dda_scene, cut.model, glued);
  region.model = scene_model::buildDdaModel(dda_scene, dda_blocks, network);
  dda3d::saveModel(region.model, model_path);
  std::fprintf(stderr, "built in %.2f s, saved to %s\n", seconds(), model_path.string().c_str());
  return region;
}

const Region* region = nullptr;

void regionRun(benchmark::State& state, dda3d::DdaSettings settings) {
  for (auto _ : state) {
    state.PauseTiming();
    dda3d::Simulation sim(region->model, settings);
    for (int k = 0; k < warm_up; ++k) sim.step();
    const dda3d::StepProfile before = sim.timings();
    int iterations = 0;
    state.ResumeTiming();
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < timed_steps; ++k) iterations += sim.step().iterations;
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.PauseTiming();
    dda3d::StepProfile spent = sim.timings();
    double total = 0.0;
    for (int p = 0; p < dda3d::kStepPhases; ++p) {
      spent.seconds[p] -= before.seconds[p];
      total += spent.seconds[p];
      state.counters[dda3d::StepProfile::name(static_cast<dda3d::StepPhase>(p))] =
          spent.seconds[p] / timed_steps;
    }
    // The step's wall time: the phases plus what lies between them (the copy of the contacts
    // a redone step starts from, the step's checks).
    state.counters["other"] = (wall - total) / timed_steps;
    state.counters["block_steps_per_s"] =
        static_cast<double>(region->model.blocks.size()) * timed_steps / wall;
    state.counters["s_per_step"] = wall / timed_steps;
    state.counters["contacts"] = static_cast<double>(sim.contacts().size());
    state.counters["iterations_per_step"] = static_cast<double>(iterations) / timed_steps;
    state.counters["broad_phase_runs"] = sim.broadPhaseRuns();
    state.counters["contact_searches"] = sim.contactSearches();
    state.counters["partial_searches"] = sim.partialSearches();
    state.ResumeTiming();
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path here = std::filesystem::absolute(argv[0]).parent_path();
  const std::string model_path = rockmass::bench::takeFlag(
      argc, argv, "region_model", (here / "xiangjiaba_region.model").string());
  const std::string scene_path = rockmass::bench::takeFlag(
      argc, argv, "region_scene", ROCKMASS_SOURCE_DIR "/examples/xiangjiaba/scene.yaml");
  warm_up = std::stoi(rockmass::bench::takeFlag(argc, argv, "region_warmup", "2"));
  timed_steps = std::stoi(rockmass::bench::takeFlag(argc, argv, "region_steps", "6"));
  const bool deformable = rockmass::bench::takeFlag(argc, argv, "region_deformable", "0") == "1";
  const Region loaded = loadRegion(scene_path, model_path);
  region = &loaded;

  std::vector<std::pair<std::string, dda3d::DdaSettings>> variants;
  dda3d::DdaSettings s = loaded.settings;
  variants.emplace_back("as_run", s);
  s.detection.hull_corners = true;
  variants.emplace_back("hull_corners", s);
  s.detection.hull_corners = false;
  s.detection.search_margin = 0.0;
  variants.emplace_back("every_step", s);
  s.detection.keep_pairs = false;
  variants.emplace_back("fresh_pairs", s);
  s.detection.keep_pairs = true;
  s.detection.surface_only = true;
  variants.emplace_back("surface_only", s);
  if (deformable) {
    s = loaded.settings;
    s.kinematics = dda3d::Kinematics::Deformable;
    variants.emplace_back("deformable", s);
  }
  for (const auto& [name, settings] : variants) {
    benchmark::RegisterBenchmark(
        ("BM_Region/" + name).c_str(),
        [settings = settings](benchmark::State& state) { regionRun(state, settings); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->UseRealTime();
  }
  benchmark::Initialize(&argc, argv);
  rockmass::bench::RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();

  // Each phase's seconds per step and its ratio to as_run's (same run).
  const rockmass::bench::Record* base = reporter.find("BM_Region/as_run");
  if (base == nullptr) return 0;
  std::vector<std::string> rows;
  for (int p = 0; p < dda3d::kStepPhases; ++p) {
    rows.push_back(dda3d::StepProfile::name(static_cast<dda3d::StepPhase>(p)));
  }
  rows.push_back("other");
  rows.push_back("s_per_step");
  std::printf("\nseconds per step by phase (ratio to as_run), %d steps after %d:\n", timed_steps,
              warm_up);
  std::printf("%-22s", "phase");
  for (const auto& variant : variants) std::printf(" %22s", variant.first.c_str());
  std::printf("\n");
  for (const std::string& row : rows) {
    std::printf("%-22s", row.c_str());
    for (const auto& variant : variants) {
      const rockmass::bench::Record* r = reporter.find("BM_Region/" + variant.first);
      if (r == nullptr) {
        std::printf(" %22s", "-");
        continue;
      }
      const double value = r->counters.at(row);
      const double reference = base->counters.at(row);
      std::printf(" %12.4f (%5.2fx)", value, reference > 0.0 ? value / reference : 0.0);
    }
    std::printf("\n");
  }
  for (const char* counter : {"block_steps_per_s", "contacts", "iterations_per_step",
                              "broad_phase_runs", "contact_searches"}) {
    std::printf("%-22s", counter);
    for (const auto& variant : variants) {
      const rockmass::bench::Record* r = reporter.find("BM_Region/" + variant.first);
      std::printf(" %22.1f", r ? r->counters.at(counter) : 0.0);
    }
    std::printf("\n");
  }
  return 0;
}
