#include "io/scene_model.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "geometry/point_in_polyhedron.h"
#include "io/atomic_file.h"
#include "io/input_error.h"

namespace rockmass::io {
namespace {

/// A face of the domain box: the axis it is normal to, which end, and its box face id
/// (blocks::FaceKind::Boundary ids 0..5: x_min, x_max, y_min, y_max, z_min, z_max).
struct DomainFace {
  int axis = 0;
  bool max_side = false;
  int box_id = 0;
};

DomainFace domainFace(const std::string& name) {
  if (name == "west") return {0, false, 0};
  if (name == "east") return {0, true, 1};
  if (name == "south") return {1, false, 2};
  if (name == "north") return {1, true, 3};
  if (name == "bottom") return {2, false, 4};
  if (name == "top") return {2, true, 5};
  throw std::invalid_argument("unknown domain face '" + name + "'");
}

/// Absolute tolerance (m) for a domain.
double tolerance(const blocks::BlockModel& blocks) {
  return kSceneModelRelativeTolerance * blocks.domain.diagonal();
}

/// True when face `f` of `piece` lies in the plane of `face` and faces outward.
bool liesOnDomainFace(const blocks::Piece& piece, int f, const DomainFace& face,
                      const geometry::Box& domain, double tol) {
  const geometry::Vec3 n = geometry::faceNormal(piece.shape, f);
  const double outward = face.max_side ? n[face.axis] : -n[face.axis];
  if (outward < 0.5) return false;
  const double plane = face.max_side ? domain.max[face.axis] : domain.min[face.axis];
  for (int v : piece.shape.faces[static_cast<std::size_t>(f)]) {
    if (std::abs(piece.shape.vertices[static_cast<std::size_t>(v)][face.axis] - plane) > tol) {
      return false;
    }
  }
  return true;
}

/// True when some piece face of `block` came from or lies on `face`.
bool touches(const blocks::Block& block, const DomainFace& face, const geometry::Box& domain,
             double tol, bool box_domain) {
  for (const blocks::Piece& piece : block.pieces) {
    for (std::size_t f = 0; f < piece.shape.faces.size(); ++f) {
      const blocks::FaceSource source =
          f < piece.face_sources.size() ? piece.face_sources[f] : blocks::FaceSource{};
      if (box_domain && source.kind == blocks::FaceKind::Boundary && source.id == face.box_id) {
        return true;
      }
      if (liesOnDomainFace(piece, static_cast<int>(f), face, domain, tol)) return true;
    }
  }
  return false;
}

/// "(x, y, z)" for messages.
std::string pointText(const geometry::Vec3& p) {
  return "(" + formatDouble(p.x()) + ", " + formatDouble(p.y()) + ", " + formatDouble(p.z()) + ")";
}

/// The joint index of every material pair (see buildDdaModel).
std::vector<std::vector<int>> jointTable(const Scene& scene) {
  const std::size_t count = scene.materials.size();
  std::vector<std::vector<int>> table(count, std::vector<int>(count, scene.default_joint));
  const auto set = [&](int a, int b, int joint) {
    if (a < 0 || b < 0 || joint < 0) return;
    table[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] = joint;
    table[static_cast<std::size_t>(b)][static_cast<std::size_t>(a)] = joint;
  };
  for (const geometry::FaultSpec& fault : scene.dfn.faults) {
    set(fault.material, scene.rock_material, fault.joint);
  }
  for (const geometry::InterlayerSpec& layer : scene.dfn.interlayers) {
    set(layer.material, scene.rock_material, layer.joint);
  }
  std::vector<bool> structure_material(count, false);
  for (const StructureSpec& s : scene.structures) {
    structure_material[static_cast<std::size_t>(s.material)] = true;
  }
  for (const StructureSpec& s : scene.structures) {
    for (std::size_t m = 0; m < count; ++m) {
      if (!structure_material[m]) set(s.material, static_cast<int>(m), s.joint);
    }
  }
  return table;
}

}  // namespace

int findContainingBlock(const blocks::BlockModel& blocks, const geometry::Vec3& point) {
  const double tol = tolerance(blocks);
  int best = -1;
  double deepest = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < blocks.blocks.size(); ++b) {
    const blocks::Block& block = blocks.blocks[b];
    if (block.bounds.distance(point) > tol) continue;
    for (const blocks::Piece& piece : block.pieces) {
      const double distance = geometry::convexPlaneDistance(piece.shape, point);
      if (distance <= tol && distance < deepest) {
        deepest = distance;
        best = static_cast<int>(b);
      }
    }
  }
  return best;
}

std::vector<bool> blocksOnDomainFaces(const blocks::BlockModel& blocks,
                                      const std::vector<std::string>& faces, bool box_domain) {
  const double tol = tolerance(blocks);
  std::vector<bool> held(blocks.blocks.size(), false);
  for (const std::string& name : faces) {
    const DomainFace face = domainFace(name);
    for (std::size_t b = 0; b < blocks.blocks.size(); ++b) {
      if (!held[b]) held[b] = touches(blocks.blocks[b], face, blocks.domain, tol, box_domain);
    }
  }
  return held;
}

dda3d::DdaModel buildDdaModel(const Scene& scene, const blocks::BlockModel& blocks) {
  if (!scene.loads.water.empty()) {
    throw InputError(locate(scene.file, 0, 0,
                            "loads.water: water pressure is not applied by the DDA of this "
                            "version yet; remove the entry or run without `analysis.dda`"));
  }
  if (scene.default_joint < 0) {
    throw InputError(locate(scene.file, 0, 0,
                            "analysis.dda needs the strength of the contacts between blocks: "
                            "give `joints` and `default_joint`"));
  }
  dda3d::DdaModel model;
  for (const Material& m : scene.materials) {
    model.materials.push_back({m.density, m.young, m.poisson});
  }
  for (const Joint& j : scene.joints) {
    model.joints.push_back({j.friction, j.cohesion, j.tensile_strength});
  }
  model.default_joint = scene.default_joint;
  model.joint_table = jointTable(scene);
  model.gravity = scene.loads.gravity.value_or(geometry::Vec3::Zero());

  const std::vector<bool> held =
      blocksOnDomainFaces(blocks, scene.fixed_faces, scene.domain_mesh.empty());
  for (std::size_t b = 0; b < blocks.blocks.size(); ++b) {
    const blocks::Block& block = blocks.blocks[b];
    if (block.material < 0 || block.material >= static_cast<int>(model.materials.size())) {
      throw InputError(locate(scene.file, 0, 0,
                              "block " + std::to_string(block.id) +
                                  " has no material: give `rock_material` (the material of "
                                  "the rock outside every slab)"));
    }
    dda3d::DdaBlock out;
    out.material = block.material;
    out.fixed = held[b];
    for (const blocks::Piece& piece : block.pieces) out.pieces.push_back(piece.shape);
    model.blocks.push_back(std::move(out));
  }

  for (const Monitor& monitor : scene.monitors) {
    const int block = findContainingBlock(blocks, monitor.point);
    if (block < 0) {
      throw InputError(locate(scene.file, 0, 0,
                              "monitors: " + monitor.name + " at " + pointText(monitor.point) +
                                  " lies in no block; a monitor must be inside the rock or a "
                                  "structure"));
    }
    model.monitors.push_back({monitor.name, monitor.point, block});
  }
  for (std::size_t i = 0; i < scene.loads.point_loads.size(); ++i) {
    const PointLoad& load = scene.loads.point_loads[i];
    const int block = findContainingBlock(blocks, load.point);
    if (block < 0) {
      throw InputError(locate(scene.file, 0, 0,
                              "loads.point_loads[" + std::to_string(i) + "] at " +
                                  pointText(load.point) +
                                  " lies in no block; a point load must act on the rock or a "
                                  "structure"));
    }
    model.point_loads.push_back({block, load.point, load.force});
  }
  return model;
}

}  // namespace rockmass::io
