// Safety factors of a DDA model (docs/stability.md): the overload method (multiply loads by
// K until the model no longer comes to rest) and strength reduction (divide the joints'
// friction and cohesion by SRF until it no longer does). Both search one factor the same
// way: a sweep over the given factors, then bisection of the bracket between the last
// factor at rest and the first that is not.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "dda3d/equilibrium.h"
#include "dda3d/model.h"
#include "dda3d/simulation.h"

namespace rockmass::dda3d {

/// Which loads the overload factor multiplies.
struct LoadScaling {
  bool gravity = false;      ///< body forces (DdaModel::gravity)
  bool water = false;        ///< pressures on exposed faces (DdaPressure, uplift = false)
  bool uplift = false;       ///< pressures in structure-rock interfaces (uplift = true)
  bool point_loads = false;  ///< DdaModel::point_loads
  bool seismic = false;      ///< DdaModel::seismic and the hydrodynamic pressures' k_h
};

/// `model` with the loads named in `scaling` multiplied by `factor` (water through its
/// unit weight, so the free surface stays where it is).
DdaModel scaledLoads(const DdaModel& model, const LoadScaling& scaling, double factor);

/// `model` with the friction f = tan(phi) and cohesion c of every joint divided by `srf`
/// (tensile strength unchanged).
DdaModel reducedStrength(const DdaModel& model, double srf);

/// How the critical factor is searched.
struct FactorSearch {
  std::vector<double> factors;  ///< increasing; the sweep
  /// Bisect the bracket [last factor at rest, first not at rest] until it is at most this
  /// wide (0: no bisection, the sweep's bracket is the answer).
  double tolerance = 0.0;
  /// Run every factor of the sweep (the overload curve), or stop at the first that is not at
  /// rest (strength reduction).
  bool sweep_all = true;
  EquilibriumSettings equilibrium;  ///< what counts as at rest
  /// Contacts every run starts from (Simulation::adoptContacts), e.g. those of the run that
  /// settled the model (settledModel); empty: each run detects its own from scratch.
  std::vector<Contact> start_contacts;
  /// false: every run starts from the search's start (the model `make` gives, with
  /// start_contacts). true (incremental): a run starts where the run at rest that set the
  /// bracket's lower end (last_stable) ended, its blocks, contacts, supports and bolts as
  /// they were (carriedState), with the model of its own factor; the first, and every run
  /// before any came to rest, from the search's start. The loads or strengths then change
  /// by steps, as in a finite-element strength reduction that continues from the state of
  /// the last factor (Plaxis's phi-c reduction), rather than all at once from the start.
  /// Monitor displacements are counted from the search's start either way.
  bool incremental = false;
};

/// One run at one factor.
struct FactorRun {
  double factor = 0.0;                 ///< K or SRF
  bool bisection = false;              ///< run by the bisection (not one of the sweep's factors)
  EquilibriumResult equilibrium;       ///< how the run ended
  std::vector<MonitorState> monitors;  ///< at the end of the run
  ActiveTerms terms;                   ///< the sub-matrices the run assembled
  std::vector<BoltState> bolts;        ///< each bolt at the end of the run
};

/// The result of a search.
struct FactorSearchResult {
  std::vector<FactorRun> runs;           ///< in the order they ran: the sweep, then the bisection
  std::optional<double> last_stable;     ///< largest factor at rest below first_unstable
  std::optional<double> first_unstable;  ///< smallest factor not at rest
  /// The critical factor: the middle of [last_stable, first_unstable] when both exist
  /// (within half the bracket width of the true one), else none.
  std::optional<double> critical;
  bool incremental = false;  ///< the runs followed the incremental path (FactorSearch)
};

/// Called after each run (progress output).
using FactorRunCallback = std::function<void(const FactorRun&)>;

/// Runs `make(factor)` to equilibrium from its initial state for each factor the search
/// needs (see FactorSearch) and returns the bracket and critical factor. The rule: the
/// first factor (ascending) at which the model does not come to rest within the step limit
/// marks the loss of stability; factors above it are not used to bracket.
FactorSearchResult searchCriticalFactor(const std::function<DdaModel(double)>& make,
                                        const DdaSettings& settings, const FactorSearch& search,
                                        const FactorRunCallback& callback = {});

/// Overload method: K_s, the critical factor of scaledLoads(model, scaling, K).
FactorSearchResult runOverload(const DdaModel& model, const DdaSettings& settings,
                               const LoadScaling& scaling, const FactorSearch& search,
                               const FactorRunCallback& callback = {});

/// Strength reduction: the critical SRF of reducedStrength(model, SRF).
FactorSearchResult runStrengthReduction(const DdaModel& model, const DdaSettings& settings,
                                        const FactorSearch& search,
                                        const FactorRunCallback& callback = {});

/// `sim`'s model with its blocks where the run has brought them: every piece as it is now,
/// each deformable block's stress as its initial stress, the monitors and point loads at
/// their current positions. A run of the result starts from that state: the contact springs
/// stay as pressed as they are (their penetrations are in the geometry); with sim.contacts()
/// as FactorSearch::start_contacts the contact states, shear springs and forces carry over
/// too. The fixed points' springs start unloaded again. The start of the overload and
/// strength-reduction runs from the settled (geostatic) state (analysis.equilibrium.start:
/// settled, docs/stability.md).
DdaModel settledModel(const Simulation& sim);

/// `target` (a model of the same blocks, e.g. with other loads or strengths) in the state of
/// `state` (a settledModel): its pieces, stresses, monitor and point-load positions, the
/// supports' current positions and the bolts as they are in `state`; everything else
/// (materials, joints, loads) of `target`. Throws std::invalid_argument when the two do not
/// have the same blocks, monitors, point loads, supports and bolts.
DdaModel carriedState(DdaModel target, const DdaModel& state);

}  // namespace rockmass::dda3d
