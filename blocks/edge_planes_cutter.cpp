// FastStrategy::EdgePlanes: every piece cut by every disc polygon that may meet it, with a
// uniform grid over the live pieces (docs/blocks.md, "Strategies").
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include "blocks/convex_partition.h"
#include "blocks/convex_split.h"
#include "blocks/piece_contacts.h"
#include "blocks/union_find.h"
#include "geometry/disc.h"
#include "geometry/interrupt.h"

#include "blocks/fast_cut_parts.h"

namespace rockmass::blocks::fastcut {

namespace {

/// The live pieces and a uniform grid over their bounding boxes, for the query "which pieces
/// may meet this polygon". Dead pieces are dropped from the cells lazily.
class PieceStore {
 public:
  PieceStore(const Box& domain, std::size_t polygons) : domain_(domain) {
    const Vec3 size = domain.size().cwiseMax(1e-300);
    const double target = std::clamp(2.0 * static_cast<double>(polygons), 1.0, 262144.0);
    const double cell = std::cbrt(size.prod() / target);
    for (int a = 0; a < 3; ++a) {
      dims_[a] = std::clamp(static_cast<int>(std::ceil(size[a] / cell)), 1, 256);
      cell_size_[a] = size[a] / dims_[a];
    }
    cells_.resize(static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2]);
  }

  int add(WorkPiece piece) {
    const int id = static_cast<int>(pieces_.size());
    boxes_.push_back(geometry::bounds(piece.piece.shape));
    pieces_.push_back(std::move(piece));
    alive_.push_back(1);
    seen_.push_back(-1);
    forCells(boxes_.back(), [&](std::vector<int>& cell) { cell.push_back(id); });
    return id;
  }
  void kill(int id) {
    alive_[id] = 0;
    pieces_[id] = WorkPiece{};
  }
  const WorkPiece& piece(int id) const { return pieces_[id]; }
  const Box& box(int id) const { return boxes_[id]; }

  /// Live pieces whose boxes meet `box`, ascending.
  std::vector<int> query(const Box& box) {
    ++stamp_;
    std::vector<int> found;
    forCells(box, [&](std::vector<int>& cell) {
      std::erase_if(cell, [&](int id) { return !alive_[id]; });
      for (int id : cell) {
        if (seen_[id] == stamp_) continue;
        seen_[id] = stamp_;
        const Box& b = boxes_[id];
        if ((b.min.array() <= box.max.array()).all() && (box.min.array() <= b.max.array()).all()) {
          found.push_back(id);
        }
      }
    });
    std::sort(found.begin(), found.end());
    return found;
  }

  /// The live pieces in creation order.
  std::vector<WorkPiece> takeAlive() {
    std::vector<WorkPiece> out;
    for (std::size_t i = 0; i < pieces_.size(); ++i) {
      if (alive_[i]) out.push_back(std::move(pieces_[i]));
    }
    return out;
  }

 private:
  template <class F>
  void forCells(const Box& box, F&& f) {
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] =
          std::clamp(static_cast<int>(std::floor((box.min[a] - domain_.min[a]) / cell_size_[a])), 0,
                     dims_[a] - 1);
      hi[a] =
          std::clamp(static_cast<int>(std::floor((box.max[a] - domain_.min[a]) / cell_size_[a])), 0,
                     dims_[a] - 1);
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x)
          f(cells_[(static_cast<std::size_t>(z) * dims_[1] + y) * dims_[0] + x]);
  }

  Box domain_;
  int dims_[3] = {1, 1, 1};
  double cell_size_[3] = {1, 1, 1};
  std::vector<std::vector<int>> cells_;
  std::vector<WorkPiece> pieces_;
  std::vector<Box> boxes_;
  std::vector<char> alive_;
  std::vector<int> seen_;
  int stamp_ = 0;
};

}  // namespace

BlockModel cutEdgePlanes(const CutInput& input, const CutTolerances& tol, FastCutReport* report) {
  FastCutReport counters;
  counters.regions = 1;
  const auto start = std::chrono::steady_clock::now();

  CutStart setup = startCut(input, tol);
  UnionFind& plane_ids = setup.plane_ids;
  std::vector<Piece>& domain = setup.domain;
  std::vector<std::vector<int>>& domain_planes = setup.domain_planes;
  const std::vector<CutPolygon>& polygons = setup.polygons;
  counters.cutting_polygons = static_cast<int>(polygons.size());

  PieceStore store(input.domain_box, polygons.size());
  for (std::size_t i = 0; i < domain.size(); ++i) {
    store.add({std::move(domain[i]), std::move(domain_planes[i])});
  }
  std::vector<int> ids;
  std::vector<CutResult> results;
  for (const CutPolygon& polygon : polygons) {
    ids = store.query(polygon.box.enlarged(tol.distance));
    std::erase_if(
        ids, [&](int id) { return boxMissesPlane(store.box(id), polygon.plane, tol.distance); });
    counters.piece_tests += static_cast<long long>(ids.size());
    // The pieces a polygon meets are cut independently (in parallel), then replaced in
    // ascending order, so the result does not depend on the thread count.
    results.assign(ids.size(), CutResult{});
    const auto cut_one = [&](std::size_t k) {
      results[k] = cutPiece(store.piece(ids[k]), polygon, tol);
    };
    if (ids.size() >= 32) {
      tbb::parallel_for(std::size_t{0}, ids.size(), cut_one);
    } else {
      for (std::size_t k = 0; k < ids.size(); ++k) cut_one(k);
    }
    for (std::size_t k = 0; k < ids.size(); ++k) {
      counters.splits += results[k].splits;
      for (const auto& [a, b] : results[k].coincident) plane_ids.unite(a, b);
      if (!results[k].pieces) continue;
      store.kill(ids[k]);
      for (WorkPiece& p : *results[k].pieces) store.add(std::move(p));
    }
  }
  std::vector<WorkPiece> work = store.takeAlive();
  counters.pieces = static_cast<int>(work.size());
  counters.cut_seconds = secondsSince(start);

  const auto assemble_start = std::chrono::steady_clock::now();
  std::vector<Piece> pieces;
  std::vector<std::vector<int>> planes;
  pieces.reserve(work.size());
  planes.reserve(work.size());
  for (WorkPiece& w : work) {
    for (int& id : w.planes) id = plane_ids.find(id);
    pieces.push_back(std::move(w.piece));
    planes.push_back(std::move(w.planes));
  }
  const std::vector<PieceContact> contacts =
      findContactsByPlane(pieces, planes, tol.distance, tol.area);
  return assembleCut(std::move(pieces), contacts, input, tol, counters, assemble_start, report);
}

}  // namespace rockmass::blocks::fastcut
