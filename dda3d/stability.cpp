#include "dda3d/stability.h"

#include <optional>
#include <stdexcept>
#include <utility>

namespace rockmass::dda3d {

DdaModel scaledLoads(const DdaModel& model, const LoadScaling& scaling, double factor) {
  DdaModel out = model;
  if (scaling.gravity) out.gravity *= factor;
  if (scaling.seismic) {
    out.seismic *= factor;
    for (DdaHydrodynamicPressure& p : out.hydrodynamic) p.k_h *= factor;
  }
  for (DdaPressure& p : out.pressures) {
    if (p.uplift ? scaling.uplift : scaling.water) p.unit_weight *= factor;
  }
  if (scaling.point_loads) {
    for (DdaPointLoad& l : out.point_loads) l.force *= factor;
  }
  return out;
}

DdaModel reducedStrength(const DdaModel& model, double srf) {
  if (!(srf > 0.0)) throw std::invalid_argument("a strength reduction factor must be > 0");
  DdaModel out = model;
  for (DdaJoint& j : out.joints) {
    j.friction /= srf;
    j.cohesion /= srf;
  }
  return out;
}

namespace {

/// Where an incremental search's next run starts: the end of the run at rest that set the
/// bracket's lower end.
struct RestState {
  DdaModel model;  ///< settledModel of that run
  std::vector<Contact> contacts;
};

/// One run of `make(factor)` to equilibrium, from `from` (incremental) or from the search's
/// start. With `keep`, the run's end state is stored there when it came to rest.
FactorRun runFactor(const std::function<DdaModel(double)>& make, const DdaSettings& settings,
                    const FactorSearch& search, const RestState* from, double factor,
                    bool bisection, std::optional<RestState>* keep) {
  DdaModel model = make(factor);
  std::vector<geometry::Vec3> origins;  // the monitors where the search started
  for (const DdaMonitor& m : model.monitors) origins.push_back(m.point);
  if (from) model = carriedState(std::move(model), from->model);
  Simulation sim(std::move(model), settings);
  const std::vector<Contact>& contacts = from ? from->contacts : search.start_contacts;
  if (!contacts.empty()) sim.adoptContacts(contacts);
  FactorRun run;
  run.factor = factor;
  run.bisection = bisection;
  run.equilibrium = runToEquilibrium(sim, search.equilibrium);
  run.monitors = sim.monitors();
  for (std::size_t k = 0; k < run.monitors.size(); ++k) {
    run.monitors[k].displacement = run.monitors[k].position - origins[k];
  }
  run.terms = sim.activeTerms();
  run.bolts = sim.bolts();
  if (keep && run.equilibrium.reached) *keep = RestState{settledModel(sim), sim.contacts()};
  return run;
}

}  // namespace

FactorSearchResult searchCriticalFactor(const std::function<DdaModel(double)>& make,
                                        const DdaSettings& settings, const FactorSearch& search,
                                        const FactorRunCallback& callback) {
  if (search.factors.empty()) throw std::invalid_argument("the factor search has no factor");
  for (std::size_t k = 1; k < search.factors.size(); ++k) {
    if (!(search.factors[k] > search.factors[k - 1])) {
      throw std::invalid_argument("the factors of a search must increase");
    }
  }
  FactorSearchResult result;
  result.incremental = search.incremental;
  // The end of the run that set last_stable (incremental searches only).
  std::optional<RestState> low_state;
  // Runs `factor`; `raises_low`: a run at rest there becomes the bracket's lower end.
  const auto run = [&](double factor, bool bisection, bool raises_low) {
    std::optional<RestState> end;
    result.runs.push_back(runFactor(make, settings, search, low_state ? &*low_state : nullptr,
                                    factor, bisection,
                                    search.incremental && raises_low ? &end : nullptr));
    if (end) low_state = std::move(end);
    if (callback) callback(result.runs.back());
    return result.runs.back().equilibrium.reached;
  };
  for (double factor : search.factors) {
    const bool stable = run(factor, false, !result.first_unstable);
    if (!result.first_unstable) {
      if (stable) {
        result.last_stable = factor;
      } else {
        result.first_unstable = factor;
        if (!search.sweep_all) break;
      }
    }
  }
  if (!result.last_stable || !result.first_unstable) return result;
  double low = *result.last_stable, high = *result.first_unstable;
  while (search.tolerance > 0.0 && high - low > search.tolerance) {
    const double middle = 0.5 * (low + high);
    (run(middle, true, true) ? low : high) = middle;
  }
  result.last_stable = low;
  result.first_unstable = high;
  result.critical = 0.5 * (low + high);
  return result;
}

FactorSearchResult runOverload(const DdaModel& model, const DdaSettings& settings,
                               const LoadScaling& scaling, const FactorSearch& search,
                               const FactorRunCallback& callback) {
  return searchCriticalFactor([&](double k) { return scaledLoads(model, scaling, k); }, settings,
                              search, callback);
}

FactorSearchResult runStrengthReduction(const DdaModel& model, const DdaSettings& settings,
                                        const FactorSearch& search,
                                        const FactorRunCallback& callback) {
  return searchCriticalFactor([&](double srf) { return reducedStrength(model, srf); }, settings,
                              search, callback);
}

DdaModel settledModel(const Simulation& sim) {
  DdaModel out = sim.model();
  const std::vector<BlockState>& blocks = sim.blocks();
  for (std::size_t b = 0; b < out.blocks.size(); ++b) {
    out.blocks[b].pieces = blocks[b].pieces;
    out.blocks[b].initial_stress = blocks[b].stress;
    out.blocks[b].initial_velocity.setZero();
    out.blocks[b].initial_angular_velocity.setZero();
  }
  const std::vector<MonitorState> monitors = sim.monitors();
  for (std::size_t k = 0; k < out.monitors.size(); ++k)
    out.monitors[k].point = monitors[k].position;
  const std::vector<geometry::Vec3> loads = sim.pointLoadPositions();
  for (std::size_t k = 0; k < out.point_loads.size() && k < loads.size(); ++k) {
    out.point_loads[k].point = loads[k];
  }
  // Supports keep their anchors and carry their reactions on: each fixed point's spring
  // stays stretched from where it was fixed to where its block carried it. Re-anchored where
  // the block is now, a roller lost its reaction at the restart, the blocks against it were
  // pushed by their neighbours alone, and the quick Xiangjiaba scene's deformable toe block
  // on the downstream rollers did not come back to rest (RunCli.XiangjiabaQuickDeformable*).
  const std::vector<geometry::Vec3> supports = sim.fixedPointPositions();
  for (std::size_t k = 0; k < out.fixed_points.size() && k < supports.size(); ++k) {
    out.fixed_points[k].current = supports[k];
  }
  // Bolts carry their force on: set between their points as they are now, pretensioned to the
  // force they hold (the same spring), broken ones still broken.
  const auto positions = sim.boltPositions();
  for (std::size_t k = 0; k < out.bolts.size(); ++k) {
    out.bolts[k].point_a = positions[k].first;
    out.bolts[k].point_b = positions[k].second;
    out.bolts[k].pretension = sim.bolts()[k].force;
    out.bolts[k].broken = sim.bolts()[k].broken;
  }
  return out;
}

DdaModel carriedState(DdaModel target, const DdaModel& state) {
  if (target.blocks.size() != state.blocks.size() ||
      target.monitors.size() != state.monitors.size() ||
      target.point_loads.size() != state.point_loads.size() ||
      target.fixed_points.size() != state.fixed_points.size() ||
      target.bolts.size() != state.bolts.size()) {
    throw std::invalid_argument("a state carries over only to a model of the same blocks");
  }
  for (std::size_t b = 0; b < target.blocks.size(); ++b) {
    DdaBlock& to = target.blocks[b];
    const DdaBlock& from = state.blocks[b];
    if (to.pieces.size() != from.pieces.size()) {
      throw std::invalid_argument("a state carries over only to a model of the same blocks");
    }
    to.pieces = from.pieces;
    to.initial_stress = from.initial_stress;
    to.initial_velocity = from.initial_velocity;
    to.initial_angular_velocity = from.initial_angular_velocity;
  }
  for (std::size_t k = 0; k < target.monitors.size(); ++k)
    target.monitors[k].point = state.monitors[k].point;
  for (std::size_t k = 0; k < target.point_loads.size(); ++k)
    target.point_loads[k].point = state.point_loads[k].point;
  for (std::size_t k = 0; k < target.fixed_points.size(); ++k)
    target.fixed_points[k].current = state.fixed_points[k].current;
  for (std::size_t k = 0; k < target.bolts.size(); ++k) {
    DdaBolt& to = target.bolts[k];
    const DdaBolt& from = state.bolts[k];
    to.point_a = from.point_a;
    to.point_b = from.point_b;
    to.pretension = from.pretension;
    to.broken = from.broken;
  }
  return target;
}

}  // namespace rockmass::dda3d
