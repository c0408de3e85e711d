#include "dda3d/simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "dda3d/block_terms.h"
#include "dda3d/contact_detection.h"
#include "dda3d/contact_joint.h"
#include "geometry/interrupt.h"

namespace rockmass::dda3d {

using geometry::Vec3;

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// Identity of a contact across steps: a vertex against a piece (its face may change), or
/// an edge against an edge.
struct ContactKey {
  int kind, block_i, piece_i, a, block_j, piece_j, b;
  bool operator==(const ContactKey&) const = default;
};
struct ContactKeyHash {
  std::size_t operator()(const ContactKey& k) const {
    std::size_t h = 1469598103934665603ull;
    for (int v : {k.kind, k.block_i, k.piece_i, k.a, k.block_j, k.piece_j, k.b}) {
      h = (h ^ static_cast<std::size_t>(static_cast<unsigned>(v))) * 1099511628211ull;
    }
    return h;
  }
};
ContactKey keyOf(const Contact& c) {
  if (c.kind == ContactKind::VertexFace) {
    return {0, c.block_i, c.piece_i, c.vertex, c.block_j, c.piece_j, -1};
  }
  if (c.kind == ContactKind::FacePoint) {
    return {2, c.block_i, c.piece_i, c.vertex, c.block_j, c.piece_j, c.face};
  }
  return {1, c.block_i, c.piece_i, c.edge_i, c.block_j, c.piece_j, c.edge_j};
}

/// The last step's contacts, found by what identifies them (keyOf): vertex-face entries
/// through a table indexed by the vertex (each vertex lists the few pieces it touched), edge
/// entries through a hash map. The narrow phase asks for the face of every vertex near a
/// piece, about a million questions a step on the Xiangjiaba region; a node-based hash map of
/// all 2e5 contacts spent most of its time in cache misses along its bucket chains. Like the
/// map it replaces, a key found twice answers with its first contact.
class PreviousContacts {
 public:
  PreviousContacts(const std::vector<BlockState>& blocks, const std::vector<Contact>& contacts)
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
    for (std::size_t v = 0; v + 1 < entry_start_.size(); ++v)
      entry_start_[v + 1] += entry_start_[v];
    entries_.resize(entry_start_.back());
    std::vector<std::size_t> next(entry_start_.begin(), entry_start_.end() - 1);
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      if (vertex_of[k] != kNone) entries_[next[vertex_of[k]]++] = static_cast<int>(k);
    }
  }

  /// Index of the last step's contact with the key of `c`, or -1.
  int find(const Contact& c) const {
    if (c.kind != ContactKind::VertexFace) {
      const auto found = edges_.find(keyOf(c));
      return found == edges_.end() ? -1 : found->second;
    }
    return findVertex(c.block_i, c.piece_i, c.vertex, c.block_j, c.piece_j);
  }

  /// The face the vertex used against piece (block_j, piece_j) last step, or -1.
  int face(int block_i, int piece_i, int vertex, int block_j, int piece_j) const {
    const int k = findVertex(block_i, piece_i, vertex, block_j, piece_j);
    return k < 0 ? -1 : contacts_[static_cast<std::size_t>(k)].face;
  }

 private:
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);

  std::size_t vertexIndex(int block, int piece, int vertex) const {
    if (block < 0 || static_cast<std::size_t>(block) + 1 >= piece_start_.size()) return kNone;
    const std::size_t p =
        piece_start_[static_cast<std::size_t>(block)] + static_cast<std::size_t>(piece);
    if (piece < 0 || p >= piece_start_[static_cast<std::size_t>(block) + 1]) return kNone;
    const std::size_t v = vertex_start_[p] + static_cast<std::size_t>(vertex);
    return vertex < 0 || v >= vertex_start_[p + 1] ? kNone : v;
  }

  int findVertex(int block_i, int piece_i, int vertex, int block_j, int piece_j) const {
    const std::size_t v = vertexIndex(block_i, piece_i, vertex);
    if (v == kNone) return -1;
    for (std::size_t e = entry_start_[v]; e < entry_start_[v + 1]; ++e) {
      const Contact& c = contacts_[static_cast<std::size_t>(entries_[e])];
      if (c.block_j == block_j && c.piece_j == piece_j) return entries_[e];
    }
    return -1;
  }

  const std::vector<Contact>& contacts_;
  std::vector<std::size_t> piece_start_;   ///< first piece of each block, then the count
  std::vector<std::size_t> vertex_start_;  ///< first vertex of each piece, then the count
  std::vector<std::size_t> entry_start_;   ///< first entry of each vertex, then the count
  std::vector<int> entries_;               ///< vertex-face contact indices, by vertex
  std::unordered_map<ContactKey, int, ContactKeyHash> edges_;
};

Vec3 tangential(const Vec3& v, const Vec3& n) {
  return v - n * n.dot(v);
}

Eigen::Matrix3d voigtToTensor(const VoigtVector& v, double shear_scale) {
  Eigen::Matrix3d t;
  // clang-format off
  t << v[0],               shear_scale * v[5], shear_scale * v[4],
       shear_scale * v[5], v[1],               shear_scale * v[3],
       shear_scale * v[4], shear_scale * v[3], v[2];
  // clang-format on
  return t;
}
VoigtVector tensorToVoigt(const Eigen::Matrix3d& t, double shear_scale) {
  VoigtVector v;
  v << t(0, 0), t(1, 1), t(2, 2), t(1, 2) / shear_scale, t(2, 0) / shear_scale,
      t(0, 1) / shear_scale;
  return v;
}
/// R s R^T for a stress (shear scale 1) or a strain with engineering shears (scale 1/2).
VoigtVector rotateVoigt(const VoigtVector& v, const Eigen::Matrix3d& r, double shear_scale) {
  return tensorToVoigt(r * voigtToTensor(v, shear_scale) * r.transpose(), shear_scale);
}

/// A step is accepted while no vertex moved farther than this many g2 l0 (step control).
constexpr double kAcceptedDisplacementRatio = 1.5;
/// Reach of a block at rest, in g2 l0: room for the step that starts it moving.
constexpr double kRestingReachRatio = 0.1;
/// Largest pull (in weights of the lighter block) of a contact held closed after it opened
/// and closed again in a step (updateContactStates).
constexpr double kHoldWeights = 12.0;
/// A contact that flipped open, closed and open again in a step closes past this many
/// allowed penetrations, or past kLateRestitution / 2 of its approach in the step, i.e. past
/// the gap it closed in the step (updateContactStates).
constexpr double kChatterClosingRatio = 0.1;
/// Largest ratio of the push-out speed of such a contact, found penetrating at the next step,
/// to its approach speed.
constexpr double kLateRestitution = 1.0;
/// A locked contact slides once its spring's force passes its shear strength by more than
/// the force of a round-off slip (open_threshold_ratio l0) and by more than this share of
/// the strength: the allowance lets a spring the predictor set at the limit stay stuck on a
/// resting block's round-off, but it is strength the joint does not have, so it must stay
/// small against the strength (updateContactStates). At 0.1 a base carried by sub-contact
/// points, whose strengths are small enough for the share to bind at every point, held 10 %
/// above its strength: eccentric dams came out 2-5 % above the shear-friction factor.
constexpr double kStickAllowance = 0.01;

/// Static mode: a block's inertia term (1 - alpha_m) M / (beta dt^2) is held to at most this
/// many contact penalties (its mass scaled down, as in dynamic relaxation). The term only
/// regularises a static step (every step starts from rest), but it also sets how much of the
/// out-of-balance force one step relieves: K / (K + c0 M). For a 5e8 kg dam at dt = 2 ms, c0 M
/// was 5.7 penalties; each step relieved 15 %, the heel corners crept at their limit for
/// tens of steps until the round-off of their slip turned the friction sideways, the dam
/// walked across its base, and the strength reduction found 2.20 where f W / H = 2.42 (2.45
/// with dt = 10 ms). Held to one penalty: 2.45 at dt = 2 ms.
constexpr double kStaticInertiaRatio = 1.0;

/// The largest ratio of a movable block's vertex displacement in `solution` to its reach.
double reachRatio(const std::vector<BlockState>& blocks, const BlockSystem& system,
                  const Eigen::VectorXd& solution, const std::vector<double>& reach) {
  double largest = 0.0;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    if (blocks[b].fixed) continue;
    const double moved =
        largestVertexDisplacement(blocks[b], system.unknowns(solution, blocks[b].dof_offset));
    largest = std::max(largest, moved / reach[b]);
  }
  return largest;
}

void checkBlockIndex(const DdaModel& model, int block, const std::string& what) {
  if (block < 0 || block >= static_cast<int>(model.blocks.size())) {
    throw std::invalid_argument(what + " refers to block " + std::to_string(block) +
                                ", but the model has " + std::to_string(model.blocks.size()) +
                                " blocks");
  }
}

}  // namespace

std::vector<std::string> ActiveTerms::names() const {
  std::vector<std::string> out;
  const std::pair<bool, const char*> all[] = {{elastic, "elastic"},
                                              {initial_stress, "initial_stress"},
                                              {inertia, "inertia"},
                                              {body_force, "body_force"},
                                              {point_loads, "point_loads"},
                                              {surface_pressure, "surface_pressure"},
                                              {fixed_points, "fixed_points"},
                                              {rollers, "rollers"},
                                              {fixed_blocks, "fixed_blocks"},
                                              {contact_normal, "contact_normal"},
                                              {contact_shear, "contact_shear"},
                                              {friction, "friction"},
                                              {bolts, "bolts"}};
  for (const auto& [on, name] : all) {
    if (on) out.emplace_back(name);
  }
  return out;
}

ActiveTerms& ActiveTerms::operator|=(const ActiveTerms& o) {
  elastic |= o.elastic;
  initial_stress |= o.initial_stress;
  inertia |= o.inertia;
  body_force |= o.body_force;
  point_loads |= o.point_loads;
  surface_pressure |= o.surface_pressure;
  fixed_points |= o.fixed_points;
  rollers |= o.rollers;
  fixed_blocks |= o.fixed_blocks;
  contact_normal |= o.contact_normal;
  contact_shear |= o.contact_shear;
  friction |= o.friction;
  bolts |= o.bolts;
  return *this;
}

Simulation::Simulation(DdaModel model, DdaSettings settings)
    : model_(std::move(model)), settings_(settings) {
  if (model_.materials.empty()) throw std::invalid_argument("the DDA model has no material");
  if (model_.joints.empty()) model_.joints.push_back(DdaJoint{});
  if (model_.default_joint < 0 || model_.default_joint >= static_cast<int>(model_.joints.size())) {
    throw std::invalid_argument("default_joint " + std::to_string(model_.default_joint) +
                                " is not an index into the joints");
  }
  checkFaceJoints(model_);
  if (!(settings_.time_step > 0.0)) throw std::invalid_argument("time_step must be > 0 s");
  if (!(settings_.min_time_step > 0.0 && settings_.min_time_step <= settings_.time_step)) {
    throw std::invalid_argument("min_time_step must be > 0 s and at most time_step");
  }
  if (!(settings_.dynamic_ratio >= 0.0 && settings_.dynamic_ratio <= 1.0)) {
    throw std::invalid_argument("dynamic_ratio must be in [0, 1]");
  }
  scheme_ = settings_.integration == TimeIntegration::Shi
                ? shiCoefficients()
                : bossakCoefficients(settings_.spectral_radius);
  if (!(settings_.max_displacement_ratio > 0.0)) {
    throw std::invalid_argument("max_displacement_ratio must be > 0");
  }
  dofs_ = settings_.kinematics == Kinematics::Rigid ? 6 : kBlockDofs;
  for (const DdaMaterial& m : model_.materials) {
    elastic_.push_back(elasticMatrix(m.young, m.poisson));
    if (!(m.density > 0.0)) throw std::invalid_argument("material density must be > 0 kg/m3");
  }

  geometry::Box all{Vec3::Constant(std::numeric_limits<double>::infinity()),
                    Vec3::Constant(-std::numeric_limits<double>::infinity())};
  int movable = 0;
  double total_volume = 0.0;
  for (std::size_t b = 0; b < model_.blocks.size(); ++b) {
    const DdaBlock& in = model_.blocks[b];
    if (in.material < 0 || in.material >= static_cast<int>(model_.materials.size())) {
      throw std::invalid_argument("block " + std::to_string(b) + " has material " +
                                  std::to_string(in.material) + ", which does not exist");
    }
    if (in.pieces.empty())
      throw std::invalid_argument("block " + std::to_string(b) + " has no piece");
    BlockState s;
    s.pieces = in.pieces;
    for (const geometry::Polyhedron& p : s.pieces) {
      if (p.vertices.size() < 4 || p.faces.size() < 4) {
        throw std::invalid_argument("block " + std::to_string(b) +
                                    " has a piece with fewer than 4 vertices or faces");
      }
      s.topology.push_back(pieceTopology(p));
      s.face_points.push_back(
          facePoints(p, in.contact_point_spacing.value_or(settings_.contact_point_spacing)));
      const geometry::Box box = geometry::bounds(p);
      all.min = all.min.cwiseMin(box.min);
      all.max = all.max.cwiseMax(box.max);
    }
    s.material = in.material;
    s.fixed = in.fixed;
    s.updateMassProperties();
    if (!(s.volume > 0.0)) {
      throw std::invalid_argument("block " + std::to_string(b) +
                                  " has a non-positive volume (faces must be CCW from outside)");
    }
    s.mass = model_.materials[static_cast<std::size_t>(in.material)].density * s.volume;
    s.stress = in.initial_stress;
    if (!s.fixed) {
      s.dof_offset = movable++;
      s.velocity.head<3>() = in.initial_velocity;
      s.velocity.segment<3>(3) = in.initial_angular_velocity;
    }
    total_volume += s.volume;
    blocks_.push_back(std::move(s));
    initial_centroids_.push_back(blocks_.back().centroid);
    active_.fixed_blocks |= in.fixed;
  }
  half_domain_ = settings_.half_domain_size > 0.0 ? settings_.half_domain_size
                                                  : 0.5 * (all.max - all.min).maxCoeff();
  // The stiffest material of the blocks in the model (a material no block uses, e.g. one the
  // scene declares for a structure elsewhere, does not stiffen the contacts).
  double young_max = 0.0;
  for (const BlockState& block : blocks_) {
    young_max =
        std::max(young_max, model_.materials.at(static_cast<std::size_t>(block.material)).young);
  }
  const double block_length =
      blocks_.empty() ? 1.0 : std::cbrt(total_volume / static_cast<double>(blocks_.size()));
  penalty_ = settings_.penalty > 0.0 ? settings_.penalty
                                     : settings_.penalty_factor * young_max * block_length;
  initial_penalty_ = penalty_;
  dt_ = settings_.time_step;

  const auto attach = [&](int block, const Vec3& p, const std::string& what) {
    checkBlockIndex(model_, block, what);
    return MaterialPoint{block, p, p, Vec3::Zero()};
  };
  for (const DdaMonitor& m : model_.monitors)
    monitor_points_.push_back(attach(m.block, m.point, "monitor " + m.name));
  for (const DdaPointLoad& l : model_.point_loads)
    load_points_.push_back(attach(l.block, l.point, "a point load"));
  for (const DdaFixedPoint& f : model_.fixed_points) {
    fixed_points_.push_back(attach(f.block, f.point, "a fixed point"));
    if (!f.direction.isZero(0.0)) {
      if (!(std::abs(f.direction.norm() - 1.0) < 1e-9)) {
        throw std::invalid_argument("a roller's direction must be a unit vector");
      }
      fixed_points_.back().direction = f.direction;
    }
  }
  for (const DdaPressure& p : model_.pressures) {
    checkBlockIndex(model_, p.block, "a pressure entry");
    const DdaBlock& b = model_.blocks[static_cast<std::size_t>(p.block)];
    if (p.piece < 0 || p.piece >= static_cast<int>(b.pieces.size()) || p.face < 0 ||
        p.face >= static_cast<int>(b.pieces[static_cast<std::size_t>(p.piece)].faces.size())) {
      throw std::invalid_argument("a pressure entry names a piece or face that does not exist");
    }
  }
  for (const DdaBolt& bolt : model_.bolts) {
    bolt_a_.push_back(attach(bolt.block_a, bolt.point_a, "a bolt"));
    if (bolt.block_b >= 0) {
      bolt_b_.push_back(attach(bolt.block_b, bolt.point_b, "a bolt"));
    } else {
      bolt_b_.push_back(MaterialPoint{-1, bolt.point_b, bolt.point_b});
    }
    if (!(bolt.stiffness > 0.0)) throw std::invalid_argument("bolt stiffness must be > 0 N/m");
  }

  system_ = std::make_unique<BlockSystem>(movable, dofs_);
  solver_ = makeLinearSolver(resolvedSolverOptions(settings_, movable));
  base_k_.assign(static_cast<std::size_t>(movable), BlockMatrix::Zero());
  base_f_.assign(static_cast<std::size_t>(movable), BlockVector::Zero());
  load_f_.assign(static_cast<std::size_t>(movable), BlockVector::Zero());
  initialAccelerations();
}

void Simulation::initialAccelerations() {
  // assembleBlockTerms leaves the loads at t = 0 in load_f_; dt is irrelevant here.
  assembleBlockTerms(settings_.time_step);
  const bool fixed_blocks = active_.fixed_blocks;
  active_ = ActiveTerms{};  // nothing was assembled into a system yet
  active_.fixed_blocks = fixed_blocks;
  std::vector<BlockVector> force = load_f_;
  for (const BlockState& block : blocks_) {
    if (block.fixed || settings_.kinematics != Kinematics::Deformable) continue;
    force[static_cast<std::size_t>(block.dof_offset)] += initialStressLoad(block);
  }
  for (std::size_t k = 0; k < bolt_a_.size(); ++k) {
    const DdaBolt& bolt = model_.bolts[k];
    const Vec3 axis = bolt.point_b - bolt.point_a;
    if (axis.norm() <= 0.0) continue;
    // The pretension pulls point a towards b and b towards a.
    const Vec3 pull = bolt.pretension * axis.normalized();
    const BlockState& a = blocks_[static_cast<std::size_t>(bolt.block_a)];
    if (!a.fixed) force[static_cast<std::size_t>(a.dof_offset)] += pointLoad(a, bolt.point_a, pull);
    if (bolt.block_b >= 0) {
      const BlockState& b = blocks_[static_cast<std::size_t>(bolt.block_b)];
      if (!b.fixed) {
        force[static_cast<std::size_t>(b.dof_offset)] += pointLoad(b, bolt.point_b, -pull);
      }
    }
  }
  for (BlockState& block : blocks_) {
    if (block.fixed) continue;
    if (settings_.mode == AnalysisMode::Static) {
      // Static mode (Shi's dynamic ratio 0): every step starts from rest, so v0 = a0 = 0 at
      // t = 0 as after every step (updateBlocks). The inertia term (1 - alpha_m) M /
      // (beta dt^2) then only regularises the step (held to kStaticInertiaRatio penalties,
      // staticMassScale); a stored a0 = g would add the load
      // M (c2 g) to the first step for any rho_inf > 0 (c2 vanishes only at rho_inf = 0).
      block.velocity.setZero();
      block.acceleration.setZero();
      continue;
    }
    const BlockMatrix m = massMatrix(block);
    const BlockVector& f = force[static_cast<std::size_t>(block.dof_offset)];
    block.acceleration.setZero();
    if (dofs_ == kBlockDofs) {
      block.acceleration = m.ldlt().solve(f);
    } else {
      block.acceleration.head<6>() = m.topLeftCorner<6, 6>().ldlt().solve(f.head<6>());
    }
  }
}

Simulation::~Simulation() = default;

double autoPcgTolerance(const DdaSettings& settings) {
  // The error bound of the step (kappa <= 1e3 for the block-Jacobi preconditioned K), capped at
  // 1e-8: bench/dda_accuracy_bench.cpp shows a train of touching blocks on a slope drifting by
  // 2 % at 4e-7 and by 0 % at 1e-8 (docs/performance.md, "DDA accuracy against time").
  return std::min(
      1e-8, 1e-2 * settings.allowed_penetration_ratio / settings.max_displacement_ratio * 1e-3);
}

SolverOptions resolvedSolverOptions(const DdaSettings& settings, int movable) {
  SolverOptions options = settings.solver;
  options.block_size = settings.kinematics == Kinematics::Rigid ? 6 : kBlockDofs;
  if (options.kind == SolverKind::Auto) {
    if (movable * options.block_size <= options.auto_cholmod_unknowns) {
      options.kind = SolverKind::Cholmod;
    } else {
      options.kind = SolverKind::Pcg;
      options.tolerance = autoPcgTolerance(settings);
    }
  }
  return options;
}

std::string Simulation::solverName() const {
  return solver_->name();
}

const DdaJoint& Simulation::jointOf(const Contact& c) const {
  return model_.joints.at(static_cast<std::size_t>(c.joint >= 0 ? c.joint : model_.default_joint));
}

int Simulation::detectContacts() {
  const PreviousContacts previous(blocks_, contacts_);
  const PreviousFace previous_face = [&](int bi, int pi, int v, int bj, int pj) {
    return previous.face(bi, pi, v, bj, pj);
  };
  // Each block's reach: how far its vertices may move in this step, from its motion and
  // the step control's limit 1.5 g2 l0; step() redoes a step that moves a block farther, so
  // a gap wider than the two blocks' reaches cannot close within it.
  const double g2_l0 = settings_.max_displacement_ratio * half_domain_;
  const ReachLimits limits{kRestingReachRatio * g2_l0, kAcceptedDisplacementRatio * g2_l0,
                           model_.gravity.norm()};
  reach_.resize(blocks_.size());
  for (std::size_t b = 0; b < blocks_.size(); ++b)
    reach_[b] = stepReach(blocks_[b], dt_, last_dt_, limits);
  // Penetrations are kept down to 3 g2 l0 (the former search distance), whatever the reach.
  std::vector<Contact> detected =
      findContacts(blocks_, reach_, 2.0 * kAcceptedDisplacementRatio * g2_l0, previous_face);
  std::vector<std::pair<int, int>> pairs;
  int late = 0;
  const double late_depth = settings_.allowed_penetration_ratio * half_domain_;
  for (Contact& c : detected) {
    const int found = previous.find(c);
    if (found >= 0) {
      const Contact& old = contacts_[static_cast<std::size_t>(found)];
      c.state = old.state;
      c.bonded = old.bonded;
      c.shear = tangential(old.shear, c.normal);
      const Vec3 slide = tangential(old.slide_direction, c.normal);
      c.slide_direction = slide.norm() > 0.0 ? Vec3(slide.normalized()) : Vec3(Vec3::Zero());
      c.normal_force = old.normal_force;
      c.slip_length = old.slip_length;
      c.overlap = std::min(old.overlap, std::max(0.0, -c.gap0));
    } else if (c.gap0 < -late_depth) {
      // First seen deeper than the allowed penetration: the detection missed it while it
      // closed (the step control keeps every contact it sees shallower). Its spring starts
      // at the depth found, resisting further penetration only: started at that depth, it
      // gave back 1/2 k_n d^2 in one step, 1.1e7 J for an edge crossing found 5.4 mm deep in
      // a pile of nine boxes whose fall had released 8.6e4 J, and threw the pile apart. The
      // overlap is removed as the blocks part; `late_contacts` counts these.
      c.overlap = -c.gap0;
      ++late;
    }
    c.gap0 += c.overlap;
    if (found < 0) {
      // Touching within round-off counts as closed: an open contact only closes once it
      // penetrates past the hysteresis threshold.
      c.state = c.gap0 <= settings_.open_threshold_ratio * half_domain_ ? ContactState::Locked
                                                                        : ContactState::Open;
    }
    c.gap = c.gap0;
    c.flips = 0;
    c.toggles = 0;
    c.held = false;
    const int i = movableIndex(c.block_i), j = movableIndex(c.block_j);
    if (i >= 0 && j >= 0) pairs.emplace_back(std::min(i, j), std::max(i, j));
  }
  for (std::size_t k = 0; k < bolt_a_.size(); ++k) {
    const int i = bolt_a_[k].block >= 0 ? movableIndex(bolt_a_[k].block) : -1;
    const int j = bolt_b_[k].block >= 0 ? movableIndex(bolt_b_[k].block) : -1;
    if (i >= 0 && j >= 0 && i != j) pairs.emplace_back(std::min(i, j), std::max(i, j));
  }
  for (Contact& c : detected) c.joint = contactJoint(model_, blocks_, c);
  contacts_ = std::move(detected);
  // A contact that crept in the last step (its slip no longer than the shear spring's stretch
  // at the shear strength) starts this one stuck, its spring carrying the shear strength along
  // the last slip (an elastic predictor). Where the loads still need more, the first iteration
  // finds it over the limit and it slides again; where they need less (the block came to rest,
  // the load moved to other contacts), it stays stuck. Carried over as sliding, such a contact
  // kept its friction f N until its slip reversed: a block whose heel slid on its way to rest
  // under an eccentric load kept creeping on a diagonal pattern of stuck and sliding corners,
  // and was never at rest below the limit load (K 12 % below f W / H on a block on a plane).
  // A contact that slid farther is sliding: stuck for a trial, a moving block would pivot on
  // its base springs.
  const double ks = penalty_ / settings_.shear_penalty_ratio;
  for (Contact& c : contacts_) {
    if (c.state != ContactState::Sliding || c.slide_direction.squaredNorm() == 0.0) continue;
    const double stretch = shearStrength(c, jointOf(c)) / ks;
    if (!(c.slip_length <= stretch)) continue;
    c.state = ContactState::Locked;
    c.shear = stretch * c.slide_direction;
  }
  if (system_->setPairs(std::move(pairs))) ++pattern_changes_;
  return late;
}

double Simulation::staticMassScale(const BlockState& block) const {
  if (settings_.mode != AnalysisMode::Static) return 1.0;
  // At the run's time step: a step redone at a smaller one still gets more inertia, which is
  // what lets a step whose open-close iteration did not settle settle.
  const double dt = settings_.time_step;
  const double c0 = (1.0 - scheme_.alpha_m) / (scheme_.beta * dt * dt);
  const double inertia = c0 * block.mass;
  const double cap = kStaticInertiaRatio * penalty_;
  return inertia > cap ? cap / inertia : 1.0;
}

void Simulation::assembleBlockTerms(double dt) {
  ActiveTerms step;
  step.inertia = true;
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    const BlockState& block = blocks_[b];
    if (block.fixed) continue;
    const std::size_t m = static_cast<std::size_t>(block.dof_offset);
    BlockMatrix& k = base_k_[m];
    BlockVector& f = base_f_[m];
    BlockVector& loads = load_f_[m];
    k.setZero();
    f.setZero();
    loads.setZero();
    if (settings_.kinematics == Kinematics::Deformable) {
      k += elasticStiffness(block, elastic_[static_cast<std::size_t>(block.material)]);
      step.elastic = true;
      if (!block.stress.isZero(0.0)) {
        f += initialStressLoad(block);
        step.initial_stress = true;
      }
    }
    inertiaTerms(staticMassScale(block) * massMatrix(block), block.velocity, block.acceleration, dt,
                 scheme_, k, f);
    if (!model_.gravity.isZero(0.0)) {
      loads += bodyForceLoad(block, model_.gravity);
      step.body_force = true;
    }
  }
  for (std::size_t l = 0; l < load_points_.size(); ++l) {
    const BlockState& block = blocks_[static_cast<std::size_t>(load_points_[l].block)];
    if (block.fixed) continue;
    load_f_[static_cast<std::size_t>(block.dof_offset)] +=
        pointLoad(block, load_points_[l].current, model_.point_loads[l].force);
    step.point_loads = true;
  }
  for (const DdaPressure& p : model_.pressures) {
    const BlockState& block = blocks_[static_cast<std::size_t>(p.block)];
    if (block.fixed) continue;
    load_f_[static_cast<std::size_t>(block.dof_offset)] += pressureLoad(
        block, block.pieces[static_cast<std::size_t>(p.piece)], p.face, p.level, p.unit_weight);
    step.surface_pressure = true;
  }
  const double fixed_k = settings_.fixed_point_penalty_ratio * penalty_;
  for (const MaterialPoint& fp : fixed_points_) {
    const BlockState& block = blocks_[static_cast<std::size_t>(fp.block)];
    if (block.fixed) continue;
    const DisplacementMatrix t = displacementMatrix(fp.current, block.centroid);
    const std::size_t m = static_cast<std::size_t>(block.dof_offset);
    if (fp.direction.isZero(0.0)) {
      base_k_[m] += fixed_k * t.transpose() * t;
      base_f_[m] -= fixed_k * t.transpose() * (fp.current - fp.initial);
      step.fixed_points = true;
    } else {
      // A roller: the spring acts along its direction n only, energy 1/2 k (n . u)^2.
      const BlockVector e = t.transpose() * fp.direction;
      base_k_[m] += fixed_k * e * e.transpose();
      base_f_[m] -= fixed_k * e * fp.direction.dot(fp.current - fp.initial);
      step.rollers = true;
    }
  }
  for (std::size_t m = 0; m < base_f_.size(); ++m) base_f_[m] += load_f_[m];
  step.bolts = !model_.bolts.empty();
  active_ |= step;
}

Simulation::AppliedFriction Simulation::addContactTerms(const Contact& c) {
  if (c.state == ContactState::Open) return {};
  const int i = movableIndex(c.block_i), j = movableIndex(c.block_j);
  const BlockState& bi = blocks_[static_cast<std::size_t>(c.block_i)];
  const BlockState& bj = blocks_[static_cast<std::size_t>(c.block_j)];
  const DisplacementMatrix ti = displacementMatrix(c.point, bi.centroid);
  const DisplacementMatrix tj = displacementMatrix(c.foot, bj.centroid);
  system_->addSpring(i, ti.transpose() * c.normal, j, -tj.transpose() * c.normal, penalty_, c.gap0);
  active_.contact_normal = true;
  if (c.state == ContactState::Locked) {
    const double ks = penalty_ / settings_.shear_penalty_ratio;
    Vec3 t[2];
    tangents(c.normal, t[0], t[1]);
    for (const Vec3& tk : t) {
      system_->addSpring(i, ti.transpose() * tk, j, -tj.transpose() * tk, ks, c.shear.dot(tk));
    }
    active_.contact_shear = true;
    return {};
  }
  // The shear strength resists the slip: f N, plus c A while a plastic joint's contact keeps
  // its cohesion (a brittle one lost it when it started to slide).
  const double friction = shearStrength(c, jointOf(c));
  system_->addForce(i, -friction * (ti.transpose() * c.slide_direction));
  system_->addForce(j, friction * (tj.transpose() * c.slide_direction));
  active_.friction = true;
  AppliedFriction applied;
  applied.force = -friction * c.slide_direction;
  if (friction > 0.0 && c.slip_length > 0.0 && c.slide_direction.squaredNorm() > 0.0) {
    // Consistent tangent of F = -f N s / |s| about the last slip s*: -f N / |s*| times the
    // slip across s*. Without it the direction is explicit, and a slip across it (a yaw of a
    // sliding block) is pushed back f N / |s*| per metre, one step late: with the small
    // slips of a static step that over-corrects and grows by ~ -3 per step. Capped at the
    // shear spring (a locked contact resists no more); rigid parts, as the direction. Only
    // once a slip is known: a tangent about a guessed direction would hold a wrong one.
    applied.transverse_stiffness =
        std::min(penalty_ / settings_.shear_penalty_ratio, friction / c.slip_length);
    applied.across = c.normal.cross(c.slide_direction).normalized();
    DisplacementMatrix ri = ti, rj = tj;
    ri.rightCols<kVoigtSize>().setZero();
    rj.rightCols<kVoigtSize>().setZero();
    system_->addSpring(i, ri.transpose() * applied.across, j, -rj.transpose() * applied.across,
                       applied.transverse_stiffness, 0.0);
  }
  return applied;
}

BlockVector Simulation::unknownsOf(const Eigen::VectorXd& solution, int block) const {
  const int m = movableIndex(block);
  return m < 0 ? BlockVector::Zero() : system_->unknowns(solution, m);
}

Vec3 Simulation::relativeDisplacement(const Contact& c, const Eigen::VectorXd& solution,
                                      bool rigid_part) const {
  const BlockState& bi = blocks_[static_cast<std::size_t>(c.block_i)];
  const BlockState& bj = blocks_[static_cast<std::size_t>(c.block_j)];
  BlockVector di = unknownsOf(solution, c.block_i);
  BlockVector dj = unknownsOf(solution, c.block_j);
  if (rigid_part) {
    di.tail<kVoigtSize>().setZero();
    dj.tail<kVoigtSize>().setZero();
  }
  return displacementMatrix(c.point, bi.centroid) * di -
         displacementMatrix(c.foot, bj.centroid) * dj;
}

Simulation::StateChanges Simulation::updateContactStates(const Eigen::VectorXd& solution) {
  const double close_tolerance = settings_.close_threshold_ratio * half_domain_;
  const double open_tolerance = settings_.open_threshold_ratio * half_domain_;
  const double ks = penalty_ / settings_.shear_penalty_ratio;
  // A sliding contact sticks only when its slip reverses by more than round-off: at a tiny
  // time step (or at rest) the rigid slip is ~1e-13 m in a random direction, and reading its
  // sign locked and released thousands of contacts of the Xiangjiaba model in turn, so that
  // the iteration never settled at any time step.
  const double reverse_tolerance = settings_.open_threshold_ratio * half_domain_;
  const double allowed = settings_.allowed_penetration_ratio * half_domain_;
  StateChanges changes;
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    Contact& c = contacts_[k];
    const Vec3 relative = relativeDisplacement(c, solution);
    const double d = c.gap0 + c.normal.dot(relative);
    const Vec3 slip = tangential(relative, c.normal);
    // The friction direction follows the rigid part of the motion: the strain part of a
    // deformable block's corner motion is elastic vibration, and letting it steer friction
    // tilts the friction forces sideways so that a block with phi > theta creeps.
    const Vec3 rigid_slip = tangential(relativeDisplacement(c, solution, true), c.normal);
    c.gap = d;
    const DdaJoint& joint = jointOf(c);
    const ContactState before = c.state;
    if (c.state == ContactState::Open) {
      c.normal_force = 0.0;
      // A contact that closed, opened (its pull over the hold limit below) and is open again
      // in this step is met mid-step by a block arriving fast: solved closed it pulls,
      // solved open it penetrates (a cube landing at 2.5 m/s on a pile: 2.6 um and
      // 0.27 mm), and flipping it every iteration never settled; the steps of a landing pile
      // of 1 000 cubes were redone down to 2e-5 s (docs/dda3d.md). It stays open while its
      // penetration is at most half its approach in the step (gap0 - d), i.e. less than the
      // gap it closed, and a tenth of the allowed penetration: found penetrating at the next
      // step, its spring pushes it out at about 2 |d| / dt, at most its approach speed (a
      // restitution of 1 or less; the scheme's damping takes the rest). A resting contact (no
      // approach) closes as any other: left open whatever its approach, contacts sank and
      // were pushed out every step, and a settled pile boiled at 0.3 m/s.
      const double approach = c.gap0 - d;
      const double close_at =
          c.toggles >= 3 ? std::max(close_tolerance, std::min(kChatterClosingRatio * allowed,
                                                              0.5 * kLateRestitution * approach))
                         : close_tolerance;
      if (d < -close_at) {
        c.state = ContactState::Locked;
        c.shear.setZero();
        ++c.toggles;
      }
    } else {
      const double tension = c.bonded ? joint.tensile_strength * c.area : 0.0;
      c.normal_force = -penalty_ * d;
      // A contact that opened and closed again in this step stays closed while its pull is
      // below kHoldWeights times the lighter block's weight: it sits where neither state is
      // consistent (solved closed it pulls by ~1e-7 m, solved open it penetrates past the
      // closing threshold, its load shared with the contacts of the same faces), and
      // flipping it back and forth never settled (piles of cubes redid their landing steps
      // down to 3e-5 s). Held, it pulls for one step: at most kHoldWeights g dt of velocity
      // between its blocks. A larger pull is a contact really opening: held there, it fought
      // a neighbouring contact with forces of 100 weights, and their work created energy
      // (random piles, docs/dda3d.md "Robustness tests"; none at 12 weights in 200 piles).
      const bool stays_closed = c.toggles >= 2 && penalty_ * d <= holdLimit(c);
      // The margin is a round-off distance: its force, penalty times it, sums over the
      // points of a face, so a sub-contact point takes its share (with the whole margin each,
      // the 512 points under a dam's lifting toe held 3e5 N of tension at 4.5e-10 m, and
      // the dam stood at 1.24 times its sliding factor).
      if (!stays_closed && d > tension / penalty_ + c.share * open_tolerance) {
        ++c.toggles;
        // Opened: a crack, whatever the joint model (its cohesion and tension are gone).
        c.state = ContactState::Open;
        c.bonded = false;
        c.normal_force = 0.0;
        c.shear.setZero();
      } else {
        const double limit = shearStrength(c, joint);
        // A contact at its friction limit with no slip velocity can flip between locked
        // and sliding forever; after two flips in a step it stays sliding (the friction
        // force then holds it at the limit, which is what both states mean there), unless its
        // friction then drives it back (below).
        const bool frozen = c.flips >= 2;
        if (c.state == ContactState::Locked) {
          // Over the limit by more than a round-off slip: a contact whose spring the
          // predictor set at the limit must not slide on the round-off of a resting block.
          const Vec3 shear = tangential(c.shear, c.normal) + slip;
          // The allowance is a force: ks times the round-off slip, but never more than
          // kStickAllowance of the strength. Allowed ks times the round-off alone, a stiff
          // penalty (40 times E l0) gave a frictionless joint 250 N of shear strength per
          // contact: the joint between two cubes pushed down a slope carried 10 % of the
          // front cube's weight to the rear one, and the pair slid 17 % too fast
          // (kStickAllowance).
          const double allowance = std::min(ks * reverse_tolerance, kStickAllowance * limit);
          if (!c.held && ks * (shear.norm() - allowance / ks) > limit) {
            ++c.flips;
            c.state = ContactState::Sliding;
            // Shi's brittle joint loses its cohesion and tension as it starts to slide; the
            // plastic joint keeps them while it slides (docs/stability.md, "Joint models").
            if (joint.model == JointModel::Brittle) c.bonded = false;
            c.slide_direction = shear.normalized();
            c.slip_length = 0.0;  // not known yet: no transverse tangent
          }
        } else if (const double back = -rigid_slip.dot(c.slide_direction);
                   limit > 0.0 && (frozen ? back > std::max(reverse_tolerance, limit / ks)
                                          : back > reverse_tolerance)) {
          // Friction alone would drive it back: it sticks, its spring carrying the friction.
          // A frozen contact (above) sticks too, for the rest of the step, once its friction
          // drove it back by more than its shear spring's stretch at the strength: its
          // friction, a load of f N along the direction of the last iteration's slip, did
          // work on the slip instead of resisting it. On a light block between heavy ones (a
          // 1 cm sliver, 106 kg, under 1e5 N corner contacts) the frozen friction forces of
          // its two faces lined up and threw it sideways at 1 m/s in one step (docs/dda3d.md,
          // "Known limits"). A smaller reversal is the creep of a contact at its limit: it
          // stays sliding, as the frozen rule means (a stuck spring would hold a wedge at
          // SRF 1.6 whose FS is 1.5).
          ++c.flips;
          c.state = ContactState::Locked;
          c.shear = (shearStrength(c, joint) / ks) * c.slide_direction;
          c.held = frozen;
        } else {
          // While the contact creeps (its slip in the step shorter than its shear spring's
          // stretch at the start of the step, the predictor's), the friction opposes the
          // trial shear, that stretch plus the slip (a return mapping). Along the slip alone,
          // a contact that creeps by 1e-7 m a step took its direction from the round-off of
          // that slip: its sideways part rolled a block on a plane, and the corners slid in
          // turn on either side. A contact that slides farther follows its slip.
          const Vec3 stretch = tangential(c.shear, c.normal);
          const Vec3 trial =
              rigid_slip.norm() < stretch.norm() ? Vec3(stretch + rigid_slip) : rigid_slip;
          if (trial.norm() > 0.0) {
            c.slide_direction = trial.normalized();
            c.slip_length = trial.norm();
          }
        }
      }
    }
    if (c.state != before) {
      ++changes.changed;
      const bool closed = before == ContactState::Open;
      changes.closed += closed;
      // The example names a contact that closed when any did (those always take another
      // iteration), else the first that changed.
      if (changes.example < 0 || (closed && changes.closed == 1)) {
        changes.example = static_cast<int>(k);
      }
    }
  }
  return changes;
}

double Simulation::holdLimit(const Contact& c) const {
  double lighter = std::numeric_limits<double>::infinity();
  for (int b : {c.block_i, c.block_j}) {
    const BlockState& block = blocks_[static_cast<std::size_t>(b)];
    if (!block.fixed) lighter = std::min(lighter, block.mass);
  }
  return kHoldWeights * model_.gravity.norm() * lighter;
}

double Simulation::shearStrength(const Contact& c, const DdaJoint& joint) const {
  return joint.friction * std::max(0.0, c.normal_force) +
         (c.bonded ? joint.cohesion * c.area : 0.0);
}

int Simulation::openCloseIterate(double dt, Eigen::VectorXd& solution, bool& settled) {
  settled = false;
  const int movable = static_cast<int>(base_k_.size());
  for (int iteration = 1; iteration <= settings_.max_open_close_iterations; ++iteration) {
    Clock::time_point start = Clock::now();
    system_->clear();
    for (int m = 0; m < movable; ++m) {
      system_->addDiagonal(m, base_k_[static_cast<std::size_t>(m)]);
      system_->addForce(m, base_f_[static_cast<std::size_t>(m)]);
    }
    applied_friction_.resize(contacts_.size());
    for (std::size_t k = 0; k < contacts_.size(); ++k) {
      applied_friction_[k] = addContactTerms(contacts_[k]);
    }
    for (std::size_t k = 0; k < bolt_a_.size(); ++k) {
      const MaterialPoint& a = bolt_a_[k];
      const MaterialPoint& b = bolt_b_[k];
      const Vec3 axis = b.current - a.current;
      const double length = axis.norm();
      if (length <= 0.0) continue;
      const Vec3 n = axis / length;
      const DdaBolt& bolt = model_.bolts[k];
      const double free_length =
          (bolt.point_b - bolt.point_a).norm() - bolt.pretension / bolt.stiffness;
      const int i = movableIndex(a.block);
      const int j = b.block >= 0 ? movableIndex(b.block) : -1;
      const BlockVector ea =
          -displacementMatrix(a.current, blocks_[static_cast<std::size_t>(a.block)].centroid)
               .transpose() *
          n;
      const BlockVector eb =
          j >= 0 ? BlockVector(displacementMatrix(
                                   b.current, blocks_[static_cast<std::size_t>(b.block)].centroid)
                                   .transpose() *
                               n)
                 : BlockVector(BlockVector::Zero());
      system_->addSpring(i, ea, j, eb, bolt.stiffness, length - free_length);
    }
    timings_.assemble_contacts += secondsSince(start);
    if (movable == 0) {
      solution.resize(0);
      settled = true;
      return iteration;
    }
    start = Clock::now();
    const bool positive = solver_->factorize(system_->matrix());
    if (solver_->stats().analyzed) ++pattern_changes_;
    timings_.factorize += secondsSince(start);
    if (!positive) {
      // No solution this attempt: step() sees the empty vector and redoes the step with a
      // smaller time step (more inertia on the diagonal), or reports the failure.
      solution.resize(0);
      return iteration;
    }
    start = Clock::now();
    // First guess (used by iterative backends): the previous iteration's solution, or for
    // the first iteration the last step's scaled to this dt.
    Eigen::VectorXd guess;
    if (iteration > 1) {
      guess = solution;
    } else if (last_solution_.size() == system_->rhs().size() && last_dt_ > 0.0) {
      guess = (dt / last_dt_) * last_solution_;
    }
    solution = guess.size() == system_->rhs().size()
                   ? solver_->solveWithGuess(system_->rhs(), guess)
                   : solver_->solve(system_->rhs());
    solver_iterations_ += solver_->stats().iterations;
    timings_.solve += secondsSince(start);
    start = Clock::now();
    const bool finite = solution.allFinite();
    const StateChanges changes = finite ? updateContactStates(solution) : StateChanges{};
    last_changes_ = changes;
    timings_.update_states += secondsSince(start);
    if (!finite) return iteration;
    // The allowance covers contacts that opened or changed between locked and sliding (they
    // carried a spring or a friction force one iteration too long), never one that closed:
    // it was solved open and may sit deep in the other block.
    const auto allowed =
        static_cast<int>(settings_.open_close_tolerance * static_cast<double>(contacts_.size()));
    if (changes.closed == 0 && changes.changed <= allowed) {
      settled = true;
      return iteration;
    }
  }
  return settings_.max_open_close_iterations;
}

double Simulation::maxDisplacementRatio(const Eigen::VectorXd& solution, int* fastest,
                                        double* weighed) const {
  double largest = 0.0;
  double largest_weighed = 0.0;
  int largest_block = -1;
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    const BlockState& block = blocks_[b];
    if (block.fixed) continue;
    const BlockVector d = system_->unknowns(solution, block.dof_offset);
    double block_largest = 0.0;
    for (const geometry::Polyhedron& piece : block.pieces) {
      for (const Vec3& v : piece.vertices) {
        block_largest = std::max(block_largest, (movedPoint(v, block.centroid, d) - v).norm());
      }
    }
    if (block_largest > largest) {
      largest = block_largest;
      largest_block = static_cast<int>(b);
    }
    largest_weighed = std::max(largest_weighed, block_largest * staticMassScale(block));
  }
  if (fastest) *fastest = largest_block;
  if (weighed) *weighed = largest_weighed;
  return largest / (settings_.max_displacement_ratio * half_domain_);
}

double Simulation::maxPenetration() const {
  double deepest = 0.0;
  for (const Contact& c : contacts_) deepest = std::max(deepest, -c.gap);
  return deepest;
}

void Simulation::accountDissipation(const Eigen::VectorXd& solution, double dt) {
  // Friction: the forces applied in the last solve, -f N s on i and +f N s on j, did the work
  // -f N s . (u_i - u_j); the blocks lost that much.
  // The transverse tangent springs of sliding contacts are friction too: the work against
  // them, k x^2 (x the rigid slip across the direction), is dissipated, not stored; the
  // numerical term below dots the whole matrix, so their 1/2 k x^2 is taken out of it.
  double transverse = 0.0;
  for (std::size_t k = 0; k < contacts_.size() && k < applied_friction_.size(); ++k) {
    const AppliedFriction& f = applied_friction_[k];
    if (f.force.isZero(0.0) && f.transverse_stiffness == 0.0) continue;
    friction_work_ -= f.force.dot(relativeDisplacement(contacts_[k], solution));
    if (f.transverse_stiffness > 0.0) {
      const double x = f.across.dot(relativeDisplacement(contacts_[k], solution, true));
      friction_work_ += f.transverse_stiffness * x * x;
      transverse += 0.5 * f.transverse_stiffness * x * x;
    }
  }
  // Springs at the start of the step, in the states the step ended with: the energy
  // 1/2 k (d0 + e^T D)^2 of every spring at D = 0. Where it differs from the springs' energy
  // at the end of the last step, contact changes between the steps added (or removed) it:
  // contacts detected already penetrating, closed or opened, shear springs restarted,
  // penalty changes. A contact still apart (d0 > 0) that closes during the step is the
  // exception: the solve counts 1/2 k d0^2 as if its spring pulled from the start and takes
  // it back in 1/2 d^T K d (an implicit, inelastic impact), so that share is moved from the
  // numerical dissipation instead of being counted as a change.
  double springs_start = pointSpringEnergy();
  double pulling = 0.0;
  const double ks = penalty_ / settings_.shear_penalty_ratio;
  for (const Contact& c : contacts_) {
    if (c.state == ContactState::Open) continue;
    (c.gap0 > 0.0 ? pulling : springs_start) += 0.5 * penalty_ * c.gap0 * c.gap0;
    if (c.state == ContactState::Locked) {
      springs_start += 0.5 * ks * tangential(c.shear, c.normal).squaredNorm();
    }
  }
  contact_changes_ += springs_start - springs_after_step_;
  numerical_dissipation_ -= pulling;
  if (solution.size() == 0) return;
  // The step solved (K + c0 M) d = F + M (c1 v0 + c2 a0). Dotted with d, and with every
  // spring and the strain energy quadratic, the work of the loads less the friction work
  // equals dU + 1/2 d^T K d (forces taken at the end of the step) + d^T M a_b, a_b =
  // (1 - alpha_m) a1 + alpha_m a0 the Bossak-weighted acceleration. The scheme removed what
  // of that did not become kinetic energy: 1/2 d^T K d + d^T M a_b - (T1 - T0).
  const double ratio = settings_.mode == AnalysisMode::Static ? 0.0 : settings_.dynamic_ratio;
  const double c0 = (1.0 - scheme_.alpha_m) / (scheme_.beta * dt * dt);
  double removed = 0.5 * solution.dot(system_->matrix() * solution);
  for (const BlockState& block : blocks_) {
    if (block.fixed) continue;
    const BlockVector d = system_->unknowns(solution, block.dof_offset);
    const BlockMatrix m = staticMassScale(block) * massMatrix(block);
    const BlockVector a1 = endAcceleration(d, block.velocity, block.acceleration, dt, scheme_);
    const BlockVector v1 = endVelocity(block.velocity, block.acceleration, a1, dt, scheme_);
    const BlockVector weighted =
        (1.0 - scheme_.alpha_m) * a1 + scheme_.alpha_m * block.acceleration;
    const double end_kinetic = 0.5 * v1.dot(m * v1);
    removed += -0.5 * c0 * d.dot(m * d) + d.dot(m * weighted) - end_kinetic +
               0.5 * block.velocity.dot(m * block.velocity);
    // A dynamic ratio below 1 (or static mode) takes a share of the kinetic energy away.
    removed += (1.0 - ratio * ratio) * end_kinetic;
  }
  numerical_dissipation_ += removed - transverse;
}

void Simulation::updateBlocks(const Eigen::VectorXd& solution, double dt) {
  for (Contact& c : contacts_) {
    if (c.state == ContactState::Locked) {
      c.shear = tangential(c.shear + relativeDisplacement(c, solution), c.normal);
    } else {
      c.shear.setZero();
    }
  }
  const double ratio = settings_.mode == AnalysisMode::Static ? 0.0 : settings_.dynamic_ratio;
  const auto move = [&](std::vector<MaterialPoint>& points) {
    for (MaterialPoint& p : points) {
      if (p.block < 0) continue;
      const BlockState& block = blocks_[static_cast<std::size_t>(p.block)];
      if (block.fixed) continue;
      p.current = movedPoint(p.current, block.centroid, unknownsOf(solution, p.block));
    }
  };
  move(monitor_points_);
  move(load_points_);
  move(fixed_points_);
  move(bolt_a_);
  move(bolt_b_);
  block_work_.resize(blocks_.size(), 0.0);
  for (std::size_t b = 0; b < blocks_.size(); ++b) {
    BlockState& block = blocks_[b];
    if (block.fixed) continue;
    const BlockVector d = system_->unknowns(solution, block.dof_offset);
    const double work = load_f_[static_cast<std::size_t>(block.dof_offset)].dot(d);
    work_of_loads_ += work;
    block_work_[b] += work;
    for (geometry::Polyhedron& piece : block.pieces) {
      for (Vec3& v : piece.vertices) v = movedPoint(v, block.centroid, d);
    }
    for (FacePoints& points : block.face_points) {
      for (FacePoint& p : points.points) p.position = movedPoint(p.position, block.centroid, d);
    }
    const Eigen::Matrix3d rotation = rotationMatrix(d.segment<3>(3));
    if (settings_.kinematics == Kinematics::Deformable) {
      const VoigtVector step_strain = d.tail<kVoigtSize>();
      block.stress += elastic_[static_cast<std::size_t>(block.material)] * step_strain;
      block.strain += step_strain;
      block.stress = rotateVoigt(block.stress, rotation, 1.0);
      block.strain = rotateVoigt(block.strain, rotation, 0.5);
    }
    const BlockVector a1 = endAcceleration(d, block.velocity, block.acceleration, dt, scheme_);
    block.velocity =
        ratio * endVelocity(block.velocity, block.acceleration, a1, dt, scheme_).eval();
    block.acceleration = ratio * a1;
    block.last_displacement = d;
    block.updateMassProperties();
  }
}

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

StepReport Simulation::step() {
  if (interruptRequested()) {
    std::ostringstream where;
    where << "the DDA at t = " << time_ << " s";
    throwIfInterrupted(where.str());
  }
  StepReport report;
  Clock::time_point start = Clock::now();
  const int patterns_before = pattern_changes_;
  solver_iterations_ = 0;
  report.late_contacts = detectContacts();
  timings_.detect_contacts += secondsSince(start);
  const std::vector<Contact> at_start = contacts_;
  const double allowed = settings_.allowed_penetration_ratio * half_domain_;
  // Capped at 1e4 x the initial penalty for the whole run: a cap taken from the current
  // penalty let it climb 1e4 per step (to 1e34 N/m on the Xiangjiaba model while another
  // fault kept the steps failing), until K was not positive definite in floating point.
  const double penalty_cap = 1e4 * initial_penalty_;
  double dt = dt_;
  Eigen::VectorXd solution;
  for (int attempt = 1;; ++attempt) {
    report.attempts = attempt;
    const bool last_chance = attempt >= settings_.max_step_attempts;
    if (attempt > 1) contacts_ = at_start;
    start = Clock::now();
    assembleBlockTerms(dt);
    timings_.assemble_block_terms += secondsSince(start);
    bool settled = false;
    report.iterations = openCloseIterate(dt, solution, settled);
    const bool can_shrink = dt > settings_.min_time_step;
    if (!settled && can_shrink && !last_chance) {
      dt = std::max(settings_.min_time_step, dt * settings_.iteration_time_step_factor);
      ++report.redo_iterations;
      continue;
    }
    if (solution.size() != system_->rhs().size()) {
      // The factorization found the matrix not positive definite on every attempt, down to
      // the smallest time step: a block with (almost) no mass or stiffness, or a mechanism.
      throw std::runtime_error("DDA step failed at t = " + std::to_string(time_) +
                               " s: the system matrix is not positive definite even at time step " +
                               std::to_string(dt) + " s (" + singularBlockHint(blocks_, *system_) +
                               ")");
    }
    if (!solution.allFinite()) {
      throw std::runtime_error(
          "DDA step failed: the system is singular at t = " + std::to_string(time_) + " s");
    }
    start = Clock::now();
    report.displacement_ratio =
        maxDisplacementRatio(solution, &report.fastest_block, &report.unbalanced_displacement);
    report.max_penetration = maxPenetration();
    const double reach_ratio = reachRatio(blocks_, *system_, solution, reach_);
    timings_.update_states += secondsSince(start);
    const bool too_far =
        report.displacement_ratio > kAcceptedDisplacementRatio || reach_ratio > 1.0;
    if (too_far && !last_chance && dt > settings_.min_time_step) {
      const double over_limit =
          report.displacement_ratio > kAcceptedDisplacementRatio ? report.displacement_ratio : 0.0;
      dt = std::max(settings_.min_time_step,
                    dt * std::max(0.1, 0.9 / std::max(over_limit, reach_ratio)));
      ++report.redo_displacement;
      continue;
    }
    if (report.max_penetration > allowed && penalty_ < penalty_cap && !last_chance) {
      const double ratio = report.max_penetration / allowed;
      penalty_ = std::min(penalty_cap, penalty_ * std::clamp(ratio * ratio, 2.0, 10.0));
      ++report.redo_penetration;
      continue;
    }
    if (!settled || too_far || report.max_penetration > allowed) {
      // Nothing left to try: dt is at its minimum (or the attempts are used up) and the step
      // still fails a check. Accepting it would go on with a step that broke the method's
      // assumptions, and runs left to do so shrank dt without end (docs/dda3d.md, "Step
      // control").
      throw StepFailure(stepFailureMessage(dt, attempt, settled, report, allowed));
    }
    break;
  }
  start = Clock::now();
  accountDissipation(solution, dt);
  updateBlocks(solution, dt);
  springs_after_step_ = springEnergy();
  last_solution_ = solution;
  last_dt_ = dt;
  timings_.update_blocks += secondsSince(start);
  time_ += dt;
  steps_at_min_ = dt <= settings_.min_time_step * (1.0 + 1e-12) ? steps_at_min_ + 1 : 0;
  if (steps_at_min_ >= settings_.max_steps_at_min_time_step) {
    throw StepFailure("DDA run cannot progress: " + std::to_string(steps_at_min_) +
                      " steps in a row at min_time_step " + numberText(settings_.min_time_step) +
                      " s, now at t = " + numberText(time_) + " s; the last step moved " +
                      blockText(report.fastest_block) + " " + numberText(stepDisplacement(report)) +
                      " m");
  }
  const double grow =
      report.displacement_ratio > 0.0 ? 0.9 / std::sqrt(report.displacement_ratio) : 1.2;
  dt_ = std::clamp(dt * std::clamp(grow, 0.5, 1.2), settings_.min_time_step, settings_.time_step);
  report.time = time_;
  report.time_step = dt;
  report.penalty = penalty_;
  report.pattern_changes = pattern_changes_ - patterns_before;
  report.solver_iterations = solver_iterations_;
  report.contacts = contactCounts();
  return report;
}

StepReport Simulation::runUntil(double end_time) {
  StepReport last;
  while (time_ < end_time * (1.0 - 1e-12)) {
    dt_ = std::min(dt_, end_time - time_);
    last = step();
  }
  return last;
}

Vec3 Simulation::centroidDisplacement(int b) const {
  return blocks_[static_cast<std::size_t>(b)].centroid -
         initial_centroids_[static_cast<std::size_t>(b)];
}

ContactCounts Simulation::contactCounts() const {
  ContactCounts counts;
  for (const Contact& c : contacts_) {
    ++counts.total;
    counts.edge_edge += c.kind == ContactKind::EdgeEdge;
    switch (c.state) {
      case ContactState::Open:
        ++counts.open;
        break;
      case ContactState::Sliding:
        ++counts.sliding;
        break;
      case ContactState::Locked:
        ++counts.locked;
        break;
    }
  }
  return counts;
}

std::vector<MonitorState> Simulation::monitors() const {
  std::vector<MonitorState> out;
  for (std::size_t k = 0; k < monitor_points_.size(); ++k) {
    const MaterialPoint& p = monitor_points_[k];
    const BlockState& block = blocks_[static_cast<std::size_t>(p.block)];
    MonitorState m;
    m.name = model_.monitors[k].name;
    m.position = p.current;
    m.displacement = p.current - p.initial;
    m.velocity = displacementMatrix(p.current, block.centroid) * block.velocity;
    out.push_back(m);
  }
  return out;
}

EnergyAccount Simulation::energy() const {
  EnergyAccount e;
  for (const BlockState& block : blocks_) {
    if (block.fixed) continue;
    e.kinetic += 0.5 * block.velocity.dot(massMatrix(block) * block.velocity);
    if (settings_.kinematics == Kinematics::Deformable) {
      e.strain +=
          0.5 * block.volume *
          block.strain.dot(elastic_[static_cast<std::size_t>(block.material)] * block.strain);
    }
  }
  e.springs = springEnergy();
  e.work_of_loads = work_of_loads_;
  e.friction = friction_work_;
  e.numerical = numerical_dissipation_;
  e.contact_changes = contact_changes_;
  return e;
}

double Simulation::springEnergy() const {
  double energy = pointSpringEnergy();
  const double ks = penalty_ / settings_.shear_penalty_ratio;
  for (const Contact& c : contacts_) {
    if (c.state == ContactState::Open) continue;
    energy += 0.5 * penalty_ * c.gap * c.gap;
    if (c.state == ContactState::Locked) energy += 0.5 * ks * c.shear.squaredNorm();
  }
  return energy;
}

double Simulation::pointSpringEnergy() const {
  double energy = 0.0;
  for (const MaterialPoint& fp : fixed_points_) {
    const Vec3 u = fp.current - fp.initial;
    const double held =
        fp.direction.isZero(0.0) ? u.squaredNorm() : fp.direction.dot(u) * fp.direction.dot(u);
    energy += 0.5 * settings_.fixed_point_penalty_ratio * penalty_ * held;
  }
  for (std::size_t k = 0; k < bolt_a_.size(); ++k) {
    const DdaBolt& bolt = model_.bolts[k];
    const double free_length =
        (bolt.point_b - bolt.point_a).norm() - bolt.pretension / bolt.stiffness;
    const double stretch = (bolt_b_[k].current - bolt_a_[k].current).norm() - free_length;
    energy += 0.5 * bolt.stiffness * stretch * stretch;
  }
  return energy;
}

}  // namespace rockmass::dda3d
