#include "dda3d/stability.h"

#include <stdexcept>

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

/// One run of `make(factor)` to equilibrium.
FactorRun runFactor(const std::function<DdaModel(double)>& make, const DdaSettings& settings,
                    const EquilibriumSettings& equilibrium,
                    const std::vector<Contact>& start_contacts, double factor, bool bisection) {
  Simulation sim(make(factor), settings);
  if (!start_contacts.empty()) sim.adoptContacts(start_contacts);
  FactorRun run;
  run.factor = factor;
  run.bisection = bisection;
  run.equilibrium = runToEquilibrium(sim, equilibrium);
  run.monitors = sim.monitors();
  run.terms = sim.activeTerms();
  run.bolts = sim.bolts();
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
  const auto run = [&](double factor, bool bisection) {
    result.runs.push_back(
        runFactor(make, settings, search.equilibrium, search.start_contacts, factor, bisection));
    if (callback) callback(result.runs.back());
    return result.runs.back().equilibrium.reached;
  };
  for (double factor : search.factors) {
    const bool stable = run(factor, false);
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
    (run(middle, true) ? low : high) = middle;
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

}  // namespace rockmass::dda3d
