// The messages of a DDA step that fails: which block, contact or check stopped it, in words
// a user can act on (docs/dda3d.md, "Step control").
#include <cstdio>
#include <string>

#include "dda3d/block_terms.h"
#include "dda3d/simulation.h"

namespace rockmass::dda3d {

using geometry::Vec3;

namespace {

/// Names the first movable block whose mass matrix is not positive definite, the usual
/// reason for a failed factorization, or says what else to check.
std::string singularBlockHint(const std::vector<BlockState>& blocks, const BlockSystem& system) {
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const BlockState& block = blocks[i];
    if (block.fixed) continue;
    const Eigen::LLT<BlockMatrix> llt(massMatrix(block));
    if (llt.info() != Eigen::Success || !(block.volume > 0.0)) {
      return "block " + std::to_string(i) + " of volume " + std::to_string(block.volume) +
             " m3 has a mass matrix that is not positive definite";
    }
  }
  const int diagonal = system.firstIndefiniteDiagonal();
  for (std::size_t i = 0; diagonal >= 0 && i < blocks.size(); ++i) {
    if (blocks[i].dof_offset != diagonal) continue;
    return "the diagonal of block " + std::to_string(i) + " (volume " +
           std::to_string(blocks[i].volume) + " m3) " +
           (system.diagonalBlock(diagonal).allFinite() ? "is not positive definite"
                                                       : "has NaN or infinite entries");
  }
  return "every block's mass matrix is positive definite: look for an unrestrained "
         "mechanism or contact springs far stiffer than the blocks";
}

std::string pointText(const Vec3& p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.6g, %.6g, %.6g)", p.x(), p.y(), p.z());
  return text;
}

std::string numberText(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

}  // namespace

double Simulation::stepDisplacement(const StepReport& report) const {
  return report.displacement_ratio * settings_.max_displacement_ratio * half_domain_;
}

std::string Simulation::blockText(int b) const {
  if (b < 0 || b >= static_cast<int>(blocks_.size())) return "no block";
  const BlockState& block = blocks_[static_cast<std::size_t>(b)];
  return "block " + std::to_string(b) + " (centroid " + pointText(block.centroid) + ", " +
         numberText(block.volume) + " m3)";
}

std::string Simulation::contactText(const Contact& c) const {
  return (c.kind == ContactKind::VertexFace  ? "the vertex-face contact of "
          : c.kind == ContactKind::FacePoint ? "the face-point contact of "
                                             : "the edge-edge contact of ") +
         blockText(c.block_i) + " on " + blockText(c.block_j) + " at " + pointText(c.point) +
         " (gap " + numberText(c.gap) + " m)";
}

std::string Simulation::singularMatrixMessage(double dt) const {
  return "DDA step failed at t = " + std::to_string(time_) +
         " s: the system matrix is not positive definite even at time step " + std::to_string(dt) +
         " s (" + singularBlockHint(blocks_, *system_) + ")";
}

std::string Simulation::stalledMessage(const StepReport& report) const {
  return "DDA run cannot progress: " + std::to_string(steps_at_min_) +
         " steps in a row at min_time_step " + numberText(settings_.min_time_step) +
         " s, now at t = " + numberText(time_) + " s; the last step moved " +
         blockText(report.fastest_block) + " " + numberText(stepDisplacement(report)) + " m";
}

std::string Simulation::stepFailureMessage(double dt, int attempts, bool settled,
                                           const StepReport& report, double allowed) const {
  std::string why;
  if (!settled) {
    why = "its open-close iteration did not settle in " +
          std::to_string(settings_.max_open_close_iterations) + " iterations (" +
          std::to_string(last_changes_.changed) + " contacts changed state in the last one, " +
          std::to_string(last_changes_.closed) + " of them closing";
    if (last_changes_.example >= 0 && last_changes_.example < static_cast<int>(contacts_.size())) {
      why += "; e.g. " + contactText(contacts_[static_cast<std::size_t>(last_changes_.example)]);
    }
    why += ")";
  } else if (report.max_penetration > allowed) {
    const Contact* deepest = nullptr;
    for (const Contact& c : contacts_) {
      if (c.state != ContactState::Open && (!deepest || c.gap < deepest->gap)) deepest = &c;
    }
    why = "a contact penetrates " + numberText(report.max_penetration) + " m, over the allowed " +
          numberText(allowed) + " m, with the penalty at its cap " + numberText(penalty_) + " N/m" +
          (deepest ? ": " + contactText(*deepest) : std::string());
  } else {
    why = "a vertex moves " + numberText(stepDisplacement(report)) +
          " m in the step, over the step control's limit, in " + blockText(report.fastest_block);
  }
  return "DDA step cannot progress at t = " + numberText(time_) + " s: at dt = " + numberText(dt) +
         " s (min_time_step " + numberText(settings_.min_time_step) + " s) after " +
         std::to_string(attempts) + (attempts == 1 ? " attempt, " : " attempts, ") + why;
}

}  // namespace rockmass::dda3d
