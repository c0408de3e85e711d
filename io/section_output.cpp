#include "io/section_output.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "io/atomic_file.h"

namespace rockmass::io {

namespace {

using geometry::Vec2;
using geometry::Vec3;

/// The section.csv `kind` of a disc origin.
const char* originKind(geometry::DiscOrigin origin) {
  switch (origin) {
    case geometry::DiscOrigin::JointSet:
      return "joint";
    case geometry::DiscOrigin::Fault:
      return "fault";
    case geometry::DiscOrigin::Interlayer:
      return "interlayer";
    case geometry::DiscOrigin::FabFile:
      return "fab";
  }
  return "joint";
}

/// The section.csv `source` of a block edge.
std::string edgeSource(const blocks::FaceSource& source) {
  switch (source.kind) {
    case blocks::FaceKind::Disc:
      return "disc:" + std::to_string(source.id);
    case blocks::FaceKind::Boundary:
      return "boundary:" + std::to_string(source.id);
    case blocks::FaceKind::Structure:
      return "structure:" + std::to_string(source.id);
    case blocks::FaceKind::Fictitious:
      return "fictitious";
  }
  return "fictitious";
}

/// Index of a disc id in the network (ids are 1..N in order, see FractureNetwork).
const geometry::Disc& discOf(const geometry::FractureNetwork& network, std::int64_t id) {
  return network.discs[static_cast<std::size_t>(id - 1)];
}

/// One CSV row.
void appendRow(std::string& out, const char* kind, std::int64_t id, const std::string& label,
               int part, int vertex, const Vec2& uv, const Vec3& xyz, const std::string& source) {
  out += kind;
  out += ',' + std::to_string(id) + ',' + csvField(label) + ',' + std::to_string(part) + ',' +
         std::to_string(vertex) + ',' + formatDouble(uv.x()) + ',' + formatDouble(uv.y()) + ',' +
         formatDouble(xyz.x()) + ',' + formatDouble(xyz.y()) + ',' + formatDouble(xyz.z()) + ',' +
         source + '\n';
}

/// Fill colours of materials, by index (pale, so that the traces stand out).
constexpr std::array<const char*, 8> kMaterialFill = {"#e8dcc4", "#d9e4ee", "#e3ecd5", "#f0d9d9",
                                                      "#e6dff0", "#f2ebcf", "#d6ece9", "#ece0d2"};

/// A coordinate for the drawing (0.01 px is far below what anyone sees).
std::string px(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2f", value);
  return buffer;
}

/// Escapes text for XML.
std::string xmlText(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

std::string formatSectionCsv(const Section& section, const geometry::FractureNetwork& network,
                             const std::vector<Material>& materials) {
  std::string out = "kind,id,label,part,vertex,u,v,x,y,z,source\n";
  for (const SectionPolygon& polygon : section.polygons) {
    const std::string material =
        polygon.material >= 0 && static_cast<std::size_t>(polygon.material) < materials.size()
            ? materials[static_cast<std::size_t>(polygon.material)].name
            : "";
    for (std::size_t k = 0; k < polygon.points.size(); ++k) {
      appendRow(out, "block", polygon.block, material, polygon.piece, static_cast<int>(k),
                polygon.points[k], section.plane.lift(polygon.points[k]),
                edgeSource(polygon.edges[k]));
    }
  }
  for (const SectionTrace& trace : section.traces) {
    const geometry::Disc& disc = discOf(network, trace.disc);
    const std::string& set = network.sets[static_cast<std::size_t>(trace.set)].name;
    const char* kind = originKind(disc.origin);
    const std::string source = disc.cuts ? "cutting" : "not_cutting";
    appendRow(out, kind, trace.disc, set, trace.part, 0, trace.a, section.plane.lift(trace.a),
              source);
    appendRow(out, kind, trace.disc, set, trace.part, 1, trace.b, section.plane.lift(trace.b),
              source);
  }
  return out;
}

namespace {

/// The drawing's frame: the extent of what is drawn, and the map from section coordinates
/// (m) to SVG pixels.
struct SvgFrame {
  Vec2 lo, hi;
  double span = 0.0;
  double scale = 0.0;  ///< px per metre
  double margin = 40.0, legend = 150.0;
  double width = 0.0, height = 0.0;
  std::string X(const Vec2& p) const { return px(margin + (p.x() - lo.x()) * scale); }
  std::string Y(const Vec2& p) const { return px(margin + 30.0 + (hi.y() - p.y()) * scale); }
};

SvgFrame svgFrame(const Section& section, const geometry::FractureNetwork& network) {
  SvgFrame f;
  f.lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  f.hi = -f.lo;
  const auto extend = [&](const Vec2& p) {
    f.lo = f.lo.cwiseMin(p);
    f.hi = f.hi.cwiseMax(p);
  };
  for (const SectionPolygon& polygon : section.polygons) {
    for (const Vec2& p : polygon.points) extend(p);
  }
  for (const SectionTrace& trace : section.traces) {
    extend(trace.a);
    extend(trace.b);
  }
  if (!(f.lo.x() <= f.hi.x())) {  // nothing crosses the plane: draw the domain's projection
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 p((corner & 1) ? network.domain.max.x() : network.domain.min.x(),
                   (corner & 2) ? network.domain.max.y() : network.domain.min.y(),
                   (corner & 4) ? network.domain.max.z() : network.domain.min.z());
      extend(section.plane.project(p));
    }
  }
  f.span = std::max({f.hi.x() - f.lo.x(), f.hi.y() - f.lo.y(), 1e-9});
  f.scale = 1400.0 / f.span;
  f.width = (f.hi.x() - f.lo.x()) * f.scale + 2 * f.margin + f.legend;
  f.height = (f.hi.y() - f.lo.y()) * f.scale + 2 * f.margin + 30.0;
  return f;
}

/// Pieces filled by material, no stroke (internal cuts are not block outlines), then block
/// outlines: every real (non-fictitious) edge.
void svgPieces(const Section& section, const SvgFrame& f, std::string& out) {
  out += "<g id=\"pieces\" stroke=\"none\">\n";
  for (const SectionPolygon& polygon : section.polygons) {
    out += "<polygon fill=\"" +
           std::string(kMaterialFill[static_cast<std::size_t>(std::max(0, polygon.material)) %
                                     kMaterialFill.size()]) +
           "\" points=\"";
    for (std::size_t k = 0; k < polygon.points.size(); ++k) {
      if (k > 0) out += ' ';
      out += f.X(polygon.points[k]);
      out += ',';
      out += f.Y(polygon.points[k]);
    }
    out += "\"/>\n";
  }
  out += "</g>\n";
  out += "<g id=\"block-outlines\" stroke=\"#404040\" stroke-width=\"0.6\">\n";
  for (const SectionPolygon& polygon : section.polygons) {
    for (std::size_t k = 0; k < polygon.points.size(); ++k) {
      if (polygon.edges[k].kind == blocks::FaceKind::Fictitious) continue;
      const Vec2& a = polygon.points[k];
      const Vec2& b = polygon.points[(k + 1) % polygon.points.size()];
      out += "<line x1=\"" + f.X(a) + "\" y1=\"" + f.Y(a) + "\" x2=\"" + f.X(b) + "\" y2=\"" +
             f.Y(b) + "\"/>\n";
    }
  }
  out += "</g>\n";
}

/// Traces, grouped by kind.
void svgTraces(const Section& section, const geometry::FractureNetwork& network, const SvgFrame& f,
               std::string& out) {
  struct Style {
    const char* id;
    const char* stroke;
    const char* width;
  };
  const auto styleOf = [&](const geometry::Disc& disc) -> Style {
    switch (disc.origin) {
      case geometry::DiscOrigin::Fault:
        return {"faults", "#c0392b", "1.6"};
      case geometry::DiscOrigin::Interlayer:
        return {"interlayers", "#8b5a2b", "2.4"};
      default:
        return disc.cuts ? Style{"joints", "#1f4e9a", "0.8"}
                         : Style{"joints-not-cutting", "#8fb3e0", "0.5"};
    }
  };
  for (const char* group : {"joints-not-cutting", "joints", "faults", "interlayers"}) {
    out += "<g id=\"" + std::string(group) + "\" fill=\"none\">\n";
    for (const SectionTrace& trace : section.traces) {
      const Style style = styleOf(discOf(network, trace.disc));
      if (std::string(style.id) != group) continue;
      out += "<line x1=\"" + f.X(trace.a) + "\" y1=\"" + f.Y(trace.a) + "\" x2=\"" + f.X(trace.b) +
             "\" y2=\"" + f.Y(trace.b) + "\" stroke=\"" + style.stroke + "\" stroke-width=\"" +
             style.width + "\"/>\n";
    }
    out += "</g>\n";
  }
}

/// Legend (trace kinds, the materials shown) and scale bar.
void svgLegend(const Section& section, const std::vector<Material>& materials, const SvgFrame& f,
               std::string& out) {
  const double lx = f.width - f.legend + 10.0;
  double ly = f.margin + 40.0;
  out += "<g id=\"legend\" font-family=\"sans-serif\" font-size=\"12\">\n";
  const std::array<std::array<const char*, 3>, 4> lines = {{{"#1f4e9a", "0.8", "joint"},
                                                            {"#8fb3e0", "0.5", "joint (RQD only)"},
                                                            {"#c0392b", "1.6", "fault"},
                                                            {"#8b5a2b", "2.4", "interlayer"}}};
  for (const auto& [stroke, stroke_width, name] : lines) {
    out += "<line x1=\"" + px(lx) + "\" y1=\"" + px(ly) + "\" x2=\"" + px(lx + 24) + "\" y2=\"" +
           px(ly) + "\" stroke=\"" + stroke + "\" stroke-width=\"" + stroke_width + "\"/>\n";
    out += "<text x=\"" + px(lx + 30) + "\" y=\"" + px(ly + 4) + "\">" + name + "</text>\n";
    ly += 18.0;
  }
  std::vector<int> shown;
  for (const SectionPolygon& polygon : section.polygons) {
    if (std::find(shown.begin(), shown.end(), polygon.material) == shown.end()) {
      shown.push_back(polygon.material);
    }
  }
  std::sort(shown.begin(), shown.end());
  for (const int m : shown) {
    const std::string name = m >= 0 && static_cast<std::size_t>(m) < materials.size()
                                 ? materials[static_cast<std::size_t>(m)].name
                                 : "material " + std::to_string(m);
    out += "<rect x=\"" + px(lx) + "\" y=\"" + px(ly - 8) +
           "\" width=\"24\" height=\"12\" fill=\"" +
           kMaterialFill[static_cast<std::size_t>(std::max(0, m)) % kMaterialFill.size()] +
           "\" stroke=\"#404040\" stroke-width=\"0.6\"/>\n";
    out +=
        "<text x=\"" + px(lx + 30) + "\" y=\"" + px(ly + 4) + "\">" + xmlText(name) + "</text>\n";
    ly += 18.0;
  }
  // Scale bar: the largest 1-2-5 length below a fifth of the span.
  double bar = std::pow(10.0, std::floor(std::log10(f.span / 5.0)));
  for (const double k : {5.0, 2.0}) {
    if (bar * k <= f.span / 5.0) {
      bar *= k;
      break;
    }
  }
  ly += 10.0;
  out += "<line x1=\"" + px(lx) + "\" y1=\"" + px(ly) + "\" x2=\"" + px(lx + bar * f.scale) +
         "\" y2=\"" + px(ly) + "\" stroke=\"black\" stroke-width=\"2\"/>\n";
  out +=
      "<text x=\"" + px(lx) + "\" y=\"" + px(ly + 16) + "\">" + formatDouble(bar) + " m</text>\n";
  out += "</g>\n";
}

}  // namespace

std::string formatSectionSvg(const Section& section, const geometry::FractureNetwork& network,
                             const std::vector<Material>& materials) {
  const SvgFrame f = svgFrame(section, network);
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + px(f.width) + "\" height=\"" +
         px(f.height) + "\" viewBox=\"0 0 " + px(f.width) + " " + px(f.height) + "\">\n";
  out += "<title>rockmass section " + xmlText(section.label) + "</title>\n";
  out += "<rect x=\"0\" y=\"0\" width=\"" + px(f.width) + "\" height=\"" + px(f.height) +
         "\" fill=\"white\"/>\n";
  out += "<text x=\"" + px(f.margin) + "\" y=\"24\" font-family=\"sans-serif\" font-size=\"16\">" +
         "Section " + xmlText(section.label) + ": " + std::to_string(section.polygons.size()) +
         " piece sections, " + std::to_string(section.traces.size()) + " traces</text>\n";
  svgPieces(section, f, out);
  svgTraces(section, network, f, out);
  svgLegend(section, materials, f, out);
  out += "</svg>\n";
  return out;
}

}  // namespace rockmass::io
