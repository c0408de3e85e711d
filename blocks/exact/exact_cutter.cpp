// The exact cutter (see exact_cutter.h): the kd split into regions, the cut of each region
// in parallel (blocks/exact/cells.cpp), the gluing of pieces into blocks, structures and the
// adjacency. Its parts are named in blocks/exact/cut_parts.h.
#include "blocks/exact_cutter.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <map>
#include <sstream>
#include <tuple>
#include <unordered_map>

#include "blocks/block_assembly.h"
#include "blocks/exact/cut_parts.h"
#include "blocks/piece_soundness.h"
#include "blocks/region_split.h"
#include "blocks/slab_material.h"
#include "geometry/interrupt.h"

namespace rockmass::blocks {
namespace {

using namespace exactcut;  // NOLINT: the exact cutter's parts

/// Splitting level along `axis` of `box` that coincides with no disc or domain plane, nor
/// comes within the prefilter tolerance of one nearly normal to the axis (so that region faces
/// are never covered by a disc or lie on the domain surface).
double splitLevel(const Context& context, const std::vector<int>& discs, const Box& box, int axis) {
  // A plane within 1e-12 rad of the axis plane and within the prefilter tolerance of the
  // level clashes too: a fault with dip 90 has a normal (1, 6e-17, 6e-17) from cos(90 deg),
  // and a region face 1e-16 m from it glued blocks across a crossing fault (issue 3's
  // two-faults-and-a-joint scene: 21 blocks against 23 with one region and with the fast
  // cutter, whose kd split has the same rule).
  const auto clashes = [&](double level) {
    const auto near = [&](const KnownPlane& p) {
      return isAxisPlane(p.exact, axis, level) ||
             (std::abs(p.normal[axis]) >= 1.0 - 1e-12 &&
              std::abs(p.offset / p.normal[axis] - level) <= context.tolerance);
    };
    bool clash = false;
    for (const int d : discs) clash = clash || near(context.discs[d].plane);
    for (const KnownPlane& p : context.boundary_planes) clash = clash || near(p);
    return clash;
  };
  return freeSplitLevel(box, axis, clashes, "exact cutter");
}

/// kd split of the domain until each region meets at most `max_discs` discs.
void splitRegions(const Context& context, const Region& region, double min_size, int max_discs,
                  std::vector<Region>& out) {
  const int axis = longestAxis(region.box);
  if (static_cast<int>(region.discs.size()) <= max_discs ||
      region.box.size()[axis] < 2.0 * min_size) {
    out.push_back(region);
    return;
  }
  const double level = splitLevel(context, region.discs, region.box, axis);
  for (int side = 0; side < 2; ++side) {
    Region child;
    child.box = region.box;
    (side == 0 ? child.box.max : child.box.min)[axis] = level;
    for (const int d : region.discs) {
      if (mayMeet(context.discs[d], child.box)) child.discs.push_back(d);
    }
    splitRegions(context, child, min_size, max_discs, out);
  }
}

/// Exact volume of the domain solids.
ExactFT exactDomainVolume(const Context& context) {
  ExactFT total = 0;
  for (const Polyhedron& solid : context.domain_solids) {
    std::vector<Point3> vertices;
    for (const Vec3& v : solid.vertices) vertices.push_back(toPoint(v));
    total += exactVolume(vertices, solid.faces);
  }
  return total;
}

/// A block from a set of pieces: mass properties and bounds.
Block makeBlock(std::vector<Piece> pieces, int material) {
  Block block;
  block.material = material;
  block.bounds.min = Vec3::Constant(std::numeric_limits<double>::infinity());
  block.bounds.max = -block.bounds.min;
  for (const Piece& piece : pieces) {
    block.mass += geometry::massProperties(piece.shape);
    const Box b = geometry::bounds(piece.shape);
    block.bounds.min = block.bounds.min.cwiseMin(b.min);
    block.bounds.max = block.bounds.max.cwiseMax(b.max);
  }
  block.pieces = std::move(pieces);
  return block;
}

std::string toString(const ExactFT& value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

/// With the Nef referee: the Nef volumes, glued across region faces, must give the same
/// partition as the exact faces (`sets`); the report gets the Nef block count and whether
/// they agree.
void refereeWithNef(const Context& context, const std::vector<FaceRecord>& records,
                    const std::vector<std::pair<int, int>>& nef_links, UnionFind& sets,
                    ExactCutReport& local) {
  const int count = static_cast<int>(sets.size());
  UnionFind nef_sets(static_cast<std::size_t>(count));
  for (const auto& [a, b] : nef_links) nef_sets.unite(a, b);
  matchFaces(context, records, nef_sets, /*discs=*/false);
  std::map<int, int> forward;
  std::map<int, int> backward;
  bool agrees = true;
  for (int i = 0; i < count; ++i) {
    const int a = sets.find(i);
    const int b = nef_sets.find(i);
    agrees = agrees && forward.try_emplace(a, b).first->second == b &&
             backward.try_emplace(b, a).first->second == a;
  }
  local.nef_blocks = static_cast<int>(backward.size());
  local.nef_agrees = agrees;
}

/// Sound pieces (piece_soundness.h): slivers are folded away and near vertices merged after
/// the gluing, which the exact faces decided, so the blocks are those of the exact partition;
/// a block of slivers only disappears. Returns which pieces were folded.
std::vector<bool> soundPieces(std::vector<Piece>& pieces, const SoundnessTolerances& soundness,
                              SoundnessReport& report) {
  std::vector<bool> folded(pieces.size(), false);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    SoundPieceReport piece_report;
    std::optional<SoundPiece> sound = soundPiece(pieces[i], soundness, &piece_report);
    addToReport(pieces[i], sound, piece_report, report);
    if (sound) {
      pieces[i] = std::move(sound->piece);
    } else {
      folded[i] = true;
    }
  }
  return folded;
}

/// The rock blocks: components of the piece graph (`sets`), in order of their first kept
/// piece, each of the material holding most of its volume. `block_of_piece` gets each
/// piece's block; a folded piece belongs to its component's block (it keeps its mass there),
/// or to none (-1).
std::vector<Block> rockBlocks(const CutInput& input, const CutTolerances& tolerances,
                              const std::vector<Piece>& pieces, const std::vector<bool>& folded,
                              UnionFind& sets, std::vector<int>& block_of_piece) {
  std::vector<std::vector<int>> members;
  std::unordered_map<int, int> component;
  block_of_piece.assign(pieces.size(), -1);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (folded[i]) continue;
    const int root_piece = sets.find(static_cast<int>(i));
    const auto [it, added] = component.try_emplace(root_piece, static_cast<int>(members.size()));
    if (added) members.emplace_back();
    members[it->second].push_back(static_cast<int>(i));
    block_of_piece[i] = it->second;
  }
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (!folded[i]) continue;
    const auto it = component.find(sets.find(static_cast<int>(i)));
    if (it != component.end()) block_of_piece[i] = it->second;
  }
  const SlabMaterials slabs(input.network, input.disc_segments, input.rock_material,
                            tolerances.distance);
  std::vector<Block> blocks;
  for (const std::vector<int>& group : members) {
    std::vector<Piece> block_pieces;
    for (const int i : group) block_pieces.push_back(pieces[i]);
    const int material = slabs.ofBlock(block_pieces);
    blocks.push_back(makeBlock(std::move(block_pieces), material));
  }
  for (std::size_t i = 0; i < pieces.size(); ++i) {  // folded slivers keep their mass
    if (!folded[i] || block_of_piece[i] < 0) continue;
    const geometry::MassProperties m = geometry::massProperties(pieces[i].shape);
    blocks[static_cast<std::size_t>(block_of_piece[i])].mass += m;
    blocks[static_cast<std::size_t>(block_of_piece[i])].folded_volume += m.volume;
  }
  return blocks;
}

/// Rock pieces near the structures, then the structures' pieces, with the block of each, and
/// the contacts between them.
struct StructureContacts {
  std::vector<Piece> near;
  std::vector<int> block_of_near;
  std::vector<PieceContact> contacts;
};

/// One block per structure appended to `blocks`, and its contacts with the rock pieces near
/// it and with the other structures.
StructureContacts structureBlocks(const CutInput& input, const CutTolerances& tolerances,
                                  const std::vector<Piece>& pieces, const std::vector<bool>& folded,
                                  const std::vector<int>& block_of_piece,
                                  std::vector<Block>& blocks) {
  StructureContacts out;
  std::vector<Piece>& near = out.near;
  std::vector<int>& block_of_near = out.block_of_near;
  if (!input.structures.empty()) {
    std::vector<Box> structure_boxes;
    for (const StructureSolid& structure : input.structures) {
      for (const Polyhedron& shape : structure.pieces) {
        structure_boxes.push_back(geometry::bounds(shape).enlarged(tolerances.distance));
      }
    }
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      if (folded[i]) continue;
      const Box b = geometry::bounds(pieces[i].shape);
      const bool close =
          std::any_of(structure_boxes.begin(), structure_boxes.end(), [&](const Box& s) {
            return (b.min.array() <= s.max.array()).all() && (s.min.array() <= b.max.array()).all();
          });
      if (close) {
        near.push_back(pieces[i]);
        block_of_near.push_back(block_of_piece[i]);
      }
    }
  }
  const std::size_t near_rock = near.size();
  for (std::size_t s = 0; s < input.structures.size(); ++s) {
    std::vector<Piece> structure_pieces = labelStructurePieces(input, s, tolerances);
    for (const Piece& piece : structure_pieces) {
      near.push_back(piece);
      block_of_near.push_back(static_cast<int>(blocks.size()));
    }
    blocks.push_back(makeBlock(std::move(structure_pieces), input.structures[s].material));
    blocks.back().structure = static_cast<int>(s);
  }
  appendStructureContacts(near, near_rock, tolerances, out.contacts);

  return out;
}

}  // namespace

BlockModel cutExact(const CutInput& input, const ExactCutOptions& options, ExactCutReport* report) {
  const Context context = makeContext(input);
  checkStructuresOutsideRock(input, cutTolerances(input.domain_box));
  Region root;
  root.box = input.domain_box;
  for (std::size_t d = 0; d < context.discs.size(); ++d) root.discs.push_back(static_cast<int>(d));
  std::vector<Region> regions;
  splitRegions(context, root, input.domain_box.size().maxCoeff() / 64.0,
               std::max(1, options.max_discs_per_region), regions);

  std::vector<RegionResult> results(regions.size());
  std::atomic<std::size_t> finished{0};
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, regions.size(), [&](std::size_t r) {
      throwIfInterrupted("the block cut (exact cutter)");
      results[r] = cutRegion(context, regions[r], options.check_exact_volume, options.nef_referee);
      if (input.progress) input.progress(++finished, regions.size());
    });
  });

  const auto glue_start = Clock::now();
  std::vector<Piece> pieces;
  std::vector<FaceRecord> records;
  std::vector<std::pair<int, int>> nef_links;
  ExactCutReport local;
  ExactFT rock_volume = 0;
  for (RegionResult& result : results) {
    const int offset = static_cast<int>(pieces.size());
    for (auto [a, b] : result.nef_links) nef_links.emplace_back(a + offset, b + offset);
    for (FaceRecord& r : result.records) {
      r.piece += offset;
      records.push_back(std::move(r));
    }
    for (Piece& p : result.pieces) pieces.push_back(std::move(p));
    rock_volume += result.exact_volume;
    local.nef_seconds += result.nef_seconds;
    local.split_seconds += result.decompose_seconds;
    local.extract_seconds += result.extract_seconds;
  }
  for (const Region& region : regions) {
    local.disc_region_pairs += static_cast<int>(region.discs.size());
  }
  UnionFind sets(pieces.size());
  const std::vector<CrackContact> cracks = matchFaces(context, records, sets, /*discs=*/true);
  if (options.nef_referee) refereeWithNef(context, records, nef_links, sets, local);

  // Sound pieces (piece_soundness.h): slivers are folded away and near vertices merged
  // after the gluing, which the exact faces decided, so the blocks are those of the exact
  // partition; a block of slivers only disappears.
  const std::vector<bool> folded =
      soundPieces(pieces, soundnessTolerances(input.domain_box), local.soundness);

  // Rock blocks: components of the piece graph, in order of their first kept piece.
  const CutTolerances tolerances = cutTolerances(input.domain_box);
  std::vector<int> block_of_piece;
  std::vector<Block> blocks = rockBlocks(input, tolerances, pieces, folded, sets, block_of_piece);
  // Structures: one block each, as the fast cutter makes them (block_assembly.h), and their
  // contacts with the rock pieces near them and with each other.
  const StructureContacts structures =
      structureBlocks(input, tolerances, pieces, folded, block_of_piece, blocks);
  // Deterministic ids: the order both cutters share.
  const std::vector<int> order = blockOrder(blocks, input.domain_box);
  std::vector<int> id_of(blocks.size());
  for (std::size_t rank = 0; rank < order.size(); ++rank) {
    id_of[order[rank]] = static_cast<int>(rank) + 1;
  }

  // Adjacency: cracks between pieces of different blocks, and contacts with structures.
  std::map<std::tuple<int, int, int, int>, double> shared;
  const auto add = [&](int block_a, int block_b, const FaceSource& source, double area) {
    if (block_a < 0 || block_b < 0) return;  // a block of slivers only, folded away
    int a = id_of[block_a];
    int b = id_of[block_b];
    if (a == b) return;
    if (a > b) std::swap(a, b);
    shared[{a, b, static_cast<int>(source.kind), source.id}] += area;
  };
  for (const CrackContact& c : cracks) {
    add(block_of_piece[c.piece_a], block_of_piece[c.piece_b], c.source, c.area);
  }
  for (const PieceContact& c : structures.contacts) {
    // The rule of assembleBlocks: no fictitious side; the structure's face names the contact
    // (piece_a's when both sides are structures).
    const FaceSource& a =
        structures.near[static_cast<std::size_t>(c.piece_a)].face_sources[c.face_a];
    const FaceSource& b =
        structures.near[static_cast<std::size_t>(c.piece_b)].face_sources[c.face_b];
    if (a.kind == FaceKind::Fictitious || b.kind == FaceKind::Fictitious) continue;
    add(structures.block_of_near[c.piece_a], structures.block_of_near[c.piece_b],
        a.kind == FaceKind::Structure ? a : b, c.area);
  }

  BlockModel model;
  model.domain = input.domain_box;
  for (const Polyhedron& solid : context.domain_solids) {
    model.domain_volume += geometry::massProperties(solid).volume;
  }
  model.blocks.resize(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    blocks[i].id = id_of[i];
    model.blocks[static_cast<std::size_t>(id_of[i] - 1)] = std::move(blocks[i]);
  }
  for (const auto& [key, area] : shared) {
    const auto [a, b, kind, id] = key;
    model.adjacency.push_back({a, b, area, {static_cast<FaceKind>(kind), id}});
  }
  local.glue_seconds = secondsSince(glue_start);
  local.regions = static_cast<int>(regions.size());
  local.pieces = static_cast<int>(pieces.size()) - local.soundness.folded_pieces;
  if (options.check_exact_volume) {
    local.rock_volume_exact = toString(rock_volume);
    const ExactFT domain = exactDomainVolume(context);
    local.domain_volume_exact = toString(domain);
    local.volume_conserved = domain == rock_volume;
  }
  if (report != nullptr) *report = local;
  return model;
}

}  // namespace rockmass::blocks
