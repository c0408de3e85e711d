// The parts of the fast cutter both its strategies share (blocks/fast_cutter.cpp: FullPlanes;
// blocks/edge_planes_cutter.cpp: EdgePlanes): cutting polygons, work pieces and their
// splits, the cut's start, disc groups and how they cover a face. Internal to the blocks
// module.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "blocks/block_assembly.h"
#include "blocks/convex_split.h"
#include "blocks/cutter.h"
#include "blocks/fast_cutter.h"
#include "blocks/piece_contacts.h"
#include "blocks/union_find.h"
#include "geometry/disc.h"

namespace rockmass::blocks::fastcut {

using geometry::Box;
using geometry::Vec2;

/// A convex cutting polygon: (part of) one disc.
struct CutPolygon {
  int disc_id = 0;
  Plane plane;               ///< the disc's plane
  std::vector<Vec3> points;  ///< counter-clockwise about plane.normal
  std::vector<Plane> edges;  ///< per edge: perpendicular to the disc, normal pointing inside
  Box box;                   ///< bounding box of the points
  int plane_id = 0;          ///< id of `plane` (a UnionFind id: coincident planes share a root)
  int first_edge_id = 0;     ///< id of edges[0]; edges[k] has first_edge_id + k
  int group = -1;            ///< FullPlanes: its DiscGroup
};

/// A piece being cut, with the id of the plane each face lies in. Faces made by one cutting
/// plane share its id; coincident planes are merged when a polygon meets a face in its
/// plane. Contacts are then searched among faces of one plane only.
struct WorkPiece {
  Piece piece;
  std::vector<int> planes;  ///< per face
};

/// The convex cutting polygons of one disc.
void addCutPolygons(const geometry::Disc& disc, int segments, double tolerance, UnionFind& ids,
                    std::vector<CutPolygon>& out);

/// Wall seconds since `start` (the report's timings).
double secondsSince(std::chrono::steady_clock::time_point start);

/// True when the box lies more than `tolerance` on one side of the plane.
bool boxMissesPlane(const Box& box, const Plane& plane, double tolerance);

/// The two halves of a split work piece, with the face of the input each face comes from
/// (-1: the new face).
struct WorkSplit {
  WorkPiece below, above;
  std::vector<int> below_origin, above_origin;
};

/// Splits a work piece by a plane with id `plane_id`; faces keep their plane ids.
std::optional<WorkSplit> splitWork(const WorkPiece& work, const Plane& plane, int plane_id,
                                   double tolerance, FaceSource cap);

/// What cutting one piece by one polygon gives.
struct CutResult {
  std::optional<std::vector<WorkPiece>> pieces;  ///< replacements, or nothing: unchanged
  std::vector<std::pair<int, int>> coincident;   ///< plane ids found to be one plane
  long long splits = 0;                          ///< plane splits made
};

/// Cuts one piece by one polygon.
CutResult cutPiece(const WorkPiece& work, const CutPolygon& polygon, const CutTolerances& tol);

/// What both strategies start from: the labelled domain pieces, one plane id per domain face
/// (faces shared by two domain pieces united), then the cutting polygons with their plane and
/// edge ids, in disc order.
struct CutStart {
  UnionFind plane_ids;  ///< coincident planes end up with one root
  std::vector<Piece> domain;
  std::vector<std::vector<int>> domain_planes;  ///< per domain piece, per face
  std::vector<CutPolygon> polygons;
};

/// The labelled domain pieces, their plane ids and the cutting polygons of `input`.
CutStart startCut(const CutInput& input, const CutTolerances& tol);

/// Discs in one plane (within the tolerance): their union is what covers a face.
struct DiscGroup {
  Plane plane;                ///< the plane of the group's first disc
  int plane_id = 0;           ///< plane id shared by all its polygons
  std::vector<int> polygons;  ///< indices of its cutting polygons
};

/// Puts every cutting polygon into the group of its plane; a polygon that joins a group is
/// moved onto the group's plane (its points projected, its edges rebuilt) and takes its id.
std::vector<DiscGroup> groupPolygons(std::vector<CutPolygon>& polygons, double tolerance);

/// How the discs of a plane cover a convex face in that plane.
enum class Cover : std::uint8_t {
  None,     ///< not at all (the covered part has no area above the tolerance)
  Partial,  ///< partly
  Whole,    ///< wholly (what is left uncovered has no area above the tolerance)
};

/// True when every point lies inside the convex polygon, within `tolerance` (m).
bool insidePolygon(const std::vector<Vec3>& points, const CutPolygon& polygon, double tolerance);

/// Polygons with more edges than this are clipped against a face rather than the face
/// against them (overlapInto). The ellipses of `disc_segments` (at most 1024 by the scene
/// reader, 24 by default) and FAB polygons of up to 64 vertices keep the face-by-edges path.
constexpr std::size_t kManyEdges = 64;

/// `out` = the part of the convex `face` (points in the polygon's plane) inside the convex
/// polygon. The face is clipped by the polygon's edges one by one; the part left can grow by
/// a vertex per edge, so a polygon of n edges over a face costs O(n^2) (a FAB circle of
/// 200 000 vertices: 97 s). A polygon of more than kManyEdges edges, and more than the face
/// has, is clipped by the face's edges instead: the same convex set, O(n m).
void overlapInto(const std::vector<Vec3>& face, const CutPolygon& polygon, std::vector<Vec3>& out,
                 std::vector<Vec3>& scratch);

/// Area (m2) of the part of `face` inside the convex polygon.
double coveredArea(const std::vector<Vec3>& face, const CutPolygon& polygon);

/// How the group's polygons cover the convex face (points in the group's plane); `disc` gets
/// the disc holding the face's centre when Whole. Double precision with the cutter's
/// tolerances: a vertex within tolerance.distance of an edge is on it, an uncovered or
/// covered part of area at most tolerance.area is none.
Cover coverage(const std::vector<Vec3>& face, const DiscGroup& group,
               const std::vector<CutPolygon>& polygons, const CutTolerances& tol, int* disc);

/// The cut's blocks from its pieces and contacts (assembleBlocks), its counters completed
/// (inconsistent contacts, soundness, pieces, assembly time since `assemble_start`) and
/// copied to `report` when given.
BlockModel assembleCut(std::vector<Piece> pieces, const std::vector<PieceContact>& contacts,
                       const CutInput& input, const CutTolerances& tol, FastCutReport& counters,
                       std::chrono::steady_clock::time_point assemble_start, FastCutReport* report,
                       const std::vector<FaceSource>* sources = nullptr,
                       const std::vector<PieceFacts>* facts = nullptr);

/// FastStrategy::EdgePlanes (blocks/edge_planes_cutter.cpp).
BlockModel cutEdgePlanes(const CutInput& input, const CutTolerances& tol, FastCutReport* report);

}  // namespace rockmass::blocks::fastcut
