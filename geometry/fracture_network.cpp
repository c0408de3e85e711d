#include "geometry/fracture_network.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>

#include "geometry/fisher.h"
#include "geometry/interrupt.h"
#include "geometry/orientation.h"
#include "geometry/random.h"

namespace rockmass::geometry {
namespace {

/// Pilot discs drawn per joint set to measure its mean area, mean projected area, mean
/// normal and the size of the margin. Their relative sampling error (~1/sqrt(n) times the
/// coefficient of variation of the area) stays well below the 3% accuracy asked of P10/P32.
constexpr int kPilotSamples = 100'000;
/// Discs larger than the margin may carry at most this share of the set's total area.
/// Discs whose centre falls outside the enlarged domain but reach into it are missed, so
/// this bounds the intensity lost at the domain's edges.
constexpr double kMissedAreaShare = 1e-3;
/// Sub-streams of the seed, per set: the pilot and the placement.
constexpr std::uint64_t kPilotStream = 0;
constexpr std::uint64_t kPlacementStream = 1;

/// Draws the orientation, size and shape of one disc of a joint set (not its centre).
class JointSetSampler {
 public:
  explicit JointSetSampler(const JointSetSpec& spec)
      : spec_(spec), trace_(spec.trace_length), scale_(traceToDiameterScale(spec.trace_length)) {
    if (spec.orientation.fisher) {
      nominal_normal_ = normalFromOrientation(
          {spec.orientation.fisher_dip_direction, spec.orientation.fisher_dip});
    } else {
      dip_direction_.emplace(spec.orientation.dip_direction);
      dip_.emplace(spec.orientation.dip);
    }
    if (!(spec.shape.aspect_ratio > 0.0 && spec.shape.aspect_ratio <= 1.0)) {
      throw std::invalid_argument("set " + spec.name + ": aspect_ratio must be in (0, 1]");
    }
    if (trace_.lower() < 0.0) {
      throw std::invalid_argument("set " + spec.name +
                                  ": trace lengths can be negative; give min > 0");
    }
  }

  /// Equal-area diameter per unit of sampled trace length (see traceToDiameterScale).
  double scale() const { return scale_; }

  /// Fills normal, major axis and semi-axes of `disc`.
  void sample(Rng& rng, Disc& disc) const {
    disc.normal = sampleNormal(rng);
    const PlaneOrientation o = orientationFromNormal(disc.normal);
    const Vec3 strike = strikeVector(o);
    const Vec3 dip = dipVector(o);
    switch (spec_.shape.major_axis) {
      case MajorAxis::Strike:
        disc.major = strike;
        break;
      case MajorAxis::Dip:
        disc.major = dip;
        break;
      case MajorAxis::Rake: {
        const double rake = radians(spec_.shape.rake);
        disc.major = std::cos(rake) * strike + std::sin(rake) * dip;
        break;
      }
    }
    // Equal-area diameter D = c L; an ellipse of aspect k = b / a with that area has
    // a b = D^2 / 4, so a = D / (2 sqrt(k)) and b = k a.
    const double diameter = scale_ * trace_.sample(rng);
    const double k = spec_.shape.aspect_ratio;
    disc.a = diameter / (2.0 * std::sqrt(k));
    disc.b = k * disc.a;
  }

 private:
  /// Upward unit normal from the Fisher model or the independent angle distributions.
  Vec3 sampleNormal(Rng& rng) const {
    if (spec_.orientation.fisher) {
      Vec3 n = sampleFisher(nominal_normal_, spec_.orientation.kappa, rng);
      return n.z() < 0.0 ? Vec3(-n) : n;
    }
    double dip_direction = dip_direction_->sample(rng);
    double dip = dip_->sample(rng);
    // Fold dips outside [0, 90] back onto the upper hemisphere of poles.
    if (dip < 0.0) {
      dip = -dip;
      dip_direction += 180.0;
    }
    if (dip > 90.0) {
      dip = 180.0 - dip;
      dip_direction += 180.0;
    }
    return normalFromOrientation({wrapDegrees(dip_direction), dip});
  }

  const JointSetSpec& spec_;
  Distribution trace_;
  double scale_;
  std::optional<Distribution> dip_direction_;
  std::optional<Distribution> dip_;
  Vec3 nominal_normal_ = Vec3::UnitZ();
};

/// What the pilot sample tells about a joint set.
struct PilotResult {
  Vec3 mean_normal = Vec3::UnitZ();  ///< Fisher mean of the normals
  double mean_area = 0.0;            ///< E[A] (m2)
  double mean_projected_area = 0.0;  ///< E[A |n . u|] along the mean normal u (m2)
  double margin = 0.0;               ///< enlargement of the domain (m)
};

/// Draws kPilotSamples discs and measures them.
PilotResult runPilot(const JointSetSampler& sampler, Rng& rng) {
  std::vector<Disc> discs(kPilotSamples);
  std::vector<Vec3> normals(kPilotSamples);
  for (int i = 0; i < kPilotSamples; ++i) {
    sampler.sample(rng, discs[i]);
    normals[i] = discs[i].normal;
  }
  PilotResult pilot;
  pilot.mean_normal = estimateFisher(normals).mean;
  double area_sum = 0.0;
  double projected_sum = 0.0;
  for (const Disc& d : discs) {
    area_sum += d.area();
    projected_sum += d.area() * std::abs(d.normal.dot(pilot.mean_normal));
  }
  pilot.mean_area = area_sum / kPilotSamples;
  pilot.mean_projected_area = projected_sum / kPilotSamples;
  // Margin: the semi-major axis above which discs carry at most kMissedAreaShare of the area.
  std::sort(discs.begin(), discs.end(), [](const Disc& p, const Disc& q) { return p.a > q.a; });
  double tail_area = 0.0;
  for (const Disc& d : discs) {
    tail_area += d.area();
    if (tail_area > kMissedAreaShare * area_sum) {
      pilot.margin = d.a;
      break;
    }
  }
  return pilot;
}

/// What a joint set will draw, known before any disc is placed: the pilot's measurements,
/// the centre density and the enlarged domain the centres are drawn in.
struct JointSetPlan {
  SetInfo info;
  double lambda = 0.0;    ///< centres per m3
  Box enlarged;           ///< the domain enlarged by the margin
  double expected = 0.0;  ///< expected number of discs drawn, lambda * enlarged volume
};

/// Runs the pilot of one joint set and plans its placement.
JointSetPlan planJointSet(const JointSetSpec& spec, int set_index, const Box& domain,
                          std::uint64_t seed) {
  const JointSetSampler sampler(spec);
  Rng pilot_rng = makeRng(seed, 2 * static_cast<std::uint64_t>(set_index) + kPilotStream);
  const PilotResult pilot = runPilot(sampler, pilot_rng);

  JointSetPlan plan;
  SetInfo& info = plan.info;
  info.name = spec.name;
  info.origin = DiscOrigin::JointSet;
  info.mean_normal = pilot.mean_normal;
  info.size_scale = sampler.scale();
  info.margin = pilot.margin;
  // Intensity of a Poisson field of discs with centre density lambda (Campbell's theorem):
  //   P32 = lambda E[A]            (area per volume, one face counted),
  //   P10(u) = lambda E[A |n.u|]   (crossings per metre of a line along u).
  // The normal spacing of the set is the spacing along its mean normal u: P10 = 1 / mean.
  if (spec.spacing) {
    info.target_p10 = 1.0 / spec.spacing->mean;
    plan.lambda = info.target_p10 / pilot.mean_projected_area;
    info.target_p32 = plan.lambda * pilot.mean_area;
  } else {
    info.target_p32 = *spec.p32;
    plan.lambda = info.target_p32 / pilot.mean_area;
    info.target_p10 = plan.lambda * pilot.mean_projected_area;
  }
  // Centres: a Poisson process in the domain enlarged by the margin, so that discs centred
  // outside the domain still reach into it.
  plan.enlarged = domain.enlarged(pilot.margin);
  plan.expected = plan.lambda * plan.enlarged.volume();
  if (!std::isfinite(plan.expected)) plan.expected = std::numeric_limits<double>::infinity();
  return plan;
}

/// Draws the discs of one joint set that touch the domain, as planned.
void generateJointSet(const JointSetSpec& spec, int set_index, const Box& domain,
                      std::uint64_t seed, JointSetPlan plan, FractureNetwork& network) {
  const JointSetSampler sampler(spec);
  SetInfo& info = plan.info;
  Rng rng = makeRng(seed, 2 * static_cast<std::uint64_t>(set_index) + kPlacementStream);
  info.generated = std::poisson_distribution<std::int64_t>(plan.expected)(rng);
  const Box& enlarged = plan.enlarged;
  const Vec3 size = enlarged.size();
  for (std::int64_t i = 0; i < info.generated; ++i) {
    if ((i & 0xffff) == 0) throwIfInterrupted("the DFN (joint set " + spec.name + ")");
    Disc disc;
    disc.center = enlarged.min + Vec3(uniformOpen01(rng) * size.x(), uniformOpen01(rng) * size.y(),
                                      uniformOpen01(rng) * size.z());
    sampler.sample(rng, disc);
    // A centre outside the domain may still belong to a disc that reaches into it.
    if (!domain.contains(disc.center) && disc.areaInside(domain) <= 0.0) continue;
    disc.set = set_index;
    disc.joint = spec.joint;
    disc.origin = DiscOrigin::JointSet;
    disc.cuts = 2.0 * disc.a >= spec.min_cut_size;
    network.discs.push_back(std::move(disc));
  }
  network.sets.push_back(info);
}

/// Adds `disc` when it touches the domain. Returns the id it will get (its 1-based position,
/// see generateNetwork), or 0 when it was left out.
std::int64_t addIfInside(Disc disc, const Box& domain, FractureNetwork& network) {
  if (disc.areaInside(domain) <= 0.0) return 0;
  network.discs.push_back(std::move(disc));
  return static_cast<std::int64_t>(network.discs.size());
}

/// A deterministic set: its SetInfo with the given mean normal.
SetInfo deterministicSet(const std::string& name, DiscOrigin origin, const Vec3& normal) {
  SetInfo info;
  info.name = name;
  info.origin = origin;
  info.mean_normal = normal;
  return info;
}

/// Adds the one or two surfaces of a fault (two for a slab of thickness > 0).
void generateFault(const FaultSpec& spec, int set_index, const Box& domain,
                   FractureNetwork& network) {
  const PlaneOrientation o{spec.dip_direction, spec.dip};
  Disc disc;
  disc.set = set_index;
  disc.joint = spec.joint;
  disc.origin = DiscOrigin::Fault;
  disc.normal = normalFromOrientation(o);
  disc.major = strikeVector(o);
  // A fault without a size crosses the whole domain: a circle as wide as the domain's
  // diagonal, centred on the given point, which the domain cannot contain.
  const double span = 2.0 * (domain.diagonal() + domain.distance(spec.center));
  disc.a = spec.size ? 0.5 * (*spec.size)[0] : span;
  disc.b = spec.size ? 0.5 * (*spec.size)[1] : span;
  SetInfo info = deterministicSet(spec.name, DiscOrigin::Fault, disc.normal);
  if (spec.thickness > 0.0) {
    Slab slab{set_index, spec.material, spec.thickness, {}, {}};
    for (const double side : {-0.5, 0.5}) {
      Disc surface = disc;
      surface.center = spec.center + side * spec.thickness * disc.normal;
      info.generated += 1;
      if (const std::int64_t id = addIfInside(surface, domain, network)) {
        (side < 0 ? slab.lower : slab.upper).push_back(id);
      }
    }
    network.slabs.push_back(std::move(slab));
  } else {
    disc.center = spec.center;
    info.generated = 1;
    addIfInside(disc, domain, network);
  }
  network.sets.push_back(info);
}

/// Offsets a polyline by `distance` along the left normal of its segments, with mitred
/// joints so that consecutive offset segments meet. Throws for a turn too sharp to mitre.
std::vector<Vec2> offsetPolyline(const std::vector<Vec2>& line, double distance,
                                 const std::string& name) {
  const auto left_normal = [&](std::size_t i) {
    const Vec2 d = (line[i + 1] - line[i]).normalized();
    return Vec2(-d.y(), d.x());
  };
  std::vector<Vec2> out(line.size());
  out.front() = line.front() + distance * left_normal(0);
  out.back() = line.back() + distance * left_normal(line.size() - 2);
  for (std::size_t i = 1; i + 1 < line.size(); ++i) {
    const Vec2 n1 = left_normal(i - 1);
    const Vec2 n2 = left_normal(i);
    const double cosine = n1.dot(n2);
    // The mitre point lies at distance / cos(half turn) along the bisector; refuse turns
    // above kMaxInterlayerTurn.
    if (cosine < std::cos(radians(kMaxInterlayerTurn))) {
      throw std::invalid_argument("interlayer " + name + ": the profile turns by more than 150" +
                                  " degrees at point " + std::to_string(i + 1) +
                                  ", too sharp for its thickness");
    }
    out[i] = line[i] + distance * (n1 + n2) / (1.0 + cosine);
  }
  return out;
}

/// The profile with each end that lies on or beyond a side of the domain section (the
/// (profile axis, z) rectangle `low`..`high`) moved outward along its end segment, until
/// both surfaces offset by `half_thickness` reach `extra` beyond that side. Without this an
/// inclined end segment's offset surfaces stop up to half a thickness short of the domain
/// face, and the slab leaves a gap through which its rock glues to the rock around it. An
/// end inside the domain stays where the profile puts it (a layer that pinches out).
std::vector<Vec2> extendProfileEnds(std::vector<Vec2> line, const Vec2& low, const Vec2& high,
                                    double half_thickness, const Vec2& extra) {
  const double reach = (high - low).norm();
  for (const bool last : {false, true}) {
    const std::size_t end = last ? line.size() - 1 : 0;
    const std::size_t inner = last ? line.size() - 2 : 1;
    const Vec2 d = (line[end] - line[inner]).normalized();  // outward along the end segment
    const Vec2 n(-d.y(), d.x());
    double shift = 0.0;
    for (int axis = 0; axis < 2; ++axis) {
      for (const double sign : {-1.0, 1.0}) {
        // The side axis = low (sign -1) or axis = high (sign +1), outward coordinate sign * x.
        const double level = sign > 0 ? high[axis] : -low[axis];
        const double beyond = sign * line[end][axis] - level;  // >= 0: on or beyond the side
        const double outward = sign * d[axis];
        if (beyond < -1e-9 * reach || outward <= 0.0) continue;
        const double needed = (half_thickness * std::abs(n[axis]) + extra[axis] - beyond) / outward;
        shift = std::max(shift, std::min(needed, reach));
      }
    }
    line[end] += shift * d;
  }
  return line;
}

/// Adds the surfaces of an interlayer: each profile segment swept across the domain.
void generateInterlayer(const InterlayerSpec& spec, int set_index, const Box& domain,
                        FractureNetwork& network) {
  const int sweep_axis = spec.sweep == 'x' ? 0 : 1;
  const int profile_axis = 1 - sweep_axis;
  // Sweep 1% beyond the domain on both sides so that the layer crosses it completely.
  const double extra = 0.01 * (domain.max[sweep_axis] - domain.min[sweep_axis]);
  const double from = domain.min[sweep_axis] - extra;
  const double to = domain.max[sweep_axis] + extra;
  const auto point3 = [&](const Vec2& p, double s) {
    Vec3 q;
    q[profile_axis] = p.x();
    q[sweep_axis] = s;
    q[2] = p.y();
    return q;
  };
  // The same 1% beyond the domain in the section plane, where the profile reaches a side.
  const Vec2 low(domain.min[profile_axis], domain.min.z());
  const Vec2 high(domain.max[profile_axis], domain.max.z());
  const std::vector<Vec2> profile =
      extendProfileEnds(spec.profile, low, high, 0.5 * spec.thickness, 0.01 * (high - low));
  std::vector<std::vector<Vec2>> lines;
  Slab slab{set_index, spec.material, spec.thickness, {}, {}};
  if (spec.thickness > 0.0) {
    lines.push_back(offsetPolyline(profile, -0.5 * spec.thickness, spec.name));
    lines.push_back(offsetPolyline(profile, 0.5 * spec.thickness, spec.name));
  } else {
    lines.push_back(profile);
  }
  SetInfo info = deterministicSet(spec.name, DiscOrigin::Interlayer, Vec3::UnitZ());
  Vec3 normal_sum = Vec3::Zero();
  for (std::size_t side = 0; side < lines.size(); ++side) {
    const std::vector<Vec2>& line = lines[side];
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      Disc disc = discFromPolygon({point3(line[i], from), point3(line[i + 1], from),
                                   point3(line[i + 1], to), point3(line[i], to)});
      if (disc.normal.z() < 0.0) disc.normal = -disc.normal;
      normal_sum += disc.area() * disc.normal;
      disc.set = set_index;
      disc.joint = spec.joint;
      disc.origin = DiscOrigin::Interlayer;
      info.generated += 1;
      const std::int64_t id = addIfInside(std::move(disc), domain, network);
      if (id != 0 && spec.thickness > 0.0) (side == 0 ? slab.lower : slab.upper).push_back(id);
    }
  }
  if (normal_sum.norm() > 0.0) info.mean_normal = normal_sum.normalized();
  if (spec.thickness > 0.0) network.slabs.push_back(std::move(slab));
  network.sets.push_back(info);
}

/// Adds the polygons of a file, exactly as given.
void generatePolygonSet(const PolygonSetSpec& spec, int set_index, const Box& domain,
                        FractureNetwork& network) {
  SetInfo info = deterministicSet(spec.name, DiscOrigin::FabFile, Vec3::UnitZ());
  std::vector<Vec3> normals;
  for (const std::vector<Vec3>& polygon : spec.polygons) {
    Disc disc = discFromPolygon(polygon);
    disc.set = set_index;
    disc.joint = spec.joint;
    disc.origin = DiscOrigin::FabFile;
    normals.push_back(disc.normal);
    info.generated += 1;
    addIfInside(std::move(disc), domain, network);
  }
  if (!normals.empty()) info.mean_normal = estimateFisher(normals).mean;
  network.sets.push_back(info);
}

}  // namespace

double traceToDiameterScale(const DistributionSpec& trace_length) {
  // Trace length -> disc size (Warburton 1980, stereology of a Poisson disc field). A plane
  // cuts a disc of diameter D with a probability proportional to D, and the mean chord
  // of the discs it cuts is pi D / 4 (a uniformly placed chord of a circle), whatever the
  // orientations. So the mean trace on an exposure is E[l] = (pi / 4) E[D^2] / E[D].
  // Discs get the equal-area diameter D = c L, with L drawn from the trace-length
  // distribution, and c chosen so that E[l] equals the mean of that distribution:
  //   c = (4 / pi) E[L]^2 / E[L^2].
  // For an untruncated distribution E[L^2] = mean^2 + std^2, so c = (4/pi) / (1 + CV^2).
  // Truncated distributions use their exact truncated moments (numerical quadrature of
  // the truncated density).
  const Distribution distribution(trace_length);
  double first = trace_length.mean;
  double second = trace_length.mean * trace_length.mean + trace_length.std * trace_length.std;
  if (trace_length.kind == DistributionKind::Exponential) second = 2.0 * first * first;
  if (trace_length.kind == DistributionKind::Constant) second = first * first;
  if ((trace_length.min || trace_length.max) && trace_length.kind != DistributionKind::Constant) {
    // Quadrature in probability space: E[g(L)] = integral over p in (0, 1) of g(Q(p)), with
    // the quantile Q found by bisection on the exact CDF. The midpoint rule on 4096 cells is
    // exact to well below the pilot's sampling error.
    constexpr int kCells = 4096;
    first = 0.0;
    second = 0.0;
    double lo_bound = distribution.lower();
    double hi_bound = distribution.upper();
    if (!std::isfinite(hi_bound)) {
      hi_bound = std::max(1.0, trace_length.mean);
      while (distribution.cdf(hi_bound) < 1.0 - 1e-12) hi_bound *= 2.0;
    }
    if (!std::isfinite(lo_bound)) lo_bound = -hi_bound;
    for (int cell = 0; cell < kCells; ++cell) {
      const double p = (cell + 0.5) / kCells;
      double lo = lo_bound;
      double hi = hi_bound;
      for (int it = 0; it < 100 && hi - lo > 1e-12 * std::max(1.0, std::abs(hi)); ++it) {
        const double mid = 0.5 * (lo + hi);
        (distribution.cdf(mid) < p ? lo : hi) = mid;
      }
      const double x = 0.5 * (lo + hi);
      first += x / kCells;
      second += x * x / kCells;
    }
  }
  return (4.0 / kPi) * first * first / second;
}

DiscBudgetExceeded::DiscBudgetExceeded(int set, bool by_size, double expected, double total,
                                       double limit, double margin)
    : std::invalid_argument(budgetMessage(by_size, expected, total, limit, margin)),
      set_(set),
      by_size_(by_size) {}

std::string DiscBudgetExceeded::budgetMessage(bool by_size, double expected, double total,
                                              double limit, double margin) {
  std::ostringstream out;
  out.precision(3);
  out << "the joint sets would draw " << total << " discs, over the limit of " << limit
      << " (raise it with --max-discs); this set draws " << expected;
  if (by_size) {
    out << ", most of them far outside the domain: its largest discs (semi-axis " << margin
        << " m) make it draw centres that far around the domain; check the trace length";
  } else {
    out << "; check its spacing or intensity and the domain size";
  }
  return out.str();
}

FractureNetwork generateNetwork(const DfnSpec& spec, std::uint64_t seed,
                                const GenerationLimits& limits) {
  if (!(spec.domain.volume() > 0.0)) {
    throw std::invalid_argument("the domain has no volume");
  }
  FractureNetwork network;
  network.domain = spec.domain;
  // Every joint set is planned (pilot sample only) before any disc is drawn, so that a
  // network over the budget is refused at once, before the work and the memory.
  std::vector<JointSetPlan> plans;
  double total = 0.0;
  for (std::size_t i = 0; i < spec.joint_sets.size(); ++i) {
    plans.push_back(planJointSet(spec.joint_sets[i], static_cast<int>(i), spec.domain, seed));
    total += plans.back().expected;
  }
  if (!(total <= limits.max_discs)) {
    std::size_t worst = 0;
    for (std::size_t i = 1; i < plans.size(); ++i) {
      if (plans[i].expected > plans[worst].expected) worst = i;
    }
    const JointSetPlan& plan = plans[worst];
    // The margin drives the count when it enlarges the domain's volume tenfold or more.
    const bool by_size = plan.enlarged.volume() >= 10.0 * spec.domain.volume();
    throw DiscBudgetExceeded(static_cast<int>(worst), by_size, plan.expected, total,
                             limits.max_discs, plan.info.margin);
  }
  int set_index = 0;
  for (const JointSetSpec& joint_set : spec.joint_sets) {
    generateJointSet(joint_set, set_index, spec.domain, seed, std::move(plans[set_index]), network);
    ++set_index;
  }
  for (const FaultSpec& fault : spec.faults) {
    generateFault(fault, set_index++, spec.domain, network);
  }
  for (const InterlayerSpec& layer : spec.interlayers) {
    generateInterlayer(layer, set_index++, spec.domain, network);
  }
  for (const PolygonSetSpec& polygons : spec.polygon_sets) {
    generatePolygonSet(polygons, set_index++, spec.domain, network);
  }
  // Ids are born here, 1..N in order (addIfInside already handed these out to slabs).
  for (std::size_t i = 0; i < network.discs.size(); ++i) {
    network.discs[i].id = static_cast<std::int64_t>(i) + 1;
  }
  return network;
}

std::vector<SetStatistics> measureSets(const FractureNetwork& network) {
  std::vector<SetStatistics> stats(network.sets.size());
  std::vector<std::vector<Vec3>> normals(network.sets.size());
  const double volume = network.domain.volume();
  for (const Disc& disc : network.discs) {
    SetStatistics& s = stats[static_cast<std::size_t>(disc.set)];
    const double inside = disc.areaInside(network.domain);
    s.count += 1;
    s.p32 += inside / volume;
    s.p10 += inside * std::abs(disc.normal.dot(network.sets[disc.set].mean_normal)) / volume;
    normals[static_cast<std::size_t>(disc.set)].push_back(disc.normal);
  }
  for (std::size_t i = 0; i < stats.size(); ++i) {
    if (normals[i].empty()) {
      stats[i].mean_normal = network.sets[i].mean_normal;
      continue;
    }
    const FisherEstimate estimate = estimateFisher(normals[i]);
    stats[i].mean_normal = estimate.mean.z() < 0.0 ? Vec3(-estimate.mean) : estimate.mean;
    stats[i].kappa = normals[i].size() >= 2 ? estimate.kappa : 0.0;
  }
  return stats;
}

}  // namespace rockmass::geometry
