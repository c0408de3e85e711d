#include "io/block_output.h"

#include <map>
#include <stdexcept>

#include "blocks/volume_statistics.h"
#include "io/atomic_file.h"
#include "io/summary_json.h"
#include "io/vtu.h"

namespace rockmass::io {
namespace {

using Json = SummaryJson;

/// The material's name, or "none" for -1.
std::string materialName(int material, const std::vector<Material>& materials) {
  if (material < 0 || material >= static_cast<int>(materials.size())) return "none";
  return materials[static_cast<std::size_t>(material)].name;
}

/// The indices in `welder`'s points of the vertices of `shape`, in `point_of`.
void weldVertices(PointWelder& welder, const geometry::Polyhedron& shape,
                  std::vector<std::int64_t>& point_of) {
  point_of.clear();
  for (const geometry::Vec3& v : shape.vertices)
    point_of.push_back(welder.index(v.x(), v.y(), v.z()));
}

}  // namespace

std::string formatBlocksCsv(const blocks::BlockModel& model, const std::vector<Material>& materials,
                            const std::vector<std::string>& structure_names) {
  std::string out = "id,volume,cx,cy,cz,material,pieces,xmin,ymin,zmin,xmax,ymax,zmax,structure\n";
  for (const blocks::Block& b : model.blocks) {
    const geometry::Vec3 c = b.mass.centroid();
    out += std::to_string(b.id) + ',' + formatDouble(b.mass.volume);
    for (int a = 0; a < 3; ++a) out += ',' + formatDouble(c[a]);
    out += ',' + materialName(b.material, materials) + ',' + std::to_string(b.pieces.size());
    for (int a = 0; a < 3; ++a) out += ',' + formatDouble(b.bounds.min[a]);
    for (int a = 0; a < 3; ++a) out += ',' + formatDouble(b.bounds.max[a]);
    // The structure the block belongs to (empty for rock; "structure_<k>" when unnamed).
    out += ',';
    if (b.structure >= 0) {
      const auto k = static_cast<std::size_t>(b.structure);
      out += csvField(k < structure_names.size() ? structure_names[k]
                                                 : "structure_" + std::to_string(k));
    }
    out += '\n';
  }
  return out;
}

std::string formatBlocksVtu(const blocks::BlockModel& model) {
  VtuPiece vtu;
  PointWelder welder(vtu.points);
  std::vector<std::int32_t> id, material;
  std::vector<double> volume, piece_volume;
  std::vector<std::int64_t> point_of;
  for (const blocks::Block& b : model.blocks) {
    for (const blocks::Piece& p : b.pieces) {
      weldVertices(welder, p.shape, point_of);
      vtu.connectivity.insert(vtu.connectivity.end(), point_of.begin(), point_of.end());
      vtu.offsets.push_back(static_cast<std::int64_t>(vtu.connectivity.size()));
      vtu.types.push_back(42);
      vtu.faces.push_back(static_cast<std::int64_t>(p.shape.faces.size()));
      for (const std::vector<int>& face : p.shape.faces) {
        vtu.faces.push_back(static_cast<std::int64_t>(face.size()));
        for (int v : face) vtu.faces.push_back(point_of[static_cast<std::size_t>(v)]);
      }
      vtu.faceoffsets.push_back(static_cast<std::int64_t>(vtu.faces.size()));
      id.push_back(b.id);
      material.push_back(b.material);
      volume.push_back(b.mass.volume);
      piece_volume.push_back(geometry::massProperties(p.shape).volume);
    }
  }
  vtu.cell_data.push_back(makeVtuArray("id", id));
  vtu.cell_data.push_back(makeVtuArray("material", material));
  vtu.cell_data.push_back(makeVtuArray("volume", volume));
  vtu.cell_data.push_back(makeVtuArray("piece_volume", piece_volume));
  return formatVtu(vtu);
}

std::string formatFacesVtu(const blocks::BlockModel& model,
                           const std::function<int(const blocks::FaceSource&)>& joint_of) {
  VtuPiece vtu;
  PointWelder welder(vtu.points);
  std::vector<std::int32_t> block, piece_index, kind, source, joint;
  std::vector<std::int64_t> point_of;
  for (const blocks::Block& b : model.blocks) {
    for (std::size_t p = 0; p < b.pieces.size(); ++p) {
      const blocks::Piece& piece = b.pieces[p];
      const std::vector<std::vector<int>>& faces = piece.shape.faces;
      weldVertices(welder, piece.shape, point_of);
      for (std::size_t f = 0; f < faces.size(); ++f) {
        const blocks::FaceSource from =
            f < piece.face_sources.size() ? piece.face_sources[f] : blocks::FaceSource{};
        if (from.kind == blocks::FaceKind::Fictitious) continue;
        for (int v : faces[f]) vtu.connectivity.push_back(point_of[static_cast<std::size_t>(v)]);
        vtu.offsets.push_back(static_cast<std::int64_t>(vtu.connectivity.size()));
        vtu.types.push_back(7);
        block.push_back(b.id);
        piece_index.push_back(static_cast<std::int32_t>(p));
        kind.push_back(from.kind == blocks::FaceKind::Disc       ? 0
                       : from.kind == blocks::FaceKind::Boundary ? 1
                                                                 : 2);
        source.push_back(from.id);
        joint.push_back(joint_of(from));
      }
    }
  }
  vtu.cell_data.push_back(makeVtuArray("block", block));
  vtu.cell_data.push_back(makeVtuArray("piece", piece_index));
  vtu.cell_data.push_back(makeVtuArray("kind", kind));
  vtu.cell_data.push_back(makeVtuArray("source", source));
  vtu.cell_data.push_back(makeVtuArray("joint", joint));
  return formatVtu(vtu);
}

namespace {

/// Sets j["volume_stats"] {min, max, mean} and j["weibull"] {shape, scale} (maximum
/// likelihood) of `volumes`; null when there is no volume, or too few to fit.
void putVolumeStatistics(Json& j, const std::vector<double>& volumes) {
  if (!volumes.empty()) {
    const blocks::VolumeStatistics s = blocks::volumeStatistics(volumes);
    j["volume_stats"] = {{"min", s.min}, {"max", s.max}, {"mean", s.mean}};
  } else {
    j["volume_stats"] = nullptr;
  }
  try {
    const blocks::WeibullFit fit = blocks::fitWeibull(volumes);
    j["weibull"] = {{"shape", fit.shape}, {"scale", fit.scale}};
  } catch (const std::invalid_argument&) {
    j["weibull"] = nullptr;  // fewer than 2 blocks, or all of one size
  }
}

}  // namespace

std::string formatBlocksSummary(const RunInfo& run, const geometry::FractureNetwork& network,
                                const blocks::BlockModel& model, const CutInfo& cut,
                                const std::vector<Material>& materials) {
  Json j = summaryHeader(run);
  std::int64_t cutting = 0;
  for (const geometry::Disc& d : network.discs) cutting += d.cuts;
  j["discs"] = network.discs.size();
  j["cutting_discs"] = cutting;
  j["cutter"] = cut.cutter;
  j["disc_segments"] = cut.disc_segments;
  j["blocks"] = model.blocks.size();
  j["pieces"] = cut.pieces;
  // The rock alone: structures (the dam) lie outside the domain box, so only the rock
  // blocks add up to the domain volume, and only they make the rock mass's block-size
  // distribution (Figure 7 of the paper).
  std::vector<double> rock;
  double structure_volume = 0.0;
  for (const blocks::Block& b : model.blocks) {
    if (b.structure < 0) {
      rock.push_back(b.mass.volume);
    } else {
      structure_volume += b.mass.volume;
    }
  }
  double rock_total = 0.0;
  for (double v : rock) rock_total += v;
  Json r;
  r["blocks"] = rock.size();
  r["total_volume"] = rock_total;
  r["volume_error"] =
      model.domain_volume > 0 ? (rock_total - model.domain_volume) / model.domain_volume : 0.0;
  putVolumeStatistics(r, rock);
  std::vector<double> volumes;
  for (const blocks::Block& b : model.blocks) volumes.push_back(b.mass.volume);
  double total = 0.0;
  for (double v : volumes) total += v;
  j["total_volume"] = total;
  j["domain_volume"] = model.domain_volume;
  // Of the rock blocks: the cut's error (structures lie outside the domain).
  j["volume_error"] = r["volume_error"];
  putVolumeStatistics(j, volumes);
  j["rock"] = r;
  j["structure_volume"] = structure_volume;
  j["adjacencies"] = model.adjacency.size();
  j["inconsistent_contacts"] = cut.inconsistent_contacts;
  std::map<int, std::pair<std::int64_t, double>> per_material;
  for (const blocks::Block& b : model.blocks) {
    per_material[b.material].first += 1;
    per_material[b.material].second += b.mass.volume;
  }
  Json mats = Json::array();
  for (const auto& [m, cv] : per_material) {
    mats.push_back(
        {{"material", materialName(m, materials)}, {"blocks", cv.first}, {"volume", cv.second}});
  }
  j["materials"] = mats;
  // The legend of the integer `material` of blocks.vtu and the DDA frames (scene order).
  Json names = Json::array();
  for (const Material& material : materials) names.push_back(material.name);
  j["material_names"] = names;
  appendTimings(j, run.timings);
  return j.dump(2) + "\n";
}

}  // namespace rockmass::io
