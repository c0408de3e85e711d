// Bolts, fixed points and fixed blocks in a run (issue 5): a block hanging from a bolt (a
// linear spring: static extension m g / k, free oscillation of period 2 pi sqrt(m / k) about
// it, e.g. Timoshenko, Vibration Problems in Engineering, ch. 1), a block held against
// gravity by one fixed point (the penalty spring k_f yields m g / k_f), and a fixed block
// carrying a loaded block without moving.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "dda3d/simulation.h"
#include "scenarios/dda_scenes.h"
#include "tests/support/verification.h"

namespace rockmass::dda3d {
namespace {

using geometry::Vec3;
constexpr double kG = 9.81;
constexpr double kPi = 3.14159265358979323846;

/// A 1 m cube (2600 kg) hanging from a vertical bolt of stiffness k (N/m) anchored to the
/// ground 1 m above the centre of its top face; the bolt starts unstretched.
DdaModel hangingBlock(double stiffness) {
  DdaModel model;
  scenes::setRock(model, 30.0);
  model.blocks.push_back(scenes::boxBlock({-0.5, -0.5, -1}, {0.5, 0.5, 0}, 0, false));
  model.bolts.push_back(DdaBolt{0, Vec3(0, 0, 0), -1, Vec3(0, 0, 1), stiffness, 0.0});
  model.gravity = Vec3(0, 0, -kG);
  return model;
}

TEST(Bolt, StaticExtensionIsMgOverK) {
  constexpr double kStiffness = 1e6;
  DdaSettings settings;
  settings.mode = AnalysisMode::Static;
  settings.kinematics = Kinematics::Rigid;
  // Static steps still carry the inertia term M / (beta dt^2) as a regulariser; with
  // dt = 0.1 s it is 0.26 k, so each step removes ~80% of the remaining imbalance.
  settings.time_step = 0.1;
  Simulation sim(hangingBlock(kStiffness), settings);
  for (int k = 0; k < 300; ++k) sim.step();
  const double expected = 2600.0 * kG / kStiffness;  // 0.0255 m
  // Static steps converge geometrically to the equilibrium; the bolt stays vertical, so its
  // linearisation along the axis is exact: 1e-6 relative.
  EXPECT_NEAR(-sim.centroidDisplacement(0).z(), expected, 1e-6 * expected);
  test::recordVerification({.group = "Bolts and fixed points",
                            .name = "1 m cube on a vertical bolt, k = 1e6 N/m, static: extension",
                            .source = "linear spring: m g / k",
                            .expected = expected,
                            .measured = -sim.centroidDisplacement(0).z(),
                            .tolerance = 1e-6,
                            .relative = true,
                            .unit = "m"});
  EXPECT_NEAR(sim.centroidDisplacement(0).head<2>().norm(), 0.0, 1e-12);
  EXPECT_TRUE(sim.activeTerms().bolts);
  // The bolt's spring holds m g * extension / 2 at equilibrium.
  EXPECT_NEAR(sim.energy().springs, 0.5 * kStiffness * expected * expected,
              1e-5 * kStiffness * expected * expected);
}

TEST(Bolt, OscillatesWithPeriodTwoPiSqrtMOverK) {
  constexpr double kStiffness = 1e6, kMass = 2600.0;
  DdaSettings settings;
  settings.kinematics = Kinematics::Rigid;
  settings.time_step = 1e-3;
  Simulation sim(hangingBlock(kStiffness), settings);
  const double period = 2.0 * kPi * std::sqrt(kMass / kStiffness);  // 0.320 s
  const double static_extension = kMass * kG / kStiffness;
  // z(t) = -x_s (1 - cos(omega t)): lowest points at T/2 and 3T/2, highest at T. Record the
  // times of the two lowest points by parabolic interpolation of three samples.
  double previous2 = 0.0, previous = 0.0, t_previous = 0.0;
  double lowest_depth = 0.0;
  std::vector<double> minima;
  int step = 0;
  while (sim.time() < 1.7 * period) {
    sim.step();
    const double z = sim.centroidDisplacement(0).z();
    if (step >= 2 && previous < previous2 && previous <= z) {
      const double dt = sim.time() - t_previous;  // steps of constant dt here
      const double shift = 0.5 * (previous2 - z) / (previous2 - 2.0 * previous + z);
      minima.push_back(t_previous + shift * dt);
      lowest_depth = std::max(lowest_depth, -previous);
    }
    previous2 = previous;
    previous = z;
    t_previous = sim.time();
    ++step;
  }
  ASSERT_EQ(minima.size(), 2u);
  // Bossak, rho_inf = 0, omega dt = 0.02: period error ~ (omega dt)^2 / 12 and damping
  // ~ 1e-4 per period, far inside 0.5%; the interpolation errs < 1e-3 T.
  EXPECT_NEAR(minima[0], 0.5 * period, 5e-3 * period);
  EXPECT_NEAR(minima[1] - minima[0], period, 5e-3 * period);
  EXPECT_NEAR(lowest_depth, 2.0 * static_extension, 5e-3 * static_extension);
  const std::string source =
      "free oscillation of a mass on a spring (Timoshenko, Vibration "
      "Problems in Engineering, ch. 1)";
  test::recordVerification({.group = "Bolts and fixed points",
                            .name = "1 m cube released on a bolt, k = 1e6 N/m: period",
                            .source = "T = 2 pi sqrt(m / k); " + source,
                            .expected = period,
                            .measured = minima[1] - minima[0],
                            .tolerance = 5e-3,
                            .relative = true,
                            .unit = "s"});
  test::recordVerification({.group = "Bolts and fixed points",
                            .name = "1 m cube released on a bolt, k = 1e6 N/m: lowest point",
                            .source = "2 m g / k; " + source,
                            .expected = 2.0 * static_extension,
                            .measured = lowest_depth,
                            .tolerance = 5e-3 / 2.0,
                            .relative = true,
                            .unit = "m"});
}

TEST(FixedPoint, HoldsABlockWithinThePenaltyCompliance) {
  // One fixed point at the centre of the top face: the block hangs from it, with no moment.
  DdaModel model;
  scenes::setRock(model, 30.0);
  model.blocks.push_back(scenes::boxBlock({-0.5, -0.5, -1}, {0.5, 0.5, 0}, 0, false));
  model.fixed_points.push_back(DdaFixedPoint{0, Vec3(0, 0, 0)});
  model.monitors.push_back(DdaMonitor{"top", Vec3(0, 0, 0), 0});
  model.gravity = Vec3(0, 0, -kG);
  for (AnalysisMode mode : {AnalysisMode::Static, AnalysisMode::Dynamic}) {
    DdaSettings settings;
    settings.mode = mode;
    settings.kinematics = Kinematics::Rigid;
    Simulation sim(model, settings);
    for (int k = 0; k < 200; ++k) sim.step();
    const double k_fixed = settings.fixed_point_penalty_ratio * sim.penalty();
    const double compliance = 2600.0 * kG / k_fixed;  // ~5e-9 m
    // Static: at equilibrium exactly m g / k_f (1e-6 relative). Dynamic: the block dropped
    // onto the spring oscillates about it; the Bossak scheme damps that stiff mode (omega dt
    // ~ 400) within a few steps, so after 200 steps it sits there too.
    EXPECT_NEAR(-sim.monitors()[0].displacement.z(), compliance, 1e-6 * compliance);
    EXPECT_NEAR(sim.monitors()[0].displacement.head<2>().norm(), 0.0, 1e-6 * compliance);
    EXPECT_TRUE(sim.activeTerms().fixed_points);
  }
}

TEST(Roller, HoldsNormalToItsPlaneAndLetsTheBlockFallAlongIt) {
  // A 1 m cube against a wall x = -0.5 on rollers (4 points at the corners of its x-min face,
  // direction -x), under gravity -z and a push of 1e4 N into the wall (-x) at its centroid.
  // Along z nothing holds it: it falls freely, z = -g t^2 / 2 (Bossak is exact for a
  // constant acceleration; 1e-9 relative). Along x the four springs take the push:
  // u_x = -F / (4 k) (static deflection, 1e-3 relative: the rollers stay parallel).
  constexpr double kPush = 1e4;
  DdaModel model;
  scenes::setRock(model, 30.0);
  model.blocks.push_back(scenes::boxBlock({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}, 0, false));
  for (double y : {-0.5, 0.5}) {
    for (double z : {-0.5, 0.5}) {
      model.fixed_points.push_back(DdaFixedPoint{0, Vec3(-0.5, y, z), Vec3(-1, 0, 0)});
    }
  }
  model.point_loads.push_back(DdaPointLoad{0, Vec3(0, 0, 0), Vec3(-kPush, 0, 0)});
  model.monitors.push_back(DdaMonitor{"c", Vec3(0, 0, 0), 0});
  model.gravity = Vec3(0, 0, -kG);
  DdaSettings settings;
  settings.kinematics = Kinematics::Rigid;
  settings.time_step = 1e-3;
  settings.max_displacement_ratio = 0.5;  // a free fall: no contact, let it move
  Simulation sim(model, settings);
  for (int k = 0; k < 100; ++k) sim.step();
  const double t = sim.time();
  const Vec3 u = sim.monitors()[0].displacement;
  EXPECT_NEAR(u.z(), -0.5 * kG * t * t, 1e-9 * 0.5 * kG * t * t);
  const double k_roller = settings.fixed_point_penalty_ratio * sim.penalty();
  EXPECT_NEAR(u.x(), -kPush / (4.0 * k_roller), 1e-3 * kPush / (4.0 * k_roller));
  EXPECT_NEAR(u.y(), 0.0, 1e-12);
  EXPECT_TRUE(sim.activeTerms().rollers);
  EXPECT_FALSE(sim.activeTerms().fixed_points);
}

TEST(FixedBlock, NeverMovesUnderALoadedBlock) {
  DdaModel model;
  scenes::setRock(model, 30.0);
  model.blocks.push_back(scenes::boxBlock({-1, -1, -1}, {1, 1, 0}, 0, true));
  model.blocks.push_back(scenes::boxBlock({-0.5, -0.5, 0}, {0.5, 0.5, 1}, 0, false));
  model.point_loads.push_back(DdaPointLoad{1, Vec3(0, 0, 1), Vec3(0, 0, -1e6)});
  model.gravity = Vec3(0, 0, -kG);
  DdaSettings settings;
  settings.kinematics = Kinematics::Rigid;  // rigid: the sinking is the springs' alone
  Simulation sim(model, settings);
  const geometry::Polyhedron before = sim.blocks()[0].pieces[0];
  for (int k = 0; k < 200; ++k) sim.step();
  // A fixed block has no unknowns: its vertices are never touched (exact).
  EXPECT_EQ(sim.blocks()[0].pieces[0].vertices, before.vertices);
  EXPECT_EQ(sim.centroidDisplacement(0), Vec3::Zero());
  EXPECT_TRUE(sim.activeTerms().fixed_blocks);
  // And it carries the load: the block on it sank only by its contact springs' compression,
  // (m g + 1 MN) / (4 corner springs of k = 4e11 N/m) ~ 6e-7 m; 1e-5 m allows the damped
  // landing on unloaded springs.
  EXPECT_GT(sim.contactCounts().total, 0);
  EXPECT_LT(-sim.centroidDisplacement(1).z(), 1e-5);
}

}  // namespace
}  // namespace rockmass::dda3d
