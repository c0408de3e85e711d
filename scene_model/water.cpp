// Water in the DDA model of a scene (scene_model/model_parts.h): the water entries on exposed
// faces and in the structure-rock interface (loads.water), the pore pressure in the
// discontinuities (loads.pore_pressure: a phreatic level or an uplift diagram with drains),
// Westergaard's added pressure of an earthquake, and the uplift each structure carries.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "dda3d/block_terms.h"
#include "io/atomic_file.h"
#include "io/input_error.h"
#include "scene_model/dda_model.h"
#include "scene_model/model_parts.h"

namespace rockmass::scene_model {

using namespace io;     // NOLINT: the scene's types
using namespace parts;  // NOLINT: the adapters' shared parts

namespace {

/// Calls visit(b, p, face, source) for every face of every piece of the model (source: the
/// face's FaceSource, fictitious where it has none).
template <class Visit>
void forEachFace(const blocks::BlockModel& blocks, Visit&& visit) {
  for (std::size_t b = 0; b < blocks.blocks.size(); ++b) {
    const blocks::Block& block = blocks.blocks[b];
    for (std::size_t p = 0; p < block.pieces.size(); ++p) {
      const blocks::Piece& piece = block.pieces[p];
      for (std::size_t f = 0; f < piece.shape.faces.size(); ++f) {
        visit(b, p, static_cast<int>(f),
              f < piece.face_sources.size() ? piece.face_sources[f] : blocks::FaceSource{});
      }
    }
  }
}

/// The lowest z of face `f` of `shape` (m).
double lowestZ(const geometry::Polyhedron& shape, int f) {
  double lowest = std::numeric_limits<double>::infinity();
  for (int v : shape.faces[static_cast<std::size_t>(f)]) {
    lowest = std::min(lowest, shape.vertices[static_cast<std::size_t>(v)].z());
  }
  return lowest;
}

/// Pressure entries of one water load: every outer piece face it wets (see buildDdaModel).
void addWaterLoad(const Scene& scene, const WaterLoad& water, const blocks::BlockModel& blocks,
                  const std::vector<int>& owner, const Members& members, dda3d::DdaModel& model) {
  const double tol = tolerance(blocks);
  // How far past a face we look for the body on its other side: far beyond the cutters'
  // snapping (tol), far below any block size that matters.
  const double probe = 100.0 * tol;
  const bool box_domain = scene.domain_mesh.empty();
  const DomainFace top = domainFace("top");
  const int structure = water.domain_top ? -1 : structureIndex(scene, water.structure);
  forEachFace(blocks, [&](std::size_t b, std::size_t p, int face,
                          const blocks::FaceSource& source) {
    const blocks::Block& block = blocks.blocks[b];
    const blocks::Piece& piece = block.pieces[p];
    const geometry::Vec3 normal = geometry::faceNormal(piece.shape, face);
    const geometry::Vec3 center = faceCenter(piece.shape, face);
    const geometry::Vec3 beyond = center + probe * normal;
    bool wet = false;
    if (water.domain_top) {
      // The reservoir floor: the rock surface not covered by a structure.
      wet = (box_domain && source.kind == blocks::FaceKind::Boundary && source.id == 5) ||
            liesOnDomainFace(piece, face, top, blocks.domain, tol);
      for (std::size_t s = 0; s < scene.structures.size() && wet; ++s) {
        wet = !insideOwnedBy(blocks, members, static_cast<int>(s), beyond, 0.5 * probe);
      }
    } else if (owner[b] == structure) {
      wet = source.kind == blocks::FaceKind::Structure && water.facing &&
            normal.dot(*water.facing) > 0.0;
    }
    wet = wet && inRegion(water.region, center);
    // Uplift (under the named structure, or under every structure for domain_top): the
    // structure's faces resting on rock and the rock's faces under the structure.
    bool uplift = false;
    if (!wet && water.uplift) {
      for (std::size_t s = 0; s < scene.structures.size() && !uplift; ++s) {
        const int under = static_cast<int>(s);
        if (structure >= 0 && under != structure) continue;
        uplift = (owner[b] == under && backsOnto(blocks, members, -1, piece.shape, face, probe)) ||
                 (owner[b] < 0 && backsOnto(blocks, members, under, piece.shape, face, probe));
      }
    }
    if (!wet && !uplift) return;
    if (lowestZ(piece.shape, face) >= water.level || internalFace(block, p, face, tol)) return;
    model.pressures.push_back(dda3d::hydrostaticPressure(
        static_cast<int>(b), static_cast<int>(p), face, water.level, water.unit_weight, uplift));
  });
}

/// The extent of a structure along `direction` (m): its blocks' vertices projected.
std::pair<double, double> structureExtent(const blocks::BlockModel& blocks, const Members& members,
                                          int structure, const geometry::Vec3& direction) {
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (int b : members[static_cast<std::size_t>(structure + 1)]) {
    for (const blocks::Piece& piece : blocks.blocks[static_cast<std::size_t>(b)].pieces) {
      for (const geometry::Vec3& v : piece.shape.vertices) {
        low = std::min(low, direction.dot(v));
        high = std::max(high, direction.dot(v));
      }
    }
  }
  return {low, high};
}

/// The head field of a pore-pressure entry as linear pieces: each a DdaPressure template
/// (level, head_gradient, within) without its face.
std::vector<dda3d::DdaPressure> headPieces(const Scene& scene, const PorePressure& pore,
                                           const blocks::BlockModel& blocks,
                                           const Members& members) {
  dda3d::DdaPressure base;
  base.unit_weight = pore.unit_weight;
  base.uplift = true;
  base.pore = true;
  const Region& r = pore.region;
  if (r.x_min) base.within.push_back({-geometry::Vec3::UnitX(), -*r.x_min});
  if (r.x_max) base.within.push_back({geometry::Vec3::UnitX(), *r.x_max});
  if (r.y_min) base.within.push_back({-geometry::Vec3::UnitY(), -*r.y_min});
  if (r.y_max) base.within.push_back({geometry::Vec3::UnitY(), *r.y_max});
  if (pore.level) {
    base.level = *pore.level;
    return {base};
  }
  const UpliftDiagram& d = *pore.diagram;
  const int structure = structureIndex(scene, d.structure);
  const auto [heel, toe] = structureExtent(blocks, members, structure, d.flow);
  // Knots (s along the flow, head): heel, drains, toe.
  std::vector<std::pair<double, double>> knots{{heel, d.upstream_level}};
  if (d.drain_distance) {
    if (!(*d.drain_distance < toe - heel)) {
      throw InputError(locate(scene, d.drain_key,
                              "the drains lie " + formatDouble(*d.drain_distance) +
                                  " m downstream of the heel, outside the structure '" +
                                  d.structure + "' (its base spans " + formatDouble(toe - heel) +
                                  " m along the flow); expected a distance below that"));
    }
    knots.push_back({heel + *d.drain_distance,
                     d.downstream_level +
                         (1.0 - d.drain_efficiency) * (d.upstream_level - d.downstream_level)});
  }
  knots.push_back({toe, d.downstream_level});
  std::vector<dda3d::DdaPressure> out;
  const auto piece = [&](double head_at_0, double slope, std::optional<double> from,
                         std::optional<double> to) {
    dda3d::DdaPressure p = base;
    p.level = head_at_0;
    p.head_gradient = slope * d.flow;
    if (from) p.within.push_back({-d.flow, -*from});
    if (to) p.within.push_back({d.flow, *to});
    out.push_back(p);
  };
  piece(d.upstream_level, 0.0, std::nullopt, heel);
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    const auto [s0, h0] = knots[k];
    const auto [s1, h1] = knots[k + 1];
    const double slope = (h1 - h0) / (s1 - s0);
    piece(h0 - slope * s0, slope, s0, s1);
  }
  piece(d.downstream_level, 0.0, toe, std::nullopt);
  return out;
}

/// Pressure entries of one pore-pressure field: both sides of every discontinuity (disc
/// faces of the rock, the structure-rock interface) below its water line.
void addPorePressure(const Scene& scene, const PorePressure& pore, const blocks::BlockModel& blocks,
                     const std::vector<int>& owner, const Members& members,
                     dda3d::DdaModel& model) {
  const double tol = tolerance(blocks);
  const double probe = 100.0 * tol;
  const std::vector<dda3d::DdaPressure> pieces = headPieces(scene, pore, blocks, members);
  // The head never rises above the level, or the reservoir's for a diagram.
  const double highest_head = pore.level ? *pore.level : pore.diagram->upstream_level;
  forEachFace(blocks, [&](std::size_t b, std::size_t p, int face,
                          const blocks::FaceSource& source) {
    const blocks::Block& block = blocks.blocks[b];
    const blocks::Piece& piece = block.pieces[p];
    bool joint = owner[b] < 0 && source.kind == blocks::FaceKind::Disc;
    if (!joint && source.kind != blocks::FaceKind::Fictitious) {
      // The structure-rock interface, from either side.
      if (owner[b] >= 0) {
        joint = source.kind == blocks::FaceKind::Structure &&
                backsOnto(blocks, members, -1, piece.shape, face, probe);
      } else {
        for (std::size_t s = 0; s < scene.structures.size() && !joint; ++s) {
          joint = backsOnto(blocks, members, static_cast<int>(s), piece.shape, face, probe);
        }
      }
    }
    if (!joint || lowestZ(piece.shape, face) >= highest_head || internalFace(block, p, face, tol)) {
      return;
    }
    for (dda3d::DdaPressure entry : pieces) {
      entry.block = static_cast<int>(b);
      entry.piece = static_cast<int>(p);
      entry.face = face;
      if (dda3d::pressureResultant(piece.shape, face, entry).isZero(0.0)) continue;
      model.pressures.push_back(std::move(entry));
    }
  });
}

/// Westergaard's added pressure on the structure's faces that face the reservoir.
void addWestergaard(const Scene& scene, const Seismic& seismic, const blocks::BlockModel& blocks,
                    const Members& members, dda3d::DdaModel& model) {
  const Westergaard& w = *seismic.westergaard;
  const int structure = structureIndex(scene, w.structure);
  const double bottom =
      w.bottom ? *w.bottom
               : structureExtent(blocks, members, structure, geometry::Vec3::UnitZ()).first;
  for (int b : members[static_cast<std::size_t>(structure + 1)]) {
    const blocks::Block& block = blocks.blocks[static_cast<std::size_t>(b)];
    for (std::size_t p = 0; p < block.pieces.size(); ++p) {
      const blocks::Piece& piece = block.pieces[p];
      for (std::size_t f = 0; f < piece.shape.faces.size(); ++f) {
        const int face = static_cast<int>(f);
        const blocks::FaceSource source =
            f < piece.face_sources.size() ? piece.face_sources[f] : blocks::FaceSource{};
        if (source.kind != blocks::FaceKind::Structure ||
            geometry::faceNormal(piece.shape, face).dot(*w.facing) <= 0.0) {
          continue;
        }
        model.hydrodynamic.push_back({.block = b,
                                      .piece = static_cast<int>(p),
                                      .face = face,
                                      .level = w.level,
                                      .depth = w.level - bottom,
                                      .k_h = seismic.k_h,
                                      .unit_weight = w.unit_weight});
      }
    }
  }
}

}  // namespace

namespace parts {

void addWater(const Scene& scene, const blocks::BlockModel& blocks, const std::vector<int>& owner,
              const Members& members, dda3d::DdaModel& model) {
  for (const WaterLoad& water : scene.loads.water) {
    addWaterLoad(scene, water, blocks, owner, members, model);
  }
  for (const PorePressure& pore : scene.loads.pore_pressure) {
    addPorePressure(scene, pore, blocks, owner, members, model);
  }
  if (const std::optional<Seismic>& seismic = scene.loads.seismic) {
    if (seismic->westergaard) addWestergaard(scene, *seismic, blocks, members, model);
  }
}

}  // namespace parts

std::vector<io::StructureUplift> structureUplift(const Scene& scene, const dda3d::DdaModel& model) {
  std::vector<io::StructureUplift> out;
  for (const StructureSpec& s : scene.structures) out.push_back({s.name, geometry::Vec3::Zero()});
  bool any = false;
  for (const dda3d::DdaPressure& p : model.pressures) {
    const dda3d::DdaBlock& block = model.blocks[static_cast<std::size_t>(p.block)];
    if (!p.uplift || block.structure < 0) continue;
    out[static_cast<std::size_t>(block.structure)].force +=
        dda3d::pressureResultant(block.pieces[static_cast<std::size_t>(p.piece)], p.face, p);
    any = true;
  }
  if (!any) out.clear();
  return out;
}

}  // namespace rockmass::scene_model
