// Hard cases that break penalty-contact codes (issue 5). Each run asserts, after every
// step: no NaN or Inf, the deepest penetration below the allowed g3 * l0, that the run
// completes, and the energy account (docs/dda3d.md, "Energy account"):
// - it balances: stored + friction + numerical = work of loads + contact changes, up to
//   the geometric non-linearity of the steps (exact rotation, moving contact frames) and
//   round-off: every term is computed on its own (friction from the applied forces and
//   slips, numerical from the scheme's formula), so a wrong sign or a lost term shows;
// - friction and the time integration only remove energy (>= 0, cumulative);
// - contact changes add at most the hysteresis allowance, 1/2 k_n (close threshold)^2 per
//   contact, so stored + dissipated never exceeds the work of loads by more than that.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "dda3d/simulation.h"
#include "scenarios/dda_scenes.h"

namespace rockmass::dda3d {
namespace {

using geometry::Vec3;
constexpr double kG = 9.81;

void runChecked(const DdaModel& model, const DdaSettings& settings, int steps) {
  Simulation sim(model, settings);
  const double allowed = settings.allowed_penetration_ratio * sim.halfDomainSize();
  double closing = 0.0;  // hysteresis allowance, summed over the steps
  long solver_iterations = 0;
  for (int k = 0; k < steps; ++k) {
    const StepReport r = sim.step();
    solver_iterations += r.solver_iterations;
    for (const BlockState& b : sim.blocks()) {
      for (const auto& p : b.pieces) {
        for (const Vec3& v : p.vertices) ASSERT_TRUE(v.allFinite()) << "step " << k;
      }
      ASSERT_TRUE(b.velocity.allFinite());
    }
    ASSERT_LE(r.max_penetration, allowed) << "step " << k;
    const EnergyAccount e = sim.energy();
    // Contact changes may add, per contact: the closing hysteresis 1/2 k_n (close
    // threshold)^2, and the elastic predictor of a creeping contact restarted stuck with its
    // shear spring at the strength, 1/2 (f N + c A)^2 / k_s (docs/dda3d.md, "Energy account").
    const double ks = sim.penalty() / settings.shear_penalty_ratio;
    closing += 0.5 * sim.penalty() *
               std::pow(settings.close_threshold_ratio * sim.halfDomainSize(), 2) *
               static_cast<double>(r.contacts.total);
    for (const Contact& c : sim.contacts()) {
      const DdaJoint& joint =
          model.joints.at(static_cast<std::size_t>(c.joint >= 0 ? c.joint : model.default_joint));
      const double strength = joint.friction * std::max(0.0, c.normal_force) +
                              (c.bonded ? joint.cohesion * c.area : 0.0);
      closing += 0.5 * strength * strength / ks;
    }
    const double scale = e.work_of_loads + std::abs(e.contact_changes) + e.dissipated() + 1.0;
    // Balance: the geometric non-linearity of a step is second order in its rotation
    // (< 1e-3 rad here): measured residuals < 1e-7 of the energies moved for rigid blocks.
    // Deformable blocks also change volume by their volumetric strain (up to ~1e-4 in the
    // 0.75 GPa layer), and the strain energy uses the current volume: measured 3e-5.
    const double balance = settings.kinematics == Kinematics::Rigid ? 1e-6 : 1e-3;
    ASSERT_NEAR(e.stored() + e.dissipated(), e.work_of_loads + e.contact_changes, balance * scale)
        << "step " << k << ": kinetic " << e.kinetic << " strain " << e.strain << " springs "
        << e.springs << " friction " << e.friction << " numerical " << e.numerical
        << " contact changes " << e.contact_changes << " work " << e.work_of_loads;
    // Friction only removes energy, rigid or deformable: a sliding contact whose whole slip
    // (strain included) turns back against its friction sticks (docs/dda3d.md).
    ASSERT_GE(e.friction, -1e-9 * scale)
        << "step " << k << ": friction did positive work " << e.friction;
    // The Bossak scheme conserves or removes a modified energy that includes
    // 1/2 (beta - gamma/2) dt^2 a^T M a (Hughes 1987, sec. 9.3, for Newmark; alpha_m shifts
    // the coefficient only), so the plain kinetic + strain + spring energy may exceed the
    // balance by at most that.
    double acceleration_term = 0.0;
    for (const BlockState& b : sim.blocks()) {
      if (!b.fixed) acceleration_term += b.acceleration.dot(massMatrix(b) * b.acceleration);
    }
    acceleration_term *= 0.5 * r.time_step * r.time_step;
    ASSERT_GE(e.numerical, -acceleration_term - 1e-9 * scale)
        << "step " << k << ": the scheme added energy";
    ASSERT_LE(e.contact_changes, closing + 1e-9 * scale)
        << "step " << k << ": contact changes added " << e.contact_changes << " J";
    ASSERT_LE(e.stored() + std::max(0.0, e.friction) + e.numerical,
              e.work_of_loads + closing + balance * scale)
        << "step " << k;
  }
  EXPECT_GT(sim.time(), 0.0);
  // Direct solvers report no iterations (exact); PCG some (a warm start that already meets
  // the tolerance costs 0, but the landing steps change the loads).
  if (resolvedSolverOptions(settings, 1).kind == SolverKind::Pcg) {
    EXPECT_GT(solver_iterations, 0);
  } else {
    EXPECT_EQ(solver_iterations, 0);
  }
}

DdaSettings hardSettings(Kinematics kinematics = Kinematics::Deformable) {
  DdaSettings s;
  s.kinematics = kinematics;
  s.time_step = 2e-3;
  return s;
}

TEST(HardCases, SingularSystemIsAnErrorNotACrash) {
  // A free rigid block touching nothing whose density is the smallest positive double (the
  // constructor accepts it): its moments of inertia underflow to exactly 0, so the rotational
  // part of its 6 x 6 diagonal block is I / dt^2 = 0 at every time step (a mechanism), and the
  // factorization fails on every attempt. The step must throw a clear std::runtime_error
  // (the CLI's exit 1), never read a missing solution.
  for (const SolverKind solver : {SolverKind::Cholmod, SolverKind::Eigen}) {
    DdaModel model;
    model.materials = {DdaMaterial{std::numeric_limits<double>::denorm_min(), 10e9, 0.25}};
    model.joints = {DdaJoint{0.6, 0.0, 0.0}};
    model.blocks.push_back(scenes::boxBlock({0, 0, 0}, {1, 1, 1}, 0, false));
    DdaSettings settings = hardSettings(Kinematics::Rigid);
    settings.solver.kind = solver;
    Simulation sim(model, settings);
    try {
      sim.step();
      ADD_FAILURE() << "a singular system was accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("not positive definite"), std::string::npos) << e.what();
    }
  }
}

TEST(HardCases, AContactFirstFoundDeepKeepsItsDepthInsteadOfThrowingTheBlock) {
  // A 1 m cube that starts 5 mm inside a fixed slab, six times the allowed penetration
  // (4e-4 l0, l0 = 2 m): as a contact the detection missed while it closed. Pushed out by
  // its spring from that depth, each corner would give back 1/2 k_n d^2 (~5e6 J against
  // the cube's 2.6e4 N weight) and throw the cube off at tens of m/s. The depth found is kept
  // (Contact::overlap): the springs resist further penetration only, and the cube rests.
  DdaModel model;
  model.materials = {DdaMaterial{2600, 10e9, 0.25}};
  model.joints = {DdaJoint{0.6, 0.0, 0.0}};
  model.blocks.push_back(scenes::boxBlock({-2, -2, -1}, {2, 2, 0}, 0, true));
  model.blocks.push_back(scenes::boxBlock({-0.5, -0.5, -0.005}, {0.5, 0.5, 0.995}, 0, false));
  model.gravity = Vec3(0, 0, -kG);
  DdaSettings settings = hardSettings(Kinematics::Rigid);
  Simulation sim(model, settings);
  const double allowed = settings.allowed_penetration_ratio * sim.halfDomainSize();
  ASSERT_LT(allowed, 0.005 / 5.0);
  const StepReport first = sim.step();
  EXPECT_EQ(first.late_contacts, 4);  // the four bottom corners
  int late = first.late_contacts;
  while (sim.time() < 0.2) late += sim.step().late_contacts;
  EXPECT_EQ(late, 4);  // found once, then carried with their depth
  // At rest on its springs: m g / k_n ~ 1e-7 m of further sinking, no rebound.
  EXPECT_LT(sim.centroidDisplacement(1).norm(), 1e-5);
  EXPECT_LT(sim.blocks()[1].velocity.head<3>().norm(), 1e-3);
  const EnergyAccount e = sim.energy();
  EXPECT_LT(e.stored(), e.work_of_loads + 1.0);
}

TEST(HardCases, SoftInterlayerBetweenStiffBlocks) {
  // E = 0.75 GPa (Table 2 soft layer P_n) between blocks of 750 GPa: contrast 10^3; and the
  // concrete (17.6 GPa, 24 kN/m3) - soft layer pair of Table 2 on top.
  DdaModel model;
  model.materials = {DdaMaterial{2650, 750e9, 0.25}, DdaMaterial{2039, 0.75e9, 0.40},
                     DdaMaterial{2446.5, 17.6e9, 0.167}};
  model.joints = {DdaJoint{0.35, 0.1e6, 0.0}};
  model.blocks.push_back(scenes::boxBlock({-2, -2, -1}, {2, 2, 0}, 0, true));
  model.blocks.push_back(scenes::boxBlock({-1, -1, 0}, {1, 1, 1}, 0, false));
  model.blocks.push_back(scenes::boxBlock({-1, -1, 1}, {1, 1, 1.2}, 1, false));
  model.blocks.push_back(scenes::boxBlock({-1, -1, 1.2}, {1, 1, 2.2}, 0, false));
  model.blocks.push_back(scenes::boxBlock({-1, -1, 2.2}, {1, 1, 2.4}, 1, false));
  model.blocks.push_back(scenes::boxBlock({-0.8, -0.8, 2.4}, {0.8, 0.8, 3.4}, 2, false));
  model.gravity = Vec3(0, 0, -kG);
  runChecked(model, hardSettings(), 200);
}

TEST(HardCases, SliversOnAndBetweenBlocks) {
  // A 1 m x 1 m x 1 mm plate (1:1000) on a block, and one squeezed between two blocks.
  DdaModel model;
  scenes::setRock(model, 30.0);
  model.blocks.push_back(scenes::boxBlock({-2, -2, -1}, {2, 2, 0}, 0, true));
  model.blocks.push_back(scenes::boxBlock({-0.5, -0.5, 0}, {0.5, 0.5, 1e-3}, 0, false));
  model.blocks.push_back(scenes::boxBlock({-0.5, -0.5, 1e-3}, {0.5, 0.5, 1.001}, 0, false));
  model.blocks.push_back(scenes::boxBlock({1.0, -0.5, 0}, {1.001, 0.5, 1}, 0, false));  // standing
  model.gravity = Vec3(0, 0, -kG);
  runChecked(model, hardSettings(), 200);
}

TEST(HardCases, CoplanarVertexOnVertexAndEdgeOnEdge) {
  // Equal cubes stacked exactly (coplanar faces, vertex on vertex), one turned 45 deg about
  // z (edges crossing in one plane), and a cube resting on an edge of another, edge on edge.
  DdaModel model;
  scenes::setRock(model, 30.0);
  model.blocks.push_back(scenes::boxBlock({-3, -3, -1}, {3, 3, 0}, 0, true));
  model.blocks.push_back(scenes::boxBlock({-2, -0.5, 0}, {-1, 0.5, 1}, 0, false));
  model.blocks.push_back(scenes::boxBlock({-2, -0.5, 1}, {-1, 0.5, 2}, 0, false));
  DdaBlock turned = scenes::boxBlock({-0.5, -0.5, 2}, {0.5, 0.5, 3}, 0, false);
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.25 * 3.14159265358979, Vec3::UnitZ()).toRotationMatrix();
  for (Vec3& v : turned.pieces[0].vertices) v = Vec3(-1.5, 0, 0) + r * v;
  model.blocks.push_back(turned);
  model.blocks.push_back(scenes::boxBlock({1, -0.5, 0}, {2, 0.5, 1}, 0, false));
  DdaBlock on_edge = scenes::boxBlock({-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}, 0, false);
  const Eigen::Matrix3d tilt =
      Eigen::AngleAxisd(0.25 * 3.14159265358979, Vec3::UnitX()).toRotationMatrix();
  for (Vec3& v : on_edge.pieces[0].vertices) v = Vec3(1.5, 0, 1 + std::sqrt(0.5)) + tilt * v;
  model.blocks.push_back(on_edge);  // its lower edge (along x) crosses nothing: lies on the face
  model.gravity = Vec3(0, 0, -kG);
  runChecked(model, hardSettings(Kinematics::Rigid), 200);
}

DdaModel tenBlockColumn() {
  DdaModel model;
  scenes::setRock(model, 35.0);
  model.blocks.push_back(scenes::boxBlock({-2, -2, -1}, {2, 2, 0}, 0, true));
  for (int k = 0; k < 10; ++k) {
    model.blocks.push_back(scenes::boxBlock({-0.5, -0.5, k * 1.0}, {0.5, 0.5, k + 1.0}, 0, false));
  }
  model.gravity = Vec3(0, 0, -kG);
  return model;
}

struct ColumnCase {
  SolverKind solver;
  Kinematics kinematics;
};
class TenBlockColumn : public ::testing::TestWithParam<ColumnCase> {};

TEST_P(TenBlockColumn, FullyDynamicWithEverySolver) {
  // Fully dynamic (ratio 1). Shi's scheme keeps a velocity sawtooth on the ten stacked
  // contact springs; the Bossak scheme (rho_inf = 0) removes it, and the column settles.
  // Deformable: the stacked faces strain apart by ~1e-5 m, so their boundary edges cross
  // next to the corners; those crossings lie in the touching faces and are carried by the
  // corners' vertex-to-face entries (no edge-to-edge entry first seen penetrating).
  DdaSettings settings = hardSettings(GetParam().kinematics);
  settings.solver.kind = GetParam().solver;
  settings.solver.tolerance = 1e-10;
  runChecked(tenBlockColumn(), settings, 300);
}
INSTANTIATE_TEST_SUITE_P(Solvers, TenBlockColumn,
                         ::testing::Values(ColumnCase{SolverKind::Cholmod, Kinematics::Rigid},
                                           ColumnCase{SolverKind::Eigen, Kinematics::Rigid},
                                           ColumnCase{SolverKind::Pcg, Kinematics::Rigid},
                                           ColumnCase{SolverKind::Cholmod, Kinematics::Deformable},
                                           ColumnCase{SolverKind::Eigen, Kinematics::Deformable},
                                           ColumnCase{SolverKind::Pcg, Kinematics::Deformable}),
                         [](const ::testing::TestParamInfo<ColumnCase>& info) {
                           const SolverKind k = info.param.solver;
                           return std::string(k == SolverKind::Cholmod ? "Cholmod"
                                              : k == SolverKind::Eigen ? "EigenLdlt"
                                                                       : "Pcg") +
                                  (info.param.kinematics == Kinematics::Rigid ? "Rigid"
                                                                              : "Deformable");
                         });

// Contacts kept between searches (DdaSettings::detection.search_margin, docs/dda3d.md,
// "Contacts kept between steps"). A column of ten cubes settling statically on a slab moves
// its blocks by micrometres a step: with the default margin (1e-3 g2 l0, 5 um here) the steps
// keep the first search's entries, and the column must settle as with a search every step
// (the same entries: stacked flush faces, no corner at a face's boundary), its top cube's
// settlement within 1e-6 of it (round-off of the refreshed geometry over 60 steps) and the
// same contact count.
TEST(KeptContacts, AColumnSettlesAsWithASearchEveryStep) {
  DdaSettings every_step = hardSettings(Kinematics::Rigid);
  every_step.mode = AnalysisMode::Static;
  every_step.detection.search_margin = 0.0;
  DdaSettings kept = every_step;
  kept.detection.search_margin = DdaSettings{}.detection.search_margin;
  Simulation a(tenBlockColumn(), every_step);
  Simulation b(tenBlockColumn(), kept);
  constexpr int kSteps = 60;
  for (int k = 0; k < kSteps; ++k) {
    const StepReport ra = a.step();
    const StepReport rb = b.step();
    ASSERT_EQ(ra.contacts.total, rb.contacts.total) << "step " << k;
  }
  EXPECT_EQ(a.contactSearches(), kSteps);
  EXPECT_LE(b.contactSearches(), kSteps / 10);
  const double settlement = a.centroidDisplacement(10).z();
  EXPECT_LT(settlement, -1e-7);  // the column's contact springs took its weight
  EXPECT_NEAR(b.centroidDisplacement(10).z(), settlement, 1e-6 * std::abs(settlement));
}

// A cube dropped 2 cm onto a slab (dynamic) moves farther than the margin every step while it
// falls and bounces (to step ~120): each such step searches, and no contact is first found
// deep (late); once it rests, its steps keep the contacts.
TEST(KeptContacts, AFallingCubeIsSearchedEveryStepUntilItRests) {
  DdaModel model;
  scenes::setRock(model, 35.0);
  model.blocks.push_back(scenes::boxBlock({-2, -2, -1}, {2, 2, 0}, 0, true));
  model.blocks.push_back(scenes::boxBlock({-0.5, -0.5, 0.02}, {0.5, 0.5, 1.02}, 0, false));
  model.gravity = Vec3(0, 0, -kG);
  DdaSettings settings = hardSettings(Kinematics::Rigid);
  Simulation sim(model, settings);
  int late = 0, kept_while_falling = 0, kept_at_the_end = 0;
  for (int k = 0; k < 200; ++k) {
    const double height = sim.blocks()[1].centroid.z();
    const StepReport r = sim.step();
    late += r.late_contacts;
    if (height > 0.501 && !r.contacts_searched) ++kept_while_falling;
    if (k >= 150 && !r.contacts_searched) ++kept_at_the_end;
  }
  EXPECT_EQ(late, 0);
  EXPECT_EQ(kept_while_falling, 0);
  EXPECT_EQ(kept_at_the_end, 50);  // at rest on the slab: the last 50 steps keep theirs
  EXPECT_NEAR(sim.blocks()[1].centroid.z(), 0.5, 1e-3);
}

// The ten-block column resting on its slab while a cube 1 mm above the slab beside it comes
// down onto it (static: about 2e-5 m a step, g dt^2 / 2): every step the cube moves farther
// than the margin, and a step searches only the cube's pairs, keeping the column's entries
// (refreshed). The column must settle and the cube land as with a search of all every step.
TEST(KeptContacts, ACubeComingDownBesideARestingColumnIsSearchedAlone) {
  DdaModel model = tenBlockColumn();
  model.blocks.push_back(scenes::boxBlock({1.0, -0.5, 0.001}, {1.8, 0.3, 0.801}, 0, false));
  DdaSettings every_step = hardSettings(Kinematics::Rigid);
  every_step.mode = AnalysisMode::Static;
  every_step.detection.search_margin = 0.0;
  DdaSettings kept = every_step;
  kept.detection.search_margin = DdaSettings{}.detection.search_margin;
  Simulation a(model, every_step);
  Simulation b(model, kept);
  constexpr int kSteps = 100;
  int late = 0, partly_while_falling = 0, searched_while_falling = 0;
  for (int k = 0; k < kSteps; ++k) {
    const bool falling = b.blocks()[11].centroid.z() > 0.40001;
    const StepReport ra = a.step();
    const StepReport rb = b.step();
    late += rb.late_contacts;
    if (falling && k > 0) {
      partly_while_falling += rb.contacts_searched_partly;
      searched_while_falling += rb.contacts_searched;
    }
    // The same entries (the column's kept, the cube's found as a search finds them).
    ASSERT_EQ(ra.contacts.total, rb.contacts.total) << "step " << k;
  }
  EXPECT_EQ(a.contactSearches(), kSteps);
  EXPECT_EQ(a.partialSearches(), 0);
  EXPECT_EQ(late, 0);
  // 1 mm at 2e-5 m a step: some 50 steps coming down, each searching the cube's pairs alone
  // (the first step searches all: nothing is kept yet),
  EXPECT_GE(partly_while_falling, 40);
  EXPECT_EQ(searched_while_falling, 0);
  // and the step that lands it (it moved beyond the margin in it) searches its pairs too.
  EXPECT_EQ(b.partialSearches(), partly_while_falling + 1);
  // The column's top settled as with a search every step (its springs took its weight), to
  // the round-off of kept against found entries; the cube landed on the slab as there.
  const double settlement = a.centroidDisplacement(10).z();
  EXPECT_LT(settlement, -1e-7);
  EXPECT_NEAR(b.centroidDisplacement(10).z(), settlement, 1e-6 * std::abs(settlement));
  EXPECT_NEAR(a.blocks()[11].centroid.z(), 0.4, 1e-5);
  EXPECT_NEAR(b.blocks()[11].centroid.z(), a.blocks()[11].centroid.z(), 1e-9);
}

/// 200 cubes dropped from a loose lattice (0.2 m gaps, staggered rows) into a fixed box.
DdaModel pile() {
  DdaModel model;
  scenes::setRock(model, 30.0);
  model.blocks.push_back(scenes::boxBlock({-4, -4, -1}, {4, 4, 0}, 0, true));
  model.blocks.push_back(scenes::boxBlock({-5, -4, -1}, {-4, 4, 12}, 0, true));
  model.blocks.push_back(scenes::boxBlock({4, -4, -1}, {5, 4, 12}, 0, true));
  for (int k = 0; k < 200; ++k) {
    const int layer = k / 25, row = (k / 5) % 5, column = k % 5;
    const double shift = layer % 2 == 0 ? 0.0 : 0.3;
    const Vec3 low(-3.0 + 1.2 * column + shift, -3.0 + 1.2 * row, 0.05 + 1.2 * layer);
    model.blocks.push_back(scenes::boxBlock(low, low + Vec3(1, 1, 1), 0, false));
  }
  model.gravity = Vec3(0, 0, -kG);
  return model;
}

TEST(HardCases, TwoHundredBlockPileSettles) {
  runChecked(pile(), hardSettings(Kinematics::Rigid), 120);
}

TEST(HardCases, OpenCloseAllowanceIsTheClassicRuleBelowTenThousandContacts) {
  // DdaSettings::open_close_tolerance = 1e-4 allows floor(1e-4 n) state changes in the last
  // iteration: none below 10^4 contacts (this pile has a few hundred), so the run must be
  // bit for bit the classic one (tolerance 0).
  DdaSettings classic = hardSettings(Kinematics::Rigid);
  classic.open_close_tolerance = 0.0;
  DdaSettings allowance = classic;
  allowance.open_close_tolerance = 1e-4;
  Simulation a(pile(), classic);
  Simulation b(pile(), allowance);
  int most_contacts = 0;
  for (int k = 0; k < 80; ++k) {
    const StepReport ra = a.step();
    const StepReport rb = b.step();
    most_contacts = std::max(most_contacts, ra.contacts.total);
    ASSERT_EQ(ra.iterations, rb.iterations) << "step " << k;
  }
  ASSERT_LT(most_contacts, 10000);
  for (std::size_t i = 0; i < a.blocks().size(); ++i) {
    EXPECT_EQ(a.blocks()[i].centroid, b.blocks()[i].centroid) << "block " << i;
  }
}

TEST(HardCases, OpenCloseAllowanceNeverAcceptsAClosingContact) {
  // Even an allowance of 20 % of the contacts must not end an iteration in which a contact
  // closed: that contact was solved open and may sit deep in the other block. Accepting it
  // let the falling pile penetrate 4.3 mm against the 2.6 mm allowed (checked: the rule
  // before closings were excluded); every step must stay within the allowed depth.
  DdaSettings loose = hardSettings(Kinematics::Rigid);
  loose.open_close_tolerance = 0.2;
  Simulation sim(pile(), loose);
  const double allowed = loose.allowed_penetration_ratio * sim.halfDomainSize();
  for (int k = 0; k < 200; ++k) {
    const StepReport r = sim.step();
    ASSERT_LE(r.max_penetration, allowed) << "step " << k;
  }
}

}  // namespace
}  // namespace rockmass::dda3d
