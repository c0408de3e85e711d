// A face-to-face contact between two blocks carried by the corners of its convex hull: the
// vertex entries of coplanar faces reduced to the extreme points of their group.
#pragma once

#include <cstddef>
#include <vector>

#include "dda3d/block_state.h"
#include "dda3d/contact.h"

namespace rockmass::dda3d {

/// Keeps, of the vertex entries where a face of block i lies against a face of block j
/// (Contact::facing_face), only the corners of the convex hull of each group of them: the
/// same two blocks and joint, the same plane of j and the same plane of i (within 1e-6 of the
/// group's extent, normals within 1.4e-3 rad). A block made of several convex pieces has
/// vertices of its pieces inside its faces and along their edges; each was a full penalty
/// spring, so a face's stiffness, and where its load went, depended on how the cutter had
/// split the block into pieces. A rigid pair of planar faces is carried by the corners of
/// their contact, as a single piece's face is (formulation doc, "Point-to-face contact").
/// Corners within 1e-6 of the extent of the line through their neighbours on the hull count
/// as on that line (vertices along an edge of the block, straight but for round-off), so
/// which of them stay does not change with the blocks' round-off from search to search.
/// Entries without a facing face (corners and edges against a face, edge crossings,
/// sub-contact points) are kept. The order of the kept entries is unchanged. Returns how many
/// entries were dropped.
std::size_t keepHullCorners(std::vector<Contact>& contacts, const std::vector<BlockState>& blocks);

}  // namespace rockmass::dda3d
