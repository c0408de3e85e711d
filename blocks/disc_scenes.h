// Random disc scenes shared by the block tests and the cutter benchmarks (bench/blocks_bench),
// so that every cutter runs on the very same series.
#pragma once

#include <cstdint>

#include "blocks/cutter.h"
#include "geometry/fracture_network.h"

namespace rockmass::blocks {

/// Elliptical discs with centres uniform in a cube [0, side]^3, normals uniform on the
/// sphere, major axes uniform in their plane, a uniform in [radius_min, radius_max] and
/// b = aspect * a.
struct DiscSceneSpec {
  int discs = 100;          ///< number of discs
  double side = 10.0;       ///< cube side (m)
  double radius_min = 3.0;  ///< smallest semi-major axis (m)
  double radius_max = 7.0;  ///< largest semi-major axis (m)
  double aspect = 0.6;      ///< b / a
  std::uint64_t seed = 1;   ///< seed of the draws
};

/// The size series of the benchmark: `discs` discs at the density of 100 discs in a 10 m
/// cube, in a cube of side 10 (discs / 100)^(1/3) m.
DiscSceneSpec sizeSeriesScene(int discs, std::uint64_t seed = 1);

/// The discs of `spec` (ids 1..N, all cutting, one joint set); domain = the cube.
geometry::FractureNetwork randomDiscNetwork(const DiscSceneSpec& spec);

/// A CutInput for a box domain (one piece) cut by `network` (kept by pointer: it must
/// outlive the input), with rock material 0 and no structures.
CutInput boxCutInput(const geometry::FractureNetwork& network, int disc_segments = 24);

}  // namespace rockmass::blocks
