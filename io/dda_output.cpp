#include "io/dda_output.h"

#include <Eigen/Eigenvalues>

#include <cstdio>
#include <stdexcept>

#include "io/atomic_file.h"
#include "io/vtu.h"

namespace rockmass::io {
namespace {

/// VTK cell type of a general polyhedron.
constexpr std::uint8_t kVtkPolyhedron = 42;

/// "x,y,z" with round-trip precision.
std::string csvVector(const geometry::Vec3& v) {
  return formatDouble(v.x()) + ',' + formatDouble(v.y()) + ',' + formatDouble(v.z());
}

const char* contactKindName(ContactKind kind) {
  switch (kind) {
    case ContactKind::VertexFace:
      return "vertex-face";
    case ContactKind::FacePoint:
      return "face-point";
    case ContactKind::EdgeEdge:
      break;
  }
  return "edge-edge";
}

/// Appends `piece` as one polyhedron cell: its points, connectivity and face stream.
void appendPolyhedronCell(VtuPiece& out, const geometry::Polyhedron& piece) {
  const auto first = static_cast<std::int64_t>(out.points.size() / 3);
  for (const geometry::Vec3& v : piece.vertices) {
    out.points.insert(out.points.end(), {v.x(), v.y(), v.z()});
  }
  for (std::size_t i = 0; i < piece.vertices.size(); ++i) {
    out.connectivity.push_back(first + static_cast<std::int64_t>(i));
  }
  out.offsets.push_back(static_cast<std::int64_t>(out.connectivity.size()));
  out.types.push_back(kVtkPolyhedron);
  out.faces.push_back(static_cast<std::int64_t>(piece.faces.size()));
  for (const std::vector<int>& face : piece.faces) {
    out.faces.push_back(static_cast<std::int64_t>(face.size()));
    for (int v : face) out.faces.push_back(first + v);
  }
  out.faceoffsets.push_back(static_cast<std::int64_t>(out.faces.size()));
}

/// True when K equals its transpose entry by entry.
bool exactlySymmetric(const dda3d::SparseMatrix& k) {
  if (k.rows() != k.cols()) return false;
  const dda3d::SparseMatrix transpose = k.transpose();
  const dda3d::SparseMatrix difference = k - transpose;
  for (int c = 0; c < difference.outerSize(); ++c) {
    for (dda3d::SparseMatrix::InnerIterator it(difference, c); it; ++it) {
      if (it.value() != 0.0) return false;
    }
  }
  return true;
}

}  // namespace

const char* contactStateName(ContactState state) {
  switch (state) {
    case ContactState::Open:
      return "open";
    case ContactState::Sliding:
      return "sliding";
    case ContactState::Locked:
      return "locked";
  }
  return "unknown";
}

std::string historyCsvHeader() {
  return "time,monitor,ux,uy,uz,vx,vy,vz,u\n";
}

std::string formatHistoryRow(const std::vector<std::string>& monitor_names,
                             const MonitorSample& s) {
  std::string out = formatDouble(s.time);
  out += ',';
  out += csvField(monitor_names.at(static_cast<std::size_t>(s.monitor)));
  out += ',' + csvVector(s.displacement) + ',' + csvVector(s.velocity) + ',' +
         formatDouble(s.displacement.norm()) + '\n';
  return out;
}

std::string boltsCsvHeader() {
  return "time,bolt,force,state\n";
}

std::string formatBoltRows(double time, const std::vector<BoltSample>& bolts) {
  std::string out;
  for (const BoltSample& b : bolts) {
    out += formatDouble(time) + ',' + csvField(b.name) + ',' + formatDouble(b.force) + ',' +
           b.state + '\n';
  }
  return out;
}

std::string formatHistoryCsv(const std::vector<std::string>& monitor_names,
                             const std::vector<MonitorSample>& samples) {
  std::string out = historyCsvHeader();
  for (const MonitorSample& s : samples) out += formatHistoryRow(monitor_names, s);
  return out;
}

geometry::Vec3 principalStresses(const std::array<double, 6>& voigt) {
  Eigen::Matrix3d s;
  s << voigt[0], voigt[5], voigt[4],  //
      voigt[5], voigt[1], voigt[3],   //
      voigt[4], voigt[3], voigt[2];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(s, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d ascending = solver.eigenvalues();
  return {ascending[2], ascending[1], ascending[0]};
}

std::string formatDdaFrameVtu(const DdaFrame& frame) {
  VtuPiece piece;
  std::vector<std::int32_t> ids, materials;
  std::vector<double> displacement, velocity, stress, principal, eccentricity;
  for (const DdaBlockState& block : frame.blocks) {
    for (const geometry::Polyhedron& shape : block.pieces) {
      appendPolyhedronCell(piece, shape);
      ids.push_back(block.id);
      materials.push_back(block.material);
      displacement.insert(displacement.end(),
                          {block.displacement.x(), block.displacement.y(), block.displacement.z()});
      velocity.insert(velocity.end(), {block.velocity.x(), block.velocity.y(), block.velocity.z()});
      stress.insert(stress.end(), block.stress.begin(), block.stress.end());
      const geometry::Vec3 s = principalStresses(block.stress);
      principal.insert(principal.end(), {s.x(), s.y(), s.z()});
      eccentricity.push_back(block.eccentricity);
    }
  }
  piece.cell_data.push_back(makeVtuArray("block", ids));
  piece.cell_data.push_back(makeVtuArray("material", materials));
  piece.cell_data.push_back(makeVtuArray("displacement", displacement, 3));
  piece.cell_data.push_back(makeVtuArray("velocity", velocity, 3));
  piece.cell_data.push_back(makeVtuArray("stress", stress, 6));
  piece.cell_data.back().component_names = {"xx", "yy", "zz", "yz", "zx", "xy"};
  piece.cell_data.push_back(makeVtuArray("principal_stress", principal, 3));
  piece.cell_data.back().component_names = {"s1", "s2", "s3"};
  piece.cell_data.push_back(makeVtuArray("eccentricity", eccentricity));
  // What the frame is, for the reader (ParaView's Information panel): its time and step,
  // and why velocity or stress may be zero everywhere: static_mode = 1, velocities reset
  // every step; deformable = 0, rigid blocks keep their initial stress.
  piece.field_data.push_back(makeVtuArray("TimeValue", std::vector<double>{frame.time}));
  piece.field_data.push_back(makeVtuArray("step", std::vector<std::int32_t>{frame.step}));
  piece.field_data.push_back(makeVtuArray(
      "static_mode", std::vector<std::uint8_t>{static_cast<std::uint8_t>(frame.static_mode)}));
  piece.field_data.push_back(makeVtuArray(
      "deformable", std::vector<std::uint8_t>{static_cast<std::uint8_t>(frame.deformable)}));
  return formatVtu(piece);
}

std::string ddaFrameFileName(int step) {
  char name[32];
  std::snprintf(name, sizeof name, "dda_%06d.vtu", step);
  return name;
}

std::string formatPvd(const std::vector<PvdEntry>& entries) {
  std::string out =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const PvdEntry& entry : entries) {
    out += "    <DataSet timestep=\"" + formatDouble(entry.time) +
           "\" group=\"\" part=\"0\" file=\"" + entry.file + "\"/>\n";
  }
  out += "  </Collection>\n</VTKFile>\n";
  return out;
}

PvdSeries::PvdSeries(std::filesystem::path folder, std::string pvd_name)
    : folder_(std::move(folder)), pvd_name_(std::move(pvd_name)) {}

void PvdSeries::add(double time, const std::string& file, const std::string& text) {
  writeFileAtomically(folder_ / file, text);
  entries_.push_back({time, file});
  writeFileAtomically(folder_ / pvd_name_, formatPvd(entries_));
}

DdaFrameWriter::DdaFrameWriter(std::filesystem::path folder, int every, bool in_background)
    : series_(std::move(folder), "dda.pvd"), every_(every), in_background_(in_background) {
  if (every < 1) throw std::invalid_argument("DdaFrameWriter: frame interval must be >= 1");
}

DdaFrameWriter::~DdaFrameWriter() {
  try {
    finish();
  } catch (...) {  // a destructor must not throw; finish() reports it
  }
}

void DdaFrameWriter::write(DdaFrame frame) {
  if (frame.step <= last_step_) return;
  finish();
  last_step_ = frame.step;
  auto add = [this, frame = std::move(frame)] {
    series_.add(frame.time, ddaFrameFileName(frame.step), formatDdaFrameVtu(frame));
  };
  if (in_background_) {
    pending_ = std::async(std::launch::async, std::move(add));
  } else {
    add();
  }
}

void DdaFrameWriter::finish() {
  if (pending_.valid()) pending_.get();
}

std::string formatMatrixMarket(const dda3d::SparseMatrix& k) {
  const bool symmetric = exactlySymmetric(k);
  std::string body;
  long long count = 0;
  for (int c = 0; c < k.outerSize(); ++c) {
    for (dda3d::SparseMatrix::InnerIterator it(k, c); it; ++it) {
      if (symmetric && it.row() < it.col()) continue;
      body += std::to_string(it.row() + 1) + ' ' + std::to_string(it.col() + 1) + ' ' +
              formatDouble(it.value()) + '\n';
      ++count;
    }
  }
  return std::string("%%MatrixMarket matrix coordinate real ") +
         (symmetric ? "symmetric" : "general") + "\n% rockmass DDA system matrix K (SI units)\n" +
         std::to_string(k.rows()) + ' ' + std::to_string(k.cols()) + ' ' + std::to_string(count) +
         '\n' + body;
}

std::string formatMatrixMarketVector(const Eigen::VectorXd& v) {
  std::string out = "%%MatrixMarket matrix array real general\n% rockmass DDA right-hand side F\n" +
                    std::to_string(v.size()) + " 1\n";
  for (Eigen::Index i = 0; i < v.size(); ++i) out += formatDouble(v[i]) + '\n';
  return out;
}

std::string formatContactsCsv(const std::vector<DdaContactRecord>& contacts) {
  std::string out =
      "kind,state,block_i,piece_i,block_j,piece_j,face_j,x,y,z,nx,ny,nz,gap,normal_force,"
      "shear_force,shear_displacement,joint\n";
  for (const DdaContactRecord& c : contacts) {
    out += std::string(contactKindName(c.kind)) + ',' + contactStateName(c.state) + ',' +
           std::to_string(c.block_i) + ',' + std::to_string(c.piece_i) + ',' +
           std::to_string(c.block_j) + ',' + std::to_string(c.piece_j) + ',' +
           std::to_string(c.face_j) + ',' + csvVector(c.point) + ',' + csvVector(c.normal) + ',' +
           formatDouble(c.gap) + ',' + formatDouble(c.normal_force) + ',' +
           formatDouble(c.shear_force) + ',' + formatDouble(c.shear_displacement) + ',' +
           std::to_string(c.joint) + '\n';
  }
  return out;
}

void writeDdaDebugDump(const std::filesystem::path& folder, int step, const dda3d::SparseMatrix& k,
                       const Eigen::VectorXd& f, const std::vector<DdaContactRecord>& contacts) {
  const std::string prefix = "debug_step" + std::to_string(step) + "_";
  writeFileAtomically(folder / (prefix + "K.mtx"), formatMatrixMarket(k));
  writeFileAtomically(folder / (prefix + "F.mtx"), formatMatrixMarketVector(f));
  writeFileAtomically(folder / (prefix + "contacts.csv"), formatContactsCsv(contacts));
}

}  // namespace rockmass::io
