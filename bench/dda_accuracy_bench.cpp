// Accuracy against time of the 3D DDA engine (issue 5), rigid and deformable, run to
// T = 0.5 s on a fixed slab inclined at theta = 30 deg, the scene turned into an oblique
// frame (as the InclineSliding verification test does):
//   block: a 1 m cube with friction phi = 20 deg, u(t) = 1/2 a t^2 with
//          a = g (sin theta - cos theta tan phi) (Goodman & Shi 1985, ch. 1);
//   train: four 1 m cubes touching face to face along the slope, phi = 20 deg: each
//          slides with the block's a, but the blocks are coupled through their contacts, so
//          that an iterative solver has a real system to solve (for one block the
//          block-Jacobi preconditioner is the exact inverse and PCG converges at once);
//   pushed: the train with phi = 25 deg under the front block: the rear ones push it, so
//          the train slides as one body with a = g (sin theta - cos theta mean(tan phi_i))
//          (equal masses), through compressed block-block contacts.
// Each benchmark is one whole run (set-up + stepping); its counters are the errors against
// u(t) (of the front block) and what the step control did.
//
// Sweeps, one setting changed at a time from the reference (dt 1 ms, automatic penalty
// 40 E l, CHOLMOD, Bossak rho_inf = 0, friction tolerance 1e-2, the engine's defaults):
//   dt       0.5, 1, 2, 4 ms, with the Bossak scheme and with Shi's scheme;
//   penalty  0.1, 1, 10 x the automatic penalty;
//   solver   CHOLMOD, Eigen LDLT, PCG with relative residual 1e-4, 1e-6, 4e-7 (what
//            SolverKind::Auto uses above 500 blocks, autoPcgTolerance()), 1e-8, 1e-10;
//   scheme   Bossak rho_inf = 0, 0.5, 1, and Shi's scheme (beta = 1/2, gamma = 1);
//   friction friction_tolerance 1e-3 and 1 (the friction of the iteration before accepted)
//            against the default 1e-2.
// Prints Google Benchmark's table, then per kinematics a table of errors and of CPU and wall
// time ratios against the reference measured in the same run.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <exception>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "bench/bench_support.h"
#include "dda3d/simulation.h"
#include "scenarios/dda_scenes.h"

namespace {

using namespace rockmass::dda3d;
using rockmass::geometry::Vec3;

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.81;           // m/s2
constexpr double kTheta = 30.0;       // deg, slope
constexpr double kPhi = 20.0;         // deg, friction angle
constexpr double kFrontPhi = 25.0;    // deg, friction angle of the pushed train's front block
constexpr int kTrain = 4;             // blocks of the train
constexpr double kSettled = 0.1;      // s, the settling phase the verification test skips
constexpr double kEndTime = 0.5;      // s, simulated time of each run
constexpr double kAutoFactor = 40.0;  // DdaSettings::penalty_factor default (E l multiples)

double radians(double degrees) {
  return degrees * kPi / 180.0;
}

/// The scenes (see the top of the file).
enum class Scene { Block, Train, Pushed };
const char* sceneName(Scene scene) {
  return scene == Scene::Block ? "block" : (scene == Scene::Train ? "train" : "pushed");
}

/// a = g (sin theta - cos theta mean(tan phi)), m/s2, of the scene.
double acceleration(Scene scene) {
  const double tan_phi =
      scene == Scene::Pushed
          ? ((kTrain - 1) * std::tan(radians(kPhi)) + std::tan(radians(kFrontPhi))) / kTrain
          : std::tan(radians(kPhi));
  return kG * (std::sin(radians(kTheta)) - std::cos(radians(kTheta)) * tan_phi);
}

/// The InclineSliding scene: a 1 m cube (or the train) on a fixed 6 x 3 x 1 m slab, gravity
/// tilted by theta about y (the slope falls towards +x), all turned into an oblique frame so
/// that nothing is aligned with the axes. `downslope` is the slope direction in that frame.
struct Incline {
  DdaModel model;
  Vec3 downslope;
};
Incline incline(Scene scene) {
  Incline s;
  scenes::setRock(s.model, kPhi);
  s.model.blocks.push_back(scenes::boxBlock({-3, -1.5, -1}, {3, 1.5, 0}, 0, true));
  s.model.blocks.push_back(scenes::boxBlock({-2.5, -0.5, 0}, {-1.5, 0.5, 1}, 0, false));
  if (scene != Scene::Block) {
    // The front block's faces are of joint 1 (pushed: phi = 25 deg) and no other face carries
    // a joint: its contacts with the slab and with the block behind it take joint 1, all
    // others the default joint 0 (dda3d/contact_joint.h).
    s.model.joints.push_back(s.model.joints[0]);
    if (scene == Scene::Pushed) s.model.joints[1].friction = std::tan(radians(kFrontPhi));
    for (int k = 1; k < kTrain; ++k) {
      const double x = -2.5 + k;
      s.model.blocks.push_back(scenes::boxBlock({x, -0.5, 0}, {x + 1, 0.5, 1}, 0, false));
    }
    s.model.blocks.back().face_joints = {std::vector<int>(6, 1)};
  }
  s.model.gravity = kG * Vec3(std::sin(radians(kTheta)), 0.0, -std::cos(radians(kTheta)));
  const Eigen::Matrix3d frame = scenes::obliqueFrame();
  scenes::rotateModel(s.model, frame);
  s.downslope = frame * Vec3::UnitX();
  return s;
}

/// One setting of the sweeps.
struct Case {
  Scene scene = Scene::Block;
  std::string sweep;    ///< "dt", "dt shi", "penalty", "solver", "scheme",
                        ///< "friction"
  std::string setting;  ///< the value changed, as printed
  Kinematics kinematics = Kinematics::Rigid;
  double dt = 1e-3;            ///< s
  double penalty_scale = 1.0;  ///< times the automatic penalty
  SolverOptions solver{.kind = SolverKind::Cholmod};
  TimeIntegration integration = TimeIntegration::Bossak;
  double rho = 0.0;  ///< Bossak spectral radius
  double friction_tolerance = DdaSettings{}.friction_tolerance;
  /// Benchmark name, e.g. "Slide/block/rigid/solver/pcg 1e-6".
  std::string name() const { return std::string("Slide/") + group() + "/" + sweep + "/" + setting; }
  /// "block/rigid", "train/deformable", ...
  std::string group() const {
    return std::string(sceneName(scene)) + "/" +
           (kinematics == Kinematics::Rigid ? "rigid" : "deformable");
  }
};

DdaSettings settingsOf(const Case& c) {
  DdaSettings s;
  s.kinematics = c.kinematics;
  s.time_step = c.dt;
  // g2 = 0.01 (the step control's limit): the table of docs/performance.md was measured with
  // it; the default 0.001 cuts dt at the blocks' first contacts.
  s.max_displacement_ratio = 0.01;
  s.penalty_factor = kAutoFactor * c.penalty_scale;
  s.solver = c.solver;
  s.integration = c.integration;
  s.spectral_radius = c.rho;
  s.friction_tolerance = c.friction_tolerance;
  return s;
}

/// What one run gives.
struct Outcome {
  double error_end = 0.0;        ///< (u(T) - 1/2 a T^2) / (1/2 a T^2), u from t = 0
  double error_sliding = 0.0;    ///< same for the increment from t = 0.1 s to T
  double error_velocity = 0.0;   ///< (v(T) - a T) / (a T)
  int steps = 0;                 ///< accepted steps
  int iterations = 0;            ///< open-close iterations of the accepted attempts
  int redos = 0;                 ///< attempts redone (dt cut or penalty raised)
  double penalty_growth = 1.0;   ///< penalty at T / initial penalty
  double max_penetration = 0.0;  ///< m, over the run
};

/// Steps to `end` (s) exactly, accumulating the step statistics.
void advance(Simulation& sim, double end, Outcome& out) {
  while (sim.time() < end * (1.0 - 1e-12)) {
    // runUntil shortens the last step so that the run ends at `end`.
    const StepReport r = sim.time() + sim.timeStep() >= end ? sim.runUntil(end) : sim.step();
    ++out.steps;
    out.iterations += r.iterations;
    out.redos += r.attempts - 1;
    out.max_penetration = std::max(out.max_penetration, r.max_penetration);
  }
}

Outcome run(const Case& c, const Incline& scene) {
  Simulation sim(scene.model, settingsOf(c));
  const double initial_penalty = sim.penalty();
  Outcome out;
  advance(sim, kSettled, out);
  const double t0 = sim.time();
  const int last = static_cast<int>(scene.model.blocks.size()) - 1;  // the front block
  const double u0 = sim.centroidDisplacement(last).dot(scene.downslope);
  advance(sim, kEndTime, out);
  const double t = sim.time();
  const double u = sim.centroidDisplacement(last).dot(scene.downslope);
  const double v =
      sim.blocks()[static_cast<std::size_t>(last)].velocity.head<3>().dot(scene.downslope);
  const double a = acceleration(c.scene);
  out.error_end = (u - 0.5 * a * t * t) / (0.5 * a * t * t);
  const double increment = 0.5 * a * (t * t - t0 * t0);
  out.error_sliding = (u - u0 - increment) / increment;
  out.error_velocity = (v - a * t) / (a * t);
  out.penalty_growth = sim.penalty() / initial_penalty;
  return out;
}

void slide(benchmark::State& state, const Case& c) {
  const Incline scene = incline(c.scene);
  Outcome out;
  try {
    for (auto _ : state) out = run(c, scene);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  state.counters["err_end"] = out.error_end;
  state.counters["err_slide"] = out.error_sliding;
  state.counters["err_v"] = out.error_velocity;
  state.counters["steps"] = out.steps;
  state.counters["iters"] = out.iterations;
  state.counters["redos"] = out.redos;
  state.counters["pen_growth"] = out.penalty_growth;
  state.counters["max_pen"] = out.max_penetration;
}

std::vector<Case> cases() {
  std::vector<Case> all;
  for (Scene scene : {Scene::Block, Scene::Train, Scene::Pushed}) {
    for (Kinematics k : {Kinematics::Rigid, Kinematics::Deformable}) {
      const Case ref{.scene = scene, .sweep = "reference", .setting = "dt 1 ms", .kinematics = k};
      all.push_back(ref);
      for (double ms : {0.5, 2.0, 4.0}) {
        Case c = ref;
        c.sweep = "dt";
        c.dt = ms * 1e-3;
        char text[32];
        std::snprintf(text, sizeof text, "dt %g ms", ms);
        c.setting = text;
        all.push_back(c);
      }
      for (double ms : {0.5, 1.0, 2.0, 4.0}) {
        Case c = ref;
        c.sweep = "dt shi";
        c.dt = ms * 1e-3;
        c.integration = TimeIntegration::Shi;
        char text[32];
        std::snprintf(text, sizeof text, "shi dt %g ms", ms);
        c.setting = text;
        all.push_back(c);
      }
      for (double scale : {0.1, 10.0}) {
        Case c = ref;
        c.sweep = "penalty";
        c.penalty_scale = scale;
        char text[32];
        std::snprintf(text, sizeof text, "penalty %g x auto", scale);
        c.setting = text;
        all.push_back(c);
      }
      {
        Case c = ref;
        c.sweep = "solver";
        c.setting = "eigen ldlt";
        c.solver = {.kind = SolverKind::Eigen};
        all.push_back(c);
      }
      // ... and the tolerance SolverKind::Auto gives PCG above 500 blocks (4e-7).
      for (double tol : {1e-4, 1e-6, autoPcgTolerance(settingsOf(ref)), 1e-8, 1e-10}) {
        Case c = ref;
        c.sweep = "solver";
        c.solver = {.kind = SolverKind::Pcg, .tolerance = tol};
        char text[32];
        std::snprintf(text, sizeof text, "pcg %g", tol);
        c.setting = text;
        all.push_back(c);
      }
      for (double rho : {0.5, 1.0}) {
        Case c = ref;
        c.sweep = "scheme";
        c.rho = rho;
        char text[32];
        std::snprintf(text, sizeof text, "bossak rho %g", rho);
        c.setting = text;
        all.push_back(c);
      }
      for (double tolerance : {1e-3, 1.0}) {
        Case c = ref;
        c.sweep = "friction";
        c.friction_tolerance = tolerance;
        char text[32];
        std::snprintf(text, sizeof text, "friction tol %g", tolerance);
        c.setting = text;
        all.push_back(c);
      }
    }
  }
  return all;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<Case> all = cases();
  for (const Case& c : all) {
    benchmark::RegisterBenchmark(c.name().c_str(), [c](benchmark::State& s) { slide(s, c); })
        ->Unit(benchmark::kMillisecond)
        ->MinTime(0.2);
  }
  benchmark::Initialize(&argc, argv);
  rockmass::bench::RecordingReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);

  for (Scene scene : {Scene::Block, Scene::Train, Scene::Pushed}) {
    const double a = acceleration(scene);
    std::printf("\n%s, theta %g deg, a = %.4f m/s2, T = %g s: u(T) = %.5f m.\n",
                scene == Scene::Block   ? "block (phi 20 deg)"
                : scene == Scene::Train ? "train of 4 blocks (phi 20 deg)"
                                        : "pushed train of 4 blocks (front phi 25, others 20 deg)",
                kTheta, a, kEndTime, 0.5 * a * kEndTime * kEndTime);
  }
  std::printf(
      "Errors are signed and relative: err(T) of u from t = 0, err(slide) of the increment\n"
      "after the %g s settling phase, err(v) of the velocity at T. Time ratios are to the\n"
      "reference (dt 1 ms, auto penalty, CHOLMOD, Bossak rho_inf 0) of the same scene and\n"
      "kinematics, measured in this run (CPU time is the fairer measure on a shared machine).\n",
      kSettled);
  for (const char* group : {"block/rigid", "block/deformable", "train/rigid", "train/deformable",
                            "pushed/rigid", "pushed/deformable"}) {
    const std::string reference = std::string("Slide/") + group + "/reference/dt 1 ms";
    const rockmass::bench::Record* ref = reporter.find(reference);
    if (ref == nullptr) continue;
    std::printf("\n%s\n", group);
    std::printf("  %-20s %9s %10s %9s %6s %7s %6s %8s %9s %9s %8s %8s\n", "setting", "err(T)",
                "err(slide)", "err(v)", "steps", "it/step", "redos", "pen x", "cpu ms", "wall ms",
                "cpu/ref", "wall/ref");
    for (const Case& c : all) {
      const std::string name = c.name();
      if (c.group() != group) continue;
      const rockmass::bench::Record* r = reporter.find(name);
      if (r == nullptr || r->counters.empty()) {
        if (r != nullptr) std::printf("  %-20s (failed)\n", c.setting.c_str());
        continue;
      }
      const auto& k = r->counters;
      std::printf(
          "  %-20s %8.3f%% %9.3f%% %8.3f%% %6.0f %7.2f %6.0f %8.3g %9.2f %9.2f %8.2f %8.2f\n",
          c.setting.c_str(), 100.0 * k.at("err_end"), 100.0 * k.at("err_slide"),
          100.0 * k.at("err_v"), k.at("steps"), k.at("iters") / k.at("steps"), k.at("redos"),
          k.at("pen_growth"), r->cpu_time, r->real_time, r->cpu_time / ref->cpu_time,
          r->real_time / ref->real_time);
    }
  }
  benchmark::Shutdown();
  return 0;
}
