#include "blocks/block_merge.h"

#include <algorithm>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace rockmass::blocks {

MergeReport mergeSmallBlocks(BlockModel& model, double min_volume) {
  MergeReport report;
  report.min_volume = min_volume;
  const int n = static_cast<int>(model.blocks.size());
  report.blocks_before = n;
  report.blocks_after = n;
  if (n == 0 || !(min_volume > 0.0)) return report;

  std::map<int, int> index_of_id;
  for (int i = 0; i < n; ++i) index_of_id[model.blocks[static_cast<std::size_t>(i)].id] = i;
  // Shared area between groups, by group index (a group is named by its receiving block).
  std::vector<std::map<int, double>> shared(static_cast<std::size_t>(n));
  for (const Adjacency& a : model.adjacency) {
    const auto ia = index_of_id.find(a.block_a), ib = index_of_id.find(a.block_b);
    if (ia == index_of_id.end() || ib == index_of_id.end() || ia->second == ib->second) continue;
    shared[static_cast<std::size_t>(ia->second)][ib->second] += a.area;
    shared[static_cast<std::size_t>(ib->second)][ia->second] += a.area;
  }
  std::vector<double> volume(static_cast<std::size_t>(n));
  std::vector<int> owner(static_cast<std::size_t>(n));  // group of each block
  std::vector<std::vector<int>> members(static_cast<std::size_t>(n));
  std::set<std::pair<double, int>> small;  // (volume, group) below the threshold
  for (int i = 0; i < n; ++i) {
    volume[static_cast<std::size_t>(i)] = model.blocks[static_cast<std::size_t>(i)].mass.volume;
    owner[static_cast<std::size_t>(i)] = i;
    members[static_cast<std::size_t>(i)] = {i};
    if (volume[static_cast<std::size_t>(i)] < min_volume) {
      small.emplace(volume[static_cast<std::size_t>(i)], i);
    }
  }
  const auto material = [&](int g) { return model.blocks[static_cast<std::size_t>(g)].material; };

  while (!small.empty()) {
    const int g = small.begin()->second;
    small.erase(small.begin());
    // The same-material neighbour sharing the most area (ties: the lower index, as the map
    // is ordered and only a strictly larger area replaces the choice).
    int target = -1;
    double best = 0.0;
    for (const auto& [other, area] : shared[static_cast<std::size_t>(g)]) {
      if (material(other) != material(g) || !(area > best)) continue;
      target = other;
      best = area;
    }
    if (target < 0) {
      ++report.left_small;
      continue;
    }
    ++report.merged;
    report.merged_volume += volume[static_cast<std::size_t>(g)];
    // target absorbs g: members, volume and g's shared areas (other than with target).
    small.erase({volume[static_cast<std::size_t>(target)], target});
    for (int m : members[static_cast<std::size_t>(g)]) owner[static_cast<std::size_t>(m)] = target;
    auto& into = members[static_cast<std::size_t>(target)];
    into.insert(into.end(), members[static_cast<std::size_t>(g)].begin(),
                members[static_cast<std::size_t>(g)].end());
    members[static_cast<std::size_t>(g)].clear();
    volume[static_cast<std::size_t>(target)] += volume[static_cast<std::size_t>(g)];
    for (const auto& [other, area] : shared[static_cast<std::size_t>(g)]) {
      auto& theirs = shared[static_cast<std::size_t>(other)];
      theirs.erase(g);
      if (other == target) continue;
      theirs[target] += area;
      shared[static_cast<std::size_t>(target)][other] += area;
    }
    shared[static_cast<std::size_t>(g)].clear();
    if (volume[static_cast<std::size_t>(target)] < min_volume) {
      small.emplace(volume[static_cast<std::size_t>(target)], target);
    }
  }
  if (report.merged == 0) return report;

  // Groups in the order of their lowest member (the blocks are sorted by id).
  std::vector<int> lowest(static_cast<std::size_t>(n), -1);
  for (int i = 0; i < n; ++i) {
    const int g = owner[static_cast<std::size_t>(i)];
    if (lowest[static_cast<std::size_t>(g)] < 0) lowest[static_cast<std::size_t>(g)] = i;
  }
  std::vector<int> order;
  for (int i = 0; i < n; ++i) {
    const int g = owner[static_cast<std::size_t>(i)];
    if (lowest[static_cast<std::size_t>(g)] == i) order.push_back(g);
  }
  std::vector<int> new_id(static_cast<std::size_t>(n), 0);  // by group
  std::vector<Block> merged;
  merged.reserve(order.size());
  for (int g : order) {
    std::vector<int> in_group = members[static_cast<std::size_t>(g)];
    std::sort(in_group.begin(), in_group.end());
    Block block;
    block.id = static_cast<int>(merged.size()) + 1;
    block.material = material(g);
    block.structure = model.blocks[static_cast<std::size_t>(in_group.front())].structure;
    block.bounds = model.blocks[static_cast<std::size_t>(in_group.front())].bounds;
    for (int m : in_group) {
      Block& source = model.blocks[static_cast<std::size_t>(m)];
      block.mass += source.mass;
      block.folded_volume += source.folded_volume;
      block.bounds.min = block.bounds.min.cwiseMin(source.bounds.min);
      block.bounds.max = block.bounds.max.cwiseMax(source.bounds.max);
      for (Piece& piece : source.pieces) block.pieces.push_back(std::move(piece));
    }
    new_id[static_cast<std::size_t>(g)] = block.id;
    merged.push_back(std::move(block));
  }
  std::map<std::pair<int, int>, Adjacency> adjacency;
  for (const Adjacency& a : model.adjacency) {
    const auto ia = index_of_id.find(a.block_a), ib = index_of_id.find(a.block_b);
    if (ia == index_of_id.end() || ib == index_of_id.end()) continue;
    int x = new_id[static_cast<std::size_t>(owner[static_cast<std::size_t>(ia->second)])];
    int y = new_id[static_cast<std::size_t>(owner[static_cast<std::size_t>(ib->second)])];
    if (x == y) continue;
    if (x > y) std::swap(x, y);
    const auto [it, fresh] = adjacency.try_emplace({x, y}, a);
    it->second.block_a = x;
    it->second.block_b = y;
    if (!fresh) it->second.area += a.area;
  }
  model.blocks = std::move(merged);
  model.adjacency.clear();
  for (auto& [key, a] : adjacency) model.adjacency.push_back(a);
  report.blocks_after = static_cast<int>(model.blocks.size());
  return report;
}

}  // namespace rockmass::blocks
