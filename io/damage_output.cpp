#include "io/damage_output.h"

#include <cstdio>

#include "io/atomic_file.h"
#include "io/vtu.h"

namespace rockmass::io {
namespace {

/// VTK cell type of a single point.
constexpr std::uint8_t kVtkVertex = 1;

const char* damageName(ContactDamage damage) {
  switch (damage) {
    case ContactDamage::BondBroken:
      return "bond_broken";
    case ContactDamage::Sliding:
      return "sliding";
    case ContactDamage::Opened:
      return "opened";
    case ContactDamage::Intact:
      break;
  }
  return "intact";
}

}  // namespace

ContactDamage damageOf(ContactState state, bool was_closed, bool bond_broken) {
  if (state == ContactState::Open)
    return was_closed ? ContactDamage::Opened : ContactDamage::Intact;
  if (state == ContactState::Sliding) return ContactDamage::Sliding;
  return bond_broken ? ContactDamage::BondBroken : ContactDamage::Intact;
}

std::string formatDamageVtu(const DamageMap& map) {
  VtuPiece piece;
  std::vector<std::int32_t> block_i, block_j, joint, state, damage, broken;
  std::vector<double> opening, slip, force, normal;
  for (const DamagePoint& c : map.contacts) {
    const auto index = static_cast<std::int64_t>(piece.types.size());
    piece.points.insert(piece.points.end(), {c.point.x(), c.point.y(), c.point.z()});
    piece.connectivity.push_back(index);
    piece.offsets.push_back(index + 1);
    piece.types.push_back(kVtkVertex);
    block_i.push_back(c.block_i);
    block_j.push_back(c.block_j);
    joint.push_back(c.joint);
    state.push_back(static_cast<std::int32_t>(c.state));
    damage.push_back(static_cast<std::int32_t>(c.damage));
    broken.push_back(c.bond_broken ? 1 : 0);
    opening.push_back(c.opening);
    slip.push_back(c.slip);
    force.push_back(c.normal_force);
    normal.insert(normal.end(), {c.normal.x(), c.normal.y(), c.normal.z()});
  }
  piece.point_data.push_back(makeVtuArray("block_i", block_i));
  piece.point_data.push_back(makeVtuArray("block_j", block_j));
  piece.point_data.push_back(makeVtuArray("joint", joint));
  piece.point_data.push_back(makeVtuArray("state", state));
  piece.point_data.push_back(makeVtuArray("damage", damage));
  piece.point_data.push_back(makeVtuArray("bond_broken", broken));
  piece.point_data.push_back(makeVtuArray("opening", opening));
  piece.point_data.push_back(makeVtuArray("slip", slip));
  piece.point_data.push_back(makeVtuArray("normal_force", force));
  piece.point_data.push_back(makeVtuArray("normal", normal, 3));
  return formatVtu(piece);
}

std::string damageFileName(int step) {
  char name[40];
  std::snprintf(name, sizeof name, "damage_%06d.vtu", step);
  return name;
}

std::string formatDamageCsv(const DamageMap& map) {
  std::string out =
      "step,time,x,y,z,nx,ny,nz,block_i,block_j,joint,state,damage,opening,slip,normal_force\n";
  const std::string head = std::to_string(map.step) + ',' + formatDouble(map.time) + ',';
  for (const DamagePoint& c : map.contacts) {
    out.append(head);
    for (const geometry::Vec3* v : {&c.point, &c.normal}) {
      for (int k = 0; k < 3; ++k) out.append(formatDouble((*v)[k])).append(",");
    }
    out.append(std::to_string(c.block_i)).append(",").append(std::to_string(c.block_j));
    out.append(",").append(std::to_string(c.joint)).append(",").append(contactStateName(c.state));
    out.append(",").append(damageName(c.damage)).append(",").append(formatDouble(c.opening));
    out.append(",").append(formatDouble(c.slip)).append(",");
    out.append(formatDouble(c.normal_force)).append("\n");
  }
  return out;
}

DamageMapWriter::DamageMapWriter(std::filesystem::path folder)
    : series_(std::move(folder), "damage.pvd") {}

void DamageMapWriter::write(const DamageMap& map) {
  if (map.step <= last_step_) return;
  series_.add(map.time, damageFileName(map.step), formatDamageVtu(map));
  last_step_ = map.step;
}

}  // namespace rockmass::io
