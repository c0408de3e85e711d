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
}

io::Scene loadScene(const CommonOptions& options, bool mesh_domain_supported) {
  io::Scene scene = io::loadScene(options.scene);
  if (options.seed) scene.seed = *options.seed;
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
    return geometry::generateNetwork(scene.dfn, scene.seed);
  } catch (const std::invalid_argument& e) {
    throw io::InputError(scene_path + ": " + e.what());
  }
}

}  // namespace rockmass::app
