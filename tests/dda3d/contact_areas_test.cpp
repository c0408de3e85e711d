// detection::assignAreas against the rule it implements, written out as a plain scan: each
// area sample goes to the nearest entry facing its way (within kAreaCosine) and lying within its
// distance of its plane, first among the entries of its own two pieces (taken when within the
// sample's distance), else among every entry of its two blocks; entries within
// kAreaTieShare of the sample's distance of the nearest are tied, and ties go to the entry
// first in (pair of pieces, found order). The implementation searches large pairs of blocks outward
// along x instead of scanning them; it must pick the same entry for every sample.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <tuple>
#include <vector>

#include "dda3d/piece_view.h"
#include "geometry/random.h"

namespace rockmass::dda3d {
namespace {

using geometry::Vec3;

/// (lower block, higher block, its piece, the other's piece): the order of the pairs.
std::array<int, 4> pieceKey(int block_a, int piece_a, int block_b, int piece_b) {
  return block_a < block_b ? std::array<int, 4>{block_a, block_b, piece_a, piece_b}
                           : std::array<int, 4>{block_b, block_a, piece_b, piece_a};
}

/// The rule, scanned: the index of the entry that takes `s`, or -1.
int takerOf(const std::vector<Contact>& contacts, const detection::AreaSample& s) {
  const auto key = pieceKey(s.block_a, s.piece_a, s.block_b, s.piece_b);
  const auto nearest = [&](bool own_pieces, double& best) {
    // The squared distance of each entry that may take the sample, or infinity.
    std::vector<double> distance(contacts.size(), std::numeric_limits<double>::infinity());
    best = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      const Contact& c = contacts[k];
      const auto ck = pieceKey(c.block_i, c.piece_i, c.block_j, c.piece_j);
      if (ck[0] != key[0] || ck[1] != key[1] || (own_pieces && ck != key)) continue;
      if (c.kind == ContactKind::FacePoint) continue;
      const Vec3 normal = c.block_j == s.block_b ? c.normal : Vec3(-c.normal);
      if (normal.dot(s.normal) < detection::kAreaCosine) continue;
      if (std::abs(s.normal.dot(c.point - s.point)) > s.distance) continue;
      distance[k] = (c.point - s.point).squaredNorm();
      best = std::min(best, distance[k]);
    }
    const double tied = std::pow(std::sqrt(best) + detection::kAreaTieShare * s.distance, 2);
    int taker = -1;
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      if (!(distance[k] <= tied)) continue;
      const auto key_of = [&](std::size_t t) {
        const Contact& o = contacts[t];
        return std::make_tuple(pieceKey(o.block_i, o.piece_i, o.block_j, o.piece_j), t);
      };
      if (taker < 0 || key_of(k) < key_of(static_cast<std::size_t>(taker))) {
        taker = static_cast<int>(k);
      }
    }
    return taker;
  };
  double best = 0.0;
  const int own = nearest(true, best);
  if (own >= 0 && best <= s.distance * s.distance) return own;
  return nearest(false, best);
}

TEST(ContactAreas, EverySampleGoesToTheEntryThePlainScanPicks) {
  // Blocks 0 and 1 share 400 entries (the searched path, above 32 a pair), blocks 0 and 2
  // share 12 (the scanned path). Entries and samples sit on a 0.5 m grid in x and y, so many
  // lie at exactly equal distances from a sample (ties: x and y are multiples of 0.25, exact,
  // and an entry's mirror image about a sample has its z) and share an x (equal sort keys);
  // normals are +-z or +x, so some entries do not face a sample's way. Weights are distinct,
  // so an entry given a wrong sample is off by a whole weight.
  geometry::Rng rng(20261127);
  const auto uniform = [](geometry::Rng& r, double low, double high) {
    return std::uniform_real_distribution<double>(low, high)(r);
  };
  std::vector<Contact> contacts;
  const auto addEntries = [&](int other, int count, int pieces) {
    for (int k = 0; k < count; ++k) {
      Contact c;
      const bool of_zero = uniform(rng, 0.0, 1.0) < 0.5;
      c.block_i = of_zero ? 0 : other;
      c.block_j = of_zero ? other : 0;
      c.piece_i = static_cast<int>(uniform(rng, 0.0, pieces - 1e-9));
      c.piece_j = static_cast<int>(uniform(rng, 0.0, pieces - 1e-9));
      c.kind = k % 37 == 5 ? ContactKind::FacePoint : ContactKind::VertexFace;
      c.area = c.kind == ContactKind::FacePoint ? 0.25 : 7.0;  // FacePoint areas are kept
      c.point =
          Vec3(0.5 * std::floor(uniform(rng, 0.0, 12.0)), 0.5 * std::floor(uniform(rng, 0.0, 12.0)),
               5e-4 * std::floor(uniform(rng, -4.0, 5.0)));
      const double pick = uniform(rng, 0.0, 1.0);
      c.normal = pick < 0.45 ? Vec3::UnitZ() : pick < 0.9 ? Vec3(-Vec3::UnitZ()) : Vec3::UnitX();
      contacts.push_back(c);
    }
  };
  addEntries(1, 400, 4);
  addEntries(2, 12, 2);
  std::vector<detection::AreaSample> samples;
  for (int k = 0; k < 900; ++k) {
    detection::AreaSample s;
    const int other = k % 5 == 0 ? 2 : 1;
    const bool a_is_zero = uniform(rng, 0.0, 1.0) < 0.5;
    s.block_a = a_is_zero ? 0 : other;
    s.block_b = a_is_zero ? other : 0;
    const int pieces = other == 1 ? 4 : 2;
    s.piece_a = static_cast<int>(uniform(rng, 0.0, pieces - 1e-9));
    s.piece_b = static_cast<int>(uniform(rng, 0.0, pieces - 1e-9));
    s.point = Vec3(0.25 * std::floor(uniform(rng, 0.0, 24.0)),
                   0.25 * std::floor(uniform(rng, 0.0, 24.0)), 0.0);
    s.normal = uniform(rng, 0.0, 1.0) < 0.5 ? Vec3::UnitZ() : Vec3(-Vec3::UnitZ());
    s.weight = 1e-3 * (k + 1);
    s.distance = k % 3 == 0 ? 1e-3 : 0.3;  // some own-piece entries too far off the plane
    samples.push_back(s);
  }
  std::vector<double> expected(contacts.size(), 0.0);
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    if (contacts[k].kind == ContactKind::FacePoint) expected[k] = contacts[k].area;
  }
  int searched = 0;
  for (const detection::AreaSample& s : samples) {
    const int taker = takerOf(contacts, s);
    if (taker >= 0) expected[static_cast<std::size_t>(taker)] += s.weight, ++searched;
  }
  ASSERT_GT(searched, 700);  // the grid and normals leave few samples without a taker
  detection::assignAreas(contacts, samples);
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    // The same samples summed, perhaps in another order: round-off of sums below 1 m2.
    EXPECT_NEAR(contacts[k].area, expected[k], 1e-12) << "entry " << k;
  }
}

// A sample about as near two entries goes to the earlier whichever is nearer by round-off or
// by a micrometre's motion, so a search that finds the same entries gives them the same areas.
// The sample is a corner of the overlap of two blocks' faces, with two vertex entries of the
// block above 0.1 m away on either side (the search's range 0.02 m: tie 2e-6 m). Nearest alone,
// the later entry took the sample whenever it came 1e-9 m nearer, and on the Xiangjiaba region
// at rest a search moved 150-900 m2 of contact area between entries (cohesion with it). Beyond
// the tie the nearer entry takes it.
TEST(ContactAreas, ASampleAboutAsNearTwoEntriesGoesToTheEarlier) {
  detection::AreaSample s;
  s.block_a = 0;
  s.block_b = 1;
  s.piece_a = s.piece_b = 0;
  s.point = Vec3(1.0, 2.0, 0.0);
  s.normal = Vec3::UnitZ();  // of block 1's face, out of it: block 0 rests on block 1
  s.weight = 0.5;
  s.distance = 0.02;
  for (const double nearer : {0.0, 1e-9, 1e-6, 3e-6, 1e-4}) {
    SCOPED_TRACE("the later entry nearer by " + std::to_string(nearer));
    std::vector<Contact> contacts(2);
    for (Contact& c : contacts) {
      c.kind = ContactKind::VertexFace;
      c.block_i = 0;
      c.block_j = 1;
      c.normal = Vec3::UnitZ();
    }
    contacts[0].point = s.point + Vec3(-0.1, 0.0, 0.0);
    contacts[1].point = s.point + Vec3(0.1 - nearer, 0.0, 0.0);
    detection::assignAreas(contacts, {s});
    const bool tied = nearer <= detection::kAreaTieShare * s.distance;  // 2e-6 m
    EXPECT_EQ(contacts[0].area, tied ? 0.5 : 0.0);
    EXPECT_EQ(contacts[1].area, tied ? 0.0 : 0.5);
  }
}

}  // namespace
}  // namespace rockmass::dda3d
