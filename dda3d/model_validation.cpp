#include "dda3d/model_validation.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "dda3d/contact_joint.h"

namespace rockmass::dda3d {

namespace {

void checkBlockIndex(const DdaModel& model, int block, const std::string& what) {
  if (block < 0 || block >= static_cast<int>(model.blocks.size())) {
    throw std::invalid_argument(what + " refers to block " + std::to_string(block) +
                                ", but the model has " + std::to_string(model.blocks.size()) +
                                " blocks");
  }
}

void checkSettings(const DdaSettings& settings) {
  if (!(settings.time_step > 0.0)) throw std::invalid_argument("time_step must be > 0 s");
  if (!(settings.min_time_step > 0.0 && settings.min_time_step <= settings.time_step)) {
    throw std::invalid_argument("min_time_step must be > 0 s and at most time_step");
  }
  if (!(settings.biot_coefficient >= 0.0 && settings.biot_coefficient <= 1.0)) {
    throw std::invalid_argument("biot_coefficient must be in [0, 1]");
  }
  if (!(settings.dynamic_ratio >= 0.0 && settings.dynamic_ratio <= 1.0)) {
    throw std::invalid_argument("dynamic_ratio must be in [0, 1]");
  }
  if (!(settings.detection.search_margin >= 0.0 &&
        settings.detection.search_margin <= kMaxSearchMargin)) {
    std::ostringstream what;
    what << "detection.search_margin must be in [0, " << kMaxSearchMargin << "] (of g2 l0)";
    throw std::invalid_argument(what.str());
  }
  if (!(settings.max_displacement_ratio > 0.0)) {
    throw std::invalid_argument("max_displacement_ratio must be > 0");
  }
}

void checkBlocks(const DdaModel& model) {
  for (std::size_t b = 0; b < model.blocks.size(); ++b) {
    const DdaBlock& in = model.blocks[b];
    if (in.material < 0 || in.material >= static_cast<int>(model.materials.size())) {
      throw std::invalid_argument("block " + std::to_string(b) + " has material " +
                                  std::to_string(in.material) + ", which does not exist");
    }
    if (in.pieces.empty()) {
      throw std::invalid_argument("block " + std::to_string(b) + " has no piece");
    }
    for (const geometry::Polyhedron& p : in.pieces) {
      if (p.vertices.size() < 4 || p.faces.size() < 4) {
        throw std::invalid_argument("block " + std::to_string(b) +
                                    " has a piece with fewer than 4 vertices or faces");
      }
    }
  }
}

void checkAttachments(const DdaModel& model) {
  for (const DdaMonitor& m : model.monitors) checkBlockIndex(model, m.block, "monitor " + m.name);
  for (const DdaPointLoad& l : model.point_loads) checkBlockIndex(model, l.block, "a point load");
  for (const DdaFixedPoint& f : model.fixed_points) {
    checkBlockIndex(model, f.block, "a fixed point");
    if (!f.direction.isZero(0.0) && !(std::abs(f.direction.norm() - 1.0) < 1e-9)) {
      throw std::invalid_argument("a roller's direction must be a unit vector");
    }
  }
  for (const DdaPressure& p : model.pressures) {
    checkBlockIndex(model, p.block, "a pressure entry");
    const DdaBlock& b = model.blocks[static_cast<std::size_t>(p.block)];
    if (p.piece < 0 || p.piece >= static_cast<int>(b.pieces.size()) || p.face < 0 ||
        p.face >= static_cast<int>(b.pieces[static_cast<std::size_t>(p.piece)].faces.size())) {
      throw std::invalid_argument("a pressure entry names a piece or face that does not exist");
    }
  }
  for (const DdaHydrodynamicPressure& p : model.hydrodynamic) {
    checkBlockIndex(model, p.block, "a hydrodynamic pressure entry");
    const DdaBlock& b = model.blocks[static_cast<std::size_t>(p.block)];
    if (p.piece < 0 || p.piece >= static_cast<int>(b.pieces.size()) || p.face < 0 ||
        p.face >= static_cast<int>(b.pieces[static_cast<std::size_t>(p.piece)].faces.size())) {
      throw std::invalid_argument(
          "a hydrodynamic pressure entry names a piece or face that does not exist");
    }
    if (!(p.depth >= 0.0)) throw std::invalid_argument("a reservoir depth must be >= 0 m");
  }
  for (const DdaBolt& bolt : model.bolts) {
    checkBlockIndex(model, bolt.block_a, "a bolt");
    if (bolt.block_b >= 0) checkBlockIndex(model, bolt.block_b, "a bolt");
    if (!(bolt.stiffness > 0.0)) throw std::invalid_argument("bolt stiffness must be > 0 N/m");
    if (!(bolt.yield_force > 0.0) || !(bolt.rupture_force > 0.0)) {
      throw std::invalid_argument("a bolt's yield and rupture forces must be > 0 N");
    }
  }
}

}  // namespace

void validateModel(const DdaModel& model, const DdaSettings& settings) {
  if (model.materials.empty()) throw std::invalid_argument("the DDA model has no material");
  if (model.default_joint < 0 || model.default_joint >= static_cast<int>(model.joints.size())) {
    throw std::invalid_argument("default_joint " + std::to_string(model.default_joint) +
                                " is not an index into the joints");
  }
  checkFaceJoints(model);
  checkSettings(settings);
  for (const DdaMaterial& m : model.materials) {
    if (!(m.density > 0.0)) throw std::invalid_argument("material density must be > 0 kg/m3");
  }
  checkBlocks(model);
  checkAttachments(model);
}

}  // namespace rockmass::dda3d
