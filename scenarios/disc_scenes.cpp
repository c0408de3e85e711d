#include "scenarios/disc_scenes.h"

#include <cmath>

#include "geometry/orientation.h"
#include "geometry/random.h"

namespace rockmass::blocks {

using geometry::Vec3;

DiscSceneSpec sizeSeriesScene(int discs, std::uint64_t seed) {
  DiscSceneSpec spec;
  spec.discs = discs;
  spec.side = 10.0 * std::cbrt(discs / 100.0);
  spec.seed = seed;
  return spec;
}

DiscSceneSpec constantIntensityScene(int discs, std::uint64_t seed) {
  DiscSceneSpec spec = sizeSeriesScene(discs, seed);
  spec.margin = spec.radius_max;
  const double grown = spec.side + 2.0 * spec.margin;
  const double density = discs / (spec.side * spec.side * spec.side);
  spec.discs = static_cast<int>(std::lround(density * grown * grown * grown));
  return spec;
}

geometry::FractureNetwork randomDiscNetwork(const DiscSceneSpec& spec) {
  geometry::Rng rng = geometry::makeRng(spec.seed, 0);
  const auto uniform = [&](double lo, double hi) {
    return lo + (hi - lo) * geometry::uniformOpen01(rng);
  };
  geometry::FractureNetwork network;
  network.domain = {Vec3::Zero(), Vec3::Constant(spec.side)};
  geometry::SetInfo set;
  set.name = "random";
  network.sets.push_back(set);
  for (int i = 0; i < spec.discs; ++i) {
    geometry::Disc d;
    d.id = i + 1;
    const double lo = -spec.margin, hi = spec.side + spec.margin;
    d.center = Vec3(uniform(lo, hi), uniform(lo, hi), uniform(lo, hi));
    const double z = uniform(-1.0, 1.0);
    const double phi = uniform(0.0, 2.0 * geometry::kPi);
    const double r = std::sqrt(1.0 - z * z);
    d.normal = Vec3(r * std::cos(phi), r * std::sin(phi), z);
    const double theta = uniform(0.0, 2.0 * geometry::kPi);
    const Vec3 u = d.normal.unitOrthogonal();
    d.major = std::cos(theta) * u + std::sin(theta) * d.normal.cross(u);
    d.a = uniform(spec.radius_min, spec.radius_max);
    d.b = spec.aspect * d.a;
    network.discs.push_back(d);
  }
  return network;
}

CutInput boxCutInput(const geometry::FractureNetwork& network, int disc_segments) {
  CutInput input;
  input.domain_pieces = {geometry::boxPolyhedron(network.domain)};
  input.domain_box = network.domain;
  input.network = &network;
  input.disc_segments = disc_segments;
  input.rock_material = 0;
  return input;
}

}  // namespace rockmass::blocks
