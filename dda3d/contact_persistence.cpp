#include "dda3d/contact_persistence.h"

#include "dda3d/contact_detection.h"

namespace rockmass::dda3d {

std::size_t ContactKeyHash::operator()(const ContactKey& k) const {
  std::size_t h = 1469598103934665603ull;
  for (int v : {k.kind, k.block_i, k.piece_i, k.a, k.block_j, k.piece_j, k.b}) {
    h = (h ^ static_cast<std::size_t>(static_cast<unsigned>(v))) * 1099511628211ull;
  }
  return h;
}

ContactKey keyOf(const Contact& c) {
  if (c.kind == ContactKind::VertexFace) {
    return {0, c.block_i, c.piece_i, c.vertex, c.block_j, c.piece_j, -1};
  }
  if (c.kind == ContactKind::FacePoint) {
    return {2, c.block_i, c.piece_i, c.vertex, c.block_j, c.piece_j, c.face};
  }
  return {1, c.block_i, c.piece_i, c.edge_i, c.block_j, c.piece_j, c.edge_j};
}

PreviousContacts::PreviousContacts(const std::vector<BlockState>& blocks,
                                   const std::vector<Contact>& contacts)
    : contacts_(contacts) {
  piece_start_ = firstPieces(blocks);
  vertex_start_.assign(piece_start_.back() + 1, 0);
  std::size_t piece = 0;
  for (const BlockState& block : blocks) {
    for (const geometry::Polyhedron& shape : block.pieces) {
      vertex_start_[piece + 1] = vertex_start_[piece] + shape.vertices.size();
      ++piece;
    }
  }
  // Counting sort of the vertex-face entries by vertex, in contact order within a vertex.
  std::vector<std::size_t> vertex_of(contacts.size(), kNone);
  entry_start_.assign(vertex_start_.back() + 1, 0);
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    if (c.kind != ContactKind::VertexFace) {
      edges_.emplace(keyOf(c), static_cast<int>(k));
      continue;
    }
    vertex_of[k] = vertexIndex(c.block_i, c.piece_i, c.vertex);
    if (vertex_of[k] != kNone) ++entry_start_[vertex_of[k] + 1];
  }
  for (std::size_t v = 0; v + 1 < entry_start_.size(); ++v) entry_start_[v + 1] += entry_start_[v];
  entries_.resize(entry_start_.back());
  std::vector<std::size_t> next(entry_start_.begin(), entry_start_.end() - 1);
  for (std::size_t k = 0; k < contacts.size(); ++k) {
    if (vertex_of[k] != kNone) entries_[next[vertex_of[k]]++] = static_cast<int>(k);
  }
}

int PreviousContacts::find(const Contact& c) const {
  if (c.kind != ContactKind::VertexFace) {
    const auto found = edges_.find(keyOf(c));
    return found == edges_.end() ? -1 : found->second;
  }
  return findVertex(c.block_i, c.piece_i, c.vertex, c.block_j, c.piece_j);
}

int PreviousContacts::face(int block_i, int piece_i, int vertex, int block_j, int piece_j) const {
  const int k = findVertex(block_i, piece_i, vertex, block_j, piece_j);
  return k < 0 ? -1 : contacts_[static_cast<std::size_t>(k)].face;
}

std::size_t PreviousContacts::vertexIndex(int block, int piece, int vertex) const {
  if (block < 0 || static_cast<std::size_t>(block) + 1 >= piece_start_.size()) return kNone;
  const std::size_t p =
      piece_start_[static_cast<std::size_t>(block)] + static_cast<std::size_t>(piece);
  if (piece < 0 || p >= piece_start_[static_cast<std::size_t>(block) + 1]) return kNone;
  const std::size_t v = vertex_start_[p] + static_cast<std::size_t>(vertex);
  return vertex < 0 || v >= vertex_start_[p + 1] ? kNone : v;
}

int PreviousContacts::findVertex(int block_i, int piece_i, int vertex, int block_j,
                                 int piece_j) const {
  const std::size_t v = vertexIndex(block_i, piece_i, vertex);
  if (v == kNone) return -1;
  for (std::size_t e = entry_start_[v]; e < entry_start_[v + 1]; ++e) {
    const Contact& c = contacts_[static_cast<std::size_t>(entries_[e])];
    if (c.block_j == block_j && c.piece_j == piece_j) return entries_[e];
  }
  return -1;
}

}  // namespace rockmass::dda3d
