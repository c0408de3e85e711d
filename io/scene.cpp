/// Scene file reader (format version 1): YAML -> validated Scene. Every check throws an
/// InputError "file:line:column: key.path: expected ..., got ..." located with yaml-cpp's marks.
#include "io/scene.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <tuple>
#include <utility>

#include "geometry/distribution.h"
#include "io/atomic_file.h"
#include "io/fab.h"
#include "io/input_error.h"
#include "io/scene_cursor.h"
#include "io/scene_sections.h"
#include "rqd/cell_grid.h"

namespace rockmass::io {
namespace {

using namespace scene_detail;

/// Standard gravity (m/s2) that turns a unit weight (N/m3) into a density (kg/m3).
constexpr double kStandardGravity = 9.81;

// ---------------------------------------------------------------------------------------------
// SceneReader: sections that refer to named materials, joints and structures
// ---------------------------------------------------------------------------------------------

/// Reads the sections in dependency order (materials and joints before what names them).
class SceneReader {
 public:
  /// Reads the whole scene from its root node.
  Scene read(const Cursor& root, const fs::path& file) {
    const Cursor m =
        root.map({"version",       "name",        "seed",          "domain",     "materials",
                  "rock_material", "joints",      "default_joint", "joint_sets", "fractures",
                  "faults",        "interlayers", "structures",    "loads",      "supports",
                  "monitors",      "bolts",       "bolt_patterns", "analysis",   "uncertainty"});
    scene_.file = file;
    const Cursor version = m.at("version");
    if (const int number = version.integer(); number != 1) {
      version.fail("expected format version 1, got " + std::to_string(number));
    }
    scene_.name = m.valueOr("name", std::string{}, &Cursor::string);
    scene_.seed = m.valueOr("seed", std::uint64_t{0}, &Cursor::unsignedInteger);
    readDomain(m.at("domain"));
    for (const auto& [name, entry] : m.valueOr("materials", Entries{}, &Cursor::entries)) {
      scene_.materials.push_back(readMaterial(entry, name));
    }
    scene_.rock_material =
        m.valueOr("rock_material", -1, [&](const Cursor& v) { return material(v); });
    for (const auto& [name, entry] : m.valueOr("joints", Entries{}, &Cursor::entries)) {
      scene_.joints.push_back(readJoint(entry, name));
    }
    named_joints_ = namesOf(scene_.joints);
    scene_.default_joint =
        m.valueOr("default_joint", -1, [&](const Cursor& v) { return joint(v); });
    forEachItem(m, "joint_sets",
                [&](const Cursor& c) { scene_.dfn.joint_sets.push_back(readJointSet(c)); });
    forEachItem(m, "fractures",
                [&](const Cursor& c) { scene_.dfn.polygon_sets.push_back(readFractures(c)); });
    forEachItem(m, "faults", [&](const Cursor& c) { scene_.dfn.faults.push_back(readFault(c)); });
    forEachItem(m, "interlayers",
                [&](const Cursor& c) { scene_.dfn.interlayers.push_back(readInterlayer(c)); });
    forEachItem(m, "structures",
                [&](const Cursor& c) { scene_.structures.push_back(readStructure(c)); });
    if (const auto loads = m.get("loads")) {
      scene_.loads = readLoads(*loads);
      checkWaterOnce(*loads);
    }
    if (const auto supports = m.get("supports")) {
      const Cursor s = supports->map({"fixed", "rollers"});
      const std::vector<std::string> names{"bottom", "top", "west", "east", "south", "north"};
      if (const auto fixed = s.get("fixed"))
        scene_.fixed_faces = fixed->distinctChoices("face", names);
      if (const auto rollers = s.get("rollers")) {
        scene_.roller_faces = rollers->distinctChoices("face", names);
        for (const std::string& face : scene_.roller_faces) {
          if (std::find(scene_.fixed_faces.begin(), scene_.fixed_faces.end(), face) !=
              scene_.fixed_faces.end()) {
            rollers->fail("face '" + face +
                          "' is already in supports.fixed; a face is fixed "
                          "or on rollers, not both");
          }
        }
      }
      if (!s.get("fixed") && !s.get("rollers")) {
        supports->fail("supports needs `fixed` or `rollers` (a list of domain faces)");
      }
    }
    UniqueNames monitor_names;
    forEachItem(m, "monitors", [&](const Cursor& c) {
      const Cursor monitor = c.map({"name", "point"});
      scene_.monitors.push_back(
          {monitor_names.claimName(monitor), monitor.at("point").vec3(), c.line()});
    });
    UniqueNames bolt_names;
    forEachItem(m, "bolts", [&](const Cursor& c) {
      const Cursor bolt =
          c.map({"name", "head", "end", "stiffness", "pretension", "yield_force", "rupture_force"});
      BoltSpec spec = readBoltSteel(bolt);
      spec.name = bolt_names.claimName(bolt);
      spec.head = bolt.at("head").vec3();
      const Cursor end = bolt.at("end");
      spec.end = end.vec3();
      if ((spec.end - spec.head).norm() <= 0.0) end.fail("the end must differ from the head");
      spec.key = locationOf(c);
      scene_.bolts.push_back(spec);
    });
    forEachItem(m, "bolt_patterns", [&](const Cursor& c) { readBoltPattern(c, bolt_names); });
    if (const auto analysis = m.get("analysis")) {
      scene_.analysis = readAnalysis(*analysis, namesOf(scene_.dfn.joint_sets), scene_.dfn.domain,
                                     !scene_.domain_mesh.empty(), !scene_.monitors.empty());
    }
    if (const auto uncertainty = m.get("uncertainty")) {
      scene_.uncertainty = readUncertainty(*uncertainty, root.node());
    }
    return std::move(scene_);
  }

 private:
  using Entries = std::vector<std::pair<std::string, Cursor>>;

  /// domain: exactly one of box {min, max} or mesh (a file).
  void readDomain(const Cursor& c) {
    const Cursor m = c.map({"box", "mesh"});
    if (m.oneOf("box", "mesh") == 1) {
      scene_.domain_mesh = m.at("mesh").existingFile();
      return;
    }
    const Cursor box = m.at("box").map({"min", "max"});
    scene_.dfn.domain.min = box.at("min").vec3();
    scene_.dfn.domain.max = box.at("max").vec3();
    for (int axis = 0; axis < 3; ++axis) {
      const double min = scene_.dfn.domain.min[axis], max = scene_.dfn.domain.max[axis];
      if (!(min < max)) {
        box.fail("expected min < max in every component, got " + formatDouble(min) +
                 " >= " + formatDouble(max) + " in " + "xyz"[axis]);
      }
    }
    // Edges of 1e-300 m have min < max and no volume in floating point.
    const double volume = scene_.dfn.domain.volume();
    if (!(volume > 0.0 && std::isfinite(volume))) {
      box.fail("expected a box with a finite volume > 0, got " + formatDouble(volume) + " m3");
    }
  }

  /// A `materials` entry: unit_weight or density, young, poisson.
  static Material readMaterial(const Cursor& c, const std::string& name) {
    const Cursor m = c.map({"unit_weight", "density", "young", "poisson"});
    Material material{.name = name};
    material.density = m.oneOf("unit_weight", "density") == 0
                           ? m.at("unit_weight").number(kPositive) / kStandardGravity
                           : m.at("density").number(kPositive);
    material.young = m.at("young").number(kPositive);
    material.poisson =
        m.at("poisson").number({.low = -1, .high = 0.5, .low_open = true, .high_open = true});
    return material;
  }

  /// Index of the material named at `c`.
  int material(const Cursor& c) const {
    return lookupName(c, namesOf(scene_.materials), "material");
  }

  /// Index of the joint named at `c` (among the `joints` section).
  int joint(const Cursor& c) const { return lookupName(c, named_joints_, "joint"); }

  /// The entry's `joint`, or the default joint when it has none.
  int jointOf(const Cursor& entry) const {
    return entry.valueOr("joint", scene_.default_joint, [&](const Cursor& v) { return joint(v); });
  }

  /// thickness (default 0) and material of a fault or interlayer; `what` is "a fault".
  std::pair<double, int> readSlab(const Cursor& entry, const std::string& what) const {
    const double thickness = entry.numberOr("thickness", 0.0, kNonNegative);
    const int slab_material =
        entry.valueOr("material", -1, [&](const Cursor& v) { return material(v); });
    if (thickness > 0 && slab_material < 0) {
      entry.fail(what + " with thickness > 0 needs a material");
    }
    return {thickness, slab_material};
  }

  /// A `joint_sets` entry.
  geometry::JointSetSpec readJointSet(const Cursor& c) {
    const Cursor m = c.map({"name", "dip_direction", "dip", "orientation", "spacing", "intensity",
                            "trace_length", "shape", "joint", "min_cut_size"});
    geometry::JointSetSpec set;
    set.name = dfn_names_.claimName(m);
    set.orientation = readOrientation(m);
    JointSetKeys keys;
    if (m.oneOf("spacing", "intensity") == 0) {
      keys.intensity = locationOf(m.at("spacing"));
      set.spacing = readSpacing(m.at("spacing"));
    } else {
      keys.intensity = locationOf(m.at("intensity"));
      set.p32 = m.at("intensity").map({"p32"}).at("p32").number(kPositive);
    }
    const Cursor trace_length = m.at("trace_length");
    keys.trace_length = locationOf(trace_length);
    scene_.joint_set_keys.push_back(keys);
    const geometry::Distribution trace_distribution = readDistribution(trace_length);
    checkTraceLength(trace_length, trace_distribution);
    set.trace_length = trace_distribution.spec();
    set.shape = m.valueOr("shape", set.shape, &readShape);
    set.joint = jointOf(m);
    set.min_cut_size = m.numberOr("min_cut_size", 0.0, kNonNegative);
    return set;
  }

  /// A `fractures` entry: the polygons of a FAB file, named after the file's stem.
  geometry::PolygonSetSpec readFractures(const Cursor& c) {
    const Cursor m = c.map({"file", "joint"});
    const Cursor file = m.at("file");
    const fs::path path = file.existingFile();
    geometry::PolygonSetSpec set;
    set.name = path.stem().string();
    dfn_names_.claim(file, set.name, m.path());
    for (FabFracture& fracture : readFab(path).fractures) {
      set.polygons.push_back(std::move(fracture.vertices));
      set.file_sets.push_back(fracture.set);
    }
    set.joint = jointOf(m);
    return set;
  }

  /// A `faults` entry.
  geometry::FaultSpec readFault(const Cursor& c) {
    const Cursor m =
        c.map({"name", "center", "dip_direction", "dip", "size", "thickness", "material", "joint"});
    geometry::FaultSpec fault;
    fault.name = dfn_names_.claimName(m);
    fault.center = m.at("center").vec3();
    fault.dip_direction = m.at("dip_direction").number(closed(0, 360));
    fault.dip = m.at("dip").number(closed(0, 90));
    if (const auto size = m.get("size")) {
      const std::vector<Cursor> axes = size->items();
      if (axes.size() != 2) size->fail("expected a list of 2 numbers [major, minor]");
      const double major = axes[0].number(kPositive);
      fault.size = {major, axes[1].number({.low = 0, .high = major, .low_open = true},
                                          "(minor must not exceed major)")};
    }
    std::tie(fault.thickness, fault.material) = readSlab(m, "a fault");
    fault.joint = jointOf(m);
    return fault;
  }

  /// An `interlayers` entry.
  geometry::InterlayerSpec readInterlayer(const Cursor& c) {
    const Cursor m = c.map({"name", "profile", "sweep", "thickness", "material", "joint"});
    geometry::InterlayerSpec layer;
    layer.name = dfn_names_.claimName(m);
    layer.profile = readProfile(m.at("profile"), 2);
    layer.sweep = readSweep(m.at("sweep"));
    std::tie(layer.thickness, layer.material) = readSlab(m, "an interlayer");
    if (layer.thickness > 0.0) {
      // The slab's surfaces are the profile offset by half the thickness, with mitred knees:
      // geometry::kMaxInterlayerTurn, which generateInterlayer also refuses.
      const std::vector<Cursor> points = m.at("profile").items();
      for (std::size_t i = 1; i + 1 < layer.profile.size(); ++i) {
        const Vec2 d1 = (layer.profile[i] - layer.profile[i - 1]).normalized();
        const Vec2 d2 = (layer.profile[i + 1] - layer.profile[i]).normalized();
        if (d1.dot(d2) < std::cos(geometry::kMaxInterlayerTurn * std::numbers::pi / 180.0)) {
          const double turn =
              std::acos(std::clamp(d1.dot(d2), -1.0, 1.0)) * 180.0 / std::numbers::pi;
          points[i].fail("the profile turns by " + formatDouble(std::round(turn * 10.0) / 10.0) +
                         " degrees at point " + std::to_string(i + 1) + ", more than the " +
                         formatDouble(geometry::kMaxInterlayerTurn) +
                         " an interlayer with thickness can turn");
        }
      }
    }
    layer.joint = jointOf(m);
    return layer;
  }

  /// A `structures` entry; an inline joint map is appended to the scene's joints.
  StructureSpec readStructure(const Cursor& c) {
    const Cursor m = c.map({"name", "prism", "mesh", "material", "joint", "contact_point_spacing"});
    StructureSpec structure;
    structure.name = structure_names_.claimName(m);
    if (m.oneOf("prism", "mesh") == 0) {
      const Cursor prism = m.at("prism").map({"profile", "sweep", "from", "to"});
      structure.prism_profile = readProfile(prism.at("profile"), 3);
      structure.profile_line = prism.at("profile").line();
      structure.profile_column = prism.at("profile").column();
      structure.prism_sweep = readSweep(prism.at("sweep"));
      structure.prism_from = prism.at("from").number();
      structure.prism_to =
          prism.at("to").number(above(structure.prism_from), "(to must exceed from)");
    } else {
      structure.mesh = m.at("mesh").existingFile();
    }
    structure.material = material(m.at("material"));
    const std::optional<Cursor> contact = m.get("joint");
    if (contact && contact->isMap()) {
      structure.joint = static_cast<int>(scene_.joints.size());
      scene_.joints.push_back(readJoint(*contact, structure.name + ".joint"));
    } else {
      structure.joint = jointOf(m);
    }
    if (const auto spacing = m.get("contact_point_spacing")) {
      structure.contact_point_spacing_line = spacing->line();
      if (!spacing->is("auto")) {
        if (!spacing->isNumber()) spacing->failExpected("'auto' or a number >= 0 (m)");
        structure.contact_point_spacing = spacing->number(kNonNegative);
      }
    }
    return structure;
  }

  /// A `loads.water` entry.
  WaterLoad readWater(const Cursor& c) const {
    const Cursor m = c.map({"level", "unit_weight", "uplift", "on"});
    WaterLoad water;
    const Cursor level = m.at("level");
    water.level = level.number();
    // Below the domain's bottom the water wets nothing (box domains: a mesh domain's extent
    // is not known here).
    if (scene_.domain_mesh.empty() && water.level < scene_.dfn.domain.min.z()) {
      level.fail("the water level " + formatDouble(water.level) +
                 " m lies below the domain bottom z = " + formatDouble(scene_.dfn.domain.min.z()) +
                 " m and would wet nothing");
    }
    water.unit_weight = m.numberOr("unit_weight", water.unit_weight, kPositive);
    water.uplift = m.valueOr("uplift", false, &Cursor::boolean);
    const Cursor on = m.at("on").map({"structure", "facing", "domain_top", "region"});
    if (on.oneOf("structure", "domain_top") == 0) {
      const Cursor structure = on.at("structure");
      lookupName(structure, namesOf(scene_.structures), "structure");
      water.structure = structure.string();
      water.facing = readDirection(on.at("facing"));
    } else {
      const Cursor top = on.at("domain_top");
      if (!top.boolean()) top.fail("expected true (or an 'on: {structure: ...}' entry), got false");
      if (on.has("facing")) {
        on.at("facing").fail("'facing' selects structure faces; remove it for domain_top");
      }
      water.domain_top = true;
    }
    water.region = on.valueOr("region", water.region, &readRegion);
    return water;
  }

  /// The steel of a bolt or pattern: stiffness, pretension, yield and rupture forces.
  static BoltSpec readBoltSteel(const Cursor& m) {
    BoltSpec spec;
    spec.stiffness = m.at("stiffness").number(kPositive);
    spec.pretension = m.numberOr("pretension", 0.0, kNonNegative);
    if (const auto y = m.get("yield_force")) spec.yield_force = y->number(kPositive);
    if (const auto r = m.get("rupture_force")) {
      spec.rupture_force = r->number(kPositive);
      if (spec.yield_force) {
        r->fail(
            "give yield_force or rupture_force, not both: a bolt that yields holds its yield "
            "force (" +
            formatDouble(*spec.yield_force) + " N) and never reaches a rupture force above it");
      }
      if (spec.pretension >= *spec.rupture_force) {
        r->fail("the pretension " + formatDouble(spec.pretension) + " N would break the bolt");
      }
    }
    return spec;
  }

  /// A `bolt_patterns` entry: rows x columns bolts, head k = origin + i along + j across,
  /// each `length` m along `direction`; named "<name>.<row>.<column>" from 1.
  void readBoltPattern(const Cursor& c, UniqueNames& names) {
    const Cursor m = c.map({"name", "origin", "along", "across", "count", "direction", "length",
                            "stiffness", "pretension", "yield_force", "rupture_force"});
    const BoltSpec steel = readBoltSteel(m);
    const std::string name = names.claimName(m);
    const Vec3 origin = m.at("origin").vec3();
    const Vec3 along = m.at("along").vec3();
    const Vec3 across = m.at("across").vec3();
    const Cursor count = m.at("count");
    const std::vector<Cursor> counts = count.items();
    if (counts.size() != 2) count.failExpected("[rows, columns]");
    const int rows = counts[0].integer(atLeast(1));
    const int columns = counts[1].integer(atLeast(1));
    if (static_cast<double>(rows) * columns > 1e5) {
      count.fail("more than 100000 bolts; expected a coarser pattern");
    }
    const Vec3 direction = readDirection(m.at("direction")).normalized();
    const double length = m.at("length").number(kPositive);
    for (int i = 0; i < rows; ++i) {
      for (int j = 0; j < columns; ++j) {
        BoltSpec spec = steel;
        spec.name = name + "." + std::to_string(i + 1) + "." + std::to_string(j + 1);
        spec.head = origin + i * along + j * across;
        spec.end = spec.head + length * direction;
        spec.key = locationOf(c);
        scene_.bolts.push_back(spec);
      }
    }
  }

  /// A `loads.pore_pressure` entry.
  PorePressure readPorePressure(const Cursor& c) const {
    const Cursor m = c.map({"level", "uplift_diagram", "unit_weight", "region"});
    PorePressure pore;
    pore.key = locationOf(c);
    pore.unit_weight = m.numberOr("unit_weight", pore.unit_weight, kPositive);
    pore.region = m.valueOr("region", pore.region, &readRegion);
    if (m.oneOf("level", "uplift_diagram") == 0) {
      pore.level = m.at("level").number();
      return pore;
    }
    const Cursor d =
        m.at("uplift_diagram")
            .map({"structure", "upstream_level", "downstream_level", "flow", "drains"});
    UpliftDiagram diagram;
    const Cursor structure = d.at("structure");
    lookupName(structure, namesOf(scene_.structures), "structure");
    diagram.structure = structure.string();
    diagram.upstream_level = d.at("upstream_level").number();
    const Cursor downstream = d.at("downstream_level");
    diagram.downstream_level = downstream.number();
    if (diagram.downstream_level > diagram.upstream_level) {
      downstream.fail("the tailwater (" + formatDouble(diagram.downstream_level) +
                      " m) lies above the reservoir (" + formatDouble(diagram.upstream_level) +
                      " m); expected downstream_level <= upstream_level");
    }
    const Cursor flow = d.at("flow");
    Vec3 direction = readDirection(flow);
    direction.z() = 0.0;
    if (direction.norm() < 1e-9) flow.fail("expected a horizontal direction (heel to toe)");
    diagram.flow = direction.normalized();
    if (const auto drains = d.get("drains")) {
      const Cursor dm = drains->map({"distance", "efficiency"});
      const Cursor distance = dm.at("distance");
      diagram.drain_distance = distance.number(kPositive);
      diagram.drain_key = locationOf(distance);
      diagram.drain_efficiency = dm.at("efficiency").number(closed(0.0, 1.0));
    }
    pore.diagram = diagram;
    return pore;
  }

  /// The `loads.seismic` section.
  Seismic readSeismic(const Cursor& c) const {
    const Cursor m = c.map({"k_h", "direction", "k_v", "westergaard"});
    Seismic seismic;
    seismic.k_h = m.numberOr("k_h", 0.0, kNonNegative);
    if (const auto direction = m.get("direction")) {
      Vec3 d = readDirection(*direction);
      d.z() = 0.0;
      if (d.norm() < 1e-9) direction->fail("expected a horizontal direction");
      seismic.direction = d.normalized();
    }
    seismic.k_v = m.numberOr("k_v", 0.0, closed(-1.0, 1.0));
    if (const auto w = m.get("westergaard")) {
      const Cursor wm = w->map({"structure", "facing", "level", "bottom", "unit_weight"});
      Westergaard westergaard;
      const Cursor structure = wm.at("structure");
      lookupName(structure, namesOf(scene_.structures), "structure");
      westergaard.structure = structure.string();
      westergaard.facing = readDirection(wm.at("facing"));
      westergaard.level = wm.at("level").number();
      if (const auto bottom = wm.get("bottom")) {
        westergaard.bottom = bottom->number();
        if (*westergaard.bottom >= westergaard.level) {
          bottom->fail("the reservoir floor must lie below its level " +
                       formatDouble(westergaard.level) + " m");
        }
      }
      westergaard.unit_weight = wm.numberOr("unit_weight", westergaard.unit_weight, kPositive);
      seismic.westergaard = westergaard;
    }
    return seismic;
  }

  /// Two pore-pressure fields that act on the same faces would count the water twice: their
  /// regions must be disjoint in plan. Nor may a field and a water entry's `uplift` both load
  /// the structure-rock interface.
  void checkWaterOnce(const Cursor& loads) const {
    const auto overlap = [](const Region& a, const Region& b) {
      const auto apart = [](const std::optional<double>& a_min, const std::optional<double>& a_max,
                            const std::optional<double>& b_min,
                            const std::optional<double>& b_max) {
        return (a_max && b_min && *a_max <= *b_min) || (b_max && a_min && *b_max <= *a_min);
      };
      return !apart(a.x_min, a.x_max, b.x_min, b.x_max) &&
             !apart(a.y_min, a.y_max, b.y_min, b.y_max);
    };
    const std::vector<PorePressure>& pore = scene_.loads.pore_pressure;
    for (std::size_t i = 0; i < pore.size(); ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        if (overlap(pore[i].region, pore[j].region)) {
          loads.at("pore_pressure")
              .fail("entries " + std::to_string(j + 1) + " and " + std::to_string(i + 1) +
                    " act on the same faces (their regions overlap in plan); the water would count "
                    "twice");
        }
      }
    }
    if (pore.empty()) return;
    const std::vector<WaterLoad>& water = scene_.loads.water;
    for (std::size_t i = 0; i < water.size(); ++i) {
      if (water[i].uplift) {
        loads.at("water").fail("entry " + std::to_string(i + 1) +
                               " has 'uplift: true' and loads.pore_pressure also loads the "
                               "structure-rock interface; the uplift would count twice (remove "
                               "one of them)");
      }
    }
  }

  /// The `loads` section.
  Loads readLoads(const Cursor& c) const {
    const Cursor m = c.map({"gravity", "water", "point_loads", "pore_pressure", "seismic"});
    Loads loads;
    if (const auto gravity = m.get("gravity")) {
      if (!gravity->isNumber() && !gravity->isList()) {
        gravity->failExpected("a number > 0 or a list of 3 numbers");
      }
      loads.gravity =
          gravity->isNumber() ? Vec3(0, 0, -gravity->number(kPositive)) : gravity->vec3();
    }
    forEachItem(m, "water", [&](const Cursor& v) { loads.water.push_back(readWater(v)); });
    forEachItem(m, "point_loads",
                [&](const Cursor& v) { loads.point_loads.push_back(readPointLoad(v)); });
    forEachItem(m, "pore_pressure",
                [&](const Cursor& v) { loads.pore_pressure.push_back(readPorePressure(v)); });
    if (const auto seismic = m.get("seismic")) loads.seismic = readSeismic(*seismic);
    return loads;
  }

  Scene scene_;                            ///< what is being read
  std::vector<std::string> named_joints_;  ///< joints of the `joints` section (referable by name)
  UniqueNames dfn_names_;                  ///< joint sets, fractures files, faults, interlayers
  UniqueNames structure_names_;            ///< structures
};

/// Length of the UTF-8 sequence that starts at text[k] (1-4), or 0 when it is not one: a
/// stray continuation byte, a truncated sequence, an overlong form, a surrogate, or a code
/// point above U+10FFFF (RFC 3629).
std::size_t utf8Length(const std::string& text, std::size_t k) {
  const auto byte = [&](std::size_t i) {
    return i < text.size() ? static_cast<unsigned char>(text[i]) : 0u;
  };
  const unsigned lead = byte(k);
  if (lead < 0x80) return 1;
  const auto continuation = [&](std::size_t i, unsigned low = 0x80, unsigned high = 0xBF) {
    return byte(i) >= low && byte(i) <= high;
  };
  if (lead >= 0xC2 && lead <= 0xDF) return continuation(k + 1) ? 2 : 0;
  if (lead >= 0xE0 && lead <= 0xEF) {
    const unsigned low = lead == 0xE0 ? 0xA0 : 0x80, high = lead == 0xED ? 0x9F : 0xBF;
    return continuation(k + 1, low, high) && continuation(k + 2) ? 3 : 0;
  }
  if (lead >= 0xF0 && lead <= 0xF4) {
    const unsigned low = lead == 0xF0 ? 0x90 : 0x80, high = lead == 0xF4 ? 0x8F : 0xBF;
    return continuation(k + 1, low, high) && continuation(k + 2) && continuation(k + 3) ? 4 : 0;
  }
  return 0;
}

/// An InputError at the first byte of `text` that is not valid UTF-8 (a scene is UTF-8, as
/// YAML and the JSON summary require); checked before anything is read or written.
void checkUtf8(const std::string& text, const fs::path& file) {
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t k = 0; k < text.size();) {
    const std::size_t length = utf8Length(text, k);
    if (length == 0) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned char>(text[k]));
      throw InputError(locate(
          file, line, static_cast<int>(k - line_start) + 1,
          std::string("invalid UTF-8 (byte ") + hex + "); the scene file must be UTF-8 text"));
    }
    if (text[k] == '\n') {
      ++line;
      line_start = k + 1;
    }
    k += length;
  }
}

/// Sees where each document of a YAML stream starts, nothing else.
class DocumentStarts : public YAML::EventHandler {
 public:
  std::vector<YAML::Mark> starts;
  void OnDocumentStart(const YAML::Mark& mark) override { starts.push_back(mark); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

/// The single YAML document of `text`, or an InputError for invalid YAML.
YAML::Node loadDocument(const std::string& text, const fs::path& file) {
  checkUtf8(text, file);
  const auto at = [&](const YAML::Mark& mark, const std::string& what) {
    return InputError(locate(file, std::max(mark.line, 0) + 1, std::max(mark.column, 0) + 1, what));
  };
  const auto invalid = [&](const YAML::Mark& mark, const std::string& what) {
    return at(mark, "invalid YAML: " + what);
  };
  try {
    // The documents are counted first, at most two, with the parser alone: yaml-cpp 0.7's
    // LoadAll never ends on a stray ',' outside [ ] or { } (the parser starts the same empty
    // document again without consuming it, and the list of documents grows until memory
    // runs out: jbeder/yaml-cpp#1040, fixed upstream after 0.8 by PR #1319). Such a document
    // starts where the previous one did.
    std::istringstream stream(text);
    YAML::Parser parser(stream);
    DocumentStarts documents;
    while (documents.starts.size() < 2 && parser.HandleNextDocument(documents)) {
    }
    if (documents.starts.size() == 2) {
      const YAML::Mark& first = documents.starts[0];
      const YAML::Mark& second = documents.starts[1];
      if (second.pos == first.pos) {
        throw invalid(second, "a ',' outside a flow collection ([ ] or { })");
      }
      throw at(second, "expected one YAML document; a second one starts here");
    }
    return documents.starts.empty() ? YAML::Node() : YAML::Load(text);
  } catch (const YAML::Exception& error) {
    throw invalid(error.mark, error.msg);
  }
}

}  // namespace

std::string locate(const Scene& scene, const KeyLocation& key, const std::string& what) {
  return locate(scene.file, key.line, key.column, key.path.empty() ? what : key.path + ": " + what);
}

Scene loadScene(const std::filesystem::path& file) {
  std::error_code error;
  std::ifstream in(file, std::ios::binary);
  if (!in || fs::is_directory(file, error)) {
    throw InputError(file.string() + ": cannot read the scene file");
  }
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(file.string() + ": cannot read the scene file");
  return parseScene(text, file);
}

Scene parseScene(const std::string& text, const std::filesystem::path& file) {
  const Source source{file, fs::absolute(file).parent_path()};
  const Cursor root(source, loadDocument(text, file), "", YAML::Mark());
  return SceneReader().read(root, file);
}

Scene parseSampledScene(const fs::path& file, const std::vector<double>& values,
                        std::uint64_t seed) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot read the scene file");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const Source source{file, fs::absolute(file).parent_path()};
  YAML::Node document = loadDocument(text, file);
  const Cursor root(source, document, "", YAML::Mark());
  const Scene scene = SceneReader().read(root, file);
  if (!scene.uncertainty || scene.uncertainty->inputs.size() != values.size()) {
    throw std::logic_error("parseSampledScene: one value per uncertainty input");
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    const UncertainInput& input = scene.uncertainty->inputs[i];
    std::string why;
    std::optional<YAML::Node> node = resolveKey(document, input.key, why);
    if (!node) throw std::logic_error("parseSampledScene: " + why);
    // A whole number is written as one ("200000", not "2e+05"), so that integer keys take it;
    // yaml-cpp keeps the node's mark: errors point at the key's line.
    const double v = values[i];
    *node = std::abs(v) < 0x1.0p53 && v == std::trunc(v) ? std::to_string(static_cast<long long>(v))
                                                         : formatDouble(v);
  }
  document["seed"] = std::to_string(seed);
  try {
    return SceneReader().read(root, file);
  } catch (const InputError& error) {
    throw InputError(std::string(error.what()) + " (a sampled value of uncertainty.inputs)");
  }
}

}  // namespace rockmass::io
