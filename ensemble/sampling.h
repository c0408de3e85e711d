// The realizations of an ensemble: each one's seed and sample of the scene's uncertain inputs
// (io::Uncertainty), derived from the scene's seed and the realization's index only, so that a
// realization is the same whoever runs it, alone or in an ensemble, in whatever order
// (docs/ensemble.md).
#pragma once

#include <cstdint>
#include <vector>

#include "io/scene.h"

namespace rockmass::ensemble {

/// The seed of realization `index` (0-based): SplitMix64 of the scene's seed and the index.
std::uint64_t realizationSeed(std::uint64_t scene_seed, int index);

/// The probability at which realization `index` draws input `input`, in (0, 1): a uniform
/// draw (Monte Carlo), or a random point of the index's stratum in that input's random
/// permutation of the `u.size` strata (Latin hypercube, McKay, Beckman & Conover 1979).
double probabilityOf(const io::Uncertainty& u, std::uint64_t scene_seed, int index, int input);

/// The value of `input` at probability p (its inverse distribution function; Boost.Math).
double quantile(const io::UncertainInput& input, double p);

/// Every input's value for realization `index`.
std::vector<double> sampleInputs(const io::Uncertainty& u, std::uint64_t scene_seed, int index);

}  // namespace rockmass::ensemble
