#pragma once
/// The one random engine of rockmass. Every stochastic stage draws from an Rng seeded by
/// `makeRng(seed, stream)`, so a scene and seed give the same numbers on every run.
#include <cstdint>
#include <random>

namespace rockmass::geometry {

/// 64-bit Mersenne Twister: the engine behind every random draw.
using Rng = std::mt19937_64;

/// An engine for sub-stream `stream` of the run seeded by `seed`. Streams are independent,
/// so adding a joint set does not change the discs of the others.
inline Rng makeRng(std::uint64_t seed, std::uint64_t stream) {
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                    static_cast<std::uint32_t>(stream), static_cast<std::uint32_t>(stream >> 32)};
  return Rng(seq);
}

/// Uniform double in the open interval (0, 1).
inline double uniformOpen01(Rng& rng) {
  // 53 random bits, shifted by half an ulp so neither 0 nor 1 can occur.
  return (static_cast<double>(rng() >> 11) + 0.5) * 0x1.0p-53;
}

}  // namespace rockmass::geometry
