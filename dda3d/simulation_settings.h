// Settings of a DDA run (scene: analysis.dda): mode, kinematics, time integration, step
// control, contact thresholds and the linear solver.
#pragma once

#include "dda3d/linear_solver.h"

namespace rockmass::dda3d {

/// Dynamic (velocities carried between steps) or static (velocities reset every step).
enum class AnalysisMode { Dynamic, Static };
/// Deformable blocks (12 unknowns) or rigid blocks (6).
enum class Kinematics { Deformable, Rigid };
/// How the inertia term is integrated in time (docs/dda3d.md, "Time integration").
enum class TimeIntegration {
  /// Bossak alpha scheme (Newmark with a weighted inertia), second-order accurate, damping
  /// the stiff contact modes by the spectral radius DdaSettings::spectral_radius.
  Bossak,
  /// Shi's scheme of the formulation doc (Newmark beta = 1/2, gamma = 1): first order, no
  /// damping of stiff modes (a velocity that flips sign every step on contact springs).
  Shi,
};

/// The largest DdaSettings::detection.search_margin (in g2 l0): half the resting reach
/// (0.1 g2 l0), so that a kept step's reach, cut by the motion since the search, stays
/// positive.
constexpr double kMaxSearchMargin = 0.05;

/// Settings of a run (scene: analysis.dda). The defaults are the scene contract's: a scene
/// that omits a key gets the value below (docs/scene-reference.md, "analysis.dda").
struct DdaSettings {
  AnalysisMode mode = AnalysisMode::Dynamic;
  Kinematics kinematics = Kinematics::Deformable;
  /// Share of the velocity (and acceleration) carried to the next step in dynamic mode (1
  /// fully dynamic). Below 1 it is an extra, non-physical velocity damping.
  double dynamic_ratio = 1.0;
  TimeIntegration integration = TimeIntegration::Bossak;
  /// Bossak: spectral radius rho_inf of the scheme for modes much stiffer than M / dt^2 (the
  /// contact springs), in [0, 1]. 0 removes them within two steps; 1 keeps them undamped.
  double spectral_radius = 0.0;
  double time_step = 0.002;  ///< s, the largest step; shrunk and regrown automatically
  /// s, the smallest step the step control may cut to. A step that fails its checks at this
  /// dt stops the run (StepFailure), and so does a run whose accepted steps stay at it for
  /// `max_steps_at_min_time_step` steps in a row (it cannot progress).
  double min_time_step = 1e-9;
  int max_steps_at_min_time_step = 1000;
  /// g2: largest displacement of any vertex in a step as a share of half the domain size.
  double max_displacement_ratio = 0.001;
  /// g3: allowed penetration as a share of half the domain size.
  double allowed_penetration_ratio = 4e-4;
  /// Normal contact penalty (N/m); 0 = automatic: penalty_factor * E_max * block size.
  double penalty = 0.0;
  double penalty_factor = 40.0;      ///< - (automatic penalty)
  double shear_penalty_ratio = 2.5;  ///< k_n / k_s
  /// Fixed points' spring (N/m) as a multiple of the normal contact penalty.
  double fixed_point_penalty_ratio = 10.0;
  /// Per attempt (the 2D reference allows 6 + 2). A pile of 1000 cubes landing on its base
  /// opens and closes a thousand contacts in one step and settles in 20-30 iterations, the
  /// changes falling off as a cascade; with 20 such steps are redone.
  int max_open_close_iterations = 40;
  /// The open-close iteration has settled when no contact closed and at most this share of
  /// the contacts opened or changed between locked and sliding in its last update (rounded
  /// down: below 1 / this many contacts, none may change, the classic rule). Among the 2e5 contacts
  /// of a large model a few always sit at a round-off gap where closing pushes them open and
  /// opening lets them close; with no allowance every step then failed its 20 iterations and cut dt
  /// down to 1e-8 s on the Xiangjiaba foundation. The contacts that changed last keep their
  /// new state for the next step; one that closed always takes another iteration.
  double open_close_tolerance = 1e-4;
  /// A sliding contact's friction f N (+ c A) is a load on the iteration's solve, taken with
  /// the normal force N of the iteration before. In a dynamic run the iteration has settled
  /// only when, for every sliding contact (beyond open_close_tolerance's allowance, counted
  /// with the state changes), that strength differs from the one of this solution's N by at
  /// most this share of the larger, or the sum of such changes over each of its movable blocks
  /// is at most this share of the strength of all that block's closed contacts: the friction
  /// then pairs with the normal force of the same step, and a block's friction impulse is f
  /// times its normal impulse. 1: the friction of the iteration before is accepted, one iteration
  /// late: a cube cut into pieces sliding from rest slid up to 8.5 % farther than limit
  /// equilibrium in 0.1 s (docs/dda3d.md, "Friction with the step's normal force"). Static
  /// runs (velocities reset every step) always take the friction of the iteration before.
  double friction_tolerance = 0.01;
  /// Deformable rock blocks in water (docs/dda3d.md, "Water in deformable blocks"): the share
  /// of the water pressure around a block that its pores carry (Biot's coefficient). 0: the
  /// block is impermeable, and the water on its faces compresses it as any surface load does;
  /// 1: it is saturated by that water (drained), and only the effective stress strains it. The
  /// pore pressure in a block is the water's field at its centroid (of its wetted faces' fields,
  /// those that apply there, weighed by the area they wet). Structures and rigid blocks: no
  /// effect.
  double biot_coefficient = 0.0;
  /// dt multiplier when the iteration fails. At 0.3 a step that failed three times in a row
  /// fell from 2e-3 s below 1e-4 s: landing piles of cubes took such steps (docs/dda3d.md,
  /// "Open-close iteration").
  double iteration_time_step_factor = 0.5;
  int max_step_attempts = 40;  ///< redo limit per step
  /// An open contact closes when d < -this * l0. The 2D reference uses 2e-4, which lets a
  /// contact that opened by round-off sink 2e-4 l0 without resistance and tilts resting
  /// blocks. A contact closed at that depth starts with 1/2 k_n d^2 in its spring, which the
  /// step gives back as motion: at 1e-6 l0 the vibrating corners of two deformable cubes
  /// closed 4e-6 m deep, 113 J in one step against 1 J of kinetic energy, and the pair
  /// bounced apart at dt = 2.5e-4 s. 1e-8 keeps the hysteresis above round-off.
  double close_threshold_ratio = 1e-8;
  /// A closed contact opens when d > T A / k_n + this * l0. The 2D reference's 2e-7 lets a
  /// stiff penalty pull with k_n * 2e-7 l0 (~10^5 N here) before opening, which glues a
  /// wedge to a plane it should leave; 1e-10 keeps only a round-off margin.
  double open_threshold_ratio = 1e-10;
  /// Sub-contact points (m): 0 = the corners of each face carry its contact (their area
  /// weights spread cohesion over the overlap of the faces); > 0 = every face at least two
  /// cells of this size wide both ways is cut into cells of about this size, and a point at
  /// each cell's centroid, carrying the cell's area, is a contact of its own against the
  /// face facing it (docs/stability.md, "Contact points"). Needed where a face contact opens
  /// in part: a base whose heel lifts keeps its cohesion on the compressed part only.
  double contact_point_spacing = 0.0;
  /// Half the domain size l0 (m); 0 = half the largest extent of all blocks' bounding box.
  double half_domain_size = 0.0;
  /// Auto: CHOLMOD up to solver.auto_cholmod_unknowns unknowns; above, CHOLMOD or PCG
  /// (warm-started from the previous step, tolerance autoPcgTolerance()) by the cost of the
  /// first matrix's factorization (SolverKind::Auto, docs/performance.md).
  SolverOptions solver{.kind = SolverKind::Auto};
  /// How the contacts are searched (bench/dda_region_bench.cpp measures each choice,
  /// docs/performance.md).
  struct Detection {
    /// Only the faces, edges and vertices on each block's surface take part (markExterior),
    /// and a corner's copies in a glued block's pieces are one point. Off (the default), the
    /// faces between the pieces of a glued block are searched too: a point pressed into the
    /// block beside such a face can take it as its face (a spring across the block's inside;
    /// docs/dda3d.md, "Contact detection on models cut from a DFN"). Not the default: its
    /// static relaxation settles worse (the Xiangjiaba scene's critical SRF 1.30 against
    /// 1.55, its runs near the answer jittering below the unbalanced-ratio rule without 5
    /// calm steps; the deformable quick box's settled start not at rest within 80 static
    /// steps; docs/dda3d.md). The scene's analysis.dda.surface_only.
    bool surface_only = false;
    /// The broad phase's pairs are kept between steps (CandidatePairs): the same contacts.
    bool keep_pairs = true;
    /// How far (in g2 l0: max_displacement_ratio times the half domain size) every block may
    /// move after a contact search before a step searches again; 0: every step searches.
    /// Between searches the entries are kept, their geometry following their blocks
    /// (refreshContacts), and each step's reach is cut by how far its block has moved since
    /// the search, so no contact the search would find can close unseen. Entries that would
    /// appear or vanish within that motion (a corner crossing a face's boundary) wait for the
    /// next search (docs/dda3d.md, "Contacts kept between steps"). The scene's
    /// analysis.dda.contact_search_margin.
    double search_margin = 1e-3;
    /// On: a face of a block lying on a face of another is carried by the corners of the
    /// convex hull of its vertex entries, the vertices of its pieces inside the face and along
    /// its edges dropped (keepHullCorners): its springs, and where its load goes, then depend
    /// on the face, not on how the cutter split the block into pieces. Off (the default),
    /// every exterior vertex of every piece is an entry. On the Xiangjiaba region it keeps 59 %
    /// of the entries and a step at rest takes 0.70 of the time, but the settling steps take
    /// twice the open-close iterations and the strength reduction's runs near the limit creep
    /// for 100 steps instead of 11-13 before they rest: the main command takes 1.2 times as
    /// long (docs/performance.md, "A face carried by its hull's corners"). The scene's
    /// analysis.dda.contact_hull_corners.
    bool hull_corners = false;
  } detection;
};

/// The relative residual |K d - F| / |F| that SolverKind::Auto gives PCG. The displacement
/// error it leaves must be a small share of the allowed penetration g3 l0 while a step moves
/// vertices by up to g2 l0: a relative error of 1e-2 g3 / g2 in d, divided by 1e3 for the
/// condition number of the block-Jacobi preconditioned K (the residual bounds the error only
/// up to it). 4e-6 with the default g2 = 0.001, g3 = 4e-4; capped at 1e-8 (the .cpp).
double autoPcgTolerance(const DdaSettings& settings);
/// The solver options a run with these settings and `movable` movable blocks uses (Auto
/// resolved; block size set from the kinematics).
SolverOptions resolvedSolverOptions(const DdaSettings& settings, int movable);

}  // namespace rockmass::dda3d
