// Contact persistence: the last step's contacts, found again by what identifies them, so a
// contact carries its state (open, sliding, locked), shear spring and history from one step
// to the next (docs/dda3d.md, "Contact persistence").
#pragma once

#include <cstddef>
#include <unordered_map>
#include <vector>

#include "dda3d/block_state.h"
#include "dda3d/contact.h"

namespace rockmass::dda3d {

/// Identity of a contact across steps: a vertex against a piece (its face may change), a
/// sub-contact point against a face, or an edge against an edge.
struct ContactKey {
  int kind, block_i, piece_i, a, block_j, piece_j, b;
  bool operator==(const ContactKey&) const = default;
};

/// FNV-1a over the key's fields.
struct ContactKeyHash {
  std::size_t operator()(const ContactKey& k) const;
};

/// The key of `c`.
ContactKey keyOf(const Contact& c);

/// The last step's contacts, found by what identifies them (keyOf): vertex-face entries
/// through a table indexed by the vertex (each vertex lists the few pieces it touched), edge
/// and point entries through a hash map. The narrow phase asks for the face of every vertex
/// near a piece, about a million questions a step on the Xiangjiaba region; a node-based hash
/// map of all 2e5 contacts spent most of its time in cache misses along its bucket chains. A
/// key found twice answers with its first contact.
class PreviousContacts {
 public:
  /// `contacts` must outlive this object.
  PreviousContacts(const std::vector<BlockState>& blocks, const std::vector<Contact>& contacts);

  /// Index of the last step's contact with the key of `c`, or -1.
  int find(const Contact& c) const;

  /// The face the vertex used against piece (block_j, piece_j) last step, or -1.
  int face(int block_i, int piece_i, int vertex, int block_j, int piece_j) const;

 private:
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);

  std::size_t vertexIndex(int block, int piece, int vertex) const;
  int findVertex(int block_i, int piece_i, int vertex, int block_j, int piece_j) const;

  const std::vector<Contact>& contacts_;
  std::vector<std::size_t> piece_start_;   ///< first piece of each block, then the count
  std::vector<std::size_t> vertex_start_;  ///< first vertex of each piece, then the count
  std::vector<std::size_t> entry_start_;   ///< first entry of each vertex, then the count
  std::vector<int> entries_;               ///< vertex-face contact indices, by vertex
  std::unordered_map<ContactKey, int, ContactKeyHash> edges_;
};

}  // namespace rockmass::dda3d
