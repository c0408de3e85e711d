#include "blocks/slab_material.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>

#include "geometry/disc.h"

namespace rockmass::blocks {
namespace {

/// The planes (outward) of the convex hull of two corresponding polygons: vertex k of one
/// faces vertex k of the other (same vertex count, same orientation).
std::vector<Plane> hullPlanes(const std::vector<Vec3>& lower, const std::vector<Vec3>& upper) {
  Vec3 center = Vec3::Zero();
  for (const Vec3& p : lower) center += p;
  for (const Vec3& p : upper) center += p;
  center /= static_cast<double>(lower.size() + upper.size());
  std::vector<Plane> planes;
  const auto add = [&](const std::vector<Vec3>& polygon) {
    const Vec3 n = geometry::polygonNormal(polygon);
    if (n.squaredNorm() == 0.0) return;
    Plane plane = Plane::through(geometry::polygonCentroid(polygon), n);
    if (plane.distance(center) > 0.0) plane = {-plane.normal, -plane.offset};
    planes.push_back(plane);
  };
  add(lower);
  add(upper);
  const std::size_t n = lower.size();
  for (std::size_t k = 0; k < n; ++k) {
    add({lower[k], lower[(k + 1) % n], upper[(k + 1) % n], upper[k]});
  }
  return planes;
}

}  // namespace

SlabMaterials::SlabMaterials(const geometry::FractureNetwork* network, int disc_segments,
                             int rock_material, double tolerance)
    : rock_material_(rock_material), tolerance_(tolerance) {
  if (network == nullptr) return;
  const std::vector<geometry::Disc>& discs = network->discs;
  const auto disc = [&](std::int64_t id) -> const geometry::Disc* {
    if (id < 1 || id > static_cast<std::int64_t>(discs.size())) return nullptr;
    return &discs[static_cast<std::size_t>(id - 1)];
  };
  for (const geometry::Slab& slab : network->slabs) {
    for (const std::int64_t lower_id : slab.lower) {
      const geometry::Disc* lower = disc(lower_id);
      if (lower == nullptr) continue;
      const geometry::Disc* upper = nullptr;
      double best = 4.0 * slab.thickness + 1e-9;
      for (const std::int64_t upper_id : slab.upper) {
        const geometry::Disc* candidate = disc(upper_id);
        if (candidate == nullptr) continue;
        const double d = (candidate->center - lower->center).norm();
        if (d <= best) {
          best = d;
          upper = candidate;
        }
      }
      if (upper == nullptr) continue;
      const std::vector<Vec3> lo = lower->outline(disc_segments);
      // The two surfaces of a slab are made alike (a fault's: the same disc shifted; an
      // interlayer's: the same quadrilateral offset), so outline vertex k of one faces
      // vertex k of the other.
      const std::vector<Vec3> up = upper->outline(disc_segments);
      if (lo.size() != up.size()) continue;
      regions_.push_back({hullPlanes(lo, up), slab.material});
    }
  }
}

int SlabMaterials::at(const Vec3& point) const {
  for (const Region& region : regions_) {
    const bool inside =
        std::all_of(region.planes.begin(), region.planes.end(),
                    [&](const Plane& p) { return p.distance(point) <= tolerance_; });
    if (inside) return region.material;
  }
  return rock_material_;
}

int SlabMaterials::ofBlock(const std::vector<Piece>& pieces) const {
  std::vector<const geometry::Polyhedron*> shapes;
  for (const Piece& piece : pieces) shapes.push_back(&piece.shape);
  return ofBlock(shapes);
}

int SlabMaterials::ofBlock(const std::vector<const geometry::Polyhedron*>& shapes) const {
  std::map<int, double> volume;
  for (const geometry::Polyhedron* shape : shapes) {
    const geometry::MassProperties m = geometry::massProperties(*shape);
    volume[m.volume > 0.0 ? at(m.centroid()) : rock_material_] += m.volume;
  }
  if (volume.empty()) return rock_material_;
  return std::max_element(volume.begin(), volume.end(),
                          [](const auto& x, const auto& y) { return x.second < y.second; })
      ->first;
}

}  // namespace rockmass::blocks
