// Deformable (12-unknown) blocks where they are hard: at rest on a slope with no energy
// created by friction, a column under a surface load against elasticity, a cantilever whose
// bending one strain field cannot show (said, not hidden), and a massive block on its base
// that must settle in a static run's step budget.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "dda3d/equilibrium.h"
#include "dda3d/simulation.h"
#include "dda3d/strain_check.h"
#include "scenarios/dda_scenes.h"
#include "tests/support/verification.h"

namespace rockmass::dda3d {
namespace {

using geometry::Vec3;
constexpr double kG = 9.81;

class DeformableOnASlope : public ::testing::TestWithParam<AnalysisMode> {};

TEST_P(DeformableOnASlope, StaysAtRestAndFrictionNeverDoesPositiveWork) {
  // A 1 m cube on a fixed slab, gravity tilted 30 deg, phi = 40 deg: Coulomb says no motion.
  // Its corners move with its strain as it settles and the contact frames turn; friction
  // must still only remove energy (a contact whose whole slip turns back against its
  // friction sticks).
  const AnalysisMode mode = GetParam();
  DdaModel model;
  scenes::setRock(model, 40.0, 1e9, 0.3);
  model.blocks.push_back(scenes::boxBlock({-3, -2, -1}, {3, 2, 0}, 0, true));
  model.blocks.push_back(scenes::boxBlock({-0.5, -0.5, 0}, {0.5, 0.5, 1}, 0, false));
  const double theta = scenes::radians(30.0);
  model.gravity = kG * Vec3(std::sin(theta), 0.0, -std::cos(theta));
  DdaSettings settings;
  settings.mode = mode;
  settings.time_step = 1e-3;
  Simulation sim(model, settings);
  Vec3 settled = Vec3::Zero();
  double least_friction = 0.0, most_created = 0.0;
  for (int k = 0; k < 3000; ++k) {
    sim.step();
    if (k == 99) settled = sim.centroidDisplacement(1);  // on its contact springs by 0.1 s
    const EnergyAccount e = sim.energy();
    const double scale = std::abs(e.work_of_loads) + e.dissipated() + 1e-3;
    least_friction = std::min(least_friction, e.friction / scale);
    most_created = std::max(
        most_created, (e.stored() + e.dissipated() - e.work_of_loads - e.contact_changes) / scale);
  }
  // Friction work >= 0 every step (round-off: 1e-9 of the energies moved).
  EXPECT_GE(least_friction, -1e-9);
  // The balance of a deformable block closes to its volume change (1e-3, docs/dda3d.md).
  EXPECT_LE(most_created, 1e-3);
  const double crept = (sim.centroidDisplacement(1) - settled).norm();
  // No motion: < 1e-6 m (of its 1 m) over the 2.9 s after it settled.
  EXPECT_LT(crept, 1e-6);
  EXPECT_EQ(sim.contactCounts().sliding, 0);
  test::recordVerification(
      {.group = "Deformable blocks",
       .name = std::string("1 m cube, theta 30 deg, phi 40 deg, deformable, ") +
               (mode == AnalysisMode::Static ? "static" : "fully dynamic") +
               ": motion over 2.9 s after settling",
       .source = "Coulomb: no motion when phi >= theta (Goodman & Shi 1985, ch. 1)",
       .expected = 0.0,
       .measured = crept,
       .tolerance = 1e-6,
       .unit = "m"});
}
INSTANTIATE_TEST_SUITE_P(Modes, DeformableOnASlope,
                         ::testing::Values(AnalysisMode::Static, AnalysisMode::Dynamic),
                         [](const auto& info) {
                           return info.param == AnalysisMode::Static ? "Static" : "Dynamic";
                         });

constexpr double kGammaW = 9810.0;

/// A 1 m cube (z 0..1) of the water's density (E 1 GPa, nu 0.3) under gravity, with still
/// water at z = `level` on its six faces; `structure`: flagged as the scene's structure 0.
DdaModel floatingCube(double level, bool structure = false) {
  DdaModel model;
  scenes::setRock(model, 30.0, 1e9, 0.3, kGammaW / kG);
  model.blocks.push_back(scenes::boxBlock({0, 0, 0}, {1, 1, 1}, 0, false));
  if (structure) model.blocks[0].structure = 0;
  model.gravity = Vec3(0, 0, -kG);
  for (int f = 0; f < 6; ++f) {
    model.pressures.push_back(hydrostaticPressure(0, 0, f, level, kGammaW));
  }
  return model;
}

/// `floatingCube` after 60 static steps of deformable blocks with `biot` (Biot's coefficient).
std::unique_ptr<Simulation> floatingCubeSettled(double level, double biot, bool structure = false) {
  DdaSettings settings;
  settings.mode = AnalysisMode::Static;
  settings.kinematics = Kinematics::Deformable;
  settings.biot_coefficient = biot;
  auto sim = std::make_unique<Simulation>(floatingCube(level, structure), settings);
  for (int k = 0; k < 60; ++k) sim->step();
  return sim;
}

TEST(DeformableInWater, ASaturatedBlockIsStrainedByTheEffectiveStressOnly) {
  // A 1 m cube of the water's density floats in still water (level z = 11 m, the cube at
  // z 0..1; water on its six faces, gravity): buoyancy and weight cancel, and the water's
  // pressure loads its strain by -V p(x_c) I (p_c = 9810 x 10.5 Pa, exact for a linear
  // field). An impermeable block (biot_coefficient 0) takes the hydrostatic stress -p_c I; a
  // saturated one carries alpha p_c in its pores and only sigma' = sigma + alpha p I strains
  // it (Terzaghi's effective stress; Biot's coefficient alpha): -(1 - alpha) p_c I, and none
  // at alpha = 1. Static steps, 60 of them (each relieves at least half of what is left).
  constexpr double kLevel = 11.0;
  const double p_c = kGammaW * (kLevel - 0.5);
  for (const double biot : {0.0, 0.5, 1.0}) {
    const std::unique_ptr<Simulation> settled = floatingCubeSettled(kLevel, biot);
    const Simulation& sim = *settled;
    const VoigtVector stress = sim.blocks()[0].stress;
    const double expected = -(1.0 - biot) * p_c;
    SCOPED_TRACE(biot);
    // Normal stresses within 1e-6 of p_c (round-off of the converged static steps); no
    // shear (1e-9 of p_c).
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(stress[k], expected, 1e-6 * p_c);
    for (int k = 3; k < 6; ++k) EXPECT_NEAR(stress[k], 0.0, 1e-9 * p_c);
    // Saturated, it keeps its volume and floats where it is (1e-9 m). Compressed, it displaces
    // less water than it weighs (by 3 (1 - alpha) p_c (1 - 2 nu) / E of its volume) and sinks,
    // as the buoyancy on its faces says it should: 1.4e-7 m in the 60 steps at alpha = 0.
    if (biot == 1.0) {
      EXPECT_LT(sim.centroidDisplacement(0).norm(), 1e-9);
    } else {
      EXPECT_LT(sim.centroidDisplacement(0).z(), -1e-8);
    }
    EXPECT_EQ(sim.activeTerms().block_pore_pressure, biot > 0.0);
    if (biot == 1.0) {
      test::recordVerification(
          {.group = "Deformable blocks",
           .name = "1 m cube floating in still water 10.5 m deep, saturated (biot_coefficient 1): "
                   "its effective normal stress",
           .source = "Terzaghi's effective stress principle, sigma' = sigma + p I (Biot alpha = 1)",
           .expected = 0.0,
           .measured = stress.head<3>().cwiseAbs().maxCoeff(),
           .tolerance = 1e-6 * p_c,
           .unit = "Pa"});
    }
  }
  // A structure's concrete is not saturated by the water on its faces: at alpha = 1 the same
  // cube flagged as a structure still takes -p_c I.
  {
    const std::unique_ptr<Simulation> sim = floatingCubeSettled(kLevel, 1.0, /*structure=*/true);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(sim->blocks()[0].stress[k], -p_c, 1e-6 * p_c);
    EXPECT_FALSE(sim->activeTerms().block_pore_pressure);
  }
  // Rigid blocks have no strain for the water to load: the term stays off.
  DdaSettings rigid;
  rigid.kinematics = Kinematics::Rigid;
  rigid.biot_coefficient = 1.0;
  Simulation sim(floatingCube(kLevel), rigid);
  sim.step();
  EXPECT_FALSE(sim.activeTerms().block_pore_pressure);
}

TEST(DeformableColumn, SurfaceLoadGivesTheUniaxialStrainsAndSettlement) {
  // A 1 x 1 x 4 m column on a fixed slab, frictionless interface (its base free to widen),
  // no gravity; 1 MPa on its top, as four corner loads of p A / 4 (consistent for a linear
  // field). Uniaxial stress: eps_z = -p / E, eps_x = eps_y = nu p / E, the top sinks p H / E
  // plus the interface's contact springs (p A / (4 k) ~ 3e-4 of it, not in the hand value).
  constexpr double kYoung = 5e9, kPoisson = 0.25, kPressure = 1e6, kHeight = 4.0;
  DdaModel model;
  scenes::setRock(model, 0.0, kYoung, kPoisson);
  model.blocks.push_back(scenes::boxBlock({-2, -2, -1}, {2, 2, 0}, 0, true));
  model.blocks.push_back(scenes::boxBlock({-0.5, -0.5, 0}, {0.5, 0.5, kHeight}, 0, false));
  for (const double x : {-0.5, 0.5}) {
    for (const double y : {-0.5, 0.5}) {
      model.point_loads.push_back({1, Vec3(x, y, kHeight), Vec3(0, 0, -kPressure / 4.0)});
    }
  }
  model.monitors.push_back({"top", Vec3(0.5, 0.5, kHeight), 1});
  DdaSettings settings;
  settings.mode = AnalysisMode::Static;
  settings.time_step = 1e-3;
  Simulation sim(model, settings);
  EquilibriumSettings rest;
  rest.max_steps = 200;
  const EquilibriumResult result = runToEquilibrium(sim, rest);
  EXPECT_TRUE(result.reached) << result.unbalanced_ratio;
  const BlockState& column = sim.blocks()[1];
  const double axial = -kPressure / kYoung, lateral = kPoisson * kPressure / kYoung;
  // Within 2 % (the bound; a uniform strain is exact here).
  EXPECT_NEAR(column.strain[2], axial, 0.02 * std::abs(axial));
  EXPECT_NEAR(column.strain[0], lateral, 0.02 * lateral);
  EXPECT_NEAR(column.strain[1], lateral, 0.02 * lateral);
  const Vec3 top = sim.monitors()[0].displacement;
  const double settlement = kPressure * kHeight / kYoung;
  EXPECT_NEAR(-top.z(), settlement, 0.02 * settlement);
  // The corner moves out by nu p / E times its 0.5 m from the axis.
  EXPECT_NEAR(top.x(), 0.5 * lateral, 0.02 * 0.5 * lateral);
  const auto record = [](const std::string& what, double expected, double measured) {
    test::recordVerification({.group = "Deformable blocks",
                              .name = "column 1 x 1 x 4 m, 1 MPa on its top, frictionless base, "
                                      "static: " +
                                      what,
                              .source = "uniaxial stress: eps_z = -p / E, eps_x = nu p / E "
                                        "(Timoshenko & Goodier, Theory of Elasticity)",
                              .expected = expected,
                              .measured = measured,
                              .tolerance = 0.02,
                              .relative = true,
                              .unit = "m"});
  };
  record("settlement of the top", settlement, -top.z());
  record("lateral displacement of a top corner", 0.5 * lateral, top.x());
  // Uniform compression: no interface bends it (the middle-third check stays quiet).
  EXPECT_LT(interfaceEccentricity(sim)[1], 0.05);
}

TEST(DeformableCantilever, ItsBendingIsSaidNotHidden) {
  // A 6 x 1 x 1 m beam clamped over its first 1.5 m between a fixed slab below and a fixed
  // block above, its 4.5 m overhang loaded by its own weight. One strain field cannot bend:
  // the clamp's contacts carry the moment m g (3 - 0.75)... as forces at the clamp's edges,
  // their resultant near the edge (e / h ~ 1), which the middle-third check must report.
  DdaModel model;
  scenes::setRock(model, 40.0, 5e9, 0.25);
  model.blocks.push_back(scenes::boxBlock({-1, -1, -1}, {1.5, 1, 0}, 0, true));
  model.blocks.push_back(scenes::boxBlock({-1, -1, 1}, {1.5, 1, 2}, 0, true));
  model.blocks.push_back(scenes::boxBlock({0, -0.5, 0}, {6, 0.5, 1}, 0, false));
  model.gravity = Vec3(0, 0, -kG);
  DdaSettings settings;
  settings.mode = AnalysisMode::Static;
  settings.time_step = 1e-3;
  Simulation sim(model, settings);
  for (int k = 0; k < 60; ++k) sim.step();
  const double ratio = interfaceEccentricity(sim)[2];
  // Beyond the middle third by far: the clamp's resultants sit at its inner edge.
  EXPECT_GT(ratio, kMiddleThird) << ratio;
  EXPECT_GT(ratio, 0.8) << ratio;
}

TEST(DeformableBlock, AMassiveBlockOnItsBaseSettlesWithinTheStepBudget) {
  // A 60 x 20 x 100 m concrete block (3.1e8 kg) on a fixed rock slab, pushed sideways at a
  // third of its height by 2.5e9 N (a reservoir's thrust), static, dt = 2 ms: at rest within
  // 40 steps. Its shear with the translation that keeps its base in place is held by its
  // elasticity alone; with the translation's inertia at one contact penalty that mode
  // relieved 1.3 % of its out-of-balance force per step (500 steps to rest,
  // Simulation::staticMassScale).
  DdaModel model;
  model.materials = {DdaMaterial{2600.0, 7e9, 0.25}, DdaMaterial{2450.0, 17.6e9, 0.167}};
  model.joints = {DdaJoint{1.2, 1.4e6, 0.0}};
  model.blocks.push_back(scenes::boxBlock({-60, -10, -20}, {60, 10, 0}, 0, true));
  model.blocks.push_back(scenes::boxBlock({-30, -10, 0}, {30, 10, 100}, 1, false));
  model.gravity = Vec3(0, 0, -kG);
  model.point_loads.push_back({1, Vec3(-30, 0, 100.0 / 3.0), Vec3(2.5e9, 0, 0)});
  DdaSettings settings;
  settings.mode = AnalysisMode::Static;
  settings.time_step = 2e-3;
  Simulation sim(model, settings);
  EquilibriumSettings rest;
  rest.max_steps = 40;
  const EquilibriumResult result = runToEquilibrium(sim, rest);
  EXPECT_TRUE(result.reached) << "unbalanced ratio " << result.unbalanced_ratio << " after "
                              << result.steps << " steps";
  EXPECT_LT(result.steps, 40);
}

}  // namespace
}  // namespace rockmass::dda3d
