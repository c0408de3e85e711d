// Textbook cases of the verification manual (docs/verification.md, issue 15) that the other
// dda3d tests do not cover, each through dda3d::Simulation and recorded in the manual:
// - toppling on an incline without sliding (Wyllie & Mah, Rock Slope Engineering, 4th ed.,
//   2004, ch. 9; Goodman & Bray 1976): a block b x h on a plane of dip psi with phi > psi
//   topples when b / h < tan psi and rests when b / h > tan psi; while it pivots on its
//   downslope edge its rotation follows the rigid-body equation about that edge;
// - a train of two blocks on one plane with different friction angles (Coulomb friction,
//   the blocks moving together: Hoek & Bray, Rock Slope Engineering, 3rd ed., 1981, ch. 6 on
//   a block pushed by another): a = g (sin psi - (W1 f1 + W2 f2) / (W1 + W2) cos psi) when
//   positive, else at rest;
// - slivers of 1:100 and 1:1000 of the width in a column of boxes (and the column without
//   one), rigid and deformable, nu = 0 and 0.25,
//   static and dynamic: settled with no NaN, the sliver in place, and the elastic settlement
//   of the top rho g H^2 / (2 E) (uniaxial stress under its own weight, free sides: any nu;
//   Timoshenko & Goodier, Theory of Elasticity);
// - the wedge of the other tests with water in its two joints (Hoek & Bray 1981, ch. 7;
//   Wyllie & Mah 2004, ch. 7): FS = ((N_A - U_A) tan phi + (N_B - U_B) tan phi) / |w . s|,
//   U_A, U_B the water forces on the two faces integrated exactly here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "dda3d/simulation.h"
#include "dda3d/stability.h"
#include "scenarios/dda_scenes.h"
#include "tests/support/verification.h"

namespace rockmass::dda3d {
namespace {

using geometry::Vec3;
constexpr double kG = 9.81;
constexpr double kGammaW = 9810.0;
using scenes::degrees;
using scenes::radians;

/// Angle (deg) through which a box block has turned: its vertical edge v4 - v0 (boxPolyhedron)
/// against the initial one.
double turned(const Simulation& sim, int block) {
  const auto& v = sim.blocks()[static_cast<std::size_t>(block)].pieces[0].vertices;
  const Vec3 edge = (v[4] - v[0]).normalized();
  return degrees(std::acos(std::clamp(edge.dot(Vec3::UnitZ()), -1.0, 1.0)));
}

// ---------------------------------------------------------------------------------------
// Toppling without sliding.

/// Rotation (rad) at time `t` of a rigid block b x h pivoting from rest on its downslope
/// bottom edge on a plane of dip psi: I theta'' = m g ((h/2) sin(psi + theta) - (b/2)
/// cos(psi + theta)), I = m (b^2 + h^2) / 3 about the edge; 4th-order Runge-Kutta, 1e-5 s.
double pivotRotation(double b, double h, double psi, double t) {
  const auto acceleration = [&](double theta) {
    return 3.0 * kG / (b * b + h * h) *
           (0.5 * h * std::sin(psi + theta) - 0.5 * b * std::cos(psi + theta));
  };
  double theta = 0.0, omega = 0.0;
  const int n = static_cast<int>(std::lround(t / 1e-5));
  const double dt = t / n;
  for (int k = 0; k < n; ++k) {
    const double k1t = omega, k1w = acceleration(theta);
    const double k2t = omega + 0.5 * dt * k1w, k2w = acceleration(theta + 0.5 * dt * k1t);
    const double k3t = omega + 0.5 * dt * k2w, k3w = acceleration(theta + 0.5 * dt * k2t);
    const double k4t = omega + dt * k3w, k4w = acceleration(theta + dt * k3t);
    theta += dt / 6.0 * (k1t + 2 * k2t + 2 * k3t + k4t);
    omega += dt / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
  }
  return theta;
}

TEST(VerificationToppling, BlockToppleWhenNarrowerThanTanPsiAndRestsWhenWider) {
  // Wyllie & Mah, ch. 9 (Figure 9.2): psi = 20 deg, phi = 35 deg > psi (no sliding);
  // tan psi = 0.364. b / h = 0.25 topples, b / h = 0.5 rests.
  constexpr double kPsi = 20.0, kPhi = 35.0, kHeight = 1.0, kTime = 0.6;
  const std::string source =
      "toppling when b/h < tan psi, no sliding when phi > psi (Wyllie & Mah, Rock Slope "
      "Engineering, 2004, ch. 9)";
  for (const double width : {0.25, 0.5}) {
    const bool topples = width / kHeight < std::tan(radians(kPsi));
    DdaModel model;
    scenes::setRock(model, kPhi);
    model.blocks.push_back(scenes::boxBlock({-4, -2, -1}, {4, 2, 0}, 0, true));
    model.blocks.push_back(scenes::boxBlock({-1, -0.5, 0}, {-1 + width, 0.5, kHeight}, 0, false));
    model.gravity = kG * Vec3(std::sin(radians(kPsi)), 0.0, -std::cos(radians(kPsi)));
    DdaSettings settings;
    settings.kinematics = Kinematics::Rigid;
    settings.time_step = 1e-3;
    Simulation sim(model, settings);
    sim.runUntil(kTime);
    const double angle = turned(sim, 1);
    if (topples) {
      // While it pivots on its edge the rigid-body equation gives the rotation; the DDA block
      // starts on contact springs (its edge sinks ~1e-8 m), so only the timing can differ:
      // 3 % of the angle, which is ~10 deg at 0.6 s.
      const double expected = degrees(pivotRotation(width, kHeight, radians(kPsi), sim.time()));
      EXPECT_NEAR(angle, expected, 0.03 * expected);
      test::recordVerification(
          {.group = "Incline: sliding and toppling",
           .name = "block b/h = 0.25 on psi = 20 deg, phi = 35 deg, topples: rotation at 0.6 s",
           .source = source + "; pivoting on its edge, I theta'' = m g ((h/2) sin(psi + theta) "
                              "- (b/2) cos(psi + theta))",
           .expected = expected,
           .measured = angle,
           .tolerance = 0.03,
           .relative = true,
           .unit = "deg"});
      // It pivots, it does not slide: the pivot edge stays where it was (the springs' shear).
      const auto& v = sim.blocks()[1].pieces[0].vertices;
      const Vec3 pivot = 0.5 * (v[1] + v[3]);  // x = max, z = 0: the downslope bottom edge
      EXPECT_LT((pivot - Vec3(-1 + width, 0, 0)).norm(), 1e-4);
    } else {
      // At rest: the springs' tilt only (~1e-6 deg), and no sliding (phi > psi).
      EXPECT_LT(angle, 0.01);
      EXPECT_LT(sim.centroidDisplacement(1).norm(), 1e-6);
      test::recordVerification({.group = "Incline: sliding and toppling",
                                .name = "block b/h = 0.5 on psi = 20 deg, phi = 35 deg, rests: "
                                        "rotation at 0.6 s",
                                .source = source,
                                .expected = 0.01,
                                .measured = angle,
                                .unit = "deg",
                                .compare = test::Compare::AtMost});
    }
  }
}

// ---------------------------------------------------------------------------------------
// A train of two blocks on one plane.

/// Two 1 m cubes side by side on a fixed slab tilted psi (downslope +x), the front one
/// (block 1, downslope) on a joint of friction angle phi_front, the rear one (block 2) on
/// phi_rear. The joint between the two cubes is frictionless, as the hand formula assumes: it
/// carries only the push along the slope, so each block keeps its own weight's normal
/// component on the plane. (With friction there the split of the normal load between the
/// two blocks is statically indeterminate for rigid blocks; with phi = 30 deg on that joint
/// the engine's springs put 12.6 % of W cos psi onto the front block and the pair below
/// accelerates at 0.90 m/s2, not 1.18.)
DdaModel trainOfTwo(double psi, double phi_front, double phi_rear) {
  DdaModel model;
  model.materials = {DdaMaterial{2600.0, 10e9, 0.25}, DdaMaterial{2600.0, 10e9, 0.25},
                     DdaMaterial{2600.0, 10e9, 0.25}};
  model.joints = {DdaJoint{std::tan(radians(phi_front))}, DdaJoint{std::tan(radians(phi_rear))},
                  DdaJoint{0.0}};
  model.blocks.push_back(scenes::boxBlock({-4, -2, -1}, {4, 2, 0}, 0, true));
  model.blocks.push_back(scenes::boxBlock({-1, -0.5, 0}, {0, 0.5, 1}, 1, false));   // front
  model.blocks.push_back(scenes::boxBlock({-2, -0.5, 0}, {-1, 0.5, 1}, 2, false));  // rear
  // Each cube's faces carry its joint to the slab, but for the faces the two cubes share
  // (the front's -x face, the rear's +x face), which carry the frictionless joint 2.
  const auto faceJoints = [](const DdaBlock& block, int joint, double shared_x) {
    const geometry::Polyhedron& p = block.pieces[0];
    std::vector<int> joints;
    for (const std::vector<int>& face : p.faces) {
      bool shared = true;
      for (int v : face) shared = shared && std::abs(p.vertices[v].x() - shared_x) < 1e-12;
      joints.push_back(shared ? 2 : joint);
    }
    return std::vector<std::vector<int>>{joints};
  };
  model.blocks[1].face_joints = faceJoints(model.blocks[1], 0, -1.0);
  model.blocks[2].face_joints = faceJoints(model.blocks[2], 1, -1.0);
  model.gravity = kG * Vec3(std::sin(radians(psi)), 0.0, -std::cos(radians(psi)));
  return model;
}

/// The pair's acceleration when it moves together: equal weights, so the mean of the two
/// friction coefficients.
double pairAcceleration(double psi, double phi_front, double phi_rear) {
  const double f = 0.5 * (std::tan(radians(phi_front)) + std::tan(radians(phi_rear)));
  return kG * (std::sin(radians(psi)) - f * std::cos(radians(psi)));
}

class VerificationTrain : public ::testing::TestWithParam<Kinematics> {};

TEST_P(VerificationTrain, PairSlidesWhenTheSumOfDrivingForcesExceedsTheSumOfResistances) {
  // psi = 30 deg; the front block alone would rest (phi 35 > 30), the rear one slides
  // (phi 10): together tan phi_mean = 0.438 < tan 30, a = 1.18 m/s2.
  constexpr double kPsi = 30.0, kFront = 35.0, kRear = 10.0;
  const double a = pairAcceleration(kPsi, kFront, kRear);
  ASSERT_GT(a, 0.0);
  DdaSettings settings;
  settings.kinematics = GetParam();
  settings.time_step = 1e-3;
  Simulation sim(trainOfTwo(kPsi, kFront, kRear), settings);
  sim.runUntil(0.5);
  const double t = sim.time();
  const double front = sim.centroidDisplacement(1).x(), rear = sim.centroidDisplacement(2).x();
  const double measured = 2.0 * front / (t * t);
  const bool rigid = GetParam() == Kinematics::Rigid;
  // The 2 %: the single block slides within 1 % (InclineSliding), the pair's forces
  // pass through one more contact (measured: +0.07 %).
  EXPECT_NEAR(measured, a, 0.02 * a);
  // Together: the rear block pushes, it does not fall behind or overtake (the contact's
  // springs, ~1e-7 m).
  EXPECT_NEAR(rear, front, 1e-4);
  test::recordVerification(
      {.group = "Trains of blocks",
       .name = std::string("two cubes, psi 30 deg, front phi 35 deg, rear phi 10 deg, ") +
               (rigid ? "rigid" : "deformable") + ": acceleration over 0.5 s",
       .source = "a = g (sin psi - (W1 tan phi1 + W2 tan phi2) / (W1 + W2) cos psi) (Coulomb, "
                 "blocks moving together, frictionless joint between them; Hoek & Bray 1981, "
                 "ch. 6)",
       .expected = a,
       .measured = measured,
       .tolerance = 0.02,
       .relative = true,
       .unit = "m/s2"});
}

TEST_P(VerificationTrain, PairRestsWhenTheSumOfResistancesExceedsTheSumOfDrivingForces) {
  // psi = 30 deg; the rear block alone would slide (phi 25 < 30) but pushes a front block on
  // phi 40: together tan phi_mean = 0.653 > tan 30 = 0.577: at rest.
  constexpr double kPsi = 30.0, kFront = 40.0, kRear = 25.0;
  ASSERT_LT(pairAcceleration(kPsi, kFront, kRear), 0.0);
  DdaSettings settings;
  settings.kinematics = GetParam();
  settings.time_step = 1e-3;
  Simulation sim(trainOfTwo(kPsi, kFront, kRear), settings);
  sim.runUntil(0.1);  // onto the contact springs
  const Vec3 settled = sim.centroidDisplacement(2);
  EXPECT_LT(settled.norm(), 1e-5);
  sim.runUntil(0.6);
  const double motion = (sim.centroidDisplacement(2) - settled).norm();
  // As InclineStable: < 1e-6 of the block size over the next 0.5 s.
  EXPECT_LT(motion, 1e-6);
  test::recordVerification(
      {.group = "Trains of blocks",
       .name = std::string("two cubes, psi 30 deg, front phi 40 deg, rear phi 25 deg, ") +
               (GetParam() == Kinematics::Rigid ? "rigid" : "deformable") +
               ": rear block's motion from 0.1 to 0.6 s",
       .source = "at rest when (W1 tan phi1 + W2 tan phi2) / (W1 + W2) > tan psi (Coulomb)",
       .expected = 0.0,
       .measured = motion,
       .tolerance = 1e-6,
       .unit = "m"});
}

INSTANTIATE_TEST_SUITE_P(Kinematics, VerificationTrain,
                         ::testing::Values(Kinematics::Rigid, Kinematics::Deformable),
                         [](const ::testing::TestParamInfo<Kinematics>& info) {
                           return std::string(info.param == Kinematics::Rigid ? "Rigid"
                                                                              : "Deformable");
                         });

struct TrainSetting {
  Kinematics kinematics;
  double time_step;       ///< s
  double penalty_factor;  ///< DdaSettings::penalty_factor
};

class VerificationTrainSettings : public ::testing::TestWithParam<TrainSetting> {};

TEST_P(VerificationTrainSettings, PairAccelerationDoesNotDependOnTheTimeStepOrThePenalty) {
  // The pushed pair of PairSlidesWhenTheSumOfDrivingForcesExceedsTheSumOfResistances, over
  // the time steps and penalties a user may choose. Before the contact fixes this checks,
  // the rigid pair slid 17 % too fast at 160 E l0 (a frictionless joint held 250 N of shear
  // per contact by the round-off allowance, moving weight from the front block to the rear
  // one), and the deformable pair lost 40-50 % at dt = 2.5e-4 s (its vibrating corners
  // closed 4e-6 m deep, the spring then threw the blocks: 113 J in one step).
  constexpr double kPsi = 30.0, kFront = 35.0, kRear = 10.0;
  const double a = pairAcceleration(kPsi, kFront, kRear);
  DdaSettings settings;
  settings.kinematics = GetParam().kinematics;
  settings.time_step = GetParam().time_step;
  settings.penalty_factor = GetParam().penalty_factor;
  Simulation sim(trainOfTwo(kPsi, kFront, kRear), settings);
  sim.runUntil(0.5);
  const double t = sim.time();
  const double front = sim.centroidDisplacement(1).x(), rear = sim.centroidDisplacement(2).x();
  // The 2 % of the issue; measured within 0.7 % over the whole range.
  EXPECT_NEAR(2.0 * front / (t * t), a, 0.02 * a);
  EXPECT_NEAR(rear, front, 1e-4);  // together, on the contact springs
}

INSTANTIATE_TEST_SUITE_P(Range, VerificationTrainSettings,
                         ::testing::Values(TrainSetting{Kinematics::Rigid, 1e-3, 10.0},
                                           TrainSetting{Kinematics::Rigid, 1e-3, 160.0},
                                           TrainSetting{Kinematics::Rigid, 2.5e-4, 160.0},
                                           TrainSetting{Kinematics::Deformable, 2e-3, 40.0},
                                           TrainSetting{Kinematics::Deformable, 1e-3, 160.0},
                                           TrainSetting{Kinematics::Deformable, 2.5e-4, 10.0},
                                           TrainSetting{Kinematics::Deformable, 2.5e-4, 160.0}),
                         [](const ::testing::TestParamInfo<TrainSetting>& info) {
                           const TrainSetting& p = info.param;
                           return std::string(p.kinematics == Kinematics::Rigid ? "Rigid"
                                                                                : "Deformable") +
                                  "_dt" + std::to_string(std::lround(p.time_step * 1e6)) +
                                  "us_penalty" + std::to_string(static_cast<int>(p.penalty_factor));
                         });

// ---------------------------------------------------------------------------------------
// Slivers in a column.

struct SliverCase {
  int ratio;  ///< width / thickness of the sliver: 100 or 1000; 0: no sliver (six cubes)
  Kinematics kinematics;
  AnalysisMode mode;
  double poisson = 0.0;  ///< nu of the blocks (rigid: irrelevant)
};

std::string sliverCaseName(const ::testing::TestParamInfo<SliverCase>& info) {
  const SliverCase& c = info.param;
  return (c.ratio > 0 ? "Ratio" + std::to_string(c.ratio) : std::string("NoSliver")) +
         (c.kinematics == Kinematics::Rigid ? "Rigid" : "Deformable") +
         (c.mode == AnalysisMode::Static ? "Static" : "Dynamic") +
         (c.poisson > 0.0 ? "Nu" + std::to_string(std::lround(100 * c.poisson)) : "");
}

class VerificationSliver : public ::testing::TestWithParam<SliverCase> {};

TEST_P(VerificationSliver, SettlesInPlaceWithTheElasticSettlement) {
  // Three 1 m cubes on a fixed slab (blocks 1-3), a 1 m x 1 m sliver of thickness 1/ratio m
  // on them (block 4), three 1 m cubes on top (blocks 5-7): H = 6 + 1/ratio m; E = 1 GPa,
  // nu = 0 or 0.25 (a rock's), rho = 2600 kg/m3. Without a sliver (ratio 0): the six cubes
  // alone (blocks 1-6), the reference column. Static: 300 steps of 10 ms (as ElasticColumn);
  // dynamic (fully, Bossak): 500 steps of 1 ms (0.5 s unless the step control cuts dt).
  const SliverCase c = GetParam();
  constexpr double kYoung = 1e9, kDensity = 2600.0;
  const bool has_sliver = c.ratio > 0;
  const int kSliver = has_sliver ? 4 : -1;
  const double thickness = has_sliver ? 1.0 / c.ratio : 0.0;
  const double height = 6.0 + thickness;
  DdaModel model;
  scenes::setRock(model, 30.0, kYoung, c.poisson, kDensity);
  model.blocks.push_back(scenes::boxBlock({-2, -2, -1}, {2, 2, 0}, 0, true));
  double z = 0.0;
  for (int k = 0; k < 7; ++k) {
    const double h = k == 3 ? thickness : 1.0;
    if (h == 0.0) continue;
    model.blocks.push_back(scenes::boxBlock({-0.5, -0.5, z}, {0.5, 0.5, z + h}, 0, false));
    z += h;
  }
  const int top = static_cast<int>(model.blocks.size()) - 1;
  model.monitors.push_back({"top", Vec3(0, 0, height), top});
  // The block watched for lateral motion: the sliver, or the column's farthest-moved cube.
  const auto lateralMotion = [&](const Simulation& s) {
    if (has_sliver) return s.centroidDisplacement(kSliver).head<2>().norm();
    double most = 0.0;
    for (int b = 1; b <= top; ++b)
      most = std::max(most, s.centroidDisplacement(b).head<2>().norm());
    return most;
  };
  model.gravity = Vec3(0, 0, -kG);
  DdaSettings settings;
  settings.kinematics = c.kinematics;
  settings.mode = c.mode;
  settings.time_step = c.mode == AnalysisMode::Static ? 0.01 : 1e-3;
  Simulation sim(model, settings);
  const int steps = c.mode == AnalysisMode::Static ? 300 : 500;
  // Fully dynamic, the column rings about its static settlement (gravity applied at once; the
  // axial period 4 H / sqrt(E / rho) = 39 ms is barely damped by the scheme at dt = 1 ms), so
  // the settlement compared with the static hand value is the mean over the last 200 steps
  // (5 periods); static runs take the last step's.
  const int averaged = c.mode == AnalysisMode::Static ? 1 : 200;
  double settlement_sum = 0.0, time_sum = 0.0;
  for (int k = 0; k < steps; ++k) {
    StepReport r;
    try {
      r = sim.step();
    } catch (const StepFailure& e) {
      // The step control could not complete a step even at the minimum dt: the run has
      // failed. Stop there and say where; the values below are where it stopped.
      ADD_FAILURE() << "step " << k << ": " << e.what() << "; lateral motion " << lateralMotion(sim)
                    << " m";
      settlement_sum = -sim.monitors()[0].displacement.z();
      time_sum = 1.0;
      break;
    }
    bool finite = true;
    for (const BlockState& b : sim.blocks()) {
      for (const Vec3& v : b.pieces[0].vertices) finite = finite && v.allFinite();
    }
    ASSERT_TRUE(finite) << "step " << k << " at t = " << sim.time();
    if (k >= steps - averaged) {
      settlement_sum += -sim.monitors()[0].displacement.z() * r.time_step;
      time_sum += r.time_step;
    }
  }
  const std::string group = has_sliver ? "Slivers in stacks" : "Deformable column";
  const std::string name =
      (has_sliver ? "column of 3 + 3 cubes of 1 m, 1:" + std::to_string(c.ratio) + " sliver, "
                  : std::string("column of 6 cubes of 1 m, ")) +
      (c.kinematics == Kinematics::Rigid ? "rigid" : "deformable") +
      (c.poisson > 0.0 ? " nu 0.25" : "") + ", " +
      (c.mode == AnalysisMode::Static ? "static" : "dynamic");
  // The sliver (or every cube) stays in place: < 1 mm sideways (the bound).
  const double lateral = lateralMotion(sim);
  EXPECT_LT(lateral, 1e-3);
  test::recordVerification(
      {.group = group,
       .name = name + (has_sliver ? ": sliver's lateral displacement"
                                  : ": largest lateral displacement of a cube"),
       .source = "symmetric column under gravity: no lateral motion",
       .expected = 1e-3,
       .measured = lateral,
       .unit = "m",
       .compare = test::Compare::AtMost});
  const double settlement = settlement_sum / time_sum;  // time-weighted mean
  if (c.kinematics == Kinematics::Deformable) {
    // Each block's one uniform strain is its mean strain rho g (H - z_mid) / E (uniaxial stress:
    // the sides are free, so nu only widens the blocks), so the strains add up to
    // rho g H^2 / (2 E) exactly (the midpoint rule is exact for the linear stress). With
    // nu > 0 the blocks widen by nu times their strain, more at the bottom; where friction
    // holds the interfaces to one width, the lateral stresses that takes sum to zero over the
    // height, and so does their effect on the total settlement. The top also sinks by the
    // interfaces' contact springs (~3e-6 m, ~0.6 % here), not in the hand value: 2 %.
    // Static with nu > 0, the interfaces stick from the first step (a contact whose slip
    // turns back against its friction sticks), and the bottom cube, one uniform strain held
    // at its base by the fixed block, cannot widen: measured lateral stresses -2.3e4 Pa in
    // it (1/6 of its vertical stress) down to +5e3 Pa in the top cube, which stiffen the
    // column by 2.2-2.4 %: 3 % there. Fully dynamic, the ringing interfaces slide and widen.
    const double expected = kDensity * kG * height * height / (2.0 * kYoung);
    const double tolerance = c.poisson > 0.0 && c.mode == AnalysisMode::Static ? 0.03 : 0.02;
    EXPECT_NEAR(settlement, expected, tolerance * expected);
    test::recordVerification({.group = group,
                              .name = name + ": settlement of the top" +
                                      (c.mode == AnalysisMode::Static ? "" : " (mean, last 0.2 s)"),
                              .source = "rho g H^2 / (2 E), uniaxial stress, free sides "
                                        "(Timoshenko & Goodier, Theory of Elasticity)",
                              .expected = expected,
                              .measured = settlement,
                              .tolerance = tolerance,
                              .relative = true,
                              .unit = "m"});
  } else {
    // Rigid: only the contact springs compress (~3e-6 m).
    EXPECT_GE(settlement, 0.0);
    EXPECT_LT(settlement, 1e-5);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Columns, VerificationSliver,
    ::testing::Values(SliverCase{100, Kinematics::Rigid, AnalysisMode::Static},
                      SliverCase{100, Kinematics::Rigid, AnalysisMode::Dynamic},
                      SliverCase{100, Kinematics::Deformable, AnalysisMode::Static},
                      SliverCase{100, Kinematics::Deformable, AnalysisMode::Dynamic},
                      SliverCase{1000, Kinematics::Rigid, AnalysisMode::Static},
                      SliverCase{1000, Kinematics::Rigid, AnalysisMode::Dynamic},
                      SliverCase{1000, Kinematics::Deformable, AnalysisMode::Static},
                      SliverCase{1000, Kinematics::Deformable, AnalysisMode::Dynamic},
                      SliverCase{100, Kinematics::Deformable, AnalysisMode::Static, 0.25},
                      SliverCase{100, Kinematics::Deformable, AnalysisMode::Dynamic, 0.25},
                      SliverCase{1000, Kinematics::Deformable, AnalysisMode::Static, 0.25},
                      SliverCase{1000, Kinematics::Deformable, AnalysisMode::Dynamic, 0.25},
                      SliverCase{0, Kinematics::Deformable, AnalysisMode::Static},
                      SliverCase{0, Kinematics::Deformable, AnalysisMode::Dynamic},
                      SliverCase{0, Kinematics::Deformable, AnalysisMode::Static, 0.25},
                      SliverCase{0, Kinematics::Deformable, AnalysisMode::Dynamic, 0.25}),
    sliverCaseName);

// ---------------------------------------------------------------------------------------
// The wedge with water in its joints.

/// Exact integral of p(z) = gamma_w max(0, level - z) over a planar polygon: the polygon
/// clipped at z = level (Sutherland-Hodgman), then area times p at the clipped part's
/// centroid (exact for a linear integrand).
double waterForce(const std::vector<Vec3>& polygon, double level) {
  std::vector<Vec3> wet;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Vec3& p = polygon[k];
    const Vec3& q = polygon[(k + 1) % polygon.size()];
    const bool p_in = p.z() <= level, q_in = q.z() <= level;
    if (p_in) wet.push_back(p);
    if (p_in != q_in) wet.push_back(p + (q - p) * ((level - p.z()) / (q.z() - p.z())));
  }
  if (wet.size() < 3) return 0.0;
  double area = 0.0;
  Vec3 moment = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
  for (std::size_t k = 1; k + 1 < wet.size(); ++k)
    normal += (wet[k] - wet[0]).cross(wet[k + 1] - wet[0]);
  normal.normalize();
  for (std::size_t k = 1; k + 1 < wet.size(); ++k) {
    const double a = 0.5 * (wet[k] - wet[0]).cross(wet[k + 1] - wet[0]).dot(normal);
    area += a;
    moment += a * (wet[0] + wet[k] + wet[k + 1]) / 3.0;
  }
  const Vec3 centroid = moment / area;
  return kGammaW * (level - centroid.z()) * area;
}

/// The wedge of Wedge.* (50 / 35 deg flanks, gravity plunging 35 deg) with phi chosen so that
/// FS = 1.5 with water standing at z = 0.8 m in both joints (the wedge is 1 m high: the upper
/// part of each face dry). With `wet` the water's pressure is applied to the two faces;
/// returns the hand FS of the model as run (with U_A = U_B = 0 when dry) and the critical SRF
/// that strength reduction finds with runs of `mode` (damped dynamic: dynamic ratio 0.95).
struct WedgeWaterRun {
  double hand_fs = 0.0;
  double critical = 0.0;  ///< 0 when not bracketed
  double phi = 0.0;       ///< deg
};
WedgeWaterRun wedgeWithWater(bool wet, AnalysisMode mode = AnalysisMode::Static,
                             Kinematics kinematics = Kinematics::Rigid) {
  constexpr double kLevel = 0.8;
  const Vec3 g = kG * Vec3(std::sin(radians(35.0)), 0.0, -std::cos(radians(35.0)));
  scenes::Wedge wedge = scenes::vGrooveWedge(50.0, 35.0, 30.0, g);
  const scenes::TwoPlane t = scenes::twoPlane(wedge.n_a, wedge.n_b, g);
  const geometry::Polyhedron& piece = wedge.model.blocks[2].pieces[0];
  // The faces on planes A and B: outward normals -n_A and -n_B.
  double u_a = 0.0, u_b = 0.0;
  std::vector<DdaPressure> pressures;
  for (int f = 0; f < static_cast<int>(piece.faces.size()); ++f) {
    const Vec3 n = geometry::faceNormal(piece, f);
    std::vector<Vec3> polygon;
    for (int v : piece.faces[static_cast<std::size_t>(f)]) polygon.push_back(piece.vertices[v]);
    if (n.dot(-wedge.n_a) > 1.0 - 1e-12) {
      u_a += waterForce(polygon, kLevel);
      pressures.push_back(hydrostaticPressure(2, 0, f, kLevel, kGammaW));
    } else if (n.dot(-wedge.n_b) > 1.0 - 1e-12) {
      u_b += waterForce(polygon, kLevel);
      pressures.push_back(hydrostaticPressure(2, 0, f, kLevel, kGammaW));
    }
  }
  EXPECT_EQ(pressures.size(), 2u);
  const double mass = Simulation(wedge.model, DdaSettings{}).blocks()[2].mass;
  const double n_a = mass * t.n_a - u_a, n_b = mass * t.n_b - u_b;
  EXPECT_GT(n_a, 0.0);  // still on both planes
  EXPECT_GT(n_b, 0.0);
  // The water takes a real share of the normal forces (here 30 %).
  EXPECT_GT(u_a + u_b, 0.25 * mass * (t.n_a + t.n_b));
  const double tan_phi = 1.5 * mass * t.drive / (n_a + n_b);
  wedge.model.joints = {DdaJoint{tan_phi}};
  WedgeWaterRun run;
  run.phi = degrees(std::atan(tan_phi));
  if (wet) {
    wedge.model.pressures = pressures;
    run.hand_fs = (n_a + n_b) * tan_phi / (mass * t.drive);  // 1.5
  } else {
    run.hand_fs = mass * (t.n_a + t.n_b) * tan_phi / (mass * t.drive);  // 2.14
  }
  DdaSettings settings;
  settings.kinematics = kinematics;
  settings.mode = mode;
  if (mode == AnalysisMode::Dynamic) settings.dynamic_ratio = 0.95;
  settings.time_step = 1e-3;
  FactorSearch search;
  search.factors = {1.0, 1.2, 1.4, 1.6, 1.8, 2.0, 2.2, 2.4, 2.6};
  search.tolerance = 0.02;
  search.sweep_all = false;
  search.equilibrium.max_steps = 150;
  const FactorSearchResult result = runStrengthReduction(wedge.model, settings, search);
  run.critical = result.critical.value_or(0.0);
  return run;
}

struct WedgeRunMode {
  AnalysisMode mode;
  Kinematics kinematics;
};

class VerificationWetWedge : public ::testing::TestWithParam<WedgeRunMode> {};

TEST_P(VerificationWetWedge, WaterInTheJointsLowersTheFactorOfSafetyByTheUpliftForces) {
  // The pressure pushes normal to each face, so the water forces U_A, U_B reduce the normal
  // forces and leave the driving force: FS = ((N_A - U_A) + (N_B - U_B)) tan phi / |w . s|
  // (Hoek & Bray 1981, ch. 7, a wedge with water pressure on its joints; Wyllie & Mah 2004,
  // ch. 7). U_A, U_B integrated exactly here (waterForce), not with the engine's rule.
  // Strength reduction must find FS within 3 %, as for the dry wedge, in static and damped
  // dynamic runs (the water applied at once), rigid or deformable.
  const WedgeRunMode p = GetParam();
  const WedgeWaterRun run = wedgeWithWater(true, p.mode, p.kinematics);
  EXPECT_NEAR(run.critical, run.hand_fs, 0.03 * run.hand_fs);
  const bool rigid_static = p.mode == AnalysisMode::Static && p.kinematics == Kinematics::Rigid;
  test::recordVerification(
      {.group = "Wedges",
       .name =
           "wedge 50/35 deg flanks, 35 deg plunge, phi 48.2 deg, water at 0.8 of its height "
           "in both joints: strength-reduction factor" +
           (rigid_static
                ? std::string()
                : std::string(", ") + (p.kinematics == Kinematics::Rigid ? "rigid" : "deformable") +
                      (p.mode == AnalysisMode::Static ? ", static" : ", damped dynamic")),
       .source = "FS = ((N_A - U_A) tan phi_A + (N_B - U_B) tan phi_B) / |w.s|, U exact "
                 "integrals of the pressure (Hoek & Bray 1981, ch. 7; Wyllie & Mah 2004, ch. 7)",
       .expected = run.hand_fs,
       .measured = run.critical,
       .tolerance = 0.03,
       .relative = true,
       .unit = "-"});
}

INSTANTIATE_TEST_SUITE_P(
    Modes, VerificationWetWedge,
    ::testing::Values(WedgeRunMode{AnalysisMode::Static, Kinematics::Rigid},
                      WedgeRunMode{AnalysisMode::Dynamic, Kinematics::Rigid},
                      WedgeRunMode{AnalysisMode::Static, Kinematics::Deformable},
                      WedgeRunMode{AnalysisMode::Dynamic, Kinematics::Deformable}),
    [](const ::testing::TestParamInfo<WedgeRunMode>& info) {
      return std::string(info.param.kinematics == Kinematics::Rigid ? "Rigid" : "Deformable") +
             (info.param.mode == AnalysisMode::Static ? "Static" : "DampedDynamic");
    });

TEST(VerificationWedge, DryWedgeWithTheSameFrictionAngle) {
  // The same wedge and phi (48.2 deg) without water: FS = (N_A + N_B) tan phi / |w . s| =
  // 2.14 (Hoek & Bray 1981, ch. 7), the dry counterpart of the test above.
  const WedgeWaterRun run = wedgeWithWater(false);
  EXPECT_NEAR(run.critical, run.hand_fs, 0.03 * run.hand_fs);
  test::recordVerification(
      {.group = "Wedges",
       .name = "wedge 50/35 deg flanks, 35 deg plunge, phi 48.2 deg, dry: strength-reduction "
               "factor",
       .source = "block theory: FS = (N_A + N_B) tan phi / |w.s| (Hoek & Bray 1981, ch. 7)",
       .expected = run.hand_fs,
       .measured = run.critical,
       .tolerance = 0.03,
       .relative = true,
       .unit = "-"});
}

}  // namespace
}  // namespace rockmass::dda3d
