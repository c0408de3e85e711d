#include "app/command.h"

#include <stdexcept>
#include <system_error>

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
      .add_option("--max-blocks", options.max_blocks,
                  "Largest estimated number of blocks a cut may make (an upper estimate, "
                  "checked before the cut)")
      ->default_val(io::Scene{}.max_blocks)
      ->check(CLI::PositiveNumber);
}

io::Scene loadScene(const CommonOptions& options, bool mesh_domain_supported) {
  io::Scene scene = io::loadScene(options.scene);
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
  return scene;
}

fs::path prepareOutput(const std::string& output) {
  std::error_code error;
  fs::create_directories(output, error);
  if (error || !fs::is_directory(output)) {
    throw std::runtime_error(output + ": cannot create the output folder (" + error.message() +
                             ")");
  }
  return fs::path(output);
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

}  // namespace rockmass::app
