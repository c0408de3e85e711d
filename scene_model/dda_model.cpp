#include "scene_model/dda_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "dda3d/block_terms.h"
#include "dda3d/contact_detection.h"
#include "geometry/disc.h"
#include "geometry/point_in_polyhedron.h"
#include "io/atomic_file.h"
#include "io/input_error.h"
#include "scene_model/model_parts.h"

namespace rockmass::scene_model {

using namespace io;  // NOLINT: the scene's types

/// Most sub-contact points a model may have (analysis.dda.contact_point_spacing): 5e6 points
/// hold about 200 MB and are each a contact candidate every step.
constexpr std::size_t kMaxContactPoints = 5'000'000;
/// Cells of a structure's `auto` sub-contact grid across its smallest extent: on a 20 m
/// base loaded beyond its middle third, 16 put the overload factor within 0.6 % of the
/// cracked-base factor, 8 within 2.6 %, 4 within 2.2 % (bench/contact_points_bench).
constexpr double kAutoPointCells = 16.0;

namespace parts {

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

/// Area (m2) of face `f` of `piece` inside the rectangle of `face` (the domain box's face,
/// thickened by `tol` across its plane so that a face lying on it is kept).
double areaOnDomainFace(const blocks::Piece& piece, int f, const DomainFace& face,
                        const geometry::Box& domain, double tol) {
  std::vector<geometry::Vec3> polygon;
  for (int v : piece.shape.faces[static_cast<std::size_t>(f)]) {
    polygon.push_back(piece.shape.vertices[static_cast<std::size_t>(v)]);
  }
  geometry::Box rectangle = domain;
  const double plane = face.max_side ? domain.max[face.axis] : domain.min[face.axis];
  rectangle.min[face.axis] = plane - tol;
  rectangle.max[face.axis] = plane + tol;
  const std::vector<geometry::Vec3> inside = geometry::clipPolygonToBox(polygon, rectangle);
  return inside.size() < 3 ? 0.0 : geometry::polygonArea(inside);
}

/// True when face `f` of `piece` came from or lies on the plane of `face` AND overlaps the
/// face's rectangle with positive area (more than tol^2): a structure standing on the
/// domain's top whose side is in the plane of a side face, but above the box, is not on it.
bool faceOnDomainFace(const blocks::Piece& piece, std::size_t f, const DomainFace& face,
                      const geometry::Box& domain, double tol, bool box_domain) {
  const blocks::FaceSource source =
      f < piece.face_sources.size() ? piece.face_sources[f] : blocks::FaceSource{};
  const bool from_face =
      box_domain && source.kind == blocks::FaceKind::Boundary && source.id == face.box_id;
  if (!from_face && !liesOnDomainFace(piece, static_cast<int>(f), face, domain, tol)) {
    return false;
  }
  return areaOnDomainFace(piece, static_cast<int>(f), face, domain, tol) > tol * tol;
}

/// True when some piece face of `block` is on `face` (faceOnDomainFace).
bool touches(const blocks::Block& block, const DomainFace& face, const geometry::Box& domain,
             double tol, bool box_domain) {
  for (const blocks::Piece& piece : block.pieces) {
    for (std::size_t f = 0; f < piece.shape.faces.size(); ++f) {
      if (faceOnDomainFace(piece, f, face, domain, tol, box_domain)) return true;
    }
  }
  return false;
}

/// The vertices of the faces of `block` on `face` (faceOnDomainFace), each once, in order of
/// appearance: where a roller holds the block.
std::vector<geometry::Vec3> pointsOnDomainFace(const blocks::Block& block, const DomainFace& face,
                                               const geometry::Box& domain, double tol,
                                               bool box_domain) {
  std::vector<geometry::Vec3> points;
  for (const blocks::Piece& piece : block.pieces) {
    for (std::size_t f = 0; f < piece.shape.faces.size(); ++f) {
      if (!faceOnDomainFace(piece, f, face, domain, tol, box_domain)) continue;
      for (int v : piece.shape.faces[f]) {
        const geometry::Vec3& p = piece.shape.vertices[static_cast<std::size_t>(v)];
        const bool seen = std::any_of(points.begin(), points.end(), [&](const geometry::Vec3& q) {
          return (q - p).norm() <= tol;
        });
        if (!seen) points.push_back(p);
      }
    }
  }
  return points;
}

/// "(x, y, z)" for messages.
std::string pointText(const geometry::Vec3& p) {
  // Appended: GCC 12 misreads a chain of + here (a false -Wrestrict).
  std::string out = "(";
  out.append(formatDouble(p.x())).append(", ").append(formatDouble(p.y())).append(", ");
  return out.append(formatDouble(p.z())).append(")");
}

/// Mean of the face's vertices (m).
geometry::Vec3 faceCenter(const geometry::Polyhedron& shape, int f) {
  geometry::Vec3 sum = geometry::Vec3::Zero();
  const std::vector<int>& face = shape.faces[static_cast<std::size_t>(f)];
  for (int v : face) sum += shape.vertices[static_cast<std::size_t>(v)];
  return sum / static_cast<double>(face.size());
}

/// True when face `f` of piece `p` is glued to another piece of the same block (its centre
/// lies on that piece): an internal face, never wet.
bool internalFace(const blocks::Block& block, std::size_t p, int f, double tol) {
  const geometry::Vec3 center = faceCenter(block.pieces[p].shape, f);
  for (std::size_t other = 0; other < block.pieces.size(); ++other) {
    if (other != p && geometry::convexPlaneDistance(block.pieces[other].shape, center) <= tol) {
      return true;
    }
  }
  return false;
}

/// True when the point's plan position lies in the region (open bounds ignored).
bool inRegion(const Region& region, const geometry::Vec3& p) {
  return (!region.x_min || p.x() >= *region.x_min) && (!region.x_max || p.x() <= *region.x_max) &&
         (!region.y_min || p.y() >= *region.y_min) && (!region.y_max || p.y() <= *region.y_max);
}

/// Index of the structure named `name` (the scene reader has checked that it exists).
int structureIndex(const Scene& scene, const std::string& name) {
  for (std::size_t s = 0; s < scene.structures.size(); ++s) {
    if (scene.structures[s].name == name) return static_cast<int>(s);
  }
  throw std::invalid_argument("unknown structure '" + name + "'");
}

/// Index of the structure a block belongs to (its outer faces are labelled Structure; the
/// cutters never glue a structure to rock), or -1 for a rock block.
int structureOf(const blocks::Block& block) {
  for (const blocks::Piece& piece : block.pieces) {
    for (const blocks::FaceSource& source : piece.face_sources) {
      if (source.kind == blocks::FaceKind::Structure) return source.id;
    }
  }
  return -1;
}

/// True when `point` lies inside a piece of a block of `owner` (structure index, or -1 for
/// rock) by more than `depth` m.
bool insideOwnedBy(const blocks::BlockModel& blocks, const Members& members, int owner,
                   const geometry::Vec3& point, double depth) {
  for (int b : members[static_cast<std::size_t>(owner + 1)]) {
    const blocks::Block& block = blocks.blocks[static_cast<std::size_t>(b)];
    if (block.bounds.distance(point) > 0.0) continue;
    // On a face between two pieces of the block (a cutter's region plane runs through the
    // rock at the domain's halves and quarters) the point is inside the block, though on the
    // boundary of each piece.
    int touching = 0;
    for (const blocks::Piece& piece : block.pieces) {
      const double distance = geometry::convexPlaneDistance(piece.shape, point);
      if (distance < -depth) return true;
      touching += distance <= 1e-3 * depth;
    }
    if (touching >= 2) return true;
  }
  return false;
}

bool backsOnto(const blocks::BlockModel& blocks, const Members& members, int owner,
               const geometry::Polyhedron& shape, int f, double probe) {
  const geometry::Vec3 center = faceCenter(shape, f);
  const geometry::Vec3 out = probe * geometry::faceNormal(shape, f);
  if (insideOwnedBy(blocks, members, owner, center + out, 0.5 * probe)) return true;
  for (int v : shape.faces[static_cast<std::size_t>(f)]) {
    const geometry::Vec3 half = 0.5 * (center + shape.vertices[static_cast<std::size_t>(v)]);
    if (insideOwnedBy(blocks, members, owner, half + out, 0.5 * probe)) return true;
  }
  return false;
}

}  // namespace parts

namespace {

using namespace parts;  // NOLINT: the adapters' shared parts

/// Sub-contact points: a structure's blocks get the structure's spacing (`auto`: a sixteenth
/// of its smallest extent where its joint has cohesion or tension, so that a base whose heel
/// lifts keeps its cohesion on the compressed part only; docs/stability.md, "Contact
/// points"), the rock blocks the run's.
/// Refused before any is made when they would pass kMaxContactPoints (each is a material
/// point moved every step and a contact candidate), at the line of the spacing that adds most.
void setContactPointSpacings(const Scene& scene, const blocks::BlockModel& blocks,
                             const Members& members, dda3d::DdaModel& model) {
  const double run = scene.analysis.dda ? scene.analysis.dda->engine.contact_point_spacing : 0.0;
  struct Source {
    std::string key;
    int line = 0;
    double spacing = 0.0;
    std::size_t points = 0;
  };
  std::vector<Source> sources;
  sources.push_back({"analysis.dda.contact_point_spacing",
                     scene.analysis.dda ? scene.analysis.dda->contact_point_spacing_line : 0, run});
  // Counted only where there are points (a spacing of 0 gives none).
  const auto count = [&](const std::vector<int>& own, Source& source) {
    if (!(source.spacing > 0.0)) return;
    for (const int b : own) {
      for (const geometry::Polyhedron& piece : model.blocks[static_cast<std::size_t>(b)].pieces) {
        source.points += dda3d::facePointBound(piece, source.spacing);
      }
    }
  };
  count(members[0], sources[0]);
  for (std::size_t s = 0; s < scene.structures.size(); ++s) {
    const StructureSpec& spec = scene.structures[s];
    const std::vector<int>& own = members[s + 1];
    if (own.empty()) continue;
    geometry::Box box = blocks.blocks[static_cast<std::size_t>(own[0])].bounds;
    for (const int b : own) {
      const geometry::Box& bb = blocks.blocks[static_cast<std::size_t>(b)].bounds;
      box.min = box.min.cwiseMin(bb.min);
      box.max = box.max.cwiseMax(bb.max);
    }
    // `auto`: points where the structure's joint has cohesion or tension, whose force spreads
    // with the compressed area; a frictional joint's strength f N does not depend on how N
    // spreads over the face, and its corners carry it.
    const int j = spec.joint >= 0 ? spec.joint : scene.default_joint;
    const bool bonded =
        j >= 0 && (scene.joints[static_cast<std::size_t>(j)].cohesion > 0.0 ||
                   scene.joints[static_cast<std::size_t>(j)].tensile_strength > 0.0);
    const double spacing = spec.contact_point_spacing.value_or(
        bonded ? (box.max - box.min).minCoeff() / kAutoPointCells : 0.0);
    Source source{"structures." + spec.name + ".contact_point_spacing",
                  spec.contact_point_spacing_line, spacing};
    for (const int b : own)
      model.blocks[static_cast<std::size_t>(b)].contact_point_spacing = spacing;
    count(own, source);
    sources.push_back(source);
  }
  std::size_t total = 0;
  for (const Source& source : sources) total += source.points;
  if (total <= kMaxContactPoints) return;
  const Source& worst =
      *std::max_element(sources.begin(), sources.end(),
                        [](const Source& a, const Source& b) { return a.points < b.points; });
  throw InputError(locate(scene.file, worst.line, 0,
                          worst.key + ": " + formatDouble(worst.spacing) + " m gives up to " +
                              std::to_string(worst.points) +
                              " sub-contact points on the faces of the DDA's blocks (" +
                              std::to_string(total) + " in all), more than " +
                              std::to_string(kMaxContactPoints) + "; expected a larger spacing"));
}

/// The scene's bolts: each end in the block that contains it (exit 2 at the entry when an end
/// lies in no block, or both in one).
void addBolts(const Scene& scene, const blocks::BlockModel& blocks, dda3d::DdaModel& model) {
  for (const BoltSpec& bolt : scene.bolts) {
    const int a = findContainingBlock(blocks, bolt.head);
    const int b = findContainingBlock(blocks, bolt.end);
    const auto refuse = [&](const std::string& what) {
      throw InputError(locate(scene, bolt.key, "bolt " + bolt.name + ": " + what));
    };
    if (a < 0) refuse("its head " + pointText(bolt.head) + " lies in no block");
    if (b < 0) refuse("its end " + pointText(bolt.end) + " lies in no block");
    if (a == b) {
      refuse("its head and end lie in one block (" +
             std::to_string(blocks.blocks[static_cast<std::size_t>(a)].id) +
             "); a bolt must cross a joint to hold anything");
    }
    dda3d::DdaBolt out;
    out.block_a = a;
    out.point_a = bolt.head;
    out.block_b = b;
    out.point_b = bolt.end;
    out.stiffness = bolt.stiffness;
    out.pretension = bolt.pretension;
    if (bolt.yield_force) out.yield_force = *bolt.yield_force;
    if (bolt.rupture_force) out.rupture_force = *bolt.rupture_force;
    model.bolts.push_back(out);
  }
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

FaceJoints::FaceJoints(const Scene& scene, const geometry::FractureNetwork& network) {
  for (const geometry::Disc& disc : network.discs) {
    if (disc.id < 1) continue;
    const std::size_t id = static_cast<std::size_t>(disc.id);
    if (disc_joints_.size() <= id) disc_joints_.resize(id + 1, -1);
    disc_joints_[id] = std::max(-1, disc.joint);
  }
  for (const StructureSpec& s : scene.structures) structure_joints_.push_back(s.joint);
}

int FaceJoints::of(const blocks::FaceSource& source) const {
  const auto lookup = [&](const std::vector<int>& joints, const char* what) {
    if (source.id < 0 || static_cast<std::size_t>(source.id) >= joints.size()) {
      throw std::invalid_argument(std::string("a piece face comes from ") + what + " " +
                                  std::to_string(source.id) + ", which does not exist");
    }
    return joints[static_cast<std::size_t>(source.id)];
  };
  switch (source.kind) {
    case blocks::FaceKind::Disc:
      return lookup(disc_joints_, "disc");
    case blocks::FaceKind::Structure:
      return lookup(structure_joints_, "structure");
    case blocks::FaceKind::Boundary:
    case blocks::FaceKind::Fictitious:
      break;
  }
  return -1;
}

std::vector<std::vector<int>> FaceJoints::of(const blocks::Block& block) const {
  std::vector<std::vector<int>> out;
  for (const blocks::Piece& piece : block.pieces) {
    std::vector<int>& row = out.emplace_back(piece.shape.faces.size(), -1);
    for (std::size_t f = 0; f < row.size() && f < piece.face_sources.size(); ++f) {
      row[f] = of(piece.face_sources[f]);
    }
  }
  return out;
}

dda3d::DdaModel buildDdaModel(const Scene& scene, const blocks::BlockModel& blocks,
                              const geometry::FractureNetwork& network) {
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
    model.joints.push_back({j.friction, j.cohesion, j.tensile_strength,
                            j.brittle ? dda3d::JointModel::Brittle : dda3d::JointModel::Plastic});
  }
  model.default_joint = scene.default_joint;
  const FaceJoints face_joints(scene, network);
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
    out.face_joints = face_joints.of(block);
    out.structure = structureOf(block);
    model.blocks.push_back(std::move(out));
  }

  // Rollers: a block on a roller face (and not held by a fixed one) is held normal to the
  // face at every vertex of its faces on it, free to slide in the face's plane.
  const double tol = tolerance(blocks);
  for (const std::string& name : scene.roller_faces) {
    const DomainFace face = domainFace(name);
    geometry::Vec3 normal = geometry::Vec3::Zero();
    normal[face.axis] = face.max_side ? 1.0 : -1.0;
    for (std::size_t b = 0; b < blocks.blocks.size(); ++b) {
      if (model.blocks[b].fixed) continue;
      for (const geometry::Vec3& p : pointsOnDomainFace(blocks.blocks[b], face, blocks.domain, tol,
                                                        scene.domain_mesh.empty())) {
        model.fixed_points.push_back({static_cast<int>(b), p, normal});
      }
    }
  }

  for (const Monitor& monitor : scene.monitors) {
    const int block = findContainingBlock(blocks, monitor.point);
    if (block < 0) {
      throw InputError(locate(scene.file, monitor.line, 0,
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
  std::vector<int> owner;
  Members members(scene.structures.size() + 1);
  for (std::size_t b = 0; b < blocks.blocks.size(); ++b) {
    owner.push_back(structureOf(blocks.blocks[b]));
    members[static_cast<std::size_t>(owner.back() + 1)].push_back(static_cast<int>(b));
  }
  addWater(scene, blocks, owner, members, model);
  addBolts(scene, blocks, model);
  if (const std::optional<Seismic>& seismic = scene.loads.seismic) {
    const double g = model.gravity.norm();
    model.seismic =
        g * (seismic->k_h * seismic->direction + seismic->k_v * geometry::Vec3::UnitZ());
  }
  setContactPointSpacings(scene, blocks, members, model);
  return model;
}

}  // namespace rockmass::scene_model
