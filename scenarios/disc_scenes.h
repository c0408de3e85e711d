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
  /// Centres are drawn in the cube grown by this much on every side (m): with margin >=
  /// radius_max every part of the domain sees the same discs around it, so the fracture
  /// intensity inside the domain does not depend on its size (no edge effect).
  double margin = 0.0;
};

/// The size series of the benchmark: `discs` discs at the density of 100 discs in a 10 m
/// cube, in a cube of side 10 (discs / 100)^(1/3) m.
DiscSceneSpec sizeSeriesScene(int discs, std::uint64_t seed = 1);

/// The constant-intensity size series: the domain is a cube of side 10 (n / 100)^(1/3) m, and
/// discs of the size series' population are centred in the cube grown by radius_max on
/// every side at the size series' density (100 discs per 1000 m3), so that the fracture
/// intensity inside the domain (P32) is the same for every n and n discs are centred in the
/// domain on average. The work per unit of volume is then constant and should grow like n.
DiscSceneSpec constantIntensityScene(int discs, std::uint64_t seed = 1);

/// The discs of `spec` (ids 1..N, all cutting, one joint set); domain = the cube.
geometry::FractureNetwork randomDiscNetwork(const DiscSceneSpec& spec);

/// A CutInput for a box domain (one piece) cut by `network` (kept by pointer: it must
/// outlive the input), with rock material 0 and no structures.
CutInput boxCutInput(const geometry::FractureNetwork& network, int disc_segments = 24);

}  // namespace rockmass::blocks
