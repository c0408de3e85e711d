#pragma once
/// The scene file (format version 1, YAML): see shared docs/scene-format.md. Reading
/// validates everything; any problem is an InputError located at file:line:column.
#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "dda3d/simulation_settings.h"
#include "geometry/dfn_spec.h"
#include "geometry/fracture_network.h"
#include "geometry/polyhedron.h"
#include "geometry/vec.h"

namespace rockmass::io {

using geometry::Vec2;
using geometry::Vec3;

/// An intact material (Table 2).
struct Material {
  std::string name;      ///< name used by the scene
  double density = 0.0;  ///< kg/m3 (from `density`, or `unit_weight` / 9.81)
  double young = 0.0;    ///< Young's modulus (Pa)
  double poisson = 0.0;  ///< Poisson's ratio, in (-1, 0.5)
};

/// Mohr-Coulomb strength of a discontinuity.
struct Joint {
  std::string name;               ///< name used by the scene ("<structure>.joint" if inline)
  double friction = 0.0;          ///< f = tan(phi) (from `friction` or `friction_angle`)
  double cohesion = 0.0;          ///< Pa
  double tensile_strength = 0.0;  ///< Pa
  /// `model`: false for `plastic` (the default: cohesion kept while the contact slides),
  /// true for `brittle` (cohesion and tensile strength lost once it slides or opens).
  bool brittle = false;
};

/// A structure standing on or in the rock (the dam).
struct StructureSpec {
  std::string name;                 ///< e.g. "dam"
  std::vector<Vec2> prism_profile;  ///< prism outline, (x, z) for sweep y, (y, z) for sweep x
  char prism_sweep = 'y';           ///< axis the outline is swept along
  double prism_from = 0.0;          ///< sweep start (m)
  double prism_to = 0.0;            ///< sweep end (m)
  std::filesystem::path mesh;       ///< closed mesh instead of a prism (absolute path)
  int material = 0;                 ///< material index
  int joint = -1;                   ///< joint index of the structure-rock contact (-1: none)
  /// Sub-contact point spacing of the structure's faces (m; 0: corners only); none: `auto`,
  /// a sixteenth of the structure's smallest extent (docs/stability.md, "Contact points").
  std::optional<double> contact_point_spacing;
  int contact_point_spacing_line = 0;  ///< its line (messages; 0: not given)
  int profile_line = 0;                ///< line of prism.profile in the scene file (messages)
  int profile_column = 0;              ///< its column
};

/// Plan-view region (m); missing bounds are open.
struct Region {
  std::optional<double> x_min, x_max, y_min, y_max;
};

/// Hydrostatic water pressure p = unit_weight * max(0, level - z) on selected faces.
struct WaterLoad {
  double level = 0.0;           ///< z of the water surface (m)
  double unit_weight = 9810.0;  ///< N/m3
  std::string structure;        ///< faces of this structure ("" when on the domain top)
  std::optional<Vec3> facing;   ///< wet faces have outward normal n with n . facing > 0
  bool domain_top = false;      ///< the top face of the domain
  Region region;                ///< restricts the wet faces in plan
  bool uplift = false;          ///< also the structure-rock interface
};

/// Where a key is in the scene file, for messages about it raised after reading (budgets).
struct KeyLocation {
  std::string path;  ///< key path, e.g. "joint_sets[0].spacing"
  int line = 0;      ///< 1-based line
  int column = 0;    ///< 1-based column
};

/// The uplift diagram under a structure (USBR, Design of Small Dams, ch. 8; USACE EM
/// 1110-2-2200): the piezometric head of the reservoir at the heel, of the tailwater at the
/// toe, linear between; with a drainage curtain, the head at the drain line is the
/// tailwater's plus (1 - efficiency) of the difference, linear from the heel to the drains
/// and from the drains to the toe. Upstream of the heel the head stays the reservoir's,
/// downstream of the toe the tailwater's.
struct UpliftDiagram {
  std::string structure;                 ///< the structure whose heel and toe it spans
  double upstream_level = 0.0;           ///< z of the reservoir (m)
  double downstream_level = 0.0;         ///< z of the tailwater (m)
  Vec3 flow = Vec3::UnitX();             ///< horizontal unit vector, heel -> toe
  std::optional<double> drain_distance;  ///< drain line, m downstream of the heel
  double drain_efficiency = 0.0;         ///< in [0, 1]
  KeyLocation drain_key;                 ///< `drains.distance` (messages)
};

/// Water pressure in the discontinuities (joints, faults, interlayers, FAB fractures, the
/// structure-rock interface): p = unit_weight * max(0, h(x) - z) on both sides of every
/// such face, with the head h a phreatic level (hydrostatic below it) or an uplift diagram.
struct PorePressure {
  std::optional<double> level;           ///< phreatic level (m)
  std::optional<UpliftDiagram> diagram;  ///< exactly one of level and diagram
  double unit_weight = 9810.0;           ///< N/m3
  Region region;                         ///< restricts the field in plan
  KeyLocation key;                       ///< the entry (messages)
};

/// Westergaard's added hydrodynamic pressure on a structure's upstream face.
struct Westergaard {
  std::string structure;         ///< the structure
  std::optional<Vec3> facing;    ///< its faces with outward normal n . facing > 0
  double level = 0.0;            ///< z of the reservoir (m)
  std::optional<double> bottom;  ///< z of the reservoir floor (m); none: the structure's lowest
  double unit_weight = 9810.0;   ///< N/m3
};

/// Pseudo-static earthquake loads.
struct Seismic {
  double k_h = 0.0;                ///< horizontal coefficient: k_h g along `direction`
  Vec3 direction = Vec3::UnitX();  ///< horizontal unit vector
  double k_v = 0.0;                ///< vertical coefficient: k_v g, upward when > 0
  std::optional<Westergaard> westergaard;
};

/// A concentrated force.
struct PointLoad {
  Vec3 point = Vec3::Zero();  ///< m
  Vec3 force = Vec3::Zero();  ///< N
};

/// Loads of the scene.
struct Loads {
  std::optional<Vec3> gravity;              ///< m/s2 vector (a number g means (0, 0, -g))
  std::vector<WaterLoad> water;             ///< water pressure entries
  std::vector<PointLoad> point_loads;       ///< point loads
  std::vector<PorePressure> pore_pressure;  ///< water in the discontinuities
  std::optional<Seismic> seismic;           ///< pseudo-static earthquake
};

/// A rock bolt or anchor: a spring from its head (in the block it holds) to its end (in the
/// block, or the fixed rock, it is anchored to), pulling the two together.
struct BoltSpec {
  std::string name;                     ///< e.g. "B1", or "P.2.3" (pattern P, row 2, column 3)
  Vec3 head = Vec3::Zero();             ///< m
  Vec3 end = Vec3::Zero();              ///< m
  double stiffness = 0.0;               ///< axial stiffness (N/m)
  double pretension = 0.0;              ///< N
  std::optional<double> yield_force;    ///< N; none: elastic
  std::optional<double> rupture_force;  ///< N; none: never breaks
  KeyLocation key;                      ///< the entry (messages)
};

/// A measure point attached to the block that contains it.
struct Monitor {
  std::string name;           ///< e.g. "P4"
  Vec3 point = Vec3::Zero();  ///< m
  int line = 0;               ///< line of the entry in the scene file (messages)
};

/// analysis.blocks
struct BlocksAnalysis {
  enum class Cutter { Exact, Fast };
  Cutter cutter = Cutter::Exact;  ///< exact (CGAL Nef) or fast (convex splitting)
  int disc_segments = 24;         ///< polygon points per ellipse (>= 3)
};

/// One RQD ball.
struct RqdBall {
  std::string name;              ///< ball name
  Vec3 center = Vec3::Zero();    ///< m
  double length = 0.0;           ///< scanline length (m), centred on the ball centre
  int directions = 2000;         ///< Fibonacci-sphere directions (>= 4: the surface needs them)
  std::optional<double> radius;  ///< surface radius R at RQD 100 (m); none: length / 2
};

/// analysis.rqd.boreholes.calibration: one intensity multiplier for a group of joint sets.
struct RqdCalibration {
  std::vector<int> sets;         ///< joint set indices of the group (all joint sets if none given)
  double min_multiplier = 0.25;  ///< lower end of the search bracket (> 0)
  double max_multiplier = 4.0;   ///< upper end (the network is generated at it)
  double tolerance = 0.5;        ///< stop when |mean bias| <= this (RQD points)
  int max_evaluations = 40;      ///< evaluations allowed
};

/// analysis.rqd
struct RqdAnalysis {
  std::vector<double> thresholds{1, 2, 3, 4, 5, 6, 7, 8, 9, 10};  ///< m
  std::vector<RqdBall> balls;                                     ///< RQD balls
  std::filesystem::path boreholes_file;       ///< collars (absolute path), empty if none
  double run_length = 3.0;                    ///< core run length (m)
  std::filesystem::path measured_file;        ///< measured log (absolute path), empty if none
  double measured_threshold = 0.1;            ///< threshold of the measured RQD (m)
  std::optional<RqdCalibration> calibration;  ///< calibrate against the measured log
  double merge_distance = 1e-3;               ///< hits closer than this are one fracture (m)
  std::optional<double> grid_spacing;         ///< RQD/P32 grid cell size (m)
  int grid_direction_count = 200;             ///< directions per grid cell
  std::optional<double> grid_length;  ///< grid scanline length (m); none: 2 x largest threshold
  std::optional<geometry::Box> grid_region;  ///< box the grid fills (m); none: the domain box
};

/// analysis.dda
struct DdaAnalysis {
  /// The engine's settings as the scene gives them: mode, kinematics, time_step,
  /// min_time_step, max_displacement_ratio, penalty (0: auto), time_integration,
  /// open_close_tolerance, friction_tolerance, contact_point_spacing. Keys the scene omits
  /// keep the engine's defaults (dda3d::DdaSettings), which are the scene contract's
  /// (docs/scene-reference.md).
  dda3d::DdaSettings engine;
  int steps = 1000;  ///< number of steps of size time_step
  /// m3: blocks smaller than this are glued to the same-material neighbour they share the
  /// most face area with before the DDA (blocks::mergeSmallBlocks); 0 glues none.
  double min_block_volume = 0.0;
  /// true: a block below min_block_volume with no neighbour of its own material is glued to
  /// its rock neighbour of any material (blocks::mergeSmallBlocks' across_materials).
  bool glue_across_materials = false;
  int contact_point_spacing_line = 0;  ///< line of `contact_point_spacing` (messages; 0: none)
  /// region {min, max}: the box the DDA (and the overload and strength reduction) runs on,
  /// inside the domain box. Its blocks are cut from the same network and structures with the
  /// region as the domain, so supports and `domain_top` loads act on the region's faces.
  /// None: the whole domain.
  std::optional<geometry::Box> region;
  /// damage_map {every}: a damage map (damage_<step>.vtu, damage.pvd; damage.csv of the last)
  /// every this many steps and at the last step; none: no damage map.
  std::optional<int> damage_every;
  /// settle {without, max_steps}: before the run, the model is brought to rest in static
  /// mode under its loads less those of `without`, and the run starts from that state with
  /// every load (the service-period run: the settled foundation loaded by the reservoir).
  struct Settle {
    bool without_water = false;        ///< water on faces, uplift and pore pressure
    bool without_seismic = false;      ///< the seismic body force and Westergaard pressures
    bool without_point_loads = false;  ///< the point loads
    int max_steps = 200;               ///< at most this many static steps
  };
  std::optional<Settle> settle;
};

/// analysis.overload
struct OverloadAnalysis {
  std::vector<double> factors;      ///< load factors K, increasing
  std::vector<std::string> scales;  ///< loads multiplied: "water", "gravity", "point_loads"
  /// Bisect [last K at rest, first K not at rest] to this width after the sweep (0: no).
  double tolerance = 0.0;
  bool scale_uplift = false;  ///< `water` also scales uplift (else uplift stays at K = 1)
};

/// analysis.strength_reduction
struct StrengthReductionAnalysis {
  std::vector<double> factors;  ///< strength reduction factors, increasing
  double tolerance = 0.02;      ///< bisection to this bracket width
  /// path: incremental: each SRF from the end of the last SRF at rest (dda3d::FactorSearch).
  bool incremental = false;
};

/// analysis.equilibrium: when an overload or strength-reduction run is at rest
/// (docs/stability.md).
struct EquilibriumAnalysis {
  std::optional<int> max_steps;    ///< step limit per run; none: analysis.dda.steps
  double unbalanced_ratio = 1e-3;  ///< step displacement / (g dt^2 / 2)
  double kinetic_ratio = 1e-6;     ///< kinetic energy / work of the loads
  int settle_steps = 5;            ///< calm steps in a row
  double dynamic_ratio = 0.95;     ///< velocity share kept per step in dynamic mode (damping)
  /// start: settled | unloaded. settled: the model is first run to rest as it is (factor 1),
  /// and every factor's run starts from that state (dda3d::settledModel); unloaded (the
  /// default): every run starts from the cut geometry with unloaded contact springs.
  bool settled_start = false;
  /// start_steps: the settled start's own step limit (it runs once, before every factor);
  /// none: the runs' max_steps.
  std::optional<int> start_steps;
  double failure_ratio = 1.0;  ///< static runs: early stop at this unbalanced ratio (0: none)
  int failure_steps = 10;      ///< ... held this many steps in a row
  /// static runs: early stop after this many steps of steady motion (0: none;
  /// dda3d::EquilibriumSettings::steady_steps)
  int steady_steps = 10;
  double steady_spread = 0.01;  ///< ... their ratios within this share of the largest
  /// static runs: early stop after this many steps of a watched block drifting (0: none;
  /// dda3d::EquilibriumSettings::drift_steps)
  int drift_steps = 0;
  /// watch: all | monitors. monitors: only the blocks that carry a monitor decide whether a
  /// run is at rest (or failing); needs a monitor in a movable block.
  bool watch_monitors = false;
  int watch_line = 0;  ///< line of `watch` in the scene file (messages)
};

/// The `analysis` section: a stage runs only when its entry is present.
struct Analysis {
  std::optional<BlocksAnalysis> blocks;
  std::optional<RqdAnalysis> rqd;
  std::optional<DdaAnalysis> dda;
  std::optional<OverloadAnalysis> overload;
  std::optional<StrengthReductionAnalysis> strength_reduction;
  std::optional<EquilibriumAnalysis> equilibrium;
};

/// One uncertain input of the `uncertainty` section: a number of the scene that varies from
/// realization to realization of an ensemble (docs/ensemble.md).
struct UncertainInput {
  std::string key;  ///< its key path, e.g. "joints.bedrock_III2.friction"
  /// normal | lognormal | uniform | triangular | sample_mean | list
  std::string distribution;
  double value = 0.0;  ///< the scene's own value at `key`
  /// Parameters as resolved: mean and std (normal, lognormal; sample_mean: the mean's
  /// normal, std / sqrt(count)), min and max (uniform, triangular, or a normal's truncation),
  /// mode (triangular).
  double mean = 0.0;
  double std = 0.0;
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  double mode = 0.0;
  /// list: realization i takes values[i mod size] (a design of chosen cases, not a draw).
  std::vector<double> values;
  KeyLocation location;  ///< of the entry's `key`
};

/// The `uncertainty` section: which inputs vary across the realizations of an ensemble and
/// how they are sampled; without it realizations differ by their DFN seed only.
struct Uncertainty {
  bool latin_hypercube = false;  ///< sampling: latin_hypercube (else monte_carlo)
  int size = 0;                  ///< the Latin hypercube's size (its strata per input)
  KeyLocation size_location;     ///< of `sampling` (for an ensemble larger than `size`)
  std::vector<UncertainInput> inputs;
  std::optional<double> overload_target;  ///< targets.overload: P(K_s < target)
  std::optional<double> strength_target;  ///< targets.strength_reduction: P(SRF < target)
};

/// The keys of a joint set that drive how many discs it draws.
struct JointSetKeys {
  KeyLocation intensity;     ///< `spacing` or `intensity`
  KeyLocation trace_length;  ///< `trace_length`
};

/// A whole scene, validated, with names resolved to indices.
struct Scene {
  std::filesystem::path file;         ///< the scene file as given
  int version = 1;                    ///< format version
  std::string name;                   ///< site name
  std::uint64_t seed = 0;             ///< seed of every random draw
  std::filesystem::path domain_mesh;  ///< closed mesh domain (absolute), empty for a box
  /// The mesh domain's checked surface (io/mesh_domain.h), filled by the commands that
  /// support mesh domains (then dfn.domain is its bounding box); empty otherwise.
  geometry::Polyhedron domain_surface;
  geometry::DfnSpec dfn;                     ///< domain box and everything the DFN is made of
  std::vector<JointSetKeys> joint_set_keys;  ///< per joint set (dfn.joint_sets order)
  /// How many discs the DFN may draw: not a scene key; the commands set it (--max-discs).
  geometry::GenerationLimits generation_limits;
  /// How many blocks a cut may make by the estimate (blocks::estimateBlocks): not a scene key;
  /// the commands set it (--max-blocks).
  double max_blocks = 1e6;
  std::vector<Material> materials;        ///< in scene order
  int rock_material = -1;                 ///< material of the rock (-1: not given)
  std::vector<Joint> joints;              ///< named joints, then inline ones (structures)
  int default_joint = -1;                 ///< joint used where none is named (-1: not given)
  std::vector<StructureSpec> structures;  ///< structures
  Loads loads;                            ///< loads
  /// supports.rollers: faces (same names) whose blocks are held only normal to the face.
  std::vector<std::string> roller_faces;
  std::vector<std::string> fixed_faces;  ///< supports.fixed: bottom, top, west, east, south, north
  std::vector<Monitor> monitors;         ///< measure points
  std::vector<BoltSpec> bolts;           ///< bolts, then the patterns' bolts row by row
  Analysis analysis;                     ///< what to compute
  std::optional<Uncertainty> uncertainty;  ///< ensembles: the inputs that vary
};

/// "file:line:column: path: what" for a key of `scene`.
std::string locate(const Scene& scene, const KeyLocation& key, const std::string& what);

/// Reads and validates a scene. Relative paths inside it are resolved against its folder;
/// FAB files named under `fractures` are read into dfn.polygon_sets.
/// Throws InputError ("file:line:column: key: what was expected") for any problem.
Scene loadScene(const std::filesystem::path& file);

/// The same, from text; `file` is used in messages and to resolve relative paths.
Scene parseScene(const std::string& text, const std::filesystem::path& file);

/// The scene of one realization of an ensemble: the file read again with `values` (one per
/// uncertainty input, in order) written at their keys and `seed` as its seed. A value the
/// key cannot take is an InputError located at the key's line, naming the value.
Scene parseSampledScene(const std::filesystem::path& file, const std::vector<double>& values,
                        std::uint64_t seed);

}  // namespace rockmass::io
