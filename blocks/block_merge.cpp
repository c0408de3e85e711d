#include "blocks/block_merge.h"

#include <algorithm>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace rockmass::blocks {

namespace {

/// Blocks gathered into groups, each named by the block that receives the others.
struct Groups {
  std::map<int, int> index_of_id;             ///< block id -> index
  std::vector<double> volume;                 ///< by group
  std::vector<int> owner;                     ///< group of each block
  std::vector<std::vector<int>> members;      ///< blocks of each group
  std::vector<std::map<int, double>> shared;  ///< face area shared with each other group
};

/// Every block its own group, with the face areas of the model's adjacency between them.
Groups singleGroups(const BlockModel& model) {
  const int n = static_cast<int>(model.blocks.size());
  Groups g;
  for (int i = 0; i < n; ++i) g.index_of_id[model.blocks[static_cast<std::size_t>(i)].id] = i;
  g.shared.resize(static_cast<std::size_t>(n));
  for (const Adjacency& a : model.adjacency) {
    const auto ia = g.index_of_id.find(a.block_a), ib = g.index_of_id.find(a.block_b);
    if (ia == g.index_of_id.end() || ib == g.index_of_id.end() || ia->second == ib->second) {
      continue;
    }
    g.shared[static_cast<std::size_t>(ia->second)][ib->second] += a.area;
    g.shared[static_cast<std::size_t>(ib->second)][ia->second] += a.area;
  }
  for (int i = 0; i < n; ++i) {
    g.volume.push_back(model.blocks[static_cast<std::size_t>(i)].mass.volume);
    g.owner.push_back(i);
    g.members.push_back({i});
  }
  return g;
}

/// Group `target` absorbs group `from`: members, volume and shared areas (other than with
/// `target`).
void absorb(Groups& g, int from, int target) {
  const auto f = static_cast<std::size_t>(from), t = static_cast<std::size_t>(target);
  for (int m : g.members[f]) g.owner[static_cast<std::size_t>(m)] = target;
  g.members[t].insert(g.members[t].end(), g.members[f].begin(), g.members[f].end());
  g.members[f].clear();
  g.volume[t] += g.volume[f];
  for (const auto& [other, area] : g.shared[f]) {
    auto& theirs = g.shared[static_cast<std::size_t>(other)];
    theirs.erase(from);
    if (other == target) continue;
    theirs[target] += area;
    g.shared[t][other] += area;
  }
  g.shared[f].clear();
}

/// The model's blocks rebuilt from the groups: one block per group, in the order of their
/// lowest member (the blocks are sorted by id), ids from 1; adjacency summed per group pair.
void rebuildModel(BlockModel& model, const Groups& g) {
  const int n = static_cast<int>(model.blocks.size());
  std::vector<int> lowest(static_cast<std::size_t>(n), -1);
  std::vector<int> order;
  for (int i = 0; i < n; ++i) {
    const int group = g.owner[static_cast<std::size_t>(i)];
    if (lowest[static_cast<std::size_t>(group)] < 0) {
      lowest[static_cast<std::size_t>(group)] = i;
      order.push_back(group);
    }
  }
  std::vector<int> new_id(static_cast<std::size_t>(n), 0);  // by group
  std::vector<Block> merged;
  merged.reserve(order.size());
  for (int group : order) {
    std::vector<int> in_group = g.members[static_cast<std::size_t>(group)];
    std::sort(in_group.begin(), in_group.end());
    Block block;
    block.id = static_cast<int>(merged.size()) + 1;
    block.material = model.blocks[static_cast<std::size_t>(group)].material;
    block.structure = model.blocks[static_cast<std::size_t>(group)].structure;
    block.bounds = model.blocks[static_cast<std::size_t>(in_group.front())].bounds;
    for (int m : in_group) {
      Block& source = model.blocks[static_cast<std::size_t>(m)];
      block.mass += source.mass;
      block.folded_volume += source.folded_volume;
      block.bounds.min = block.bounds.min.cwiseMin(source.bounds.min);
      block.bounds.max = block.bounds.max.cwiseMax(source.bounds.max);
      for (Piece& piece : source.pieces) block.pieces.push_back(std::move(piece));
    }
    new_id[static_cast<std::size_t>(group)] = block.id;
    merged.push_back(std::move(block));
  }
  std::map<std::pair<int, int>, Adjacency> adjacency;
  for (const Adjacency& a : model.adjacency) {
    const auto ia = g.index_of_id.find(a.block_a), ib = g.index_of_id.find(a.block_b);
    if (ia == g.index_of_id.end() || ib == g.index_of_id.end()) continue;
    int x = new_id[static_cast<std::size_t>(g.owner[static_cast<std::size_t>(ia->second)])];
    int y = new_id[static_cast<std::size_t>(g.owner[static_cast<std::size_t>(ib->second)])];
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
}

}  // namespace

MergeReport mergeSmallBlocks(BlockModel& model, double min_volume, bool across_materials) {
  MergeReport report;
  report.min_volume = min_volume;
  const int n = static_cast<int>(model.blocks.size());
  report.blocks_before = n;
  report.blocks_after = n;
  if (n == 0 || !(min_volume > 0.0)) return report;

  Groups g = singleGroups(model);
  std::set<std::pair<double, int>> small;  // (volume, group) below the threshold
  for (int i = 0; i < n; ++i) {
    if (g.volume[static_cast<std::size_t>(i)] < min_volume) {
      small.emplace(g.volume[static_cast<std::size_t>(i)], i);
    }
  }
  const auto material = [&](int group) {
    return model.blocks[static_cast<std::size_t>(group)].material;
  };
  const auto rock = [&](int group) {
    return model.blocks[static_cast<std::size_t>(group)].structure < 0;
  };
  // The rock neighbour of group `from` that `takes` accepts and that shares the most face area
  // with it (ties: the lower index, as the map is ordered and only a strictly larger area
  // replaces the choice); -1 when there is none.
  const auto largestNeighbour = [&](int from, const auto& takes) {
    int target = -1;
    double best = 0.0;
    for (const auto& [other, area] : g.shared[static_cast<std::size_t>(from)]) {
      if (!rock(other) || !takes(other) || !(area > best)) continue;
      target = other;
      best = area;
    }
    return target;
  };
  while (!small.empty()) {
    const int from = small.begin()->second;
    small.erase(small.begin());
    // A structure is never glued nor glued to, even where it shares a material with the rock
    // or another structure. A rock block goes to a rock neighbour of its own material, else
    // (with across_materials) to one of any material.
    int target = -1;
    if (rock(from)) {
      target = largestNeighbour(from, [&](int other) { return material(other) == material(from); });
      if (target < 0 && across_materials) target = largestNeighbour(from, [](int) { return true; });
    }
    if (target < 0) {
      ++report.left_small;
      continue;
    }
    ++report.merged;
    small.erase({g.volume[static_cast<std::size_t>(target)], target});
    absorb(g, from, target);
    if (g.volume[static_cast<std::size_t>(target)] < min_volume) {
      small.emplace(g.volume[static_cast<std::size_t>(target)], target);
    }
  }
  if (report.merged == 0) return report;
  // The cut blocks glued into another (each counted once, whatever the glue steps it went
  // through), and those of them whose glued block is of another material.
  for (int i = 0; i < n; ++i) {
    const int group = g.owner[static_cast<std::size_t>(i)];
    if (group == i) continue;
    const double volume = model.blocks[static_cast<std::size_t>(i)].mass.volume;
    report.merged_volume += volume;
    if (material(group) != material(i)) {
      ++report.merged_across;
      report.merged_across_volume += volume;
    }
  }
  rebuildModel(model, g);
  report.blocks_after = static_cast<int>(model.blocks.size());
  return report;
}

}  // namespace rockmass::blocks
