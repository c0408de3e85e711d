// Readers of the scene's sections that need nothing but their node (distributions, joints,
// profiles, regions, loads, the analysis sections), over the cursor of io/scene_cursor.h.
// Internal to io (io/scene.cpp).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "geometry/distribution.h"
#include "io/scene.h"
#include "io/scene_cursor.h"

namespace rockmass::io::scene_detail {

using geometry::DistributionKind;
using geometry::DistributionSpec;

// ---------------------------------------------------------------------------------------------
// Readers that need nothing but their node
// ---------------------------------------------------------------------------------------------

/// The families a distribution map can name, in the order error messages list them.
inline constexpr std::array kDistributionKinds{
    DistributionKind::Normal, DistributionKind::Lognormal, DistributionKind::Uniform,
    DistributionKind::Exponential, DistributionKind::Constant};

/// The names of kDistributionKinds as written in scenes.
std::vector<std::string> distributionNames();

/// The optional bounds `min_key` and `max_key` of the map m; max must exceed min when both are
/// given (distribution truncation, plan regions).
std::pair<std::optional<double>, std::optional<double>> readBounds(const Cursor& m,
                                                                   const std::string& min_key,
                                                                   const std::string& max_key);

/// Mean and std of a uniform distribution: from {mean, std}, or from {min, max}.
void readUniformMoments(const Cursor& m, DistributionSpec& spec);

/// A distribution map {distribution, mean, std, min, max}, validated by geometry::Distribution.
geometry::Distribution readDistribution(const Cursor& c);

/// The shortest mean trace length or spacing a joint set may have (m).
constexpr double kShortestLength = 1e-6;

/// Fails unless a trace length distribution gives only values > 0, with a mean of at least
/// kShortestLength.
void checkTraceLength(const Cursor& c, const geometry::Distribution& distribution);

/// A spacing distribution: its mean (which sets P10) must be > 0.
DistributionSpec readSpacing(const Cursor& c);

/// Orientation of a joint set: dip_direction and dip distributions, or a Fisher `orientation`.
geometry::OrientationSpec readOrientation(const Cursor& set);

/// shape: {aspect_ratio, major_axis: strike | dip | {rake}}.
geometry::ShapeSpec readShape(const Cursor& c);

/// The strength of a joint: `joints` entries and inline structure joints.
Joint readJoint(const Cursor& c, std::string name);

/// A polyline of at least `min_points` [a, b] points with no zero-length segment.
std::vector<Vec2> readProfile(const Cursor& c, std::size_t min_points);

/// A sweep axis: 'x' or 'y'.
char readSweep(const Cursor& c);

/// A direction vector that is not zero.
Vec3 readDirection(const Cursor& c);

/// region: {x_min, x_max, y_min, y_max}, each optional; a max must exceed its min.
Region readRegion(const Cursor& c);

/// A point load {point, force}.
PointLoad readPointLoad(const Cursor& c);

/// analysis.blocks
BlocksAnalysis readBlocksAnalysis(const Cursor& c);

/// A box {min, max} with min < max in every component (m).
geometry::Box readBox(const Cursor& c);

/// analysis.rqd.boreholes.calibration; `joint_sets` names the joint sets in order.
RqdCalibration readRqdCalibration(const Cursor& c, const std::vector<std::string>& joint_sets);

/// analysis.rqd; `joint_sets` names the joint sets in order; the grid fills its region or
/// the domain box (unless the domain is a mesh).
RqdAnalysis readRqdAnalysis(const Cursor& c, const std::vector<std::string>& joint_sets,
                            const geometry::Box& domain, bool mesh_domain);

/// analysis.dda
DdaAnalysis readDdaAnalysis(const Cursor& c, const geometry::Box& domain, bool mesh_domain);

/// analysis.overload
OverloadAnalysis readOverloadAnalysis(const Cursor& c);

/// analysis.strength_reduction
StrengthReductionAnalysis readStrengthReductionAnalysis(const Cursor& c);

/// analysis.equilibrium
EquilibriumAnalysis readEquilibriumAnalysis(const Cursor& c, bool has_monitors);

/// The `analysis` section: each stage present only when its key is.
Analysis readAnalysis(const Cursor& c, const std::vector<std::string>& joint_sets,
                      const geometry::Box& domain, bool mesh_domain, bool has_monitors);

/// The number node at a key path of the scene ("joints.soft.friction", "loads.water[0].level",
/// "joint_sets.J1.dip.mean": a list item by index or by its `name`), or an empty optional with
/// `why` saying what is missing.
std::optional<YAML::Node> resolveKey(const YAML::Node& root, const std::string& key,
                                     std::string& why);

/// The `uncertainty` section (docs/ensemble.md); `root` is the scene's root node, on which
/// every input's key is resolved.
Uncertainty readUncertainty(const Cursor& c, const YAML::Node& root);

}  // namespace rockmass::io::scene_detail
