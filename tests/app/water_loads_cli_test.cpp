// Dam-foundation loads through the command line, each against its hand calculation: water
// pressure in the discontinuities (a phreatic level; the USBR / USACE uplift diagram with a
// drainage curtain; a wedge with water in both joints), bolts and anchors (statics, rupture,
// patterns), a pseudo-static earthquake, and the errors bad fields and bolts give.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "tests/support/cli_support.h"
#include "tests/support/test_support.h"
#include "tests/support/verification.h"

namespace rockmass {
namespace {

using Vec3 = Eigen::Vector3d;

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;
constexpr double kGammaW = 9810.0;

class WaterLoadsCli : public ::testing::Test {
 protected:
  test::TempDir dir{"water_loads_cli"};

  /// Runs `rockmass <command>` on `scene` and returns its summary (the test fails on exit != 0).
  nlohmann::json summaryOf(const std::string& command, const std::string& name,
                           const std::string& scene) {
    std::string output;
    const int code = test::runOnScene(command, dir.path(), name, scene, &output);
    EXPECT_EQ(code, 0) << output;
    return nlohmann::json::parse(test::readFile(dir.path() / name / "summary.json"));
  }

  /// Runs `rockmass <command>` on a scene that must be refused: exit 2, the output returned.
  std::string refusal(const std::string& command, const std::string& name,
                      const std::string& scene) {
    std::string output;
    EXPECT_EQ(test::runOnScene(command, dir.path(), name, scene, &output), 2) << output;
    return output;
  }
};

/// The 1-based line of the first occurrence of `key` in `text`.
int lineOf(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(key);
  EXPECT_NE(at, std::string::npos) << key;
  return 1 + static_cast<int>(
                 std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

// ---------------------------------------------------------------------------------------
// A block on an inclined joint under a phreatic level.

constexpr double kPsi = 30.0;        // joint dip (deg), dipping east (+x)
constexpr double kFriction = 1.108;  // tan(phi) of the joint
constexpr double kPhreatic = -4.0;   // m

/// A 20 x 10 x 15 m rock box cut by one persistent joint z = -x tan(psi): the wedge above it
/// (a 1155 m3 triangular prism) rests on the joint, free on every other side; the box below
/// is held by its bottom. `pore`: the loads.pore_pressure entries ("" for none).
std::string inclineScene(const std::string& pore) {
  return R"(version: 1
name: block-on-an-inclined-joint
seed: 1
domain:
  box: {min: [0, 0, -15], max: [20, 10, 0]}
materials:
  rock: {density: 2600, young: 10.0e9, poisson: 0.25}
rock_material: rock
joints:
  plane: {friction: )" +
         std::to_string(kFriction) + R"(, cohesion: 0}
default_joint: plane
faults:
  - {name: plane, center: [10, 5, -5.773502691896258], dip_direction: 90, dip: 30}
loads:
  gravity: 9.81
)" + pore +
         R"(supports:
  fixed: [bottom]
monitors:
  - {name: top, point: [15, 5, -1]}
analysis:
  blocks: {cutter: fast}
  dda: {mode: static, kinematics: rigid, steps: 300, time_step: 0.001}
  equilibrium: {max_steps: 300}
  strength_reduction: {factors: [1, 1.2, 1.4, 1.6, 1.8, 2.0, 2.2], tolerance: 0.02}
)";
}

TEST_F(WaterLoadsCli, BlockOnAnInclinedJointUnderAPhreaticLevel) {
  // Plane sliding with water in the joint (Hoek & Bray, Rock Slope Engineering, ch. 6; Wyllie
  // & Mah, ch. 6): FS = (W cos psi - U) tan phi / (W sin psi), U the water force on the joint:
  // hydrostatic below the level, zero above it. The joint runs from z = 0 to z = -20 tan psi;
  // below z = -4 it is wet over (z_wet / sin psi) x 10 m with a mean head z_wet / 2.
  const double psi = kPsi * kPi / 180.0;
  const double depth = 20.0 * std::tan(psi);
  const double weight = 2600.0 * kG * 0.5 * 20.0 * depth * 10.0;
  const double z_wet = kPhreatic + depth;  // the wet height of the joint (m)
  const double uplift = kGammaW * 10.0 * (z_wet / std::sin(psi)) * z_wet / 2.0;
  const double wet = (weight * std::cos(psi) - uplift) * kFriction / (weight * std::sin(psi));
  const double dry = kFriction / std::tan(psi);
  ASSERT_GT(uplift, 0.15 * weight * std::cos(psi));  // the water matters: 22 % of N

  const nlohmann::json w =
      summaryOf("strength", "wet", inclineScene("  pore_pressure:\n    - {level: -4.0}\n"));
  ASSERT_TRUE(w["safety_factor"].is_number()) << w.dump(2);
  // The issue's 2 % (bisection to 0.02: 1.3 % of FS).
  EXPECT_NEAR(w["safety_factor"].get<double>(), wet, 0.02 * wet);
  test::recordFactor(
      "Water loads", "block on a 30 deg joint, phreatic level 4 m below the crest: critical SRF",
      "FS = (W cos psi - U) tan phi / (W sin psi) (Hoek & Bray, Rock Slope Engineering, ch. 6)",
      wet, w["safety_factor"].get<double>(), 0.02);
  // Both sides of the joint carry the pressure: two entries, one per face.
  EXPECT_EQ(w["pressures"].get<int>(), 2);

  const nlohmann::json d = summaryOf("strength", "dry", inclineScene(""));
  ASSERT_TRUE(d["safety_factor"].is_number()) << d.dump(2);
  EXPECT_NEAR(d["safety_factor"].get<double>(), dry, 0.02 * dry);
  test::recordFactor("Incline: sliding and toppling", "the same block, dry: critical SRF",
                     "FS = tan phi / tan psi (Hoek & Bray, ch. 6)", dry,
                     d["safety_factor"].get<double>(), 0.02);
}

// ---------------------------------------------------------------------------------------
// A tetrahedral wedge with water in both joints.

/// Upward unit normal of a plane of dip direction `dd` and dip `dip` (degrees).
Vec3 planeNormal(double dd, double dip) {
  const double a = dd * kPi / 180.0, d = dip * kPi / 180.0;
  return {std::sin(d) * std::sin(a), std::sin(d) * std::cos(a), std::cos(d)};
}

/// Water force gw * integral of max(0, level - z) over a planar polygon (clipped at the level:
/// the pressure is linear on the wet part, so its mean is its value at the wet centroid).
double waterForce(const std::vector<Vec3>& polygon, double level) {
  std::vector<Vec3> wet;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Vec3& a = polygon[k];
    const Vec3& b = polygon[(k + 1) % polygon.size()];
    if (a.z() <= level) wet.push_back(a);
    if ((a.z() <= level) != (b.z() <= level)) {
      wet.push_back(a + (level - a.z()) / (b.z() - a.z()) * (b - a));
    }
  }
  double force = 0.0;
  for (std::size_t k = 1; k + 1 < wet.size(); ++k) {
    const double area = 0.5 * (wet[k] - wet[0]).cross(wet[k + 1] - wet[0]).norm();
    const double z = (wet[0].z() + wet[k].z() + wet[k + 1].z()) / 3.0;
    force += kGammaW * area * (level - z);
  }
  return force;
}

/// The wedge of planes A (45/105) and B (70/235) through (16, 12, 20) on the top of a
/// 40 x 30 x 20 m box, daylighting in the free south face (y = 0); phi = 35 deg, c = 0;
/// `pore`: the pore_pressure entries.
std::string wedgeScene(const std::string& pore) {
  return R"(version: 1
name: wedge
seed: 1
domain:
  box: {min: [0, 0, 0], max: [40, 30, 20]}
materials:
  rock: {unit_weight: 26.0e3, young: 10.0e9, poisson: 0.25}
rock_material: rock
joints:
  rj: {friction_angle: 35, cohesion: 0}
default_joint: rj
faults:
  - {name: A, center: [16, 12, 20], dip_direction: 105, dip: 45}
  - {name: B, center: [16, 12, 20], dip_direction: 235, dip: 70}
loads:
  gravity: 9.81
)" + pore +
         R"(supports:
  fixed: [bottom, west, east, north]
monitors:
  - {name: W, point: [18.5, 3, 18]}
analysis:
  blocks: {cutter: fast}
  dda: {mode: static, kinematics: rigid, steps: 150, time_step: 0.002}
  strength_reduction: {factors: [0.6, 0.8, 1.0, 1.2, 1.4, 1.6, 1.8, 2.0], tolerance: 0.02}
)";
}

TEST_F(WaterLoadsCli, WedgeWithWaterInBothJoints) {
  // Hoek & Bray, Rock Slope Engineering (ch. 7, wedge failure with water pressure), as
  // SWedge computes it: W + (N_A + U_A) n_A + (N_B + U_B) n_B + T s = 0 along the line of
  // intersection s, FS = (N_A + N_B) tan phi / T with the effective normal forces N and the
  // water forces U of each joint face (hydrostatic below the level z = 18.5, 1.5 m under the
  // crest; the faces are clipped at it).
  const Vec3 p0(16, 12, 20);
  const Vec3 na = planeNormal(105, 45), nb = planeNormal(235, 70);
  const auto onTopSouth = [&](const Vec3& n) {
    return Vec3(p0.x() + n.y() * p0.y() / n.x(), 0.0, 20.0);
  };
  Vec3 s = na.cross(nb).normalized();
  if (s.z() > 0) s = -s;
  const Vec3 daylight = p0 + (-p0.y() / s.y()) * s;
  const Vec3 ta = onTopSouth(na), tb = onTopSouth(nb);
  const double volume = std::abs((ta - p0).cross(tb - p0).dot(daylight - p0)) / 6.0;
  Eigen::Matrix3d m;
  m << na, nb, s;
  const Vec3 r = m.colPivHouseholderQr().solve(Vec3(0, 0, 26.0e3 * volume));  // (N_A, N_B, T)
  constexpr double kLevel = 18.5;
  const double u_a = waterForce({p0, ta, daylight}, kLevel);
  const double u_b = waterForce({p0, tb, daylight}, kLevel);
  const double tan_phi = std::tan(35.0 * kPi / 180.0);
  const double dry = (r[0] + r[1]) * tan_phi / -r[2];
  const double wet = (r[0] - u_a + r[1] - u_b) * tan_phi / -r[2];
  ASSERT_GT(r[0] - u_a, 0.0);  // still on both planes
  ASSERT_GT(r[1] - u_b, 0.0);
  ASSERT_LT(wet, 0.85 * dry);  // the water takes a real share

  const nlohmann::json w =
      summaryOf("strength", "wedge-wet", wedgeScene("  pore_pressure:\n    - {level: 18.5}\n"));
  ASSERT_TRUE(w["safety_factor"].is_number()) << w.dump(2);
  EXPECT_NEAR(w["safety_factor"].get<double>(), wet, 0.03 * wet);  // the issue's 3 %
  test::recordFactor(
      "Wedges",
      "wedge 45/105 and 70/235 deg, phi = 35 deg, water to 1.5 m below the crest: critical SRF",
      "FS = (N_A + N_B) tan phi / T with N = N_dry - U (Hoek & Bray, Rock Slope Engineering, "
      "ch. 7; SWedge)",
      wet, w["safety_factor"].get<double>(), 0.03);
  const nlohmann::json d = summaryOf("strength", "wedge-dry", wedgeScene(""));
  ASSERT_TRUE(d["safety_factor"].is_number()) << d.dump(2);
  EXPECT_NEAR(d["safety_factor"].get<double>(), dry, 0.03 * dry);
  test::recordFactor("Wedges", "the same wedge, dry: critical SRF",
                     "FS = (N_A + N_B) tan phi / T (Hoek & Bray, ch. 7)", dry,
                     d["safety_factor"].get<double>(), 0.03);
}

// ---------------------------------------------------------------------------------------
// A gravity dam with the uplift diagram and a drainage curtain.

/// A dam of section (0,0) (8,0) (2,6) (0,6), 4 m wide, 2400 kg/m3, on a fixed slab, water to
/// the crest (6 m) on its upstream face, the joint f = 0.6, c = 30 kPa (plastic). `pore`: the
/// pore_pressure entries.
std::string damScene(const std::string& pore, const std::string& water_extra = "") {
  return R"(version: 1
name: dam
seed: 1
domain:
  box: {min: [-4, -2, -2], max: [12, 6, 0]}
materials:
  rock: {density: 2400, young: 20.0e9, poisson: 0.2}
  concrete: {density: 2400, young: 20.0e9, poisson: 0.2}
rock_material: rock
joints:
  rj: {friction: 0.6, cohesion: 0}
default_joint: rj
structures:
  - name: dam
    prism: {profile: [[0, 0], [8, 0], [2, 6], [0, 6]], sweep: y, from: 0, to: 4}
    material: concrete
    joint: {friction: 0.6, cohesion: 30000}
loads:
  gravity: 9.81
  water:
    - {level: 6.0)" +
         water_extra + R"(, on: {structure: dam, facing: [-1, 0, 0]}}
)" + pore +
         R"(supports:
  fixed: [bottom]
monitors:
  - {name: crest, point: [0.5, 2, 5.5]}
analysis:
  blocks: {cutter: fast}
  dda: {mode: static, kinematics: rigid, steps: 300, time_step: 0.001}
  equilibrium: {max_steps: 300}
  overload: {factors: [0.5, 1, 1.5, 2, 2.5, 3, 3.5, 4], scales: [water], tolerance: 0.02}
)";
}

const std::string kDrainedDiagram = R"(  pore_pressure:
    - uplift_diagram:
        structure: dam
        upstream_level: 6.0
        downstream_level: 0.0
        flow: [1, 0, 0]
        drains: {distance: 2.0, efficiency: 0.5}
)";

TEST_F(WaterLoadsCli, DamWithAnUpliftDiagramAndADrainageCurtain) {
  // USBR, Design of Small Dams, ch. 8, and USACE EM 1110-2-2200: the head at the heel is the
  // reservoir's (6 m above the base), at the toe the tailwater's (0), and at the drain line
  // 2 m downstream of the heel tailwater + (1 - E) (reservoir - tailwater) = 3 m for E = 0.5;
  // linear between. U = gw * 4 m * ((6 + 3) / 2 * 2 + (3 + 0) / 2 * 6) = 706 kN (against
  // 1884 kN of full uplift). Shear-friction factor K = (f (W - U) + c A) / H.
  const double weight = 2400.0 * kG * 0.5 * (8.0 + 2.0) * 6.0 * 4.0;
  const double uplift = kGammaW * 4.0 * ((6.0 + 3.0) / 2.0 * 2.0 + 3.0 / 2.0 * 6.0);
  const double thrust = 0.5 * kGammaW * 36.0 * 4.0;
  const double expected = (0.6 * (weight - uplift) + 30.0e3 * 8.0 * 4.0) / thrust;  // 3.16
  const nlohmann::json s = summaryOf("overload", "drained", damScene(kDrainedDiagram));
  ASSERT_TRUE(s["safety_factor"].is_number()) << s.dump(2);
  EXPECT_NEAR(s["safety_factor"].get<double>(), expected, 0.02 * expected);
  test::recordFactor(
      "Dams",
      "dam 8/2/6 m, f = 0.6, c = 30 kPa, uplift diagram with drains 2 m from the heel "
      "(E = 0.5): overload factor K_s",
      "K = (f (W - U) + c A) / H, U from the USBR uplift diagram (Design of Small Dams, ch. 8; "
      "USACE EM 1110-2-2200)",
      expected, s["safety_factor"].get<double>(), 0.02);
  // The summary's uplift on the dam's base: the diagram's U, upward (the pressure is linear:
  // its integral is exact).
  ASSERT_EQ(s["uplift"].size(), 1u) << s.dump(2);
  EXPECT_EQ(s["uplift"][0]["structure"], "dam");
  EXPECT_NEAR(s["uplift"][0]["vertical"].get<double>(), uplift, 1e-9 * uplift);
  EXPECT_NEAR(s["uplift"][0]["force"][0].get<double>(), 0.0, 1e-9 * uplift);
  // A vertical joint in the rock right under the middle of the base (x = 4): the interface is
  // found on both sides of it, not only where the base's centre meets unjointed rock.
  std::string jointed = damScene(kDrainedDiagram);
  jointed.replace(jointed.find("structures:"), 11,
                  "faults:\n  - {name: F, center: [4, 2, -1], dip_direction: 90, dip: 90}\n"
                  "structures:");
  jointed.replace(jointed.find("steps: 300"), 10, "steps: 1");
  const nlohmann::json j = summaryOf("dda", "jointed", jointed);
  ASSERT_EQ(j["uplift"].size(), 1u) << j.dump(2);
  EXPECT_NEAR(j["uplift"][0]["vertical"].get<double>(), uplift, 1e-9 * uplift);
}

TEST_F(WaterLoadsCli, BadPorePressureFieldsAreRefusedAtTheirKey) {
  // No head: neither a level nor a diagram.
  {
    const std::string scene = damScene("  pore_pressure:\n    - {unit_weight: 9810}\n");
    const std::string out = refusal("overload", "no-level", scene);
    EXPECT_NE(out.find(":" + std::to_string(lineOf(scene, "{unit_weight: 9810}")) + ":"),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("expected 'level' or 'uplift_diagram'"), std::string::npos) << out;
  }
  // Drains downstream of the toe (the base is 8 m long).
  {
    std::string scene = damScene(kDrainedDiagram);
    scene.replace(scene.find("distance: 2.0"), 13, "distance: 9.0");
    const std::string out = refusal("overload", "drain-outside", scene);
    EXPECT_NE(out.find(":" + std::to_string(lineOf(scene, "distance: 9.0")) + ":"),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("outside the structure 'dam'"), std::string::npos) << out;
  }
  // The field and `uplift: true` on the same interface: a double count.
  {
    const std::string scene = damScene(kDrainedDiagram, ", uplift: true");
    const std::string out = refusal("overload", "twice", scene);
    EXPECT_NE(out.find("the uplift would count twice"), std::string::npos) << out;
    EXPECT_NE(out.find("loads.water"), std::string::npos) << out;
  }
  // Two fields over the same faces.
  {
    const std::string scene =
        damScene("  pore_pressure:\n    - {level: 1.0}\n    - {level: 2.0, region: {x_min: 4}}\n");
    const std::string out = refusal("overload", "overlap", scene);
    EXPECT_NE(out.find("entries 1 and 2 act on the same faces"), std::string::npos) << out;
  }
}

// ---------------------------------------------------------------------------------------
// Bolts and anchors.

/// The block on the 30 deg joint above, the joint frictionless, held by one anchor from
/// (12, 5, -4) in the block to (6, 5, -8) in the rock below; `steel`: the bolt's stiffness
/// and forces; `analysis`: the analysis section's body.
std::string boltedScene(const std::string& steel, const std::string& analysis) {
  std::string scene = inclineScene("");
  scene.replace(scene.find("friction: " + std::to_string(kFriction)),
                ("friction: " + std::to_string(kFriction)).size(), "friction: 0");
  scene.replace(scene.find("analysis:\n"), std::string::npos, "analysis:\n" + analysis);
  return scene + "bolts:\n  - {name: B1, head: [12, 5, -4], end: [6, 5, -8], " + steel + "}\n";
}

/// Damped dynamic runs (the equilibrium's dynamic ratio 0.95): a static run loads a bolt
/// 1e-6 m a step, far too slowly for a 3000 t block.
const std::string kAtRest = R"(  blocks: {cutter: fast}
  dda: {mode: dynamic, kinematics: rigid, steps: 300, time_step: 0.002}
  equilibrium: {max_steps: 1000}
  strength_reduction: {factors: [1.0], tolerance: 0.01}
)";

TEST_F(WaterLoadsCli, AnAnchoredBlockHoldsAtTheStaticForceAndSlidesWhenItsBoltBreaks) {
  // Statics of a frictionless block on a plane held by an anchor along d (Hoek & Bray, Rock
  // Slope Engineering, ch. 6, "reinforcement"): along the down-dip direction t, W sin psi +
  // F d . t = 0, so F = W sin psi / (-d . t); the anchor also presses the block on the plane.
  const double psi = kPsi * kPi / 180.0;
  const double weight = 2600.0 * kG * 0.5 * 20.0 * 20.0 * std::tan(psi) * 10.0;
  const Vec3 d = Vec3(-6.0, 0.0, -4.0).normalized();
  const Vec3 t(std::cos(psi), 0.0, -std::sin(psi));
  const double force = weight * std::sin(psi) / -d.dot(t);  // 33.2 MN
  const nlohmann::json held =
      summaryOf("strength", "anchored", boltedScene("stiffness: 1.0e10", kAtRest));
  const nlohmann::json& run = held["strength_reduction"]["runs"][0];
  ASSERT_TRUE(run["at_rest"].get<bool>()) << held.dump(2);
  EXPECT_NEAR(run["bolts"]["largest_force"].get<double>(), force, 0.02 * force);  // the issue's
  EXPECT_EQ(run["bolts"]["broken"].get<int>(), 0);
  test::recordVerification(
      {.group = "Bolts and fixed points",
       .name = "frictionless block on a 30 deg joint held by one anchor: anchor force at rest",
       .source = "F = W sin psi / (-d . t) (statics; Hoek & Bray, Rock Slope Engineering, ch. 6)",
       .expected = force,
       .measured = run["bolts"]["largest_force"].get<double>(),
       .tolerance = 0.02,
       .relative = true,
       .unit = "N"});
  // A rupture force below it: the bolt breaks and the block slides (not at rest).
  const nlohmann::json broke = summaryOf(
      "strength", "broken",
      boltedScene("stiffness: 1.0e10, rupture_force: " + std::to_string(0.8 * force), kAtRest));
  const nlohmann::json& failed = broke["strength_reduction"]["runs"][0];
  EXPECT_FALSE(failed["at_rest"].get<bool>()) << broke.dump(2);
  EXPECT_EQ(failed["bolts"]["broken"].get<int>(), 1);
}

TEST_F(WaterLoadsCli, ABoltPatternGivesTheBoltsItDeclaresAndTheirForcesEveryStep) {
  // A 3 x 4 pattern across the joint, 1.5 m by 2 m, each 10 m long along (-1, 0, -1).
  std::string scene = boltedScene("stiffness: 1.0e9", R"(  blocks: {cutter: fast}
  dda: {mode: static, kinematics: rigid, steps: 3, time_step: 0.001}
)");
  scene += R"(bolt_patterns:
  - {name: P, origin: [14, 2, -3], along: [1.5, 0, 0], across: [0, 2, 0], count: [3, 4],
     direction: [-1, 0, -1], length: 10, stiffness: 1.0e8, pretension: 1.0e5}
)";
  const nlohmann::json s = summaryOf("dda", "pattern", scene);
  const nlohmann::json& bolts = s["bolts"];
  ASSERT_EQ(bolts.size(), 1u + 12u) << s.dump(2);  // B1, then the pattern row by row
  const double l = 10.0 / std::sqrt(2.0);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) {
      const nlohmann::json& b = bolts[static_cast<std::size_t>(1 + 4 * i + j)];
      EXPECT_EQ(b["name"], "P." + std::to_string(i + 1) + "." + std::to_string(j + 1));
      const Vec3 head(14.0 + 1.5 * i, 2.0 + 2.0 * j, -3.0);
      for (int k = 0; k < 3; ++k) {
        EXPECT_DOUBLE_EQ(b["head"][static_cast<std::size_t>(k)].get<double>(), head[k]);
      }
      EXPECT_NEAR(b["end"][0].get<double>(), head.x() - l, 1e-12);
      EXPECT_NEAR(b["end"][2].get<double>(), head.z() - l, 1e-12);
      EXPECT_EQ(b["state"], "intact");
    }
  }
  // bolts.csv: the header, then every bolt at t = 0 and after each of the 3 steps.
  const std::string csv = test::readFile(dir.path() / "pattern" / "bolts.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 4 * 13);
  EXPECT_EQ(csv.rfind("time,bolt,force,state\n0,B1,0,intact\n", 0), 0u) << csv.substr(0, 80);
}

TEST_F(WaterLoadsCli, BadBoltsAreRefusedAtTheirKey) {
  // An end above the domain, in no block.
  {
    std::string scene = boltedScene("stiffness: 1.0e9", kAtRest);
    scene.replace(scene.find("end: [6, 5, -8]"), 15, "end: [6, 5, 8]");
    const std::string out = refusal("strength", "no-block", scene);
    EXPECT_NE(out.find(":" + std::to_string(lineOf(scene, "{name: B1")) + ":"), std::string::npos)
        << out;
    EXPECT_NE(out.find("bolt B1: its end (6, 5, 8) lies in no block"), std::string::npos) << out;
  }
  // Both a yield and a rupture force: a yielding bolt would never reach the rupture force.
  {
    const std::string scene =
        boltedScene("stiffness: 1.0e9, yield_force: 1.0e6, rupture_force: 2.0e6", kAtRest);
    const std::string out = refusal("strength", "yield-and-rupture", scene);
    EXPECT_NE(out.find(":" + std::to_string(lineOf(scene, "{name: B1")) + ":"), std::string::npos)
        << out;
    EXPECT_NE(out.find("give yield_force or rupture_force, not both"), std::string::npos) << out;
  }
  // A negative stiffness.
  {
    const std::string scene = boltedScene("stiffness: -1.0e9", kAtRest);
    const std::string out = refusal("strength", "negative", scene);
    EXPECT_NE(out.find(":" + std::to_string(lineOf(scene, "stiffness: -1.0e9")) + ":"),
              std::string::npos)
        << out;
    EXPECT_NE(out.find("stiffness"), std::string::npos) << out;
  }
}

// ---------------------------------------------------------------------------------------
// A pseudo-static earthquake.

TEST_F(WaterLoadsCli, ABlockOnAPlaneSlidesAtTheCriticalSeismicCoefficient) {
  // Pseudo-static sliding of a block on a horizontal frictional plane (Kramer, Geotechnical
  // Earthquake Engineering, ch. 10; Newmark 1965): k_h W = f (W - k_v W) at the critical
  // coefficients. The overload method scales the earthquake as a whole (scales: [seismic]:
  // k_h and k_v together) from k_h = k_v = 0.1: K 0.1 = f (1 - K 0.1), K_s = f / (0.1 (1 + f))
  // = 3.75 with f = 0.6. A squat 20 x 20 x 10 m block: overturning needs k_h near 2.
  const std::string scene = R"(version: 1
name: seismic-block
seed: 1
domain:
  box: {min: [0, 0, -20], max: [100, 20, 0]}
materials:
  rock: {unit_weight: 26.0e3, young: 7.0e9, poisson: 0.25}
  concrete: {unit_weight: 24.0e3, young: 17.6e9, poisson: 0.167}
rock_material: rock
joints:
  rj: {friction: 0.6, cohesion: 0}
default_joint: rj
structures:
  - name: block
    prism: {profile: [[40, 0], [60, 0], [60, 10], [40, 10]], sweep: y, from: 0, to: 20}
    material: concrete
    joint: {friction: 0.6, cohesion: 0}
loads:
  gravity: 9.81
  seismic: {k_h: 0.1, direction: [1, 0, 0], k_v: 0.1}
supports:
  fixed: [bottom]
monitors:
  - {name: M, point: [50, 10, 5]}
analysis:
  blocks: {cutter: fast}
  dda: {mode: static, kinematics: rigid, steps: 150, time_step: 0.002}
  overload: {factors: [1, 2, 3, 4, 5], scales: [seismic], tolerance: 0.05}
)";
  const double expected = 0.6 / (0.1 * (1.0 + 0.6));
  const nlohmann::json s = summaryOf("overload", "seismic", scene);
  ASSERT_TRUE(s["safety_factor"].is_number()) << s.dump(2);
  // The issue's 2 % (bisection to 0.05: 1.3 % of K).
  EXPECT_NEAR(s["safety_factor"].get<double>(), expected, 0.02 * expected);
  test::recordFactor(
      "Earthquakes",
      "block on a horizontal plane (f = 0.6), k_h = k_v = 0.1 (upward) scaled together: "
      "overload factor K_s",
      "k_h = f (1 - k_v) at sliding (pseudo-static; Kramer, Geotechnical Earthquake "
      "Engineering, ch. 10)",
      expected, s["safety_factor"].get<double>(), 0.02);
}

}  // namespace
}  // namespace rockmass
