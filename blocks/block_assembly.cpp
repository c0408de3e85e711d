#include "blocks/block_assembly.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>

#include "blocks/convex_split.h"
#include "blocks/piece_contacts.h"
#include "blocks/piece_soundness.h"
#include "blocks/slab_material.h"
#include "blocks/union_find.h"
#include "geometry/disc.h"

namespace rockmass::blocks {
namespace {

using geometry::Vec3;

/// Marks Fictitious the faces of `pieces` wholly covered by faces of other pieces of the same
/// solid (internal faces of a convex decomposition).
void markInternalFaces(std::vector<Piece>& pieces, const CutTolerances& tolerances) {
  if (pieces.size() < 2) return;
  std::vector<std::vector<double>> covered(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i)
    covered[i].assign(pieces[i].shape.faces.size(), 0);
  for (const PieceContact& c : findPieceContacts(pieces, tolerances.distance, tolerances.area)) {
    covered[c.piece_a][c.face_a] += c.area;
    covered[c.piece_b][c.face_b] += c.area;
  }
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    for (std::size_t f = 0; f < pieces[i].shape.faces.size(); ++f) {
      std::vector<Vec3> points;
      for (int v : pieces[i].shape.faces[f]) points.push_back(pieces[i].shape.vertices[v]);
      const double area = geometry::polygonArea(points);
      if (covered[i][f] >= area * (1.0 - 1e-9) - tolerances.area) {
        pieces[i].face_sources[f] = {FaceKind::Fictitious, -1};
      }
    }
  }
}

}  // namespace

CutTolerances cutTolerances(const geometry::Box& domain) {
  const double diagonal = domain.diagonal();
  CutTolerances t;
  t.distance = 1e-11 * diagonal;
  t.area = t.distance * diagonal;
  return t;
}

std::vector<int> blockOrder(const std::vector<Block>& blocks, const geometry::Box& domain) {
  const double length = std::max(domain.diagonal(), 1e-300) * 1e-9;
  const double volume = std::max(domain.volume(), 1e-300) * 1e-12;
  using Key = std::tuple<long long, long long, long long, long long, std::size_t>;
  std::vector<Key> keys;
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    const Vec3 c = blocks[k].mass.centroid();
    keys.emplace_back(std::llround(c.x() / length), std::llround(c.y() / length),
                      std::llround(c.z() / length), std::llround(blocks[k].mass.volume / volume),
                      k);
  }
  std::sort(keys.begin(), keys.end());
  std::vector<int> order;
  for (const Key& key : keys) order.push_back(static_cast<int>(std::get<4>(key)));
  return order;
}

void appendStructureContacts(const std::vector<Piece>& all, std::size_t rock_count,
                             const CutTolerances& tolerances, std::vector<PieceContact>& contacts) {
  if (all.size() == rock_count) return;
  std::vector<geometry::Box> structure_boxes;
  for (std::size_t i = rock_count; i < all.size(); ++i) {
    structure_boxes.push_back(geometry::bounds(all[i].shape).enlarged(tolerances.distance));
  }
  std::vector<int> index;  // into `all`
  for (std::size_t i = 0; i < rock_count; ++i) {
    const geometry::Box b = geometry::bounds(all[i].shape);
    const bool near =
        std::any_of(structure_boxes.begin(), structure_boxes.end(), [&](const auto& s) {
          return (b.min.array() <= s.max.array()).all() && (s.min.array() <= b.max.array()).all();
        });
    if (near) index.push_back(static_cast<int>(i));
  }
  for (std::size_t i = rock_count; i < all.size(); ++i) index.push_back(static_cast<int>(i));
  std::vector<Piece> subset;
  for (int i : index) subset.push_back(all[i]);
  for (PieceContact c : findPieceContacts(subset, tolerances.distance, tolerances.area)) {
    c.piece_a = index[c.piece_a];
    c.piece_b = index[c.piece_b];
    if (c.piece_b < static_cast<int>(rock_count)) continue;  // rock-rock: given already
    contacts.push_back(c);
  }
}

void checkStructuresOutsideRock(const CutInput& input, const CutTolerances& tolerances) {
  for (std::size_t s = 0; s < input.structures.size(); ++s) {
    for (const geometry::Polyhedron& shape : input.structures[s].pieces) {
      for (const geometry::Polyhedron& domain : input.domain_pieces) {
        // Clip the structure piece by the domain piece's face planes.
        Piece inside{shape, std::vector<FaceSource>(shape.faces.size())};
        bool empty = false;
        for (std::size_t f = 0; f < domain.faces.size() && !empty; ++f) {
          const Plane plane = Plane::through(domain.vertices[domain.faces[f][0]],
                                             geometry::faceNormal(domain, static_cast<int>(f)));
          const Section section = planeSection(inside, plane, tolerances.distance);
          if (section.kind == SectionKind::Crossing) {
            inside = splitPiece(inside, plane, tolerances.distance, {})->below;
          } else {
            // Not crossed: wholly inside or wholly outside this face's half-space.
            const Vec3 c = geometry::massProperties(inside.shape).centroid();
            empty = plane.distance(c) > 0.0;
          }
        }
        if (!empty && geometry::massProperties(inside.shape).volume >
                          tolerances.area * tolerances.distance * 1e6) {
          throw std::invalid_argument("structure " + std::to_string(s + 1) +
                                      " overlaps the rock domain; the cutters need structures "
                                      "that stand on or beside the rock, not in it");
        }
      }
    }
  }
}

std::vector<Piece> labelStructurePieces(const CutInput& input, std::size_t structure,
                                        const CutTolerances& tolerances) {
  std::vector<Piece> pieces;
  for (const geometry::Polyhedron& shape : input.structures[structure].pieces) {
    Piece piece;
    piece.shape = shape;
    piece.face_sources.assign(shape.faces.size(),
                              {FaceKind::Structure, static_cast<int>(structure)});
    pieces.push_back(std::move(piece));
  }
  markInternalFaces(pieces, tolerances);
  return pieces;
}

std::vector<Piece> labelDomainPieces(const CutInput& input, const CutTolerances& tolerances) {
  std::vector<Piece> pieces;
  int face_id = 0;
  for (const geometry::Polyhedron& shape : input.domain_pieces) {
    Piece piece;
    piece.shape = shape;
    for (std::size_t f = 0; f < shape.faces.size(); ++f) {
      piece.face_sources.push_back({FaceKind::Boundary, face_id++});
    }
    pieces.push_back(std::move(piece));
  }
  markInternalFaces(pieces, tolerances);
  return pieces;
}

namespace {

/// The pieces glued into blocks: a contact whose shared part is not wholly covered by discs
/// (fictitious on both sides, or as the cutter decided: `decided(k)`) joins its pieces, and
/// the pieces of one structure are one block. A contact with one outer side and one inner
/// counts as inconsistent in `report`.
UnionFind glueClusters(const std::vector<Piece>& all, std::size_t rock_count,
                       const std::vector<int>& structure_of,
                       const std::vector<PieceContact>& contacts,
                       const std::function<const FaceSource*(std::size_t)>& decided,
                       AssemblyReport& report) {
  UnionFind clusters(all.size());
  const auto fictitious = [&](int piece, int face) {
    return all[piece].face_sources[face].kind == FaceKind::Fictitious;
  };
  const auto outer = [&](int piece, int face) {
    const FaceKind kind = all[piece].face_sources[face].kind;
    return kind == FaceKind::Boundary || kind == FaceKind::Structure;
  };
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const PieceContact& c = contacts[k];
    if (const FaceSource* source = decided(k)) {
      if (outer(c.piece_a, c.face_a) != outer(c.piece_b, c.face_b)) {
        ++report.inconsistent_contacts;
      } else if (source->kind == FaceKind::Fictitious) {
        clusters.unite(c.piece_a, c.piece_b);
      }
      continue;
    }
    const bool fa = fictitious(c.piece_a, c.face_a);
    const bool fb = fictitious(c.piece_b, c.face_b);
    if (fa && fb) {
      clusters.unite(c.piece_a, c.piece_b);
    } else if (fa != fb) {
      ++report.inconsistent_contacts;
    }
  }
  for (std::size_t i = rock_count; i < all.size(); ++i) {
    for (std::size_t j = rock_count; j < i; ++j) {
      if (structure_of[i] == structure_of[j]) {
        clusters.unite(static_cast<int>(i), static_cast<int>(j));
        break;
      }
    }
  }
  return clusters;
}

/// Rock pieces made sound: which were repaired (their face labels before the repair kept for
/// the contacts that refer to them), the mass properties of every piece as kept, and which
/// were folded away (they keep their mass in their block).
struct SoundRock {
  std::vector<std::vector<FaceSource>> repaired_sources;  ///< by piece; empty: not repaired
  std::vector<char> repaired;                             ///< by rock piece
  std::vector<geometry::MassProperties> mass;             ///< by piece
  std::vector<bool> folded;                               ///< by piece
};

/// Sound rock pieces (piece_soundness.h): `all`'s first `rock_count` pieces with vertices to
/// merge are repaired in place, slivers folded; counts go to `report`.
SoundRock soundRockPieces(std::vector<Piece>& all, std::size_t rock_count,
                          const std::vector<PieceFacts>* rock_facts,
                          const SoundnessTolerances& soundness, SoundnessReport& report) {
  SoundRock out;
  // The face labels the contacts refer to, before soundPiece renumbers faces: copied only
  // for the pieces it repairs (the others keep their faces; see sourcesOf below).
  out.repaired_sources.resize(all.size());
  // Most pieces have no vertices to merge: soundPiece would give them unchanged (or fold them
  // when below the volume tolerance), so they are neither copied nor repaired. Each piece's
  // mass properties (of the piece as kept, or as folded) are computed once, here.
  std::vector<std::optional<SoundPiece>> sound(rock_count);
  std::vector<SoundPieceReport> sound_reports(rock_count);
  out.repaired.assign(rock_count, 0);
  out.mass.resize(all.size());
  tbb::parallel_for(std::size_t{0}, rock_count, [&](std::size_t i) {
    const PieceFacts* facts = rock_facts != nullptr ? &(*rock_facts)[i] : nullptr;
    if (facts ? facts->close_vertices : hasCloseVertices(all[i], soundness)) {
      out.repaired[i] = 1;
      sound[i] = soundPiece(all[i], soundness, &sound_reports[i]);
    }
    out.mass[i] = sound[i] ? geometry::massProperties(sound[i]->piece.shape)
                  : facts  ? facts->mass
                           : geometry::massProperties(all[i].shape);
  });
  for (std::size_t i = rock_count; i < all.size(); ++i) {
    out.mass[i] = geometry::massProperties(all[i].shape);
  }
  out.folded.assign(all.size(), false);
  for (std::size_t i = 0; i < rock_count; ++i) {
    if (!out.repaired[i]) {
      // As soundPiece and addToReport count an unchanged piece.
      if (!(out.mass[i].volume >= soundness.volume)) {
        out.folded[i] = true;
        ++report.folded_pieces;
        report.folded_volume += out.mass[i].volume;
      }
      continue;
    }
    addToReport(all[i], sound[i], sound_reports[i], report);
    if (sound[i]) {
      out.repaired_sources[i] = std::move(all[i].face_sources);
      all[i] = std::move(sound[i]->piece);
    } else {
      out.folded[i] = true;
    }
  }
  return out;
}

/// Adjacency: real contacts between different blocks (`block_of` each piece's block id, 0:
/// none), their areas summed per pair and source. The source is the cutter's decision
/// (`decided`), else the structure when one side is a structure, else the face of the block
/// with the smaller id (`sources_of`: a piece's face labels as the contacts refer to them).
std::vector<Adjacency> blockAdjacency(
    const std::vector<PieceContact>& contacts, const std::vector<int>& block_of,
    const std::function<const FaceSource*(std::size_t)>& decided,
    const std::function<const std::vector<FaceSource>&(int)>& sources_of) {
  // Adjacency: real contacts between different blocks. The source is the structure when
  // one side is a structure, else the face of the block with the smaller id.
  std::map<std::tuple<int, int, int, int>, double> areas;
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const PieceContact& c = contacts[k];
    int a = block_of[c.piece_a], b = block_of[c.piece_b];
    if (a == b || a == 0 || b == 0) continue;
    if (const FaceSource* source = decided(k)) {
      if (source->kind == FaceKind::Fictitious) continue;
      if (a > b) std::swap(a, b);
      areas[{a, b, static_cast<int>(source->kind), source->id}] += c.area;
      continue;
    }
    const FaceSource source_a = sources_of(c.piece_a)[c.face_a];
    const FaceSource source_b = sources_of(c.piece_b)[c.face_b];
    if (source_a.kind == FaceKind::Fictitious || source_b.kind == FaceKind::Fictitious) continue;
    FaceSource source = a < b ? source_a : source_b;
    if (source_b.kind == FaceKind::Structure) source = source_b;
    if (source_a.kind == FaceKind::Structure) source = source_a;
    if (a > b) std::swap(a, b);
    areas[{a, b, static_cast<int>(source.kind), source.id}] += c.area;
  }
  std::vector<Adjacency> adjacency;
  for (const auto& [key, area] : areas) {
    const auto& [a, b, kind, id] = key;
    adjacency.push_back({a, b, area, {static_cast<FaceKind>(kind), id}});
  }
  return adjacency;
}

/// The clusters of glued pieces in the order of their roots (smallest piece): each lists its
/// kept pieces ascending, and its folded ones.
struct Clusters {
  std::vector<std::vector<int>> kept;
  std::vector<std::vector<int>> folded;
};

Clusters keptClusters(UnionFind& clusters, const std::vector<bool>& folded) {
  Clusters out;
  std::vector<int> cluster_of(folded.size(), -1);
  for (std::size_t i = 0; i < folded.size(); ++i) {
    if (folded[i]) continue;
    const int root = clusters.find(static_cast<int>(i));
    if (cluster_of[root] < 0) {
      cluster_of[root] = static_cast<int>(out.kept.size());
      out.kept.emplace_back();
    }
    out.kept[cluster_of[root]].push_back(static_cast<int>(i));
  }
  out.folded.resize(out.kept.size());
  for (std::size_t i = 0; i < folded.size(); ++i) {
    const int cluster = cluster_of[clusters.find(static_cast<int>(i))];
    if (folded[i] && cluster >= 0) out.folded[cluster].push_back(static_cast<int>(i));
  }
  return out;
}

/// The bounding box of each piece: the cutter's (rock_facts) where the piece was not
/// repaired, else computed.
struct PieceBoxes {
  const std::vector<Piece>& all;
  std::size_t rock_count;
  const std::vector<PieceFacts>* rock_facts;
  const std::vector<char>& repaired;
  geometry::Box operator()(int i) const {
    return rock_facts != nullptr && static_cast<std::size_t>(i) < rock_count && !repaired[i]
               ? (*rock_facts)[i].box
               : geometry::bounds(all[i].shape);
  }
};

/// The block of one cluster: mass properties (folded slivers keep their mass), bounds and
/// material (a structure's, else the one holding the largest volume; ties go to the smaller
/// material index).
Block clusterBlock(const std::vector<int>& list, const std::vector<int>& folded_list,
                   const std::vector<geometry::MassProperties>& mass, const PieceBoxes& boxes,
                   const SlabMaterials& slabs, const std::vector<int>& structure_of,
                   const CutInput& input) {
  Block b;
  b.bounds.min = Vec3::Constant(std::numeric_limits<double>::infinity());
  b.bounds.max = -b.bounds.min;
  // Material volumes as SlabMaterials::ofBlock counts them (each convex piece with its
  // volume for the material at its centroid), from the mass properties computed here.
  std::map<int, double> material_volume;
  for (int i : list) {
    const geometry::MassProperties& m = mass[i];
    b.mass += m;
    material_volume[m.volume > 0.0 ? slabs.at(m.centroid()) : input.rock_material] += m.volume;
    const geometry::Box box = boxes(i);
    b.bounds.min = b.bounds.min.cwiseMin(box.min);
    b.bounds.max = b.bounds.max.cwiseMax(box.max);
  }
  for (int i : folded_list) {
    const geometry::MassProperties& m = mass[i];
    b.mass += m;
    b.folded_volume += m.volume;
  }
  const int structure = structure_of[list.front()];
  if (structure >= 0) {
    b.material = input.structures[structure].material;
    b.structure = structure;
  } else {
    b.material = std::max_element(material_volume.begin(), material_volume.end(),
                                  [](const auto& x, const auto& y) { return x.second < y.second; })
                     ->first;
  }
  return b;
}

}  // namespace

BlockModel assembleBlocks(std::vector<Piece> rock_pieces,
                          const std::vector<PieceContact>& rock_contacts, const CutInput& input,
                          const CutTolerances& tolerances, AssemblyReport* report,
                          const std::vector<FaceSource>* contact_sources,
                          const std::vector<PieceFacts>* rock_facts) {
  std::vector<Piece> all = std::move(rock_pieces);
  const std::size_t rock_count = all.size();
  std::vector<int> structure_of(rock_count, -1);
  for (std::size_t s = 0; s < input.structures.size(); ++s) {
    for (Piece& p : labelStructurePieces(input, s, tolerances)) {
      all.push_back(std::move(p));
      structure_of.push_back(static_cast<int>(s));
    }
  }

  std::vector<PieceContact> contacts = rock_contacts;
  appendStructureContacts(all, rock_count, tolerances, contacts);
  // The source of contact k as the cutter decided it (rock contacts), else nothing.
  const auto decided = [&](std::size_t k) -> const FaceSource* {
    return contact_sources != nullptr && k < rock_contacts.size() ? &(*contact_sources)[k]
                                                                  : nullptr;
  };
  AssemblyReport local_report;
  UnionFind clusters = glueClusters(all, rock_count, structure_of, contacts, decided, local_report);

  // Sound rock pieces (piece_soundness.h), after the gluing, as the exact cutter does: slivers
  // are folded away, near vertices merged; a block of slivers only disappears.
  const SoundRock sound = soundRockPieces(
      all, rock_count, rock_facts, soundnessTolerances(input.domain_box), local_report.soundness);
  const std::vector<std::vector<FaceSource>>& repaired_sources = sound.repaired_sources;
  const std::vector<char>& repaired = sound.repaired;
  const std::vector<geometry::MassProperties>& mass = sound.mass;
  const std::vector<bool>& folded = sound.folded;

  const SlabMaterials slabs(input.network, input.disc_segments, input.rock_material,
                            tolerances.distance);
  const Clusters clustered = keptClusters(clusters, folded);
  const std::vector<std::vector<int>>& unordered_pieces = clustered.kept;
  const std::vector<std::vector<int>>& folded_pieces = clustered.folded;
  // Mass properties, boxes and materials per block, in parallel (each block on its own).
  std::vector<Block> unordered(unordered_pieces.size());
  const PieceBoxes boxes{all, rock_count, rock_facts, repaired};
  tbb::parallel_for(std::size_t{0}, unordered.size(), [&](std::size_t k) {
    unordered[k] = clusterBlock(unordered_pieces[k], folded_pieces[k], mass, boxes, slabs,
                                structure_of, input);
  });
  const std::vector<int> order = blockOrder(unordered, input.domain_box);
  struct Pending {
    Block block;
    std::vector<int> pieces;
  };
  std::vector<Pending> pending;
  for (const int k : order) pending.push_back({std::move(unordered[k]), unordered_pieces[k]});

  BlockModel model;
  model.domain = input.domain_box;
  for (const geometry::Polyhedron& p : input.domain_pieces) {
    model.domain_volume += geometry::massProperties(p).volume;
  }
  std::vector<int> block_of(all.size(), 0);  // 0: folded, in no block
  std::vector<int> slot_of(all.size(), -1);  // index in its block's pieces
  model.blocks.reserve(pending.size());
  for (std::size_t k = 0; k < pending.size(); ++k) {
    Block& b = pending[k].block;
    b.id = static_cast<int>(k) + 1;
    b.pieces.reserve(pending[k].pieces.size());
    for (int i : pending[k].pieces) {
      block_of[i] = b.id;
      slot_of[i] = static_cast<int>(b.pieces.size());
      b.pieces.push_back(std::move(all[i]));
    }
    model.blocks.push_back(std::move(b));
  }
  // The face labels of piece i as the contacts refer to them (before any repair).
  const auto sourcesOf = [&](int i) -> const std::vector<FaceSource>& {
    if (!repaired_sources[i].empty()) return repaired_sources[i];
    if (slot_of[i] >= 0) return model.blocks[block_of[i] - 1].pieces[slot_of[i]].face_sources;
    return all[i].face_sources;  // folded: still in `all`
  };
  // A folded piece's contacts count for the block of its cluster, when that block exists.
  for (std::size_t k = 0; k < pending.size(); ++k) {
    for (int i : folded_pieces[static_cast<std::size_t>(order[k])]) {
      block_of[i] = static_cast<int>(k) + 1;
    }
  }

  model.adjacency = blockAdjacency(contacts, block_of, decided, sourcesOf);
  if (report) *report = local_report;
  return model;
}

}  // namespace rockmass::blocks
