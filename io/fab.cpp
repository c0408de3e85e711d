#include "io/fab.h"

#include <algorithm>
#include <cassert>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "geometry/disc.h"
#include "io/atomic_file.h"
#include "io/input_error.h"

namespace rockmass::io {
namespace {

using geometry::Vec3;

/// Appends "prefix x y z\n", the coordinates in shortest round-trip form.
void appendPointLine(std::string& out, const std::string& prefix, const Vec3& point) {
  out += prefix;
  for (int axis = 0; axis < 3; ++axis) out += ' ' + formatDouble(point[axis]);
  out += '\n';
}

/// True for the blanks that separate words on a FAB line.
bool isBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

/// `text` without leading and trailing blanks.
std::string_view trimmed(std::string_view text) {
  while (!text.empty() && isBlank(text.front())) text.remove_prefix(1);
  while (!text.empty() && isBlank(text.back())) text.remove_suffix(1);
  return text;
}

/// The blank-separated words of `text`.
std::vector<std::string_view> splitWords(std::string_view text) {
  std::vector<std::string_view> words;
  std::size_t start = 0;
  while (start < text.size()) {
    while (start < text.size() && isBlank(text[start])) ++start;
    std::size_t end = start;
    while (end < text.size() && !isBlank(text[end])) ++end;
    if (end > start) words.push_back(text.substr(start, end - start));
    start = end;
  }
  return words;
}

/// ASCII case-insensitive equality.
bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; };
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (lower(a[i]) != lower(b[i])) return false;
  }
  return true;
}

/// `text` in single quotes for an error message, shortened when it is long (binary garbage).
std::string quoted(std::string_view text) {
  constexpr std::size_t kMaxShown = 60;
  std::string result = "'";
  result += text.substr(0, kMaxShown);
  result += text.size() > kMaxShown ? "...'" : "'";
  return result;
}

/// `word` as a Number when the whole word is one (a leading '+' is allowed).
template <typename Number>
std::optional<Number> tryNumber(std::string_view word) {
  if (word.size() > 1 && word[0] == '+' && word[1] != '-') word.remove_prefix(1);
  Number value{};
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (error != std::errc() || end != word.data() + word.size()) return std::nullopt;
  return value;
}

/// One non-blank line: its 1-based number, its text without surrounding blanks, its words.
struct FabLine {
  int number = 0;
  std::string_view text;
  std::vector<std::string_view> words;
};

/// The section name of a "<keyword> <name>" line (e.g. "BEGIN FRACTURE"), if it is one.
std::optional<std::string_view> sectionName(const FabLine& line, std::string_view keyword) {
  if (line.words.size() != 2 || !equalsIgnoringCase(line.words[0], keyword)) return std::nullopt;
  return line.words[1];
}

/// True when `line` is "END <section>".
bool isSectionEnd(const FabLine& line, std::string_view section) {
  const std::optional<std::string_view> name = sectionName(line, "END");
  return name && equalsIgnoringCase(*name, section);
}

/// True for the length units FAB files write for metres.
bool isMetre(std::string_view unit) {
  for (std::string_view name : {"Meter", "Meters", "Metre", "Metres", "m"}) {
    if (equalsIgnoringCase(unit, name)) return true;
  }
  return false;
}

/// Largest coordinate of a FAB vertex (m).
constexpr double kLargestCoordinate = 1e12;
/// Largest distance of a FAB polygon's vertex from its plane, in polygon sizes (bounding-box
/// diagonals): FAB files from other tools round their coordinates to 6 or more digits.
constexpr double kPlanarity = 1e-2;

/// Reads FAB text line by line and turns every problem into an InputError at file:line.
class FabParser {
 public:
  /// Parses `text`, which came from `file` (used in messages only).
  FabParser(std::string_view text, const std::filesystem::path& file) : text_(text), file_(file) {}

  /// The fractures of the whole text.
  FabFile parse() {
    FabFile fab;
    bool has_fracture_section = false;
    while (const std::optional<FabLine> line = nextLine()) {
      const std::optional<std::string_view> section = sectionName(*line, "BEGIN");
      if (!section) fail(line->number, "expected 'BEGIN <section>', got " + quoted(line->text));
      if (equalsIgnoringCase(*section, "FORMAT")) {
        parseFormat(*section);
      } else if (equalsIgnoringCase(*section, "FRACTURE")) {
        parseFractures(*section, fab);
        has_fracture_section = true;
      } else if (equalsIgnoringCase(*section, "SETS")) {
        fab.set_names = parseNames(*section, "Set");
      } else if (equalsIgnoringCase(*section, "PROPERTIES")) {
        fab.property_names = parseNames(*section, "Prop");
      } else {
        skipSection(*section);
      }
    }
    if (!has_fracture_section) fail(0, "no BEGIN FRACTURE section");
    // Property values belong to the names: a fracture whose header does not carry one value
    // per property keeps none (files of other tools may list properties they do not write).
    for (FabFracture& fracture : fab.fractures) {
      if (fracture.properties.size() != fab.property_names.size()) fracture.properties.clear();
    }
    if (declared_fractures_ &&
        *declared_fractures_ != static_cast<long long>(fab.fractures.size())) {
      fail(declared_fractures_line_,
           "header says No_Fractures = " + std::to_string(*declared_fractures_) +
               " but the file has " + std::to_string(fab.fractures.size()));
    }
    return fab;
  }

 private:
  /// Throws the InputError for `message` at `line` (0: the file as a whole).
  [[noreturn]] void fail(int line, const std::string& message) const {
    throw InputError(locate(file_, line, 0, message));
  }

  /// The next non-blank line, or nothing at the end of the text.
  std::optional<FabLine> nextLine() {
    while (position_ < text_.size()) {
      std::size_t end = text_.find('\n', position_);
      if (end == std::string_view::npos) end = text_.size();
      const std::string_view text = trimmed(text_.substr(position_, end - position_));
      position_ = end + 1;
      ++line_number_;
      if (!text.empty()) return FabLine{line_number_, text, splitWords(text)};
    }
    return std::nullopt;
  }

  /// The next non-blank line inside BEGIN `section`; the end of the text is an error there.
  FabLine lineInside(std::string_view section) {
    std::optional<FabLine> line = nextLine();
    if (!line) {
      const std::string name(section);
      fail(line_number_, "file ends inside BEGIN " + name + " (missing END " + name + ")");
    }
    return std::move(*line);
  }

  /// `word` as a Number, or an InputError at `line` naming what was expected.
  template <typename Number>
  Number number(std::string_view word, int line) const {
    const std::optional<Number> value = tryNumber<Number>(word);
    if (!value) {
      fail(line, std::string(std::is_integral_v<Number> ? "expected an integer, got "
                                                        : "expected a number, got ") +
                     quoted(word));
    }
    return *value;
  }

  /// The BEGIN FORMAT block: "key = value" lines with case-insensitive keys. Only
  /// No_Fractures (checked against the fractures read), Format and Length_Unit matter.
  void parseFormat(std::string_view section) {
    for (FabLine line = lineInside(section); !isSectionEnd(line, section);
         line = lineInside(section)) {
      const std::size_t equals = line.text.find('=');
      if (equals == std::string_view::npos) {
        fail(line.number, "expected 'key = value' in BEGIN FORMAT, got " + quoted(line.text));
      }
      const std::string_view key = trimmed(line.text.substr(0, equals));
      const std::string_view value = trimmed(line.text.substr(equals + 1));
      if (equalsIgnoringCase(key, "No_Fractures")) {
        declared_fractures_ = number<long long>(value, line.number);
        declared_fractures_line_ = line.number;
      } else if (equalsIgnoringCase(key, "Format") && !equalsIgnoringCase(value, "Ascii")) {
        fail(line.number, "Format = " + std::string(value) + " is not supported (only Ascii)");
      } else if (equalsIgnoringCase(key, "Length_Unit") && !isMetre(value)) {
        fail(line.number, "Length_Unit = " + std::string(value) +
                              " is not supported (coordinates must be in metres: Meter)");
      }
    }
  }

  /// The fractures of one BEGIN FRACTURE section, appended to `fab`.
  void parseFractures(std::string_view section, FabFile& fab) {
    for (FabLine line = lineInside(section); !isSectionEnd(line, section);
         line = lineInside(section)) {
      fab.fractures.push_back(parseFracture(section, line));
    }
  }

  /// One fracture: the header "id nvertices set [properties...]", the vertex lines
  /// "k x y z" (k >= 1) and the normal line "0 nx ny nz" (ignored).
  FabFracture parseFracture(std::string_view section, const FabLine& header) {
    if (header.words.size() < 3) {
      fail(header.number,
           "expected a fracture header 'id nvertices set', got " + quoted(header.text));
    }
    FabFracture fracture;
    fracture.id = number<long long>(header.words[0], header.number);
    const long long vertex_count = number<long long>(header.words[1], header.number);
    fracture.set = number<int>(header.words[2], header.number);
    const std::string name = "fracture " + std::to_string(fracture.id);
    if (vertex_count < 3) {
      fail(header.number,
           name + " has " + std::to_string(vertex_count) + " vertices; a polygon needs at least 3");
    }
    for (long long k = 1; k <= vertex_count; ++k) {
      const FabLine line = lineInside(section);
      if (isSectionEnd(line, section) || tryNumber<long long>(line.words[0]) == 0) {
        fail(line.number, "expected " + std::to_string(vertex_count) + " vertex lines for " + name +
                              ", found " + quoted(line.text));
      }
      if (line.words.size() < 4) {
        fail(line.number,
             "expected a vertex line 'k x y z' for " + name + ", got " + quoted(line.text));
      }
      number<long long>(line.words[0], line.number);  // k must be an integer; its value is not used
      Vec3 vertex;
      for (int axis = 0; axis < 3; ++axis) {
        vertex[axis] = number<double>(line.words[axis + 1], line.number);
        if (!std::isfinite(vertex[axis])) {
          fail(line.number, "vertex " + std::to_string(k) + " of " + name +
                                " has a non-finite coordinate " + quoted(line.words[axis + 1]));
        }
        // Beyond 1e12 m the polygon's area and normal overflow (1e308 gave "a plane normal
        // must be a finite non-zero vector" with no line).
        if (std::abs(vertex[axis]) > kLargestCoordinate) {
          fail(line.number, "vertex " + std::to_string(k) + " of " + name + " has a coordinate " +
                                quoted(line.words[axis + 1]) + " beyond 1e12 m");
        }
      }
      fracture.vertices.push_back(vertex);
    }
    checkPolygon(fracture.vertices, name, header.number);
    // Values after the set: the properties (numbers), or nothing of use.
    for (std::size_t w = 3; w < header.words.size(); ++w) {
      const std::optional<double> value = tryNumber<double>(header.words[w]);
      if (!value) {
        fracture.properties.clear();
        break;
      }
      fracture.properties.push_back(*value);
    }
    const FabLine normal = lineInside(section);
    if (tryNumber<long long>(normal.words[0]) != 0) {
      fail(normal.number, "expected the normal line '0 nx ny nz' after the " +
                              std::to_string(vertex_count) + " vertices of " + name + ", got " +
                              quoted(normal.text));
    }
    return fracture;
  }

  /// A fracture must be a plane polygon with an area: one whose vertices are collinear, one
  /// that crosses itself into lobes of opposite turn (a bow-tie: no net area), or one whose
  /// vertices lie off its plane by more than kPlanarity of its size is refused at its header.
  void checkPolygon(const std::vector<Vec3>& vertices, const std::string& name, int line) {
    const double size = geometry::bounds(vertices).size().norm();
    // The fan's triangles summed without sign: zero only when the vertices are collinear.
    double unsigned_area = 0.0;
    for (std::size_t k = 1; k + 1 < vertices.size(); ++k) {
      unsigned_area +=
          0.5 * (vertices[k] - vertices[0]).cross(vertices[k + 1] - vertices[0]).norm();
    }
    const double tiny = 1e-12 * size * size;
    if (!(unsigned_area > tiny)) {
      fail(line, name + " has no area: its vertices are collinear or coincide");
    }
    if (!(geometry::polygonArea(vertices) > tiny)) {
      fail(line, name + " crosses itself: its lobes turn opposite ways and cancel (no net area)");
    }
    const Vec3 normal = geometry::polygonNormal(vertices);
    const Vec3 centre = vertices.front();
    double farthest = 0.0, mean_offset = 0.0;
    for (const Vec3& v : vertices) mean_offset += normal.dot(v - centre);
    mean_offset /= static_cast<double>(vertices.size());
    std::size_t worst = 0;
    for (std::size_t k = 0; k < vertices.size(); ++k) {
      const double off = std::abs(normal.dot(vertices[k] - centre) - mean_offset);
      if (off > farthest) {
        farthest = off;
        worst = k;
      }
    }
    if (farthest > kPlanarity * size) {
      fail(line, name + " is not planar: vertex " + std::to_string(worst + 1) + " lies " +
                     formatDouble(farthest) + " m off its plane (at most " +
                     formatDouble(kPlanarity) + " of its size, " + formatDouble(kPlanarity * size) +
                     " m)");
    }
  }

  /// The names of a SETS or PROPERTIES section: lines "<prefix><k> = ... \"name\"" give
  /// name k (1-based); other lines are skipped, as tools write more there than rockmass uses.
  std::vector<std::string> parseNames(std::string_view section, std::string_view prefix) {
    std::vector<std::string> names;
    for (FabLine line = lineInside(section); !isSectionEnd(line, section);
         line = lineInside(section)) {
      const std::string_view text = line.text;
      const std::size_t equals = text.find('=');
      const std::size_t open = text.find('"');
      const std::size_t close = open == std::string_view::npos ? open : text.find('"', open + 1);
      if (equals == std::string_view::npos || close == std::string_view::npos) continue;
      const std::string_view key = trimmed(text.substr(0, equals));
      if (key.size() <= prefix.size() ||
          !equalsIgnoringCase(key.substr(0, prefix.size()), prefix)) {
        continue;
      }
      const std::optional<long long> k = tryNumber<long long>(key.substr(prefix.size()));
      // At most 10^5 names: a garbled index must not allocate without bound.
      if (!k || *k < 1 || *k > 100000) continue;
      if (names.size() < static_cast<std::size_t>(*k)) names.resize(static_cast<std::size_t>(*k));
      names[static_cast<std::size_t>(*k - 1)] =
          std::string(text.substr(open + 1, close - open - 1));
    }
    return names;
  }

  /// Skips an optional section (TESSFRACTURE, ROCKBLOCK...) up to its END.
  void skipSection(std::string_view section) {
    while (!isSectionEnd(lineInside(section), section)) {
    }
  }

  std::string_view text_;
  const std::filesystem::path& file_;
  std::size_t position_ = 0;                     ///< start of the next line in text_
  int line_number_ = 0;                          ///< number of the last line read
  std::optional<long long> declared_fractures_;  ///< No_Fractures, when the header gives it
  int declared_fractures_line_ = 0;              ///< line of No_Fractures
};

/// The bytes of `file`, or nothing when it cannot be opened or read (e.g. a folder).
std::optional<std::string> readWholeFile(const std::filesystem::path& file) {
  std::ifstream stream(file, std::ios::binary);
  if (!stream) return std::nullopt;
  try {
    std::string text(std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>{});
    if (stream.bad()) return std::nullopt;
    return text;
  } catch (const std::ios_base::failure&) {
    return std::nullopt;
  }
}

/// `name` as a FAB string: its double quotes (which would end it) become single quotes.
std::string fabString(const std::string& name) {
  std::string out = name;
  std::replace(out.begin(), out.end(), '"', '\'');
  return '"' + out + '"';
}

}  // namespace

/// FORMAT, PROPERTIES and SETS blocks, one FRACTURE section with header, vertex and
/// Newell-normal lines, an empty TESSFRACTURE section.
std::string formatFab(const FabFile& fab) {
  std::size_t node_count = 0;
  for (const FabFracture& fracture : fab.fractures) node_count += fracture.vertices.size();
  std::string out =
      "BEGIN FORMAT\n"
      "    Format = Ascii\n"
      "    Length_Unit = Meter\n"
      "    XAxis = East\n"
      "    Scale = 1.0\n"
      "    No_Fractures = " +
      std::to_string(fab.fractures.size()) +
      "\n"
      "    No_TessFractures = 0\n"
      "    No_Nodes = " +
      std::to_string(node_count) +
      "\n"
      "    No_Properties = " +
      std::to_string(fab.property_names.size()) +
      "\n"
      "END FORMAT\n"
      "\n"
      "BEGIN PROPERTIES\n";
  for (std::size_t k = 0; k < fab.property_names.size(); ++k) {
    out += "    Prop" + std::to_string(k + 1) + " = (Real*4) " + fabString(fab.property_names[k]) +
           '\n';
  }
  out += "END PROPERTIES\n\nBEGIN SETS\n";
  for (std::size_t k = 0; k < fab.set_names.size(); ++k) {
    out += "    Set" + std::to_string(k + 1) + " = " + fabString(fab.set_names[k]) + '\n';
  }
  out += "END SETS\n\nBEGIN FRACTURE\n";
  for (const FabFracture& fracture : fab.fractures) {
    assert(fracture.vertices.size() >= 3 && "a FAB polygon needs at least 3 vertices");
    out += std::to_string(fracture.id) + ' ' + std::to_string(fracture.vertices.size()) + ' ' +
           std::to_string(fracture.set);
    for (const double value : fracture.properties) out += ' ' + formatDouble(value);
    out += '\n';
    for (std::size_t k = 0; k < fracture.vertices.size(); ++k) {
      appendPointLine(out, std::to_string(k + 1), fracture.vertices[k]);
    }
    appendPointLine(out, "0", geometry::polygonNormal(fracture.vertices));
  }
  // Empty, but present: readers that expect FracMan's sections (porepy's asks for the
  // tessellated fractures) find it.
  out += "END FRACTURE\n\nBEGIN TESSFRACTURE\nEND TESSFRACTURE\n";
  return out;
}

/// Parses FAB text (see FabParser for what is accepted).
FabFile parseFab(const std::string& text, const std::filesystem::path& file) {
  return FabParser(text, file).parse();
}

/// Reads the whole file, then parses it.
FabFile readFab(const std::filesystem::path& file) {
  const std::optional<std::string> text = readWholeFile(file);
  if (!text) throw InputError(locate(file, 0, 0, "cannot read the FAB file"));
  return parseFab(*text, file);
}

}  // namespace rockmass::io
