#include "ensemble/sampling.h"

#include <boost/math/distributions/lognormal.hpp>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/triangular.hpp>
#include <cmath>
#include <map>
#include <mutex>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace rockmass::ensemble {

namespace {

/// SplitMix64's output function (Steele, Lea & Flood 2014): a well-mixed 64-bit hash.
std::uint64_t mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// A double in (0, 1) from 53 bits of a hash.
double unitOf(std::uint64_t bits) {
  return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53;
}

/// Streams of draws, kept apart so that no two uses share a hash input.
enum Stream : std::uint64_t { kSeed = 1, kDraw = 2, kPermutation = 3 };

std::uint64_t hashOf(std::uint64_t seed, Stream stream, std::uint64_t a, std::uint64_t b) {
  return mix(mix(mix(seed ^ mix(stream)) ^ a) ^ mix(b + 0x632be59bd9b4e019ULL));
}

/// The stratum of realization `index` in the random permutation of `size` strata for an
/// input (Fisher-Yates, from the end). Each permutation is made once and kept: an ensemble
/// draws every realization's inputs before it starts (O(size) each, not O(size^2) in all).
int stratumOf(std::uint64_t seed, int input, int size, int index) {
  static std::mutex mutex;
  static std::map<std::tuple<std::uint64_t, int, int>, std::vector<int>> permutations;
  const std::lock_guard<std::mutex> lock(mutex);
  std::vector<int>& order = permutations[{seed, input, size}];
  if (order.empty()) {
    order.resize(static_cast<std::size_t>(size));
    std::iota(order.begin(), order.end(), 0);
    for (int k = size - 1; k > 0; --k) {
      const std::uint64_t bits = hashOf(seed, kPermutation, static_cast<std::uint64_t>(input),
                                        static_cast<std::uint64_t>(k));
      const auto j = static_cast<int>(bits % static_cast<std::uint64_t>(k + 1));
      std::swap(order[static_cast<std::size_t>(k)], order[static_cast<std::size_t>(j)]);
    }
  }
  return order[static_cast<std::size_t>(index)];
}

}  // namespace

std::uint64_t realizationSeed(std::uint64_t scene_seed, int index) {
  return hashOf(scene_seed, kSeed, static_cast<std::uint64_t>(index), 0);
}

double probabilityOf(const io::Uncertainty& u, std::uint64_t scene_seed, int index, int input) {
  const double draw = unitOf(hashOf(scene_seed, kDraw, static_cast<std::uint64_t>(index),
                                    static_cast<std::uint64_t>(input)));
  if (!u.latin_hypercube) return draw;
  if (index < 0 || index >= u.size) {
    throw std::out_of_range("realization " + std::to_string(index) +
                            " is outside the Latin hypercube of size " + std::to_string(u.size));
  }
  return (stratumOf(scene_seed, input, u.size, index) + draw) / u.size;
}

double quantile(const io::UncertainInput& input, double p) {
  namespace bm = boost::math;
  const std::string& kind = input.distribution;
  if (kind == "normal" || kind == "sample_mean") {
    const bm::normal normal(input.mean, input.std);
    const double low = std::isfinite(input.min) ? bm::cdf(normal, input.min) : 0.0;
    const double high = std::isfinite(input.max) ? bm::cdf(normal, input.max) : 1.0;
    if (!(high > low)) return std::clamp(input.mean, input.min, input.max);
    return std::clamp(bm::quantile(normal, low + p * (high - low)), input.min, input.max);
  }
  if (kind == "lognormal") {
    // The value's mean m and standard deviation s: sigma^2 = ln(1 + s^2 / m^2),
    // mu = ln m - sigma^2 / 2.
    const double sigma2 = std::log1p(input.std * input.std / (input.mean * input.mean));
    const bm::lognormal lognormal(std::log(input.mean) - 0.5 * sigma2, std::sqrt(sigma2));
    return bm::quantile(lognormal, p);
  }
  if (kind == "uniform") return input.min + p * (input.max - input.min);
  if (kind == "triangular") {
    return bm::quantile(bm::triangular(input.min, input.mode, input.max), p);
  }
  throw std::logic_error("unknown distribution " + kind);
}

std::vector<double> sampleInputs(const io::Uncertainty& u, std::uint64_t scene_seed, int index) {
  std::vector<double> values;
  for (std::size_t j = 0; j < u.inputs.size(); ++j) {
    const io::UncertainInput& input = u.inputs[j];
    if (input.distribution == "list") {
      values.push_back(input.values[static_cast<std::size_t>(index) % input.values.size()]);
      continue;
    }
    values.push_back(
        quantile(u.inputs[j], probabilityOf(u, scene_seed, index, static_cast<int>(j))));
  }
  return values;
}

}  // namespace rockmass::ensemble
