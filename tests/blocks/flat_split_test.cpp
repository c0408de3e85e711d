// The flat forms the fast cutter works on (convex_split.h: splitFlat, planeSectionFlat;
// piece_contacts.h: ContactFaces, decideTableContacts; piece_soundness.h: hasCloseVertices)
// must give exactly what the Piece-based functions give: the fast cutter's results are
// checked bitwise against the previous implementation only by hand (bench/blocks_model_hash),
// so these tests pin the equivalence on random convex pieces.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>
#include <vector>

#include "blocks/convex_split.h"
#include "blocks/piece_contacts.h"
#include "blocks/piece_soundness.h"
#include "geometry/box.h"
#include "geometry/polyhedron.h"

namespace rockmass::blocks {
namespace {

using geometry::Vec3;

/// A piece in flat arrays (what the fast cutter's cell store holds).
struct Flat {
  std::vector<Vec3> vertices;
  std::vector<int> loops, begin, size;
  FlatPieceView view() const { return {vertices, loops, begin, size}; }
};

Flat flatten(const Piece& piece) {
  Flat f;
  f.vertices = piece.shape.vertices;
  for (const std::vector<int>& face : piece.shape.faces) {
    f.begin.push_back(static_cast<int>(f.loops.size()));
    f.size.push_back(static_cast<int>(face.size()));
    f.loops.insert(f.loops.end(), face.begin(), face.end());
  }
  return f;
}

/// The unit box cut by `cuts` random planes through its inside (keeping the half below each),
/// so pieces have various face counts and constructed (rounded) corners.
Piece randomConvexPiece(std::mt19937_64& rng, int cuts) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Piece piece;
  piece.shape = geometry::boxPolyhedron({Vec3::Zero(), Vec3::Ones()});
  piece.face_sources.assign(6, {FaceKind::Boundary, 0});
  for (int k = 0; k < cuts; ++k) {
    const Vec3 normal = Vec3(u(rng), u(rng), u(rng)).normalized();
    const Vec3 through = Vec3::Constant(0.5) + 0.2 * Vec3(u(rng), u(rng), u(rng));
    if (auto split =
            splitPiece(piece, Plane::through(through, normal), 1e-12, {FaceKind::Disc, k})) {
      piece = std::move(split->below);
    }
  }
  return piece;
}

/// Checks one flat half against the Piece half bitwise.
void expectSameHalf(const Piece& piece, const std::vector<int>& origin,
                    const std::vector<Vec3>& vertices, const std::vector<int>& loops,
                    const std::vector<int>& sizes, const std::vector<int>& flat_origin) {
  ASSERT_EQ(vertices.size(), piece.shape.vertices.size());
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    EXPECT_EQ(vertices[v], piece.shape.vertices[v]);  // bitwise: the same arithmetic
  }
  ASSERT_EQ(sizes.size(), piece.shape.faces.size());
  std::size_t at = 0;
  for (std::size_t f = 0; f < sizes.size(); ++f) {
    const std::vector<int> loop(loops.begin() + static_cast<std::ptrdiff_t>(at),
                                loops.begin() + static_cast<std::ptrdiff_t>(at) + sizes[f]);
    EXPECT_EQ(loop, piece.shape.faces[f]);
    at += static_cast<std::size_t>(sizes[f]);
  }
  EXPECT_EQ(at, loops.size());
  EXPECT_EQ(flat_origin, origin);
}

TEST(FlatSplit, SplitFlatGivesBitwiseTheHalvesOfSplitPiece) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int crossings = 0;
  FlatSplit flat, reused;
  for (int trial = 0; trial < 200; ++trial) {
    const Piece piece = randomConvexPiece(rng, 1 + trial % 6);
    const Flat f = flatten(piece);
    // Planes through a random point of the box, and (every 10th) through a vertex, so that
    // ON vertices occur.
    const Vec3 normal = Vec3(u(rng), u(rng), u(rng)).normalized();
    const Vec3 through = trial % 10 == 0 ? piece.shape.vertices[0]
                                         : Vec3::Constant(0.5) + 0.4 * Vec3(u(rng), u(rng), u(rng));
    const Plane plane = Plane::through(through, normal);
    const auto split = splitPiece(piece, plane, 1e-12, {FaceKind::Fictitious, -1});
    ASSERT_EQ(splitFlat(f.view(), plane, 1e-12, flat), split.has_value());
    if (!split) continue;
    ++crossings;
    expectSameHalf(split->below, split->below_origin, flat.below_vertices, flat.below_loops,
                   flat.below_size, flat.below_origin);
    expectSameHalf(split->above, split->above_origin, flat.above_vertices, flat.above_loops,
                   flat.above_size, flat.above_origin);
    // The fast cutter's path: the section first, then the split from the section's work
    // (SectionScratch) gives the very same halves, and the section is the new face of `below`
    // (its last face), point for point.
    std::vector<Vec3> section;
    int face = -1;
    SectionScratch scratch;
    ASSERT_EQ(planeSectionFlat(f.view(), plane, 1e-12, section, &face, scratch),
              SectionKind::Crossing);
    ASSERT_TRUE(splitFlat(f.view(), scratch, reused));
    expectSameHalf(split->below, split->below_origin, reused.below_vertices, reused.below_loops,
                   reused.below_size, reused.below_origin);
    expectSameHalf(split->above, split->above_origin, reused.above_vertices, reused.above_loops,
                   reused.above_size, reused.above_origin);
    const std::vector<int>& cap = split->below.shape.faces.back();
    ASSERT_EQ(section.size(), cap.size());
    for (std::size_t k = 0; k < cap.size(); ++k) {
      EXPECT_EQ(section[k], split->below.shape.vertices[cap[k]]);
    }
  }
  EXPECT_GT(crossings, 100);  // most planes through the box's middle cross the piece
}

TEST(FlatSplit, PlaneSectionFlatGivesTheSectionOfPlaneSection) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int kinds[3] = {0, 0, 0};
  std::vector<Vec3> polygon;
  for (int trial = 0; trial < 150; ++trial) {
    const Piece piece = randomConvexPiece(rng, 1 + trial % 5);
    const Flat f = flatten(piece);
    Plane plane;
    if (trial % 3 == 0) {
      // The plane of a face (OnFace), oriented either way.
      const int face = trial % static_cast<int>(piece.shape.faces.size());
      const Vec3 n = geometry::faceNormal(piece.shape, face);
      plane = Plane::through(piece.shape.vertices[piece.shape.faces[face][0]],
                             trial % 2 == 0 ? n : Vec3(-n));
    } else {
      plane = Plane::through(Vec3::Constant(0.5) + 0.8 * Vec3(u(rng), u(rng), u(rng)),
                             Vec3(u(rng), u(rng), u(rng)).normalized());
    }
    const Section section = planeSection(piece, plane, 1e-9);
    int face = -1;
    const SectionKind kind = planeSectionFlat(f.view(), plane, 1e-9, polygon, &face);
    ASSERT_EQ(kind, section.kind);
    ++kinds[static_cast<int>(kind)];
    EXPECT_EQ(face, section.face);
    ASSERT_EQ(polygon.size(), section.polygon.size());
    for (std::size_t k = 0; k < polygon.size(); ++k) EXPECT_EQ(polygon[k], section.polygon[k]);
  }
  // Every kind occurred (the test covers all three paths).
  EXPECT_GT(kinds[static_cast<int>(SectionKind::None)], 0);
  EXPECT_GT(kinds[static_cast<int>(SectionKind::Crossing)], 0);
  EXPECT_GT(kinds[static_cast<int>(SectionKind::OnFace)], 0);
}

/// A box split into a 3 x 3 x 3 grid by axis planes, then by two oblique planes (faces of
/// the axis planes have source Disc 0-5, of the oblique ones Disc 6-7).
std::vector<Piece> gridPieces() {
  std::vector<Piece> pieces;
  {
    Piece box;
    box.shape = geometry::boxPolyhedron({Vec3::Zero(), Vec3::Constant(3.0)});
    box.face_sources.assign(6, {FaceKind::Boundary, 0});
    pieces.push_back(box);
  }
  std::vector<Plane> planes;
  for (int axis = 0; axis < 3; ++axis) {
    for (double level : {1.0, 2.0}) planes.push_back({Vec3::Unit(axis), level});
  }
  planes.push_back(Plane::through(Vec3(1.5, 1.4, 1.3), Vec3(1, 2, 3).normalized()));
  planes.push_back(Plane::through(Vec3(0.7, 2.2, 1.9), Vec3(-2, 1, 0.5).normalized()));
  for (std::size_t p = 0; p < planes.size(); ++p) {
    std::vector<Piece> next;
    for (const Piece& piece : pieces) {
      if (auto split = splitPiece(piece, planes[p], 1e-12, {FaceKind::Disc, int(p)})) {
        next.push_back(split->below);
        next.push_back(split->above);
      } else {
        next.push_back(piece);
      }
    }
    pieces = std::move(next);
  }
  return pieces;
}

/// Glues across the axis planes, cracks across the oblique ones: gluing makes the searches
/// skip pairs already glued, so the skipping is compared too.
ContactDecision gridDecision(const std::vector<Piece>& pieces) {
  return [&pieces](const PieceContact& c, bool) {
    const FaceSource source = pieces[c.piece_a].face_sources[c.face_a];
    return source.kind == FaceKind::Disc && source.id < 6 ? FaceSource{FaceKind::Fictitious, -1}
                                                          : source;
  };
}

/// `got` (with its face sources) equals `expected` entry by entry, areas bitwise: the same
/// arithmetic on the same table numbers.
void expectSameContacts(const std::vector<PieceContact>& got,
                        const std::vector<FaceSource>& sources,
                        const std::vector<PieceContact>& expected,
                        const std::vector<FaceSource>& expected_sources) {
  ASSERT_EQ(got.size(), expected.size());
  ASSERT_EQ(sources.size(), expected_sources.size());
  for (std::size_t k = 0; k < got.size(); ++k) {
    EXPECT_EQ(got[k].piece_a, expected[k].piece_a);
    EXPECT_EQ(got[k].face_a, expected[k].face_a);
    EXPECT_EQ(got[k].piece_b, expected[k].piece_b);
    EXPECT_EQ(got[k].face_b, expected[k].face_b);
    EXPECT_EQ(got[k].area, expected[k].area);
    EXPECT_EQ(sources[k], expected_sources[k]);
  }
}

TEST(FlatSplit, TableContactsEqualCandidateContacts) {
  // Every pair of faces of different pieces of gridPieces is a candidate. A table built face
  // by face with ContactFaces::add must give the very contacts and decisions
  // decideCandidateContacts gives.
  const std::vector<Piece> pieces = gridPieces();
  std::vector<FacePair> candidates;
  for (int i = 0; i < static_cast<int>(pieces.size()); ++i) {
    for (int j = i + 1; j < static_cast<int>(pieces.size()); ++j) {
      for (int fa = 0; fa < static_cast<int>(pieces[i].shape.faces.size()); ++fa) {
        for (int fb = 0; fb < static_cast<int>(pieces[j].shape.faces.size()); ++fb) {
          candidates.push_back({{i, fa}, {j, fb}});
        }
      }
    }
  }
  const ContactDecision decide = gridDecision(pieces);
  std::vector<FaceSource> expected_sources, sources;
  const std::vector<PieceContact> expected =
      decideCandidateContacts(pieces, candidates, 1e-9, 1e-9, decide, &expected_sources);
  ContactFaces table;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (const FacePair& c : candidates) {
    // One table entry per occurrence (duplicates are allowed: the tests read entries only).
    const auto add = [&](const FaceRef& r) {
      const Piece& p = pieces[r.piece];
      return table.add(r.piece, r.face, p.shape.vertices, p.shape.faces[r.face]);
    };
    const std::uint32_t a = add(c.first);
    pairs.emplace_back(a, add(c.second));
  }
  const std::vector<PieceContact> got =
      decideTableContacts(table, pieces.size(), pairs, 1e-9, 1e-9, decide, &sources);
  ASSERT_GT(expected.size(), 50u);  // 27+ pieces touching across many faces
  expectSameContacts(got, sources, expected, expected_sources);
}

TEST(FlatSplit, TableContactsOfSeveralPartsGiveTheSameClustersAndBlockContacts) {
  // The fast cutter's regions each keep their own table (ContactTablePart). Two parts (the
  // pieces below and above half the count, every face pair within a part a candidate) must
  // give what one table holding both parts' faces and pairs gives: the same clusters and the
  // very same contacts (bitwise areas, sources) between different clusters. Contacts inside a
  // cluster may differ: the batches differ, and a glued pair is skipped.
  const std::vector<Piece> pieces = gridPieces();
  const int n = static_cast<int>(pieces.size());
  const int half = n / 2;
  ContactFaces one, part_table[2];
  std::vector<std::pair<std::uint32_t, std::uint32_t>> one_pairs, part_pairs[2];
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if ((i < half) != (j < half)) continue;
      const int part = i < half ? 0 : 1;
      const int offset = part == 0 ? 0 : half;
      for (int fa = 0; fa < static_cast<int>(pieces[i].shape.faces.size()); ++fa) {
        for (int fb = 0; fb < static_cast<int>(pieces[j].shape.faces.size()); ++fb) {
          const auto add = [&](ContactFaces& table, int piece, int face, int shift) {
            const Piece& p = pieces[piece];
            return table.add(piece - shift, face, p.shape.vertices, p.shape.faces[face]);
          };
          const std::uint32_t a = add(one, i, fa, 0);
          one_pairs.emplace_back(a, add(one, j, fb, 0));
          const std::uint32_t pa = add(part_table[part], i, fa, offset);
          part_pairs[part].emplace_back(pa, add(part_table[part], j, fb, offset));
        }
      }
    }
  }
  const ContactDecision decide = gridDecision(pieces);
  std::vector<FaceSource> one_sources, sources;
  const std::vector<PieceContact> expected =
      decideTableContacts(one, pieces.size(), one_pairs, 1e-9, 1e-9, decide, &one_sources);
  const ContactTablePart parts[2] = {{&part_table[0], 0, part_pairs[0], {}},
                                     {&part_table[1], half, part_pairs[1], {}}};
  const std::vector<PieceContact> got =
      decideTableContacts(parts, pieces.size(), 1e-9, 1e-9, decide, &sources);
  const auto clustersOf = [&](const std::vector<PieceContact>& contacts,
                              const std::vector<FaceSource>& decided) {
    std::vector<int> label(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) label[i] = i;
    const auto find = [&](int i) {
      while (label[i] != i) i = label[i];
      return i;
    };
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      if (decided[k].kind == FaceKind::Fictitious) {
        const int a = find(contacts[k].piece_a), b = find(contacts[k].piece_b);
        label[std::max(a, b)] = std::min(a, b);
      }
    }
    std::vector<int> root(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) root[i] = find(i);
    return root;
  };
  const std::vector<int> expected_root = clustersOf(expected, one_sources);
  const std::vector<int> root = clustersOf(got, sources);
  EXPECT_EQ(root, expected_root);
  // Several clusters (the oblique cracks separate) and contacts between them.
  std::vector<int> distinct = root;
  std::sort(distinct.begin(), distinct.end());
  EXPECT_GT(std::unique(distinct.begin(), distinct.end()) - distinct.begin(), 1);
  const auto between = [&](const std::vector<PieceContact>& contacts,
                           const std::vector<FaceSource>& decided, const std::vector<int>& r) {
    std::vector<std::tuple<int, int, int, int, double, int, int>> out;
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      const PieceContact& c = contacts[k];
      if (r[c.piece_a] == r[c.piece_b]) continue;
      out.emplace_back(c.piece_a, c.face_a, c.piece_b, c.face_b, c.area,
                       static_cast<int>(decided[k].kind), decided[k].id);
    }
    return out;
  };
  const auto expected_between = between(expected, one_sources, expected_root);
  EXPECT_GT(expected_between.size(), 10u);  // the oblique cracks cut across many pieces
  EXPECT_EQ(between(got, sources, root), expected_between);
}

TEST(FlatSplit, MirroredContactsFoundOutsideTheTableAreDecidedAsInIt) {
  // The fast cutter decides the two sides of one cut (bitwise the same loop, run backwards)
  // without table entries: mirroredContactArea, passed as ContactTablePart::mirrored. Against
  // one table holding every candidate pair of gridPieces, the same contacts, areas (bitwise)
  // and decisions, in the same order.
  const std::vector<Piece> pieces = gridPieces();
  const int n = static_cast<int>(pieces.size());
  const auto corners = [&](int piece, int face) {
    std::vector<Vec3> out;
    for (int v : pieces[piece].shape.faces[face]) out.push_back(pieces[piece].shape.vertices[v]);
    return out;
  };
  const auto reversed = [](const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    if (a.size() != b.size()) return false;
    const std::size_t m = a.size();
    for (std::size_t start = 0; start < m; ++start) {
      if (b[start] != a[0]) continue;
      for (std::size_t k = 0; k < m; ++k) {
        if (a[k] != b[(start + m - k) % m]) return false;
      }
      return true;
    }
    return false;
  };
  ContactFaces all, rest;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> all_pairs, rest_pairs;
  std::vector<PieceContact> mirrored;
  int mirrored_pairs = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      for (int fa = 0; fa < static_cast<int>(pieces[i].shape.faces.size()); ++fa) {
        for (int fb = 0; fb < static_cast<int>(pieces[j].shape.faces.size()); ++fb) {
          const auto add = [&](ContactFaces& table, int piece, int face) {
            const Piece& p = pieces[piece];
            return table.add(piece, face, p.shape.vertices, p.shape.faces[face]);
          };
          const std::uint32_t a = add(all, i, fa);
          all_pairs.emplace_back(a, add(all, j, fb));
          const std::vector<Vec3> ca = corners(i, fa), cb = corners(j, fb);
          if (reversed(ca, cb)) {
            ++mirrored_pairs;
            if (const auto area = mirroredContactArea(ca, cb, 1e-9, 1e-9)) {
              mirrored.push_back({i, fa, j, fb, *area});
            }
            continue;
          }
          const std::uint32_t ra = add(rest, i, fa);
          rest_pairs.emplace_back(ra, add(rest, j, fb));
        }
      }
    }
  }
  const ContactDecision decide = gridDecision(pieces);
  std::vector<FaceSource> expected_sources, sources;
  const std::vector<PieceContact> expected =
      decideTableContacts(all, pieces.size(), all_pairs, 1e-9, 1e-9, decide, &expected_sources);
  const ContactTablePart part[1] = {{&rest, 0, rest_pairs, mirrored}};
  const std::vector<PieceContact> got =
      decideTableContacts(part, pieces.size(), 1e-9, 1e-9, decide, &sources);
  EXPECT_GT(mirrored_pairs, 50);  // the grid's cuts: both sides of every cut face
  EXPECT_EQ(static_cast<int>(mirrored.size()), mirrored_pairs);  // all of them touch
  expectSameContacts(got, sources, expected, expected_sources);
  // Faces that are not the same loop, or a face with itself not reversed, are no pair.
  const std::vector<Vec3> face = corners(0, 0);
  EXPECT_FALSE(mirroredContactArea(face, face, 1e-9, 1e-9));  // same normals: no contact
}

TEST(FlatSplit, PiecesWithoutCloseVerticesAreKeptAsTheyAreBySoundPiece) {
  // hasCloseVertices is the assembly's shortcut: false must mean soundPiece keeps the piece.
  std::mt19937_64 rng(3);
  const SoundnessTolerances tol = soundnessTolerances({Vec3::Zero(), Vec3::Ones()});
  for (int trial = 0; trial < 50; ++trial) {
    const Piece piece = randomConvexPiece(rng, 1 + trial % 6);
    if (hasCloseVertices(piece, tol)) continue;
    SoundPieceReport report;
    const std::optional<SoundPiece> sound = soundPiece(piece, tol, &report);
    ASSERT_TRUE(sound.has_value());
    EXPECT_EQ(sound->piece.shape.vertices, piece.shape.vertices);
    EXPECT_EQ(sound->piece.shape.faces, piece.shape.faces);
    EXPECT_EQ(sound->piece.face_sources, piece.face_sources);
    EXPECT_EQ(report.merged_vertices, 0);
  }
  // Two corners 1e-9 m apart in a 1 m box (tolerance 1.7e-7 m): close.
  Piece close = randomConvexPiece(rng, 0);
  close.shape.vertices[1] = close.shape.vertices[0] + Vec3(1e-9, 0, 0);
  EXPECT_TRUE(hasCloseVertices(close, tol));
}

}  // namespace
}  // namespace rockmass::blocks
