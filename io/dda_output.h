#pragma once
/// Files of the `dda` stage: history.csv (monitors), dda.pvd + dda_<step>.vtu frames (block
/// motion for ParaView) and the debug dump of one step (system matrix, right-hand side and
/// contacts). Written from the plain structs below, which the CLI fills from the engine's
/// state, so the writers do not depend on the engine's internals.
#include <array>
#include <filesystem>
#include <future>
#include <string>
#include <vector>

#include "dda3d/linear_solver.h"
#include "geometry/polyhedron.h"
#include "geometry/vec.h"
#include "io/summary.h"

namespace rockmass::io {

// ---------------------------------------------------------------------------------------------
// history.csv

/// One monitor reading.
struct MonitorSample {
  double time = 0.0;                                     ///< simulated time since 0 (s)
  int monitor = 0;                                       ///< index into the monitor names
  geometry::Vec3 displacement = geometry::Vec3::Zero();  ///< of the point since time 0 (m)
  geometry::Vec3 velocity = geometry::Vec3::Zero();      ///< of the point (m/s)
};

/// history.csv: `time,monitor,ux,uy,uz,vx,vy,vz,u`, one row per sample in the given order;
/// monitor is the monitor's name, u = |(ux, uy, uz)| (m). Numbers round-trip exactly.
std::string formatHistoryCsv(const std::vector<std::string>& monitor_names,
                             const std::vector<MonitorSample>& samples);
/// history.csv's header line, with its newline (for a file written as the run goes).
std::string historyCsvHeader();
/// One history.csv row, with its newline.
std::string formatHistoryRow(const std::vector<std::string>& monitor_names,
                             const MonitorSample& sample);

/// bolts.csv's header line: `time,bolt,force,state`, with its newline.
std::string boltsCsvHeader();
/// One bolts.csv row per bolt at `time`, each with its newline.
std::string formatBoltRows(double time, const std::vector<BoltSample>& bolts);

// ---------------------------------------------------------------------------------------------
// dda.pvd + frames

/// One block in an output frame.
struct DdaBlockState {
  int id = 0;                                            ///< block id (as in blocks.csv)
  int material = 0;                                      ///< material index (scene order)
  std::vector<geometry::Polyhedron> pieces;              ///< convex pieces, current vertices (m)
  geometry::Vec3 displacement = geometry::Vec3::Zero();  ///< of the centroid since time 0 (m)
  geometry::Vec3 velocity = geometry::Vec3::Zero();      ///< of the centroid (m/s)
  /// Stress (Pa) in Voigt order sx, sy, sz, tyz, tzx, txy (tension positive).
  std::array<double, 6> stress{};
  /// The largest eccentricity ratio e / h of its interfaces (dda3d::interfaceEccentricity):
  /// above 1/3 the block bends more than one strain field shows.
  double eccentricity = 0.0;
};

/// The state of every block after `step` accepted steps.
struct DdaFrame {
  int step = 0;                       ///< accepted steps so far (0: the initial state)
  double time = 0.0;                  ///< simulated time (s)
  bool static_mode = false;           ///< static steps: velocities reset to 0 every step
  bool deformable = false;            ///< blocks with strains (else rigid: stress is initial)
  std::vector<DdaBlockState> blocks;  ///< in block order
};

/// The principal stresses s1 >= s2 >= s3 (Pa, tension positive) of a stress in Voigt order
/// (xx, yy, zz, yz, zx, xy).
geometry::Vec3 principalStresses(const std::array<double, 6>& voigt);

/// A frame as VTK XML unstructured grid: one polyhedron cell (type 42) per convex piece, with
/// cell data block (id), material, displacement (3), velocity (3), stress (6: components
/// named xx, yy, zz, yz, zx, xy, Pa, tension positive), principal_stress (3: s1 >= s2 >=
/// s3) and eccentricity (the interfaces' e / h), the block's values repeated on each of its
/// pieces.
std::string formatDdaFrameVtu(const DdaFrame& frame);

/// "dda_<step, 6 digits>.vtu"; wider steps keep all their digits.
std::string ddaFrameFileName(int step);

/// One dataset of a ParaView collection.
struct PvdEntry {
  double time = 0.0;  ///< s
  std::string file;   ///< relative to the .pvd
};

/// A ParaView collection file (.pvd) listing `entries` as time steps.
std::string formatPvd(const std::vector<PvdEntry>& entries);

/// A time series of files in a folder listed by a .pvd collection: after every file the
/// .pvd is rewritten (atomically), so an interrupted run leaves a collection whose every
/// entry exists.
class PvdSeries {
 public:
  PvdSeries(std::filesystem::path folder, std::string pvd_name);
  /// Writes `text` to folder/file (atomically) and lists it at `time`.
  void add(double time, const std::string& file, const std::string& text);
  const std::vector<PvdEntry>& entries() const { return entries_; }

 private:
  std::filesystem::path folder_;
  std::string pvd_name_;
  std::vector<PvdEntry> entries_;
};

/// Writes dda_<step>.vtu frames into a folder and keeps dda.pvd listing them (PvdSeries).
/// With `in_background`, a frame is formatted and written on a thread of its own while the
/// caller goes on (a frame of the Xiangjiaba region, 25 608 pieces, takes 0.35 s to compress
/// and write); one frame at a time, in order, so the files are those of writing each at once.
class DdaFrameWriter {
 public:
  /// Frames go to `folder` (which must exist); a frame is due every `every` steps (>= 1).
  DdaFrameWriter(std::filesystem::path folder, int every, bool in_background = true);
  /// Waits for the frame being written (an error of it is dropped: call finish() to see it).
  ~DdaFrameWriter();
  DdaFrameWriter(const DdaFrameWriter&) = delete;
  DdaFrameWriter& operator=(const DdaFrameWriter&) = delete;
  /// True when `step` is a multiple of the frame interval.
  bool due(int step) const { return step % every_ == 0; }
  /// Writes the frame and updates dda.pvd, after the frame before it is written (whose error,
  /// if any, is thrown here). A frame whose step was already written is ignored, so the
  /// caller may always write the last step.
  void write(DdaFrame frame);
  /// Waits until every frame is written; throws the error of one that could not be.
  void finish();
  /// The frames written so far (finish() first).
  const std::vector<PvdEntry>& entries() {
    finish();
    return series_.entries();
  }

 private:
  PvdSeries series_;
  int every_ = 1;
  int last_step_ = -1;
  bool in_background_ = true;
  std::future<void> pending_;  ///< the frame being written
};

// ---------------------------------------------------------------------------------------------
// Debug dump of one step

/// How a contact was found.
enum class ContactKind { VertexFace, EdgeEdge, FacePoint };
/// Open-close state of a contact.
enum class ContactState { Open, Sliding, Locked };

/// "open", "sliding" or "locked".
const char* contactStateName(ContactState state);

/// One point-to-face contact entry of the dumped step.
struct DdaContactRecord {
  ContactKind kind = ContactKind::VertexFace;
  ContactState state = ContactState::Open;
  int block_i = 0;  ///< block id of the vertex / first edge
  int piece_i = 0;  ///< piece index in block i
  int block_j = 0;  ///< block id of the reference face / second edge
  int piece_j = 0;  ///< piece index in block j
  int face_j = 0;   ///< reference face index in piece j (-1 for edge-edge)
  geometry::Vec3 point = geometry::Vec3::Zero();   ///< contact point P (m)
  geometry::Vec3 normal = geometry::Vec3::Zero();  ///< unit normal out of block j
  double gap = 0.0;                                ///< normal distance d (m), < 0 penetrating
  double normal_force = 0.0;                       ///< N, compression positive
  double shear_force = 0.0;                        ///< N, magnitude
  double shear_displacement = 0.0;                 ///< accumulated shear offset (m)
  /// Joint the contact acts with (index into the scene's joints): that of the faces it lies
  /// on, or default_joint where they carry none (dda3d/contact_joint.h).
  int joint = 0;
};

/// The system matrix in Matrix Market coordinate format (1-based): `symmetric` with the lower
/// triangle when K is exactly symmetric, `general` with every entry otherwise.
std::string formatMatrixMarket(const dda3d::SparseMatrix& k);

/// A vector in Matrix Market array format (one column).
std::string formatMatrixMarketVector(const Eigen::VectorXd& v);

/// contacts CSV: `kind,state,block_i,piece_i,block_j,piece_j,face_j,x,y,z,nx,ny,nz,gap,
/// normal_force,shear_force,shear_displacement,joint`, kind vertex-face | edge-edge, state
/// open | sliding | locked.
std::string formatContactsCsv(const std::vector<DdaContactRecord>& contacts);

/// Writes debug_step<step>_K.mtx, debug_step<step>_F.mtx and debug_step<step>_contacts.csv
/// into `folder` (the system of the step's last open-close iteration).
void writeDdaDebugDump(const std::filesystem::path& folder, int step, const dda3d::SparseMatrix& k,
                       const Eigen::VectorXd& f, const std::vector<DdaContactRecord>& contacts);

}  // namespace rockmass::io
