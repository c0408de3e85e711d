// Prints a bitwise hash of the fast cutter's block model for benchmark scenes, to check that a
// change of the cutter's implementation keeps its results bit-identical (every block, piece,
// vertex coordinate, face loop and source, mass properties and adjacency entry). Usage:
//   blocks_model_hash [-rK] [n ...]   (default: 100 300; scenes of the size series,
//   sizeSeriesScene; -rK cuts each scene K times, for profiling with perf stat / perf record)
// Compare the printed lines before and after a change (docs/performance.md, blocks).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "blocks/fast_cutter.h"
#include "scenarios/disc_scenes.h"

namespace {

using namespace rockmass::blocks;

/// FNV-1a over raw bytes.
struct Hash {
  std::uint64_t h = 1469598103934665603ULL;
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ULL;
  }
  void number(double x) { bytes(&x, sizeof x); }
  void integer(long long x) { bytes(&x, sizeof x); }
};

std::uint64_t hashModel(const BlockModel& model) {
  Hash h;
  h.integer(static_cast<long long>(model.blocks.size()));
  for (const Block& block : model.blocks) {
    h.integer(block.id);
    h.integer(block.material);
    h.number(block.mass.volume);
    for (int a = 0; a < 3; ++a) h.number(block.mass.first[a]);
    for (int a = 0; a < 9; ++a) h.number(block.mass.second.data()[a]);
    h.number(block.folded_volume);
    h.integer(static_cast<long long>(block.pieces.size()));
    for (const Piece& piece : block.pieces) {
      for (const auto& v : piece.shape.vertices) h.bytes(v.data(), 3 * sizeof(double));
      for (const auto& face : piece.shape.faces) {
        h.integer(static_cast<long long>(face.size()));
        h.bytes(face.data(), face.size() * sizeof(int));
      }
      for (const FaceSource& s : piece.face_sources) {
        h.integer(static_cast<int>(s.kind));
        h.integer(s.id);
      }
    }
  }
  for (const Adjacency& a : model.adjacency) {
    h.integer(a.block_a);
    h.integer(a.block_b);
    h.number(a.area);
    h.integer(static_cast<int>(a.source.kind));
    h.integer(a.source.id);
  }
  return h.h;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes;
  int repeat = 1;
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], "-r", 2) == 0) {
      repeat = std::max(1, std::atoi(argv[i] + 2));
    } else {
      sizes.push_back(std::atoi(argv[i]));
    }
  }
  if (sizes.empty()) sizes = {100, 300};
  for (int n : sizes) {
    const rockmass::geometry::FractureNetwork network = randomDiscNetwork(sizeSeriesScene(n));
    const CutInput input = boxCutInput(network, 24);
    FastCutReport report;
    BlockModel model = cutFast(input, &report);
    for (int k = 1; k < repeat; ++k) model = cutFast(input, &report);
    std::fprintf(stderr, "size %d: regions %d polygons %d piece tests %lld splits %lld\n", n,
                 report.regions, report.cutting_polygons, report.piece_tests, report.splits);
    std::printf("size %d: blocks %zu pieces %d adjacency %zu hash %016llx\n", n,
                model.blocks.size(), report.pieces, model.adjacency.size(),
                static_cast<unsigned long long>(hashModel(model)));
  }
  return 0;
}
