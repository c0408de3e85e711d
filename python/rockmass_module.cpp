// The Python module `rockmass` (pybind11): scenes from files or dicts with the CLI's errors,
// each stage's results as NumPy arrays, the `run` of the command line, and a DDA stepped from
// Python (docs/python.md). Long calls release the GIL and stop at their next safe point on
// Ctrl-C (KeyboardInterrupt).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/command.h"
#include "app/run.h"
#include "app/stages.h"
#include "app/version.h"
#include "blocks/block_surface.h"
#include "geometry/interrupt.h"
#include "io/input_error.h"
#include "io/scene.h"
#include "scene_model/scene_blocks.h"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace rockmass::python {

namespace {

// ----------------------------------------------------------------------------------------------
// Arrays without copies: a vector moved to the heap, owned by the array's capsule.

template <class T>
py::array_t<T> owned(std::vector<T>&& data, std::vector<py::ssize_t> shape) {
  auto* held = new std::vector<T>(std::move(data));
  py::capsule free(held, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, held->data(), free);
}

/// n x 3 doubles viewing a moved vector of Vec3 (Eigen's Vector3d is three packed doubles).
py::array_t<double> owned(std::vector<geometry::Vec3>&& points) {
  static_assert(sizeof(geometry::Vec3) == 3 * sizeof(double));
  auto* held = new std::vector<geometry::Vec3>(std::move(points));
  py::capsule free(held, [](void* p) { delete static_cast<std::vector<geometry::Vec3>*>(p); });
  return py::array_t<double>({static_cast<py::ssize_t>(held->size()), py::ssize_t{3}},
                             held->empty() ? nullptr : held->front().data(), free);
}

py::array_t<double> vec3(const geometry::Vec3& v) {
  return owned(std::vector<double>{v.x(), v.y(), v.z()}, {3});
}

// ----------------------------------------------------------------------------------------------
// Errors and interruption

/// Raised for a bad scene: the message is the CLI's (file:line:column: key: what).
PyObject* scene_error = nullptr;

/// Runs `work` with the GIL released; Ctrl-C (SIGINT) on the main thread asks it to stop at its
/// next safe point (as the program's handler does) and raises KeyboardInterrupt. Other Python
/// threads run meanwhile.
template <class Work>
auto interruptible(Work&& work) -> decltype(work()) {
  clearInterrupt();
  // Signal handlers belong to the main thread (as Python's own SIGINT handler does).
  const py::module_ threading = py::module_::import("threading");
  const bool main_thread = threading.attr("current_thread")().is(threading.attr("main_thread")());
  struct sigaction previous {};
  bool installed = false;
  if (main_thread) {
    struct sigaction action {};
    action.sa_handler = [](int signal) { requestInterrupt(signal); };
    sigemptyset(&action.sa_mask);
    installed = sigaction(SIGINT, &action, &previous) == 0;
  }
  const auto restore = [&] {
    if (installed) sigaction(SIGINT, &previous, nullptr);
  };
  try {
    py::gil_scoped_release release;
    auto result = work();
    restore();
    throwIfInterrupted("the call");
    return result;
  } catch (const Interrupted&) {
    restore();
    clearInterrupt();
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  } catch (...) {
    restore();
    throw;
  }
}

// ----------------------------------------------------------------------------------------------
// Scenes

/// A scene read and checked, with the file it came from (relative paths and messages).
struct Scene {
  io::Scene scene;
  std::string path;
};

app::CommonOptions optionsOf(const std::string& path) {
  app::CommonOptions options;
  options.scene = path;
  return options;
}

std::shared_ptr<Scene> loadScene(const std::string& path) {
  auto s = std::make_shared<Scene>();
  s->path = path;
  s->scene = app::loadScene(optionsOf(path));
  return s;
}

/// A dict as a scene: written as indented JSON (YAML's flow style), one key per line, so that
/// an error's line and key path point into it; relative paths from `base_dir`.
std::shared_ptr<Scene> sceneFromDict(const py::dict& d, const std::string& base_dir) {
  const std::string text =
      py::module_::import("json").attr("dumps")(d, py::arg("indent") = 1).cast<std::string>();
  auto s = std::make_shared<Scene>();
  s->path = (fs::path(base_dir) / "<dict>.yaml").string();
  s->scene = io::parseScene(text, s->path);
  app::applyCommonOptions(s->scene, optionsOf(s->path));
  return s;
}

// ----------------------------------------------------------------------------------------------
// DFN

struct Dfn {
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<geometry::FractureNetwork> network;
  std::vector<geometry::SetStatistics> stats;
};

std::shared_ptr<Dfn> dfnOf(const std::shared_ptr<Scene>& scene) {
  auto out = std::make_shared<Dfn>();
  out->scene = scene;
  app::DfnStage stage = interruptible([&] { return app::runDfnStage(scene->scene, scene->path); });
  out->network = std::make_shared<geometry::FractureNetwork>(std::move(stage.network));
  out->stats = std::move(stage.stats);
  return out;
}

py::dict dfnArrays(const Dfn& d) {
  const auto& discs = d.network->discs;
  std::vector<geometry::Vec3> centers, normals, majors;
  std::vector<double> axes;
  std::vector<int> sets;
  std::vector<std::int64_t> ids;
  std::vector<std::uint8_t> cuts;
  for (const geometry::Disc& disc : discs) {
    centers.push_back(disc.center);
    normals.push_back(disc.normal);
    majors.push_back(disc.major);
    axes.push_back(disc.a);
    axes.push_back(disc.b);
    sets.push_back(disc.set);
    ids.push_back(disc.id);
    cuts.push_back(disc.cuts ? 1 : 0);
  }
  py::dict r;
  const auto n = static_cast<py::ssize_t>(discs.size());
  r["id"] = owned(std::move(ids), {n});
  r["center"] = owned(std::move(centers));
  r["normal"] = owned(std::move(normals));
  r["major_axis"] = owned(std::move(majors));
  r["semi_axes"] = owned(std::move(axes), {n, 2});
  r["set"] = owned(std::move(sets), {n});
  r["cuts"] = owned(std::move(cuts), {n}).attr("astype")("bool");
  py::list names, stats;
  for (std::size_t k = 0; k < d.network->sets.size(); ++k) {
    names.append(d.network->sets[k].name);
    const geometry::SetStatistics& s = d.stats[k];
    py::dict e;
    e["name"] = d.network->sets[k].name;
    e["count"] = s.count;
    e["p32"] = s.p32;
    e["p10"] = s.p10;
    e["mean_normal"] = vec3(s.mean_normal);
    e["kappa"] = s.kappa;
    stats.append(e);
  }
  r["set_names"] = names;
  r["sets"] = stats;
  return r;
}

// ----------------------------------------------------------------------------------------------
// Blocks

struct Blocks {
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<scene_model::SceneBlocks> cut;
};

std::shared_ptr<Blocks> cutBlocks(const std::shared_ptr<Scene>& scene,
                                  const std::shared_ptr<Dfn>& network, const std::string& cutter) {
  auto out = std::make_shared<Blocks>();
  out->scene = scene;
  out->cut = interruptible([&] {
    const std::string chosen = scene_model::chooseCutter(scene->scene, cutter, scene->path);
    return std::make_shared<scene_model::SceneBlocks>(
        scene_model::cutSceneBlocks(scene->scene, *network->network, chosen, scene->path));
  });
  return out;
}

py::dict blockArrays(const Blocks& b) {
  const auto& blocks = b.cut->model.blocks;
  const auto n = static_cast<py::ssize_t>(blocks.size());
  std::vector<double> volumes;
  std::vector<geometry::Vec3> centroids;
  std::vector<int> ids, materials, structures, pieces;
  for (const blocks::Block& block : blocks) {
    volumes.push_back(block.mass.volume);
    centroids.push_back(block.mass.centroid());
    ids.push_back(block.id);
    materials.push_back(block.material);
    structures.push_back(block.structure);
    pieces.push_back(static_cast<int>(block.pieces.size()));
  }
  py::dict r;
  r["id"] = owned(std::move(ids), {n});
  r["volume"] = owned(std::move(volumes), {n});
  r["centroid"] = owned(std::move(centroids));
  r["material"] = owned(std::move(materials), {n});
  r["structure"] = owned(std::move(structures), {n});
  r["pieces"] = owned(std::move(pieces), {n});
  py::list names;
  for (const io::Material& m : b.scene->scene.materials) names.append(m.name);
  r["material_names"] = names;
  return r;
}

/// The convex pieces of block i: a list of (vertices n x 3, faces as lists of vertex indices).
py::list blockPieces(const Blocks& b, std::size_t i) {
  const auto& blocks = b.cut->model.blocks;
  if (i >= blocks.size()) throw py::index_error("no block " + std::to_string(i));
  py::list out;
  for (const blocks::Piece& piece : blocks[i].pieces) {
    std::vector<geometry::Vec3> vertices = piece.shape.vertices;
    py::list faces;
    for (const auto& face : piece.shape.faces) faces.append(py::cast(face));
    out.append(py::make_tuple(owned(std::move(vertices)), faces));
  }
  return out;
}

/// The closed outer surface of block i: (vertices n x 3, triangles m x 3).
py::tuple blockSurface(const Blocks& b, std::size_t i) {
  const auto& blocks = b.cut->model.blocks;
  if (i >= blocks.size()) throw py::index_error("no block " + std::to_string(i));
  blocks::TriangleSurface s = blocks::blockSurface(blocks[i]);
  std::vector<int> triangles;
  for (const auto& t : s.triangles) triangles.insert(triangles.end(), t.begin(), t.end());
  const auto m = static_cast<py::ssize_t>(s.triangles.size());
  return py::make_tuple(owned(std::move(s.vertices)), owned(std::move(triangles), {m, 3}));
}

// ----------------------------------------------------------------------------------------------
// RQD

py::dict rqdOf(const std::shared_ptr<Scene>& scene, const std::shared_ptr<Dfn>& network) {
  app::RqdOverrides overrides;
  app::RqdStage stage = interruptible([&] {
    app::RqdPlan plan = app::planRqd(scene->scene, overrides, scene->path);
    return app::runRqdStage(scene->scene, scene->path, *network->network, std::move(plan),
                            overrides);
  });
  io::RqdReport& report = stage.report;
  py::dict r;
  r["thresholds"] = report.thresholds;
  py::list balls;
  for (io::BallReport& ball : report.balls) {
    py::dict e;
    e["name"] = ball.name;
    e["center"] = vec3(ball.spec.center);
    e["length"] = ball.spec.length;
    const auto m = static_cast<py::ssize_t>(ball.result.directions.size());
    const auto t = static_cast<py::ssize_t>(ball.result.thresholds.size());
    e["thresholds"] = ball.result.thresholds;
    e["directions"] = owned(std::move(ball.result.directions));
    e["rqd"] = owned(std::move(ball.result.rqd), {m, t});  // [direction, threshold] (%)
    balls.append(e);
  }
  r["balls"] = balls;
  py::list holes;
  if (report.boreholes) {
    const io::BoreholeReport& b = *report.boreholes;
    for (std::size_t h = 0; h < b.holes.size(); ++h) {
      py::dict e;
      e["id"] = b.holes[h].id;
      e["collar"] = vec3(b.holes[h].collar);
      e["length"] = b.holes[h].length;
      e["thresholds"] = b.thresholds;
      e["rqd"] = b.hole_rqd[h];
      holes.append(e);
    }
  }
  r["boreholes"] = holes;
  return r;
}

// ----------------------------------------------------------------------------------------------
// run (the command line's), and the summary as a dict

py::object readJson(const fs::path& file) {
  std::ifstream in(file);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return py::module_::import("json").attr("loads")(text);
}

py::object run(const std::shared_ptr<Scene>& scene, const std::string& out, bool quick,
               bool figures) {
  app::RunOptions options;
  options.common = optionsOf(scene->path);
  options.common.output = out;
  options.quick = quick;
  options.no_figures = !figures;
  interruptible([&] { return app::runScene(options, scene->scene); });
  return readJson(fs::path(out) / "summary.json");
}

/// Runs the scene's DDA-based stability analysis `which` ("overload" or "strength_reduction")
/// alone, as `rockmass overload` / `rockmass strength` do, into `out`; returns summary.json.
py::object stability(const std::shared_ptr<Scene>& scene, const std::string& out, bool quick,
                     const std::string& which) {
  io::Scene s = scene->scene;
  const bool overload = which == "overload";
  if (overload ? !s.analysis.overload : !s.analysis.strength_reduction) {
    throw io::InputError(scene->path + ": analysis." + which + ": the scene has no " + which +
                         " analysis");
  }
  if (overload) {
    s.analysis.strength_reduction.reset();
  } else {
    s.analysis.overload.reset();
  }
  s.analysis.rqd.reset();
  app::RunOptions options;
  options.common = optionsOf(scene->path);
  options.common.output = out;
  options.quick = quick;
  options.no_figures = true;
  options.section = "none";
  interruptible([&] { return app::runScene(options, std::move(s)); });
  return readJson(fs::path(out) / "summary.json");
}

// ----------------------------------------------------------------------------------------------
// A DDA stepped from Python

struct Dda {
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<scene_model::SceneBlocks> region;  // the DDA's own cut, when it has a region
  blocks::BlockModel model;                          // the DDA's blocks (glued)
  app::DdaRun run;
  std::vector<std::string> monitor_names;
};

std::shared_ptr<Dda> makeDda(const std::shared_ptr<Scene>& scene, const std::shared_ptr<Dfn>& d,
                             const std::optional<std::shared_ptr<Blocks>>& cut) {
  if (!scene->scene.analysis.dda) {
    throw io::InputError(scene->path + ": analysis.dda: the scene has no DDA analysis");
  }
  auto out = std::make_shared<Dda>();
  out->scene = scene;
  interruptible([&] {
    const io::Scene dda_scene = scene_model::ddaScene(scene->scene);
    std::optional<blocks::MergeReport> glued;
    const std::string cutter = scene_model::chooseCutter(scene->scene, "", scene->path);
    if (scene->scene.analysis.dda->region || !cut) {
      out->region = std::make_shared<scene_model::SceneBlocks>(
          scene_model::cutSceneBlocks(dda_scene, *d->network, cutter, scene->path));
      out->model = scene_model::ddaBlocks(dda_scene, out->region->model, glued);
    } else {
      out->model = scene_model::ddaBlocks(dda_scene, (*cut)->cut->model, glued);
    }
    out->run = app::makeDdaRun(dda_scene, out->model, *d->network, app::DdaOverrides{});
    return 0;
  });
  for (const dda3d::DdaMonitor& m : out->run.simulation->model().monitors) {
    out->monitor_names.push_back(m.name);
  }
  return out;
}

py::dict stepOnce(Dda& dda) {
  const dda3d::StepReport report = interruptible([&] { return dda.run.simulation->step(); });
  py::dict r;
  r["time"] = dda.run.simulation->time();
  r["time_step"] = report.time_step;
  r["iterations"] = report.iterations;
  r["contacts"] = report.contacts.total;
  r["open"] = report.contacts.open;
  r["sliding"] = report.contacts.sliding;
  r["displacement_ratio"] = report.displacement_ratio;
  r["max_penetration"] = report.max_penetration;
  return r;
}

py::list monitors(const Dda& dda) {
  py::list out;
  for (const dda3d::MonitorState& m : dda.run.simulation->monitors()) {
    py::dict e;
    e["name"] = m.name;
    e["position"] = vec3(m.position);
    e["displacement"] = vec3(m.displacement);
    e["velocity"] = vec3(m.velocity);
    out.append(e);
  }
  return out;
}

py::dict blockStates(const Dda& dda) {
  const dda3d::Simulation& sim = *dda.run.simulation;
  const auto& blocks = sim.blocks();
  const auto n = static_cast<py::ssize_t>(blocks.size());
  std::vector<geometry::Vec3> centroids, displacements;
  std::vector<double> velocity, stress;
  std::vector<std::uint8_t> fixed;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    centroids.push_back(blocks[b].centroid);
    displacements.push_back(sim.centroidDisplacement(static_cast<int>(b)));
    for (int k = 0; k < 12; ++k) velocity.push_back(blocks[b].velocity[k]);
    for (int k = 0; k < 6; ++k) stress.push_back(blocks[b].stress[k]);
    fixed.push_back(blocks[b].fixed ? 1 : 0);
  }
  py::dict r;
  r["centroid"] = owned(std::move(centroids));
  r["displacement"] = owned(std::move(displacements));
  r["velocity"] = owned(std::move(velocity), {n, 12});  // u, v, w, rotations, strain rates
  r["stress"] = owned(std::move(stress), {n, 6});  // Voigt: xx yy zz yz zx xy (Pa, tension > 0)
  r["fixed"] = owned(std::move(fixed), {n}).attr("astype")("bool");
  return r;
}

geometry::Vec3 toVec3(const std::vector<double>& v, const char* what) {
  if (v.size() != 3) throw py::value_error(std::string(what) + ": expected 3 numbers");
  return {v[0], v[1], v[2]};
}

}  // namespace
}  // namespace rockmass::python

using namespace rockmass::python;  // NOLINT: the module's definitions below
namespace io = rockmass::io;
namespace app = rockmass::app;
namespace dda3d = rockmass::dda3d;

PYBIND11_MODULE(rockmass, m) {
  m.doc() =
      "rockmass: fractured rock workbench (DFN, blocks, RQD, 3D DDA) from Python "
      "(docs/python.md)";
  scene_error = PyErr_NewException("rockmass.SceneError", PyExc_ValueError, nullptr);
  m.attr("SceneError") = py::handle(scene_error);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const io::InputError& e) {
      PyErr_SetString(scene_error, e.what());
    } catch (const dda3d::StepFailure& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
  });
  m.attr("__version__") = app::versionText();

  py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene", "A scene read and checked")
      .def_property_readonly("name", [](const Scene& s) { return s.scene.name; })
      .def_property_readonly("seed", [](const Scene& s) { return s.scene.seed; })
      .def_property_readonly("path", [](const Scene& s) { return s.path; })
      .def_property_readonly("has_dda",
                             [](const Scene& s) { return s.scene.analysis.dda.has_value(); })
      .def("__repr__", [](const Scene& s) {
        return "<rockmass.Scene '" + s.scene.name + "' from " + s.path + ">";
      });
  m.def("load_scene", &loadScene, py::arg("path"),
        "Reads and checks a scene file; SceneError (file:line:column: key: what) when bad");
  m.def("scene_from_dict", &sceneFromDict, py::arg("scene"), py::arg("base_dir") = ".",
        "A scene from a dict (the YAML's structure); relative paths from base_dir");

  py::class_<Dfn, std::shared_ptr<Dfn>>(m, "Dfn", "A fracture network")
      .def_property_readonly("count", [](const Dfn& d) { return d.network->discs.size(); })
      .def("arrays", &dfnArrays,
           "id, center, normal, major_axis (n x 3), semi_axes (n x 2: a, b), set, cuts; "
           "set_names; sets (count, p32, p10, mean normal, kappa per set)");
  m.def("dfn", &dfnOf, py::arg("scene"), "Generates the scene's fracture network");

  py::class_<Blocks, std::shared_ptr<Blocks>>(m, "Blocks", "The blocks of a cut")
      .def_property_readonly("count", [](const Blocks& b) { return b.cut->model.blocks.size(); })
      .def("arrays", &blockArrays,
           "id, volume, centroid (n x 3), material, structure (-1: rock), pieces; material_names")
      .def("pieces", &blockPieces, py::arg("block"),
           "Convex pieces of a block (0-based index): [(vertices, faces)]")
      .def("surface", &blockSurface, py::arg("block"),
           "Closed outer surface of a block: (vertices n x 3, triangles m x 3)");
  m.def("blocks", &cutBlocks, py::arg("scene"), py::arg("dfn"), py::arg("cutter") = "",
        "Cuts the scene's domain into blocks (cutter: '', 'fast' or 'exact')");
  m.def("rqd", &rqdOf, py::arg("scene"), py::arg("dfn"),
        "RQD balls ({name, center, directions m x 3, thresholds, rqd m x t}) and boreholes");
  m.def("run", &run, py::arg("scene"), py::arg("out"), py::arg("quick") = false,
        py::arg("figures") = false,
        "Every stage the scene names, as `rockmass run SCENE -o OUT`; returns summary.json");

  m.def(
      "overload",
      [](const std::shared_ptr<Scene>& s, const std::string& out, bool quick) {
        return stability(s, out, quick, "overload");
      },
      py::arg("scene"), py::arg("out"), py::arg("quick") = false,
      "The overload analysis (with the DDA it runs on) into out; returns summary.json "
      "(K_s in ['overload']['K_s'], the runs in ['overload']['runs'])");
  m.def(
      "strength",
      [](const std::shared_ptr<Scene>& s, const std::string& out, bool quick) {
        return stability(s, out, quick, "strength_reduction");
      },
      py::arg("scene"), py::arg("out"), py::arg("quick") = false,
      "The strength reduction into out; returns summary.json (['strength_reduction'])");

  py::class_<Dda, std::shared_ptr<Dda>>(m, "Dda", "A DDA of the scene, stepped from Python")
      .def(py::init(&makeDda), py::arg("scene"), py::arg("dfn"), py::arg("blocks") = py::none())
      .def("step", &stepOnce, "One accepted step; returns its report")
      .def(
          "run",
          [](Dda& d, int steps) {
            py::list reports;
            for (int k = 0; k < steps; ++k) reports.append(stepOnce(d));
            return reports;
          },
          py::arg("steps"))
      .def_property_readonly("time", [](const Dda& d) { return d.run.simulation->time(); })
      .def_property_readonly("monitor_names", [](const Dda& d) { return d.monitor_names; })
      .def("monitors", &monitors, "Each monitor's name, position, displacement, velocity")
      .def("blocks", &blockStates,
           "centroid, displacement (n x 3), velocity (n x 12), stress (n x 6: xx yy zz yz zx "
           "xy, Pa), fixed")
      .def(
          "set_gravity",
          [](Dda& d, const std::vector<double>& g) {
            d.run.simulation->setGravity(toVec3(g, "gravity"));
          },
          py::arg("gravity"), "Gravity (m/s^2) from the next step on")
      .def(
          "set_point_load",
          [](Dda& d, std::size_t k, const std::vector<double>& f) {
            if (k >= d.run.simulation->model().point_loads.size()) {
              throw py::index_error("no point load " + std::to_string(k));
            }
            d.run.simulation->setPointLoadForce(k, toVec3(f, "force"));
          },
          py::arg("index"), py::arg("force"), "Force (N) of point load k from the next step on");
}
