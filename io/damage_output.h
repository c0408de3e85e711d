// The damage map of a DDA run (docs/dda-io.md, "Damage map"): per contact that has been
// closed, whether it is locked, sliding or opened, whether its bond (cohesion, tension) is
// broken, its opening and the slip it accumulated; as VTU points (damage_<step>.vtu, listed
// in damage.pvd) and, for the last map, damage.csv.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "geometry/vec.h"
#include "io/dda_output.h"

namespace rockmass::io {

/// What has happened at a contact (its damage), worst first.
enum class ContactDamage {
  Intact = 0,      ///< closed and locked, its bond intact (or it never had one)
  BondBroken = 1,  ///< closed and locked, but its cohesion or tension is gone
  Sliding = 2,     ///< closed and sliding
  Opened = 3,      ///< open now, after having been closed (a crack)
};

/// One contact of the map.
struct DamagePoint {
  geometry::Vec3 point = geometry::Vec3::Zero();   ///< contact point P (m)
  geometry::Vec3 normal = geometry::Vec3::Zero();  ///< unit normal out of block j
  int block_i = 0;                                 ///< block id of the point
  int block_j = 0;                                 ///< block id of the face
  int joint = 0;                                   ///< joint index (scene order)
  ContactState state = ContactState::Open;         ///< now
  ContactDamage damage = ContactDamage::Intact;
  bool bond_broken = false;   ///< its joint had cohesion or tension, and the contact lost it
  double opening = 0.0;       ///< gap of an opened contact (m), else 0
  double slip = 0.0;          ///< sliding distance accumulated over the run (m)
  double normal_force = 0.0;  ///< N, compression positive (0 when open)
};

/// A damage map: the contacts of one step.
struct DamageMap {
  int step = 0;       ///< accepted steps so far
  double time = 0.0;  ///< simulated time (s)
  std::vector<DamagePoint> contacts;
};

/// The damage class of a contact: its state now, whether it was ever closed, and whether its
/// bond is broken.
ContactDamage damageOf(ContactState state, bool was_closed, bool bond_broken);

/// The map as a VTK unstructured grid of vertex cells, point data block_i, block_j, joint,
/// state (0 open, 1 sliding, 2 locked), damage (ContactDamage), bond_broken (0/1),
/// opening (m), slip (m), normal_force (N) and normal (3).
std::string formatDamageVtu(const DamageMap& map);

/// "damage_<step, 6 digits>.vtu".
std::string damageFileName(int step);

/// The map as CSV: step,time,x,y,z,nx,ny,nz,block_i,block_j,joint,state,damage,opening,slip,
/// normal_force (state: open | sliding | locked; damage: intact | bond_broken | sliding |
/// opened).
std::string formatDamageCsv(const DamageMap& map);

/// Writes damage_<step>.vtu maps into a folder, keeping damage.pvd listing them.
class DamageMapWriter {
 public:
  explicit DamageMapWriter(std::filesystem::path folder);
  /// Writes the map and updates damage.pvd; a step already written is ignored.
  void write(const DamageMap& map);
  const std::vector<PvdEntry>& entries() const { return series_.entries(); }

 private:
  PvdSeries series_;
  int last_step_ = -1;
};

}  // namespace rockmass::io
