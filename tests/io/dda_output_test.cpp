// The files of the dda stage: history.csv and the contacts CSV (exact contents), Matrix
// Market dumps (read back entry by entry), VTU frames with polyhedron cells (decoded with the
// test's own base64 reader) and the ParaView collection (every listed file exists), and the
// summary (everything but "timings" independent of the clock).
#include "io/dda_output.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/dda_summary.h"
#include "tests/support/test_support.h"
#include "tests/support/vtu_reading.h"

namespace rockmass::io {
namespace {

using geometry::Vec3;

TEST(DdaHistoryCsv, ExactContents) {
  // Two monitors over two samples; one name needs CSV quoting. 3-4-0 makes |u| = 5 exact.
  const std::vector<std::string> names = {"P4", "crest, left"};
  const std::vector<MonitorSample> samples = {
      {0.0, 0, Vec3::Zero(), Vec3::Zero()},
      {0.0, 1, Vec3::Zero(), Vec3::Zero()},
      {0.002, 0, Vec3(0.003, -0.004, 0.0), Vec3(0.5, 0.0, -1.25)},
      {0.002, 1, Vec3(0.0, 0.0, -1e-7), Vec3(0.0, 0.0, -0.1)},
  };
  EXPECT_EQ(formatHistoryCsv(names, samples),
            "time,monitor,ux,uy,uz,vx,vy,vz,u\n"
            "0,P4,0,0,0,0,0,0,0\n"
            "0,\"crest, left\",0,0,0,0,0,0,0\n"
            "0.002,P4,0.003,-0.004,0,0.5,0,-1.25,0.005\n"
            "0.002,\"crest, left\",0,0,-1e-07,0,0,-0.1,1e-07\n");
}

TEST(DdaContactsCsv, ExactContents) {
  DdaContactRecord vertex;
  vertex.kind = ContactKind::VertexFace;
  vertex.state = ContactState::Locked;
  vertex.block_i = 2;
  vertex.piece_i = 0;
  vertex.block_j = 1;
  vertex.piece_j = 1;
  vertex.face_j = 5;
  vertex.point = Vec3(0.5, 0.25, 1.0);
  vertex.normal = Vec3(0, 0, 1);
  vertex.gap = -2.5e-5;
  vertex.normal_force = 2500.0;
  vertex.shear_force = 12.5;
  vertex.shear_displacement = 1e-6;
  vertex.joint = 2;
  DdaContactRecord edge = vertex;
  edge.kind = ContactKind::EdgeEdge;
  edge.state = ContactState::Sliding;
  edge.face_j = -1;
  DdaContactRecord open = vertex;
  open.state = ContactState::Open;
  open.gap = 0.001;
  open.normal_force = 0.0;
  open.shear_force = 0.0;
  open.joint = 0;
  EXPECT_EQ(formatContactsCsv({vertex, edge, open}),
            "kind,state,block_i,piece_i,block_j,piece_j,face_j,x,y,z,nx,ny,nz,gap,normal_force,"
            "shear_force,shear_displacement,joint\n"
            "vertex-face,locked,2,0,1,1,5,0.5,0.25,1,0,0,1,-2.5e-05,2500,12.5,1e-06,2\n"
            "edge-edge,sliding,2,0,1,1,-1,0.5,0.25,1,0,0,1,-2.5e-05,2500,12.5,1e-06,2\n"
            "vertex-face,open,2,0,1,1,5,0.5,0.25,1,0,0,1,0.001,0,0,1e-06,0\n");
}

/// Reads a Matrix Market coordinate file back into a dense matrix (mirroring the lower
/// triangle of a symmetric one); `symmetric` tells which form it was.
Eigen::MatrixXd readMatrixMarket(const std::string& text, bool& symmetric) {
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  symmetric = line.find("symmetric") != std::string::npos;
  while (in.peek() == '%') std::getline(in, line);
  int rows = 0, cols = 0, count = 0;
  in >> rows >> cols >> count;
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(rows, cols);
  for (int e = 0; e < count; ++e) {
    int r = 0, c = 0;
    double v = 0;
    in >> r >> c >> v;
    m(r - 1, c - 1) = v;
    if (symmetric) m(c - 1, r - 1) = v;
  }
  EXPECT_TRUE(static_cast<bool>(in)) << "fewer entries than announced";
  return m;
}

TEST(DdaDebugDump, MatrixMarketRoundTripsExactly) {
  // Values that need all 17 digits: the dump must read back bit for bit.
  Eigen::MatrixXd dense(3, 3);
  dense << 4.0 / 3.0, -1e-300, 0.0,  //
      -1e-300, 2e12, 0.1,            //
      0.0, 0.1, 1.0 / 7.0;
  const dda3d::SparseMatrix symmetric_k = dense.sparseView();
  bool symmetric = false;
  const std::string text = formatMatrixMarket(symmetric_k);
  EXPECT_TRUE(text.starts_with("%%MatrixMarket matrix coordinate real symmetric\n"));
  EXPECT_EQ(readMatrixMarket(text, symmetric), dense);
  EXPECT_TRUE(symmetric);
  // The symmetric form lists the lower triangle only: 5 of the 7 nonzeros.
  EXPECT_NE(text.find("\n3 3 5\n"), std::string::npos) << text;

  dense(0, 2) = 1e-3;  // now K != K^T: every entry is written
  const std::string general = formatMatrixMarket(dense.sparseView());
  EXPECT_TRUE(general.starts_with("%%MatrixMarket matrix coordinate real general\n"));
  EXPECT_EQ(readMatrixMarket(general, symmetric), dense);
  EXPECT_FALSE(symmetric);

  const Eigen::Vector3d f(1.0 / 3.0, -9.81e3, 0.0);
  EXPECT_EQ(formatMatrixMarketVector(f),
            "%%MatrixMarket matrix array real general\n% rockmass DDA right-hand side F\n3 1\n"
            "0.3333333333333333\n-9810\n0\n");
}

TEST(DdaDebugDump, WritesTheThreeFilesOfTheStep) {
  const test::TempDir dir("dda_debug_dump");
  const dda3d::SparseMatrix k = Eigen::Matrix2d::Identity().sparseView();
  writeDdaDebugDump(dir.path(), 7, k, Eigen::Vector2d(1, 2), {});
  EXPECT_EQ(test::readFile(dir.path() / "debug_step7_K.mtx"), formatMatrixMarket(k));
  EXPECT_EQ(test::readFile(dir.path() / "debug_step7_F.mtx"),
            formatMatrixMarketVector(Eigen::Vector2d(1, 2)));
  EXPECT_EQ(test::readFile(dir.path() / "debug_step7_contacts.csv"), formatContactsCsv({}));
}

/// Two blocks: a unit cube (one piece) and an L made of two boxes.
DdaFrame smallFrame(int step, double time) {
  DdaFrame frame;
  frame.step = step;
  frame.time = time;
  DdaBlockState cube;
  cube.id = 1;
  cube.material = 0;
  cube.pieces = {geometry::boxPolyhedron({{0, 0, 0}, {1, 1, 1}})};
  cube.displacement = Vec3(0, 0, -0.001 * step);
  cube.velocity = Vec3(0, 0, -0.5);
  cube.stress = {-1e5, -2e5, -3e5, 10, 20, 30};
  DdaBlockState l_block;
  l_block.id = 2;
  l_block.material = 1;
  l_block.pieces = {geometry::boxPolyhedron({{2, 0, 0}, {3, 1, 2}}),
                    geometry::boxPolyhedron({{3, 0, 0}, {4, 1, 1}})};
  frame.blocks = {cube, l_block};
  return frame;
}

TEST(DdaFrameVtu, PolyhedronCellsWithBlockData) {
  const std::string xml = formatDdaFrameVtu(smallFrame(10, 0.02));
  // 3 pieces of 8 vertices: 24 points, 3 polyhedron cells.
  EXPECT_NE(xml.find("NumberOfPoints=\"24\" NumberOfCells=\"3\""), std::string::npos);
  EXPECT_EQ(test::dataArray(xml, "types"), std::vector<double>(3, 42.0));
  EXPECT_EQ(test::dataArray(xml, "offsets"), (std::vector<double>{8, 16, 24}));
  // The face stream of each cell: 6 faces of 4 points = 1 + 6 * 5 = 31 entries per cell,
  // with point ids offset by the cell's first point.
  const std::vector<double> faces = test::dataArray(xml, "faces");
  ASSERT_EQ(faces.size(), 93u);
  EXPECT_EQ(test::dataArray(xml, "faceoffsets"), (std::vector<double>{31, 62, 93}));
  const geometry::Polyhedron box = geometry::boxPolyhedron({{0, 0, 0}, {1, 1, 1}});
  for (int cell = 0; cell < 3; ++cell) {
    const std::size_t at = 31 * static_cast<std::size_t>(cell);
    EXPECT_EQ(faces[at], 6.0);
    EXPECT_EQ(faces[at + 1], 4.0);
    for (int v = 0; v < 4; ++v) EXPECT_EQ(faces[at + 2 + v], 8 * cell + box.faces[0][v]);
  }
  // Block data repeated on each piece of a block.
  EXPECT_EQ(test::dataArray(xml, "block"), (std::vector<double>{1, 2, 2}));
  EXPECT_EQ(test::dataArray(xml, "material"), (std::vector<double>{0, 1, 1}));
  const std::vector<double> displacement = test::dataArray(xml, "displacement");
  ASSERT_EQ(displacement.size(), 9u);
  EXPECT_EQ(displacement[2], -0.01);
  const std::vector<double> stress = test::dataArray(xml, "stress");
  ASSERT_EQ(stress.size(), 18u);
  EXPECT_EQ(stress[2], -3e5);
  EXPECT_EQ(stress[5], 30.0);
  // The stress components are named for ParaView, and the principal stresses follow.
  EXPECT_NE(xml.find("Name=\"stress\" NumberOfComponents=\"6\" ComponentName0=\"xx\" "
                     "ComponentName1=\"yy\" ComponentName2=\"zz\" ComponentName3=\"yz\" "
                     "ComponentName4=\"zx\" ComponentName5=\"xy\""),
            std::string::npos);
  const std::vector<double> principal = test::dataArray(xml, "principal_stress");
  ASSERT_EQ(principal.size(), 9u);
  // The cube's stress is nearly diagonal (-1e5, -2e5, -3e5; shears of 10-30 Pa): s1 the least
  // compressive, shifted by the shears to second order (xy^2 / (xx - yy) + zx^2 / (xx - zz) =
  // 0.011 Pa for s1).
  EXPECT_NEAR(principal[0], -1e5 + 0.011, 1e-3);
  EXPECT_NEAR(principal[2], -3e5, 0.01);
  // The last point is the (4, 1, 1) corner of the L's second piece.
  const std::vector<double> points = test::dataArray(xml, "Points");
  ASSERT_EQ(points.size(), 72u);
  const Vec3 last = box.vertices.back();
  EXPECT_EQ(Vec3(points[69], points[70], points[71]), Vec3(3, 0, 0) + last);
}

TEST(DdaFrame, PrincipalStressesOfARotatedUniaxialStress) {
  // A uniaxial tension of 1 MPa along (1, 1, 0) / sqrt(2): xx = yy = xy = 0.5 MPa. Its
  // principal stresses are (1 MPa, 0, 0) whatever the frame (the eigenvalues of the tensor).
  const Vec3 s = principalStresses({0.5e6, 0.5e6, 0.0, 0.0, 0.0, 0.5e6});
  EXPECT_NEAR(s.x(), 1e6, 1e-6);
  EXPECT_NEAR(s.y(), 0.0, 1e-6);
  EXPECT_NEAR(s.z(), 0.0, 1e-6);
  // Pure shear yz = 2 MPa: +2, 0, -2 MPa, in descending order.
  const Vec3 shear = principalStresses({0.0, 0.0, 0.0, 2e6, 0.0, 0.0});
  EXPECT_NEAR(shear.x(), 2e6, 1e-6);
  EXPECT_NEAR(shear.y(), 0.0, 1e-6);
  EXPECT_NEAR(shear.z(), -2e6, 1e-6);
}

TEST(DdaFrameWriter, AFrameThatCannotBeWrittenIsAnErrorOfTheNextCall) {
  // Frames are written on a thread of their own: a failure there (the folder gone) must reach
  // the caller, at the next write or at finish(), not be lost.
  test::TempDir dir("dda_frames_gone");
  const std::filesystem::path folder = dir.path() / "frames";
  std::filesystem::create_directories(folder);
  DdaFrameWriter writer(folder, 1);
  writer.write(smallFrame(0, 0.0));
  writer.finish();
  EXPECT_TRUE(std::filesystem::exists(folder / "dda_000000.vtu"));
  std::filesystem::remove_all(folder);
  writer.write(smallFrame(1, 0.002));
  EXPECT_ANY_THROW(writer.finish());
}

TEST(DdaFrameWriter, CollectionListsOnlyWrittenFrames) {
  const test::TempDir dir("dda_frames");
  DdaFrameWriter writer(dir.path(), 10);
  for (int step = 0; step <= 25; ++step) {
    if (writer.due(step)) writer.write(smallFrame(step, 0.002 * step));
  }
  writer.write(smallFrame(25, 0.05));  // the last step, always written
  writer.write(smallFrame(25, 0.05));  // once only
  ASSERT_EQ(writer.entries().size(), 4u);
  const std::string pvd = test::readFile(dir.path() / "dda.pvd");
  EXPECT_EQ(pvd,
            "<?xml version=\"1.0\"?>\n"
            "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            "  <Collection>\n"
            "    <DataSet timestep=\"0\" group=\"\" part=\"0\" file=\"dda_000000.vtu\"/>\n"
            "    <DataSet timestep=\"0.02\" group=\"\" part=\"0\" file=\"dda_000010.vtu\"/>\n"
            "    <DataSet timestep=\"0.04\" group=\"\" part=\"0\" file=\"dda_000020.vtu\"/>\n"
            "    <DataSet timestep=\"0.05\" group=\"\" part=\"0\" file=\"dda_000025.vtu\"/>\n"
            "  </Collection>\n"
            "</VTKFile>\n");
  // Every referenced file exists and holds the frame of its step.
  for (const PvdEntry& entry : writer.entries()) {
    const std::string xml = test::readFile(dir.path() / entry.file);
    ASSERT_FALSE(xml.empty()) << entry.file;
    const int step = std::stoi(entry.file.substr(4, 6));
    EXPECT_EQ(xml, formatDdaFrameVtu(smallFrame(step, entry.time)));
  }
  // Nothing else (no temporary files) in the folder: 4 frames + the collection.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()),
                          std::filesystem::directory_iterator()),
            5);
  EXPECT_EQ(ddaFrameFileName(1234567), "dda_1234567.vtu");
}

TEST(DdaSummary, LongRunsKeepEveryStrideThStepAcrossTheRun) {
  // summary.json keeps at most `limit` step records: each time the limit is passed the
  // stride doubles and the records off it go. 1000 steps under a limit of 100: stride 16,
  // the 62 multiples of 16 up to 992; every kept record is a multiple of the stride.
  std::vector<DdaStepRecord> steps;
  int stride = 1;
  for (int step = 1; step <= 1000; ++step) {
    DdaStepRecord r;
    r.step = step;
    keepStepRecord(steps, stride, r, 100);
  }
  EXPECT_EQ(stride, 16);
  ASSERT_EQ(steps.size(), 62u);
  EXPECT_EQ(steps.front().step, 16);
  EXPECT_EQ(steps.back().step, 992);
  for (const DdaStepRecord& r : steps) EXPECT_EQ(r.step % 16, 0);
  // steps.csv has every step: one row per record, no wall-clock times.
  DdaStepRecord r;
  r.step = 7;
  r.time = 0.25;
  r.time_step = 0.001;
  r.contacts = 4;
  r.open = 1;
  r.locked = 3;
  r.open_close_iterations = 2;
  r.max_displacement = 1.5e-5;
  r.phase_seconds = {{"solve", 0.5}};
  EXPECT_EQ(stepsCsvHeader(),
            "step,time,time_step,contacts,open,sliding,locked,iterations,retries,"
            "max_displacement,max_penetration\n");
  EXPECT_EQ(formatStepsRow(r), "7,0.25,0.001,4,1,0,3,2,0,1.5e-05,0\n");
}

TEST(DdaSummary, StepStatisticsAndTimingsApart) {
  RunInfo run;
  run.command = "dda";
  run.name = "tiny";
  run.seed = 7;
  run.effects = {"gravity", "contacts", "inertia"};
  run.timings = {{"cut", 0.5}, {"dda", 2.0}};
  DdaRunSummary dda;
  dda.blocks = 3;
  dda.unknowns = 36;
  dda.solver = "cholmod";
  dda.steps_requested = 2;
  dda.monitors = {{"P1", 2, Vec3(0, 0, -0.004)}};
  DdaStepRecord first;
  first.step = 1;
  first.time = 0.001;
  first.time_step = 0.001;
  first.contacts = 8;
  first.open = 2;
  first.sliding = 1;
  first.locked = 5;
  first.open_close_iterations = 3;
  first.phase_seconds = {{"detect", 0.25}, {"solve", 0.5}};
  DdaStepRecord second = first;
  second.step = 2;
  second.time = 0.002;
  second.contacts = 9;
  second.phase_seconds = {{"detect", 0.125}, {"assemble", 0.0625}, {"solve", 0.5}};
  dda.steps = {first, second};

  const nlohmann::json j = nlohmann::json::parse(formatDdaSummary(run, dda));
  EXPECT_EQ(j["blocks"], 3);
  EXPECT_EQ(j["steps_taken"], 2);
  // The default scheme with its spectral radius; Shi's scheme has no parameter.
  EXPECT_EQ(j["time_integration"],
            nlohmann::json({{"scheme", "bossak"}, {"spectral_radius", 0.0}}));
  DdaRunSummary shi = dda;
  shi.time_integration = "shi";
  EXPECT_EQ(nlohmann::json::parse(formatDdaSummary(run, shi))["time_integration"],
            nlohmann::json({{"scheme", "shi"}}));
  EXPECT_EQ(j["steps"]["contacts"], nlohmann::json::array({8, 9}));
  EXPECT_EQ(j["steps"]["iterations"], nlohmann::json::array({3, 3}));
  EXPECT_EQ(j["monitors"][0]["u"], 0.004);
  EXPECT_EQ(j["effects"], nlohmann::json::array({"gravity", "contacts", "inertia"}));
  // Per-phase totals are sums over steps (binary fractions: exact); a phase missing in a
  // step counts 0 there.
  EXPECT_EQ(j["timings"]["dda_phases"]["detect"], 0.375);
  EXPECT_EQ(j["timings"]["dda_steps"]["assemble"], nlohmann::json::array({0.0, 0.0625}));
  EXPECT_EQ(j["timings"]["dda"], 2.0);

  // Other timings, same run otherwise: only "timings" differs.
  dda.steps[0].phase_seconds = {{"detect", 9.0}};
  run.timings = {{"cut", 1.5}};
  nlohmann::json other = nlohmann::json::parse(formatDdaSummary(run, dda));
  nlohmann::json same = j;
  other.erase("timings");
  same.erase("timings");
  EXPECT_EQ(other.dump(), same.dump());
  EXPECT_EQ(std::string(formatDdaSummary(run, dda)), formatDdaSummary(run, dda));
}

}  // namespace
}  // namespace rockmass::io
