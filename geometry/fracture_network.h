#pragma once
/// The discrete fracture network (DFN): generation from a DfnSpec.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/dfn_spec.h"
#include "geometry/disc.h"

namespace rockmass::geometry {

/// What the generator knows and measured about one set (joint set, fault, interlayer,
/// or polygon file).
struct SetInfo {
  std::string name;                          ///< set name
  DiscOrigin origin = DiscOrigin::JointSet;  ///< kind of set
  Vec3 mean_normal = Vec3::UnitZ();  ///< mean normal of the sampled orientation model (unit)
  double target_p10 = 0.0;           ///< 1/mean spacing along mean_normal (1/m); 0 if not set
  double target_p32 = 0.0;           ///< target area per volume (m2/m3); 0 if not set
  double size_scale = 0.0;           ///< equal-area diameter / sampled trace length
  double margin = 0.0;               ///< enlargement of the domain for centres (m)
  std::int64_t generated = 0;        ///< discs drawn in the enlarged domain
};

/// A slab (fault or interlayer with thickness): the region between two surfaces.
struct Slab {
  int set = 0;                      ///< set index of the fault or interlayer
  int material = -1;                ///< material index
  double thickness = 0.0;           ///< m
  std::vector<std::int64_t> lower;  ///< ids of the discs bounding it on one side
  std::vector<std::int64_t> upper;  ///< ids of the discs bounding it on the other side
};

/// All fractures of a site: every disc that touches the domain, with provenance.
struct FractureNetwork {
  Box domain;                 ///< rock volume (m)
  std::vector<SetInfo> sets;  ///< joint sets, then faults, interlayers, polygon files
  std::vector<Disc> discs;    ///< ids are 1..N in this order
  std::vector<Slab> slabs;    ///< slabs of thick faults and interlayers
};

/// What the generator may draw before it refuses the spec.
struct GenerationLimits {
  /// Largest expected number of joint-set discs drawn (centres placed in the enlarged
  /// domains, summed over the sets): 5e6 take about 5 s and at most ~1 GB.
  double max_discs = 5e6;
};

/// A spec whose joint sets would draw more discs than GenerationLimits::max_discs, refused
/// before any disc is drawn. `set()` is the set that draws the most; `bySize()` says whether
/// its largest discs (the margin around the domain) rather than its intensity drive it.
class DiscBudgetExceeded : public std::invalid_argument {
 public:
  DiscBudgetExceeded(int set, bool by_size, double expected, double total, double limit,
                     double margin);
  int set() const { return set_; }
  bool bySize() const { return by_size_; }

 private:
  static std::string budgetMessage(bool by_size, double expected, double total, double limit,
                                   double margin);
  int set_;
  bool by_size_;
};

/// Generates the network. Deterministic: the same spec and seed give the same discs.
/// Throws std::invalid_argument for a spec it cannot honour (with a message that says why),
/// DiscBudgetExceeded before any disc is drawn when the joint sets exceed `limits`.
FractureNetwork generateNetwork(const DfnSpec& spec, std::uint64_t seed,
                                const GenerationLimits& limits = {});

/// Ratio between the equal-area diameter D of a disc and the trace length L drawn from a
/// set's trace-length distribution, D = c L. See fracture_network.cpp for the derivation.
double traceToDiameterScale(const DistributionSpec& trace_length);

/// Per-set measurements of a network inside its domain.
struct SetStatistics {
  std::int64_t count = 0;            ///< discs of the set that touch the domain
  double p32 = 0.0;                  ///< disc area inside the domain / domain volume (m2/m3)
  double p10 = 0.0;                  ///< mean crossings per metre along the set's mean normal (1/m)
  Vec3 mean_normal = Vec3::UnitZ();  ///< Fisher mean of the disc normals (unit)
  double kappa = 0.0;                ///< Fisher concentration estimate (0 for fewer than 2 discs)
};
/// Measures every set of `network` (in the order of network.sets).
std::vector<SetStatistics> measureSets(const FractureNetwork& network);

}  // namespace rockmass::geometry
