/// Scene file reader (format version 1): YAML -> validated Scene. Every check throws an
/// InputError "file:line:column: key.path: expected ..., got ..." located with yaml-cpp's marks.
#include "io/scene.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <tuple>
#include <utility>

#include "geometry/distribution.h"
#include "io/atomic_file.h"
#include "io/fab.h"
#include "io/input_error.h"
#include "rqd/cell_grid.h"

namespace rockmass::io {
namespace {

namespace fs = std::filesystem;
using geometry::DistributionKind;
using geometry::DistributionSpec;

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Standard gravity (m/s2) that turns a unit weight (N/m3) into a density (kg/m3).
constexpr double kStandardGravity = 9.81;

// ---------------------------------------------------------------------------------------------
// Text helpers
// ---------------------------------------------------------------------------------------------

/// Items joined by ", ".
std::string joined(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return text;
}

/// The number a plain YAML scalar spells ("-0.5", "+3", "2.6e4"), if it is a finite one.
std::optional<double> parseNumber(std::string_view text) {
  if (text.starts_with('+') && !text.starts_with("+-")) text.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

/// The integer a YAML scalar spells ("12", "-3", "+4"), if it is one that fits in T.
template <class T>
std::optional<T> parseInteger(std::string_view text) {
  if (text.starts_with('+') && !text.starts_with("+-")) text.remove_prefix(1);
  T value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

/// The set of values a number may take, e.g. "> 0" or "in [0, 90)".
struct Range {
  double low = -kInf;      ///< lower bound
  double high = kInf;      ///< upper bound
  bool low_open = false;   ///< true: the lower bound itself is excluded
  bool high_open = false;  ///< true: the upper bound itself is excluded

  /// True when x is in the range.
  bool contains(double x) const {
    return (low_open ? x > low : x >= low) && (high_open ? x < high : x <= high);
  }
  /// " > 0", " in [0, 90)", or "" for all numbers: appended to "expected a number".
  std::string text() const {
    const bool bounded_low = low > -kInf, bounded_high = high < kInf;
    if (bounded_low && bounded_high) {
      return std::string(" in ") + (low_open ? "(" : "[") + formatDouble(low) + ", " +
             formatDouble(high) + (high_open ? ")" : "]");
    }
    if (bounded_low) return (low_open ? " > " : " >= ") + formatDouble(low);
    if (bounded_high) return (high_open ? " < " : " <= ") + formatDouble(high);
    return "";
  }
};

constexpr Range kAnyNumber{};
constexpr Range kPositive{.low = 0.0, .low_open = true};
constexpr Range kNonNegative{.low = 0.0};

/// Numbers x with x > low.
constexpr Range above(double low) {
  return {.low = low, .low_open = true};
}
/// Numbers x with x >= low.
constexpr Range atLeast(double low) {
  return {.low = low};
}
/// Numbers in [low, high].
constexpr Range closed(double low, double high) {
  return {.low = low, .high = high};
}

// ---------------------------------------------------------------------------------------------
// Cursor: a node, its key path and typed getters
// ---------------------------------------------------------------------------------------------

/// The file a scene comes from: named in messages, and the base of relative paths.
struct Source {
  fs::path file;    ///< as given by the caller (used in messages)
  fs::path folder;  ///< absolute folder of the file
};

/// One node of the scene with its key path ("joint_sets[0].spacing"). Typed getters validate
/// and throw an InputError located at the node ("file:line:column: path: ...").
class Cursor {
 public:
  /// A cursor on `node`. An empty value is located at `fallback` (its key, or its list): yaml-cpp
  /// marks it at the token after it, often on the next line.
  Cursor(const Source& source, YAML::Node node, std::string path, const YAML::Mark& fallback)
      : source_(&source),
        node_(std::move(node)),
        path_(std::move(path)),
        mark_(node_.IsNull() || node_.Mark().is_null() ? fallback : node_.Mark()) {}

  /// 1-based line of this node in the scene file.
  int line() const { return mark_.line + 1; }
  /// 1-based column of this node in the scene file.
  int column() const { return mark_.column + 1; }

  /// The key path, e.g. "materials.concrete.young" ("" at the root).
  const std::string& path() const { return path_; }

  /// Throws "file:line:column: path: what" located at this node.
  [[noreturn]] void fail(const std::string& what) const { throw InputError(located(what)); }

  /// "file:line:column: path: what", the message fail() throws.
  std::string located(const std::string& what) const {
    return locate(source_->file, mark_.line + 1, mark_.column + 1,
                  path_.empty() ? what : path_ + ": " + what);
  }

  // ----- maps -----

  /// Checks that this is a map (an empty value counts as an empty map) whose keys are all in
  /// `allowed` and appear once; returns the cursor for chaining.
  Cursor map(const std::vector<std::string>& allowed) const {
    requireMap();
    std::vector<std::string> seen;
    for (const auto& entry : node_) {
      const Cursor key = keyCursor(entry.first);
      if (!entry.first.IsScalar()) key.failExpected("a key name");
      const std::string& name = entry.first.Scalar();
      if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
        key.fail("unknown key '" + name + "'; expected one of: " + joined(allowed) +
                 suggestion(name, allowed));
      }
      if (std::find(seen.begin(), seen.end(), name) != seen.end()) {
        key.fail("duplicate key '" + name + "'");
      }
      seen.push_back(name);
    }
    return *this;
  }

  /// True when this is a map (not an empty value).
  bool isMap() const { return node_.IsMap(); }

  /// True when this is a list (not an empty value).
  bool isList() const { return node_.IsSequence(); }

  /// The entries of a map whose keys are user names (materials, joints), in file order.
  std::vector<std::pair<std::string, Cursor>> entries() const {
    requireMap();
    map(keyNames());
    std::vector<std::pair<std::string, Cursor>> result;
    for (const auto& entry : node_) {
      if (entry.first.Scalar().empty()) keyCursor(entry.first).failExpected("a name");
      result.emplace_back(entry.first.Scalar(), child(entry.first, entry.second));
    }
    return result;
  }

  /// True when the map has `key`.
  bool has(std::string_view key) const { return get(key).has_value(); }

  /// The value of `key`, if present (a const walk: yaml-cpp's operator[] may add the key).
  std::optional<Cursor> get(std::string_view key) const {
    if (node_.IsMap()) {
      for (const auto& entry : node_) {
        if (entry.first.IsScalar() && entry.first.Scalar() == key) {
          return child(entry.first, entry.second);
        }
      }
    }
    return std::nullopt;
  }

  /// The value of a required `key` (error located at this map when it is missing).
  Cursor at(std::string_view key) const {
    if (std::optional<Cursor> value = get(key)) return *value;
    Cursor(*source_, node_, childPath(std::string(key)), mark_).fail("required key is missing");
  }

  /// Which of two exclusive keys the map has: 0 for `first`, 1 for `second`.
  int oneOf(std::string_view first, std::string_view second) const {
    const bool has_first = has(first), has_second = has(second);
    if (has_first && has_second) {
      fail("give either '" + std::string(first) + "' or '" + std::string(second) + "', not both");
    }
    if (!has_first && !has_second) {
      fail("expected '" + std::string(first) + "' or '" + std::string(second) + "'");
    }
    return has_first ? 0 : 1;
  }

  /// The value read from `key` by `read`, or `fallback` when the key is absent.
  template <class T, class Read>
  T valueOr(std::string_view key, T fallback, Read&& read) const {
    const std::optional<Cursor> value = get(key);
    return value ? T(std::invoke(read, *value)) : fallback;
  }

  /// number(range) of `key`, or `fallback` when the key is absent.
  double numberOr(std::string_view key, double fallback, const Range& range) const {
    return valueOr(key, fallback, [&](const Cursor& c) { return c.number(range); });
  }

  /// integer(range) of `key`, or `fallback` when the key is absent.
  int integerOr(std::string_view key, int fallback, const Range& range) const {
    return valueOr(key, fallback, [&](const Cursor& c) { return c.integer(range); });
  }

  // ----- lists -----

  /// The items of a list (an empty value counts as an empty list).
  std::vector<Cursor> items() const {
    if (!node_.IsSequence() && !node_.IsNull()) failExpected("a list");
    std::vector<Cursor> result;
    for (std::size_t i = 0; i < node_.size(); ++i) {
      result.emplace_back(*source_, node_[i], path_ + "[" + std::to_string(i) + "]", mark_);
    }
    return result;
  }

  /// A list of exactly n numbers.
  std::vector<double> numbers(std::size_t n) const {
    if (!node_.IsSequence() || node_.size() != n) {
      failExpected("a list of " + std::to_string(n) + " numbers");
    }
    std::vector<double> values;
    for (const Cursor& item : items()) values.push_back(item.number());
    return values;
  }

  /// [x, y, z]
  Vec3 vec3() const {
    const std::vector<double> v = numbers(3);
    return {v[0], v[1], v[2]};
  }

  /// [a, b]
  Vec2 vec2() const {
    const std::vector<double> v = numbers(2);
    return {v[0], v[1]};
  }

  /// A non-empty list of numbers in `range`, each greater than the one before.
  std::vector<double> increasingNumbers(const Range& range) const {
    const std::vector<Cursor> list = items();
    if (list.empty()) failExpected("a non-empty list of numbers");
    std::vector<double> values;
    for (const Cursor& item : list) {
      values.push_back(values.empty()
                           ? item.number(range)
                           : item.number(above(values.back()), "(the list must increase)"));
    }
    return values;
  }

  /// A non-empty list of distinct words, each one of `options` (e.g. supports.fixed).
  std::vector<std::string> distinctChoices(std::string_view noun,
                                           const std::vector<std::string>& options) const {
    const std::vector<Cursor> list = items();
    if (list.empty()) failExpected("a non-empty list");
    std::vector<std::string> chosen;
    for (const Cursor& item : list) {
      const std::string& word = options[item.choice(noun, options)];
      if (std::find(chosen.begin(), chosen.end(), word) != chosen.end()) {
        item.fail("duplicate " + std::string(noun) + " '" + word + "'");
      }
      chosen.push_back(word);
    }
    return chosen;
  }

  // ----- scalars -----

  /// True when this is a scalar that spells a number.
  bool isNumber() const { return node_.IsScalar() && parseNumber(node_.Scalar()).has_value(); }

  /// True when this is the scalar `word`.
  bool is(std::string_view word) const { return node_.IsScalar() && node_.Scalar() == word; }

  /// A number in `range`; `context` ("for a lognormal distribution") explains the range.
  double number(const Range& range = kAnyNumber, std::string_view context = {}) const {
    const std::optional<double> value =
        node_.IsScalar() ? parseNumber(node_.Scalar()) : std::nullopt;
    if (!value) failExpected("a number");
    if (!range.contains(*value)) {
      fail("expected a number" + range.text() + (context.empty() ? "" : " ") +
           std::string(context) + ", got " + node_.Scalar());
    }
    return *value;
  }

  /// An integer in `range` that fits in an int.
  int integer(const Range& range = kAnyNumber) const {
    const std::optional<long long> value =
        node_.IsScalar() ? parseInteger<long long>(node_.Scalar()) : std::nullopt;
    if (!value) failExpected("an integer");
    const bool fits =
        *value >= std::numeric_limits<int>::min() && *value <= std::numeric_limits<int>::max();
    if (!fits || !range.contains(static_cast<double>(*value))) {
      fail("expected an integer" + range.text() + ", got " + node_.Scalar());
    }
    return static_cast<int>(*value);
  }

  /// An integer >= 0 up to 2^64 - 1.
  std::uint64_t unsignedInteger() const {
    const std::string text = node_.IsScalar() ? node_.Scalar() : "";
    if (const std::optional<std::uint64_t> value = parseInteger<std::uint64_t>(text)) return *value;
    if (parseInteger<long long>(text)) fail("expected an integer >= 0, got " + text);
    failExpected("an integer");
  }

  /// true or false (YAML 1.2 spellings; "yes"/"on" are not booleans here).
  bool boolean() const {
    constexpr std::array<std::string_view, 3> kTrue{"true", "True", "TRUE"};
    constexpr std::array<std::string_view, 3> kFalse{"false", "False", "FALSE"};
    const std::string text = node_.IsScalar() ? node_.Scalar() : "";
    if (std::find(kTrue.begin(), kTrue.end(), text) != kTrue.end()) return true;
    if (std::find(kFalse.begin(), kFalse.end(), text) != kFalse.end()) return false;
    failExpected("true or false");
  }

  /// A non-empty string (a name).
  std::string string() const {
    if (!node_.IsScalar() || node_.Scalar().empty()) failExpected("a string");
    return node_.Scalar();
  }

  /// Index in `options` of this word; `noun` names it in messages ("unknown sweep axis 'z'").
  std::size_t choice(std::string_view noun, const std::vector<std::string>& options) const {
    if (!node_.IsScalar()) failExpected("one of: " + joined(options));
    const std::string& word = node_.Scalar();
    const auto found = std::find(options.begin(), options.end(), word);
    if (found == options.end()) {
      fail("unknown " + std::string(noun) + " '" + word + "'; expected one of: " + joined(options) +
           suggestion(word, options));
    }
    return static_cast<std::size_t>(found - options.begin());
  }

  /// Throws "expected <what>[, got <found>]", quoting a scalar or saying "nothing" when empty.
  [[noreturn]] void failExpected(const std::string& what) const {
    std::string found;
    if (node_.IsScalar()) found = ", got '" + node_.Scalar() + "'";
    if (node_.IsNull()) found = ", got nothing";
    fail("expected " + what + found);
  }

  /// A path to an existing file, relative to the scene's folder; returned absolute.
  fs::path existingFile() const {
    const std::string given = string();
    const fs::path path = fs::weakly_canonical(source_->folder / given);
    if (!fs::is_regular_file(path)) {
      fail("expected an existing file, got '" + given + "' (looked for " + path.string() + ")");
    }
    return path;
  }

 private:
  /// Fails unless this is a map or an empty value (which counts as an empty map).
  void requireMap() const {
    if (!node_.IsMap() && !node_.IsNull()) failExpected("a map");
  }

  /// The path of a child `key`.
  std::string childPath(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }

  /// A cursor on the value of the map entry (key, value); an empty value is located at the key.
  Cursor child(const YAML::Node& key, const YAML::Node& value) const {
    return Cursor(*source_, value, childPath(key.Scalar()), key.Mark());
  }

  /// A cursor on a key node itself: errors about the key are located at it, path is this map's.
  Cursor keyCursor(const YAML::Node& key) const { return Cursor(*source_, key, path_, mark_); }

  /// Every key of this map (for maps whose keys are user names).
  std::vector<std::string> keyNames() const {
    std::vector<std::string> names;
    for (const auto& entry : node_) names.push_back(entry.first.Scalar());
    return names;
  }

  const Source* source_;  ///< file of the scene (outlives every cursor)
  YAML::Node node_;       ///< the node itself
  std::string path_;      ///< key path for messages
  YAML::Mark mark_;       ///< where messages about this node point
};

// ---------------------------------------------------------------------------------------------
// Names
// ---------------------------------------------------------------------------------------------

/// Calls `read` for every item of the list under `key` of the map m, if present.
template <class Read>
void forEachItem(const Cursor& m, std::string_view key, Read&& read) {
  if (const auto list = m.get(key)) {
    for (const Cursor& item : list->items()) read(item);
  }
}

/// The `name` of every item (materials, joints, structures), in order.
template <class T>
std::vector<std::string> namesOf(const std::vector<T>& items) {
  std::vector<std::string> names;
  for (const T& item : items) names.push_back(item.name);
  return names;
}

/// Where `c` is, kept for messages raised after the scene is read.
KeyLocation locationOf(const Cursor& c) {
  return {c.path(), c.line(), c.column()};
}

/// Index of the name at `c` among `names`; `noun` ("joint") words the error.
int lookupName(const Cursor& c, const std::vector<std::string>& names, const std::string& noun) {
  const std::string name = c.string();
  const auto found = std::find(names.begin(), names.end(), name);
  if (found == names.end()) {
    c.fail("unknown " + noun + " '" + name + "'; " +
           (names.empty() ? "no " + noun + "s are defined"
                          : "defined " + noun + "s: " + joined(names)) +
           suggestion(name, names));
  }
  return static_cast<int>(found - names.begin());
}

/// Names that must not repeat, each remembered with the entry that took it.
class UniqueNames {
 public:
  /// Takes `name` for the entry at path `owner`; fails at `at` if an earlier entry has it.
  void claim(const Cursor& at, const std::string& name, const std::string& owner) {
    const auto [it, inserted] = owners_.emplace(name, owner);
    if (!inserted) at.fail("name '" + name + "' is already used by " + it->second);
  }

  /// Claims and returns the required `name` key of `entry`.
  std::string claimName(const Cursor& entry) {
    const Cursor name = entry.at("name");
    std::string text = name.string();
    claim(name, text, entry.path());
    return text;
  }

 private:
  std::map<std::string, std::string> owners_;  ///< name -> path of the entry that took it
};

// ---------------------------------------------------------------------------------------------
// Readers that need nothing but their node
// ---------------------------------------------------------------------------------------------

/// The families a distribution map can name, in the order error messages list them.
constexpr std::array kDistributionKinds{DistributionKind::Normal, DistributionKind::Lognormal,
                                        DistributionKind::Uniform, DistributionKind::Exponential,
                                        DistributionKind::Constant};

/// The names of kDistributionKinds as written in scenes.
std::vector<std::string> distributionNames() {
  std::vector<std::string> names;
  for (DistributionKind kind : kDistributionKinds) {
    names.emplace_back(geometry::distributionName(kind));
  }
  return names;
}

/// The optional bounds `min_key` and `max_key` of the map m; max must exceed min when both are
/// given (distribution truncation, plan regions).
std::pair<std::optional<double>, std::optional<double>> readBounds(const Cursor& m,
                                                                   const std::string& min_key,
                                                                   const std::string& max_key) {
  const std::optional<double> min =
      m.valueOr(min_key, std::optional<double>{}, [](const Cursor& v) { return v.number(); });
  const std::string context = "(" + max_key + " must exceed " + min_key + ")";
  const std::optional<double> max =
      m.valueOr(max_key, std::optional<double>{},
                [&](const Cursor& v) { return min ? v.number(above(*min), context) : v.number(); });
  return {min, max};
}

/// Mean and std of a uniform distribution: from {mean, std}, or from {min, max}.
void readUniformMoments(const Cursor& m, DistributionSpec& spec) {
  if (m.has("mean") || m.has("std")) {
    spec.mean = m.at("mean").number();
    spec.std = m.at("std").number(kPositive, "for a uniform distribution");
    return;
  }
  const auto [min, max] = readBounds(m, "min", "max");
  if (!min || !max) m.fail("a uniform distribution needs min and max, or mean and std");
  spec.mean = 0.5 * (*min + *max);
  spec.std = (*max - *min) / std::sqrt(12.0);
}

/// A distribution map {distribution, mean, std, min, max}, validated by geometry::Distribution.
geometry::Distribution readDistribution(const Cursor& c) {
  const Cursor m = c.map({"distribution", "mean", "std", "min", "max"});
  DistributionSpec spec;
  spec.kind = kDistributionKinds[m.at("distribution").choice("distribution", distributionNames())];
  const std::string context =
      std::string("for a ") + geometry::distributionName(spec.kind) + " distribution";
  switch (spec.kind) {
    case DistributionKind::Normal:
      spec.mean = m.at("mean").number();
      spec.std = m.at("std").number(kPositive, context);
      break;
    case DistributionKind::Lognormal:
      spec.mean = m.at("mean").number(kPositive, context);
      spec.std = m.at("std").number(kPositive, context);
      break;
    case DistributionKind::Uniform:
      readUniformMoments(m, spec);
      break;
    case DistributionKind::Exponential:
      if (m.has("std")) m.at("std").fail("exponential takes only mean (its std equals its mean)");
      spec.mean = m.at("mean").number(kPositive, context);
      spec.std = spec.mean;
      break;
    case DistributionKind::Constant:
      for (const char* key : {"std", "min", "max"}) {
        if (m.has(key)) m.at(key).fail("a constant takes only mean");
      }
      spec.mean = m.at("mean").number();
      break;
  }
  std::tie(spec.min, spec.max) = readBounds(m, "min", "max");
  try {
    return geometry::Distribution(spec);
  } catch (const std::invalid_argument& error) {
    m.fail(error.what());
  }
}

/// The shortest mean trace length or spacing a joint set may have (m).
constexpr double kShortestLength = 1e-6;

/// Fails unless a trace length distribution gives only values > 0, with a mean of at least
/// kShortestLength.
void checkTraceLength(const Cursor& c, const geometry::Distribution& distribution) {
  const DistributionSpec& spec = distribution.spec();
  if (spec.kind == DistributionKind::Normal && !(spec.min && *spec.min > 0)) {
    c.fail("a normal trace length can be negative; give min > 0");
  }
  const bool positive =
      spec.kind == DistributionKind::Constant ? spec.mean > 0 : distribution.lower() >= 0;
  if (!positive) {
    c.fail("expected only values > 0 for a trace length, but the distribution reaches " +
           formatDouble(distribution.lower()));
  }
  // Below a micrometre the discs' count (P32 over a disc's area) overflows: a mean of 5e-324
  // asked for NaN discs.
  if (!(spec.mean >= kShortestLength)) {
    c.get("mean").value_or(c).fail(
        "expected a mean trace length >= " + formatDouble(kShortestLength) + " m, got " +
        formatDouble(spec.mean));
  }
}

/// A spacing distribution: its mean (which sets P10) must be > 0.
DistributionSpec readSpacing(const Cursor& c) {
  const DistributionSpec spec = readDistribution(c).spec();
  if (spec.mean <= 0) {
    c.get("mean").value_or(c).fail("expected a mean > 0 for a spacing, got " +
                                   formatDouble(spec.mean));
  }
  if (spec.mean < kShortestLength) {
    c.get("mean").value_or(c).fail("expected a mean spacing >= " + formatDouble(kShortestLength) +
                                   " m, got " + formatDouble(spec.mean));
  }
  return spec;
}

/// Orientation of a joint set: dip_direction and dip distributions, or a Fisher `orientation`.
geometry::OrientationSpec readOrientation(const Cursor& set) {
  const bool independent = set.has("dip_direction") || set.has("dip");
  geometry::OrientationSpec orientation;
  if (independent && set.has("orientation")) {
    set.fail("give either 'orientation' or 'dip_direction' and 'dip', not both");
  }
  if (independent) {
    orientation.dip_direction = readDistribution(set.at("dip_direction")).spec();
    orientation.dip = readDistribution(set.at("dip")).spec();
    return orientation;
  }
  if (!set.has("orientation")) {
    set.fail("expected an orientation: 'dip_direction' and 'dip' distributions, or 'orientation'");
  }
  const Cursor m = set.at("orientation").map({"distribution", "dip_direction", "dip", "kappa"});
  m.at("distribution").choice("orientation distribution", {"fisher"});
  orientation.fisher = true;
  orientation.fisher_dip_direction = m.at("dip_direction").number(closed(0, 360));
  orientation.fisher_dip = m.at("dip").number(closed(0, 90));
  orientation.kappa = m.at("kappa").number(kPositive);
  return orientation;
}

/// shape: {aspect_ratio, major_axis: strike | dip | {rake}}.
geometry::ShapeSpec readShape(const Cursor& c) {
  const Cursor m = c.map({"aspect_ratio", "major_axis"});
  geometry::ShapeSpec shape;
  shape.aspect_ratio = m.numberOr("aspect_ratio", 1.0, {.low = 0, .high = 1, .low_open = true});
  if (const std::optional<Cursor> axis = m.get("major_axis")) {
    if (axis->isMap()) {
      shape.major_axis = geometry::MajorAxis::Rake;
      shape.rake = axis->map({"rake"}).at("rake").number(closed(-90, 90));
    } else {
      constexpr std::array kAxes{geometry::MajorAxis::Strike, geometry::MajorAxis::Dip};
      shape.major_axis = kAxes[axis->choice("major axis", {"strike", "dip"})];
    }
  }
  return shape;
}

/// The strength of a joint: `joints` entries and inline structure joints.
Joint readJoint(const Cursor& c, std::string name) {
  const Cursor m = c.map({"friction", "friction_angle", "cohesion", "tensile_strength", "model"});
  Joint joint;
  joint.name = std::move(name);
  if (m.oneOf("friction", "friction_angle") == 0) {
    joint.friction = m.at("friction").number(kNonNegative);
  } else {
    const double angle = m.at("friction_angle").number({.low = 0, .high = 90, .high_open = true});
    joint.friction = std::tan(angle * std::numbers::pi / 180.0);
  }
  joint.cohesion = m.numberOr("cohesion", 0.0, kNonNegative);
  joint.tensile_strength = m.numberOr("tensile_strength", 0.0, kNonNegative);
  joint.brittle = m.valueOr("model", joint.brittle, [](const Cursor& v) {
    return v.choice("joint model", {"plastic", "brittle"}) == 1;
  });
  return joint;
}

/// A polyline of at least `min_points` [a, b] points with no zero-length segment.
std::vector<Vec2> readProfile(const Cursor& c, std::size_t min_points) {
  const std::vector<Cursor> items = c.items();
  if (items.size() < min_points) {
    c.fail("expected a list of at least " + std::to_string(min_points) + " points [a, b], got " +
           std::to_string(items.size()));
  }
  std::vector<Vec2> profile;
  for (const Cursor& item : items) {
    profile.push_back(item.vec2());
    if (profile.size() > 1 && profile.back() == profile[profile.size() - 2]) {
      item.fail("zero-length segment: this point repeats the previous one");
    }
  }
  return profile;
}

/// A sweep axis: 'x' or 'y'.
char readSweep(const Cursor& c) {
  return c.choice("sweep axis", {"x", "y"}) == 0 ? 'x' : 'y';
}

/// A direction vector that is not zero.
Vec3 readDirection(const Cursor& c) {
  const Vec3 direction = c.vec3();
  if (direction.isZero(0.0)) c.fail("expected a nonzero vector");
  return direction;
}

/// region: {x_min, x_max, y_min, y_max}, each optional; a max must exceed its min.
Region readRegion(const Cursor& c) {
  const Cursor m = c.map({"x_min", "x_max", "y_min", "y_max"});
  Region region;
  std::tie(region.x_min, region.x_max) = readBounds(m, "x_min", "x_max");
  std::tie(region.y_min, region.y_max) = readBounds(m, "y_min", "y_max");
  return region;
}

/// A point load {point, force}.
PointLoad readPointLoad(const Cursor& c) {
  const Cursor m = c.map({"point", "force"});
  return {m.at("point").vec3(), m.at("force").vec3()};
}

/// analysis.blocks
BlocksAnalysis readBlocksAnalysis(const Cursor& c) {
  const Cursor m = c.map({"cutter", "disc_segments"});
  BlocksAnalysis blocks;
  constexpr std::array kCutters{BlocksAnalysis::Cutter::Exact, BlocksAnalysis::Cutter::Fast};
  blocks.cutter = m.valueOr("cutter", blocks.cutter, [&](const Cursor& v) {
    return kCutters[v.choice("cutter", {"exact", "fast"})];
  });
  // At 1024 segments the polygon is within 5e-6 of its radius from the ellipse (1 - cos(pi /
  // 1024)); more only costs memory (2^31 ran out of it).
  blocks.disc_segments = m.integerOr("disc_segments", blocks.disc_segments, closed(3, 1024));
  return blocks;
}

/// A box {min, max} with min < max in every component (m).
geometry::Box readBox(const Cursor& c) {
  const Cursor box = c.map({"min", "max"});
  const geometry::Box read{box.at("min").vec3(), box.at("max").vec3()};
  for (int axis = 0; axis < 3; ++axis) {
    if (!(read.min[axis] < read.max[axis])) {
      box.fail("expected min < max in every component, got " + formatDouble(read.min[axis]) +
               " >= " + formatDouble(read.max[axis]) + " in " + "xyz"[axis]);
    }
  }
  return read;
}

/// analysis.rqd.boreholes.calibration; `joint_sets` names the joint sets in order.
RqdCalibration readRqdCalibration(const Cursor& c, const std::vector<std::string>& joint_sets) {
  const Cursor m = c.map({"sets", "range", "tolerance", "max_evaluations"});
  RqdCalibration calibration;
  if (const auto sets = m.get("sets")) {
    const std::vector<Cursor> items = sets->items();
    if (items.empty()) sets->failExpected("a non-empty list of joint set names");
    for (const Cursor& item : items) {
      const int index = lookupName(item, joint_sets, "joint set");
      if (std::find(calibration.sets.begin(), calibration.sets.end(), index) !=
          calibration.sets.end()) {
        item.fail("joint set '" + item.string() + "' is listed twice");
      }
      calibration.sets.push_back(index);
    }
  } else {
    for (int i = 0; i < static_cast<int>(joint_sets.size()); ++i) calibration.sets.push_back(i);
    if (joint_sets.empty()) m.fail("calibration needs at least one joint set in the scene");
  }
  if (const auto range = m.get("range")) {
    const std::vector<double> bounds = range->increasingNumbers(kPositive);
    if (bounds.size() != 2) range->failExpected("a list of 2 increasing numbers > 0");
    calibration.min_multiplier = bounds[0];
    calibration.max_multiplier = bounds[1];
  }
  calibration.tolerance = m.numberOr("tolerance", calibration.tolerance, kPositive);
  calibration.max_evaluations =
      m.integerOr("max_evaluations", calibration.max_evaluations, atLeast(2));
  return calibration;
}

/// analysis.rqd; `joint_sets` names the joint sets in order; the grid fills its region or
/// the domain box (unless the domain is a mesh).
RqdAnalysis readRqdAnalysis(const Cursor& c, const std::vector<std::string>& joint_sets,
                            const geometry::Box& domain, bool mesh_domain) {
  const Cursor m = c.map({"thresholds", "balls", "boreholes", "grid", "merge_distance"});
  RqdAnalysis rqd;
  if (const auto thresholds = m.get("thresholds")) {
    rqd.thresholds = thresholds->increasingNumbers(kPositive);
  }
  rqd.merge_distance = m.numberOr("merge_distance", rqd.merge_distance, kNonNegative);
  UniqueNames ball_names;
  forEachItem(m, "balls", [&](const Cursor& item) {
    const Cursor ball = item.map({"name", "center", "length", "directions", "radius"});
    rqd.balls.push_back(
        {.name = ball_names.claimName(ball),
         .center = ball.at("center").vec3(),
         .length = ball.at("length").number(kPositive),
         .directions = ball.integerOr("directions", 2000, atLeast(4)),
         .radius = ball.valueOr("radius", std::optional<double>{}, [](const Cursor& v) {
           return std::optional(v.number(kPositive));
         })});
  });
  if (const auto holes = m.get("boreholes")) {
    holes->map({"file", "run_length", "measured", "measured_threshold", "calibration"});
    rqd.boreholes_file = holes->at("file").existingFile();
    rqd.run_length = holes->numberOr("run_length", rqd.run_length, kPositive);
    rqd.measured_file = holes->valueOr("measured", fs::path{}, &Cursor::existingFile);
    rqd.measured_threshold =
        holes->numberOr("measured_threshold", rqd.measured_threshold, kPositive);
    if (const auto calibration = holes->get("calibration")) {
      if (rqd.measured_file.empty()) {
        calibration->fail("calibration needs a measured log: give boreholes.measured");
      }
      rqd.calibration = readRqdCalibration(*calibration, joint_sets);
    }
  }
  if (const auto grid = m.get("grid")) {
    grid->map({"spacing", "direction_count", "length", "region"});
    rqd.grid_spacing = grid->at("spacing").number(kPositive);
    rqd.grid_direction_count =
        grid->integerOr("direction_count", rqd.grid_direction_count, atLeast(1));
    if (const auto length = grid->get("length")) rqd.grid_length = length->number(kPositive);
    if (const auto region = grid->get("region")) rqd.grid_region = readBox(*region);
    // The grid fills its region, or the domain box (a mesh domain's box is known later; the
    // grid builder checks it then).
    if (rqd.grid_region || !mesh_domain) {
      const geometry::Vec3 size = (rqd.grid_region ? *rqd.grid_region : domain).size();
      double cells = 1.0;
      for (int axis = 0; axis < 3; ++axis) {
        cells *= std::max(1.0, rqd::cellsAlong(size[axis], *rqd.grid_spacing));
      }
      if (cells > rqd::kMaxGridCells) {
        grid->at("spacing").fail(
            "expected a spacing that gives at most " + formatDouble(rqd::kMaxGridCells) +
            " cells in the grid's region, got " + formatDouble(*rqd.grid_spacing) + " m (" +
            formatDouble(cells) + " cells)");
      }
    }
  }
  return rqd;
}

/// analysis.dda
DdaAnalysis readDdaAnalysis(const Cursor& c, const geometry::Box& domain, bool mesh_domain) {
  const Cursor m = c.map({"mode", "kinematics", "steps", "time_step", "max_displacement_ratio",
                          "penalty", "time_integration", "min_block_volume", "open_close_tolerance",
                          "region", "min_time_step", "contact_point_spacing"});
  DdaAnalysis dda;
  dda3d::DdaSettings& e = dda.engine;
  e.mode = m.valueOr("mode", e.mode, [](const Cursor& v) {
    return v.choice("mode", {"dynamic", "static"}) == 0 ? dda3d::AnalysisMode::Dynamic
                                                        : dda3d::AnalysisMode::Static;
  });
  e.kinematics = m.valueOr("kinematics", e.kinematics, [](const Cursor& v) {
    return v.choice("kinematics", {"deformable", "rigid"}) == 0 ? dda3d::Kinematics::Deformable
                                                                : dda3d::Kinematics::Rigid;
  });
  // At most 1e7 steps: hours on a small model (the histories go to disk as the run goes and
  // summary.json keeps at most 1e5 step records, so memory does not grow with the steps).
  dda.steps = m.integerOr("steps", dda.steps, closed(1, 1e7));
  e.time_step = m.numberOr("time_step", e.time_step, kPositive);
  if (const auto step = m.get("time_step");
      step && !m.get("min_time_step") && e.time_step < e.min_time_step) {
    step->fail("expected a time step >= min_time_step (" + formatDouble(e.min_time_step) +
               " s; set min_time_step to go lower), got " + formatDouble(e.time_step));
  }
  if (const auto min_step = m.get("min_time_step")) {
    e.min_time_step = min_step->number(kPositive);
    if (e.min_time_step > e.time_step) {
      min_step->fail("expected a time step no larger than time_step (" + formatDouble(e.time_step) +
                     " s)");
    }
  }
  e.max_displacement_ratio = m.numberOr("max_displacement_ratio", e.max_displacement_ratio,
                                        {.low = 0, .high = 1, .low_open = true, .high_open = true});
  if (const auto penalty = m.get("penalty"); penalty && !penalty->is("auto")) {
    if (!penalty->isNumber()) penalty->failExpected("'auto' or a number > 0");
    e.penalty = penalty->number(kPositive);
  }
  dda.min_block_volume = m.numberOr("min_block_volume", dda.min_block_volume, kNonNegative);
  e.open_close_tolerance = m.numberOr("open_close_tolerance", e.open_close_tolerance,
                                      {.low = 0, .high = 1, .high_open = true});
  if (const auto spacing = m.get("contact_point_spacing")) {
    e.contact_point_spacing = spacing->number(kNonNegative);
    dda.contact_point_spacing_line = spacing->line();
  }
  if (const auto region = m.get("region")) {
    if (mesh_domain) region->fail("a DDA region needs a box domain (domain.box)");
    const geometry::Box read = readBox(*region);
    for (int axis = 0; axis < 3; ++axis) {
      if (read.min[axis] < domain.min[axis] || read.max[axis] > domain.max[axis]) {
        region->fail(std::string("expected a box inside the domain box; in ") + "xyz"[axis] +
                     " the region spans " + formatDouble(read.min[axis]) + " .. " +
                     formatDouble(read.max[axis]) + ", the domain " +
                     formatDouble(domain.min[axis]) + " .. " + formatDouble(domain.max[axis]));
      }
    }
    dda.region = read;
  }
  if (const auto integration = m.get("time_integration")) {
    const Cursor t = integration->map({"scheme", "spectral_radius"});
    e.integration = t.valueOr("scheme", e.integration, [](const Cursor& v) {
      return v.choice("scheme", {"bossak", "shi"}) == 0 ? dda3d::TimeIntegration::Bossak
                                                        : dda3d::TimeIntegration::Shi;
    });
    if (const auto radius = t.get("spectral_radius")) {
      // Shi's scheme has no parameter: a spectral radius with it would be silently ignored.
      if (e.integration != dda3d::TimeIntegration::Bossak)
        radius->fail("only with scheme: bossak (Shi's scheme has no parameter)");
      e.spectral_radius = radius->number({.low = 0, .high = 1});
    }
  }
  return dda;
}

/// analysis.overload
OverloadAnalysis readOverloadAnalysis(const Cursor& c) {
  const Cursor m = c.map({"factors", "scales", "tolerance", "scale_uplift"});
  OverloadAnalysis overload{
      .factors = m.at("factors").increasingNumbers(kPositive),
      .scales = m.at("scales").distinctChoices("load", {"water", "gravity", "point_loads"})};
  overload.tolerance = m.numberOr("tolerance", overload.tolerance, kNonNegative);
  overload.scale_uplift = m.valueOr("scale_uplift", overload.scale_uplift, &Cursor::boolean);
  return overload;
}

/// analysis.strength_reduction
StrengthReductionAnalysis readStrengthReductionAnalysis(const Cursor& c) {
  const Cursor m = c.map({"factors", "tolerance"});
  StrengthReductionAnalysis srf{.factors = m.at("factors").increasingNumbers(kPositive)};
  srf.tolerance = m.numberOr("tolerance", srf.tolerance, kPositive);
  return srf;
}

/// analysis.equilibrium
EquilibriumAnalysis readEquilibriumAnalysis(const Cursor& c, bool has_monitors) {
  const Cursor m = c.map({"max_steps", "unbalanced_ratio", "kinetic_ratio", "settle_steps",
                          "dynamic_ratio", "start", "failure_ratio", "failure_steps", "watch"});
  EquilibriumAnalysis e;
  if (const auto watch = m.get("watch")) {
    e.watch_monitors = watch->choice("watch", {"all", "monitors"}) == 1;
    if (e.watch_monitors && !has_monitors) {
      watch->fail("`monitors` needs a `monitors` list in the scene (the blocks it watches)");
    }
    e.watch_line = watch->line();
  }
  e.settled_start = m.valueOr("start", e.settled_start, [](const Cursor& v) {
    return v.choice("start", {"unloaded", "settled"}) == 1;
  });
  if (const auto steps = m.get("max_steps")) e.max_steps = steps->integer(above(0));
  e.unbalanced_ratio = m.numberOr("unbalanced_ratio", e.unbalanced_ratio, kPositive);
  e.kinetic_ratio = m.numberOr("kinetic_ratio", e.kinetic_ratio, kPositive);
  e.failure_ratio = m.numberOr("failure_ratio", e.failure_ratio, kNonNegative);
  e.failure_steps = m.integerOr("failure_steps", e.failure_steps, above(0));
  e.settle_steps = m.integerOr("settle_steps", e.settle_steps, above(0));
  e.dynamic_ratio = m.numberOr("dynamic_ratio", e.dynamic_ratio,
                               {.low = 0, .high = 1, .low_open = false, .high_open = false});
  return e;
}

/// The `analysis` section: each stage present only when its key is.
Analysis readAnalysis(const Cursor& c, const std::vector<std::string>& joint_sets,
                      const geometry::Box& domain, bool mesh_domain, bool has_monitors) {
  const Cursor m = c.map({"blocks", "rqd", "dda", "overload", "strength_reduction", "equilibrium"});
  Analysis analysis;
  if (const auto v = m.get("blocks")) analysis.blocks = readBlocksAnalysis(*v);
  if (const auto v = m.get("rqd")) {
    analysis.rqd = readRqdAnalysis(*v, joint_sets, domain, mesh_domain);
  }
  if (const auto v = m.get("dda")) analysis.dda = readDdaAnalysis(*v, domain, mesh_domain);
  if (const auto v = m.get("overload")) analysis.overload = readOverloadAnalysis(*v);
  if (const auto v = m.get("strength_reduction")) {
    analysis.strength_reduction = readStrengthReductionAnalysis(*v);
  }
  if (const auto v = m.get("equilibrium"))
    analysis.equilibrium = readEquilibriumAnalysis(*v, has_monitors);
  return analysis;
}

// ---------------------------------------------------------------------------------------------
// SceneReader: sections that refer to named materials, joints and structures
// ---------------------------------------------------------------------------------------------

/// Reads the sections in dependency order (materials and joints before what names them).
class SceneReader {
 public:
  /// Reads the whole scene from its root node.
  Scene read(const Cursor& root, const fs::path& file) {
    const Cursor m =
        root.map({"version", "name", "seed", "domain", "materials", "rock_material", "joints",
                  "default_joint", "joint_sets", "fractures", "faults", "interlayers", "structures",
                  "loads", "supports", "monitors", "analysis"});
    scene_.file = file;
    const Cursor version = m.at("version");
    if (const int number = version.integer(); number != 1) {
      version.fail("expected format version 1, got " + std::to_string(number));
    }
    scene_.name = m.valueOr("name", std::string{}, &Cursor::string);
    scene_.seed = m.valueOr("seed", std::uint64_t{0}, &Cursor::unsignedInteger);
    readDomain(m.at("domain"));
    for (const auto& [name, entry] : m.valueOr("materials", Entries{}, &Cursor::entries)) {
      scene_.materials.push_back(readMaterial(entry, name));
    }
    scene_.rock_material =
        m.valueOr("rock_material", -1, [&](const Cursor& v) { return material(v); });
    for (const auto& [name, entry] : m.valueOr("joints", Entries{}, &Cursor::entries)) {
      scene_.joints.push_back(readJoint(entry, name));
    }
    named_joints_ = namesOf(scene_.joints);
    scene_.default_joint =
        m.valueOr("default_joint", -1, [&](const Cursor& v) { return joint(v); });
    forEachItem(m, "joint_sets",
                [&](const Cursor& c) { scene_.dfn.joint_sets.push_back(readJointSet(c)); });
    forEachItem(m, "fractures",
                [&](const Cursor& c) { scene_.dfn.polygon_sets.push_back(readFractures(c)); });
    forEachItem(m, "faults", [&](const Cursor& c) { scene_.dfn.faults.push_back(readFault(c)); });
    forEachItem(m, "interlayers",
                [&](const Cursor& c) { scene_.dfn.interlayers.push_back(readInterlayer(c)); });
    forEachItem(m, "structures",
                [&](const Cursor& c) { scene_.structures.push_back(readStructure(c)); });
    if (const auto loads = m.get("loads")) scene_.loads = readLoads(*loads);
    if (const auto supports = m.get("supports")) {
      const Cursor s = supports->map({"fixed", "rollers"});
      const std::vector<std::string> names{"bottom", "top", "west", "east", "south", "north"};
      if (const auto fixed = s.get("fixed"))
        scene_.fixed_faces = fixed->distinctChoices("face", names);
      if (const auto rollers = s.get("rollers")) {
        scene_.roller_faces = rollers->distinctChoices("face", names);
        for (const std::string& face : scene_.roller_faces) {
          if (std::find(scene_.fixed_faces.begin(), scene_.fixed_faces.end(), face) !=
              scene_.fixed_faces.end()) {
            rollers->fail("face '" + face +
                          "' is already in supports.fixed; a face is fixed "
                          "or on rollers, not both");
          }
        }
      }
      if (!s.get("fixed") && !s.get("rollers")) {
        supports->fail("supports needs `fixed` or `rollers` (a list of domain faces)");
      }
    }
    UniqueNames monitor_names;
    forEachItem(m, "monitors", [&](const Cursor& c) {
      const Cursor monitor = c.map({"name", "point"});
      scene_.monitors.push_back(
          {monitor_names.claimName(monitor), monitor.at("point").vec3(), c.line()});
    });
    if (const auto analysis = m.get("analysis")) {
      scene_.analysis = readAnalysis(*analysis, namesOf(scene_.dfn.joint_sets), scene_.dfn.domain,
                                     !scene_.domain_mesh.empty(), !scene_.monitors.empty());
    }
    return std::move(scene_);
  }

 private:
  using Entries = std::vector<std::pair<std::string, Cursor>>;

  /// domain: exactly one of box {min, max} or mesh (a file).
  void readDomain(const Cursor& c) {
    const Cursor m = c.map({"box", "mesh"});
    if (m.oneOf("box", "mesh") == 1) {
      scene_.domain_mesh = m.at("mesh").existingFile();
      return;
    }
    const Cursor box = m.at("box").map({"min", "max"});
    scene_.dfn.domain.min = box.at("min").vec3();
    scene_.dfn.domain.max = box.at("max").vec3();
    for (int axis = 0; axis < 3; ++axis) {
      const double min = scene_.dfn.domain.min[axis], max = scene_.dfn.domain.max[axis];
      if (!(min < max)) {
        box.fail("expected min < max in every component, got " + formatDouble(min) +
                 " >= " + formatDouble(max) + " in " + "xyz"[axis]);
      }
    }
    // Edges of 1e-300 m have min < max and no volume in floating point.
    const double volume = scene_.dfn.domain.volume();
    if (!(volume > 0.0 && std::isfinite(volume))) {
      box.fail("expected a box with a finite volume > 0, got " + formatDouble(volume) + " m3");
    }
  }

  /// A `materials` entry: unit_weight or density, young, poisson.
  static Material readMaterial(const Cursor& c, const std::string& name) {
    const Cursor m = c.map({"unit_weight", "density", "young", "poisson"});
    Material material{.name = name};
    material.density = m.oneOf("unit_weight", "density") == 0
                           ? m.at("unit_weight").number(kPositive) / kStandardGravity
                           : m.at("density").number(kPositive);
    material.young = m.at("young").number(kPositive);
    material.poisson =
        m.at("poisson").number({.low = -1, .high = 0.5, .low_open = true, .high_open = true});
    return material;
  }

  /// Index of the material named at `c`.
  int material(const Cursor& c) const {
    return lookupName(c, namesOf(scene_.materials), "material");
  }

  /// Index of the joint named at `c` (among the `joints` section).
  int joint(const Cursor& c) const { return lookupName(c, named_joints_, "joint"); }

  /// The entry's `joint`, or the default joint when it has none.
  int jointOf(const Cursor& entry) const {
    return entry.valueOr("joint", scene_.default_joint, [&](const Cursor& v) { return joint(v); });
  }

  /// thickness (default 0) and material of a fault or interlayer; `what` is "a fault".
  std::pair<double, int> readSlab(const Cursor& entry, const std::string& what) const {
    const double thickness = entry.numberOr("thickness", 0.0, kNonNegative);
    const int slab_material =
        entry.valueOr("material", -1, [&](const Cursor& v) { return material(v); });
    if (thickness > 0 && slab_material < 0) {
      entry.fail(what + " with thickness > 0 needs a material");
    }
    return {thickness, slab_material};
  }

  /// A `joint_sets` entry.
  geometry::JointSetSpec readJointSet(const Cursor& c) {
    const Cursor m = c.map({"name", "dip_direction", "dip", "orientation", "spacing", "intensity",
                            "trace_length", "shape", "joint", "min_cut_size"});
    geometry::JointSetSpec set;
    set.name = dfn_names_.claimName(m);
    set.orientation = readOrientation(m);
    JointSetKeys keys;
    if (m.oneOf("spacing", "intensity") == 0) {
      keys.intensity = locationOf(m.at("spacing"));
      set.spacing = readSpacing(m.at("spacing"));
    } else {
      keys.intensity = locationOf(m.at("intensity"));
      set.p32 = m.at("intensity").map({"p32"}).at("p32").number(kPositive);
    }
    const Cursor trace_length = m.at("trace_length");
    keys.trace_length = locationOf(trace_length);
    scene_.joint_set_keys.push_back(keys);
    const geometry::Distribution trace_distribution = readDistribution(trace_length);
    checkTraceLength(trace_length, trace_distribution);
    set.trace_length = trace_distribution.spec();
    set.shape = m.valueOr("shape", set.shape, &readShape);
    set.joint = jointOf(m);
    set.min_cut_size = m.numberOr("min_cut_size", 0.0, kNonNegative);
    return set;
  }

  /// A `fractures` entry: the polygons of a FAB file, named after the file's stem.
  geometry::PolygonSetSpec readFractures(const Cursor& c) {
    const Cursor m = c.map({"file", "joint"});
    const Cursor file = m.at("file");
    const fs::path path = file.existingFile();
    geometry::PolygonSetSpec set;
    set.name = path.stem().string();
    dfn_names_.claim(file, set.name, m.path());
    for (FabFracture& fracture : readFab(path).fractures) {
      set.polygons.push_back(std::move(fracture.vertices));
      set.file_sets.push_back(fracture.set);
    }
    set.joint = jointOf(m);
    return set;
  }

  /// A `faults` entry.
  geometry::FaultSpec readFault(const Cursor& c) {
    const Cursor m =
        c.map({"name", "center", "dip_direction", "dip", "size", "thickness", "material", "joint"});
    geometry::FaultSpec fault;
    fault.name = dfn_names_.claimName(m);
    fault.center = m.at("center").vec3();
    fault.dip_direction = m.at("dip_direction").number(closed(0, 360));
    fault.dip = m.at("dip").number(closed(0, 90));
    if (const auto size = m.get("size")) {
      const std::vector<Cursor> axes = size->items();
      if (axes.size() != 2) size->fail("expected a list of 2 numbers [major, minor]");
      const double major = axes[0].number(kPositive);
      fault.size = {major, axes[1].number({.low = 0, .high = major, .low_open = true},
                                          "(minor must not exceed major)")};
    }
    std::tie(fault.thickness, fault.material) = readSlab(m, "a fault");
    fault.joint = jointOf(m);
    return fault;
  }

  /// An `interlayers` entry.
  geometry::InterlayerSpec readInterlayer(const Cursor& c) {
    const Cursor m = c.map({"name", "profile", "sweep", "thickness", "material", "joint"});
    geometry::InterlayerSpec layer;
    layer.name = dfn_names_.claimName(m);
    layer.profile = readProfile(m.at("profile"), 2);
    layer.sweep = readSweep(m.at("sweep"));
    std::tie(layer.thickness, layer.material) = readSlab(m, "an interlayer");
    if (layer.thickness > 0.0) {
      // The slab's surfaces are the profile offset by half the thickness, with mitred knees:
      // geometry::kMaxInterlayerTurn, which generateInterlayer also refuses.
      const std::vector<Cursor> points = m.at("profile").items();
      for (std::size_t i = 1; i + 1 < layer.profile.size(); ++i) {
        const Vec2 d1 = (layer.profile[i] - layer.profile[i - 1]).normalized();
        const Vec2 d2 = (layer.profile[i + 1] - layer.profile[i]).normalized();
        if (d1.dot(d2) < std::cos(geometry::kMaxInterlayerTurn * std::numbers::pi / 180.0)) {
          const double turn =
              std::acos(std::clamp(d1.dot(d2), -1.0, 1.0)) * 180.0 / std::numbers::pi;
          points[i].fail("the profile turns by " + formatDouble(std::round(turn * 10.0) / 10.0) +
                         " degrees at point " + std::to_string(i + 1) + ", more than the " +
                         formatDouble(geometry::kMaxInterlayerTurn) +
                         " an interlayer with thickness can turn");
        }
      }
    }
    layer.joint = jointOf(m);
    return layer;
  }

  /// A `structures` entry; an inline joint map is appended to the scene's joints.
  StructureSpec readStructure(const Cursor& c) {
    const Cursor m = c.map({"name", "prism", "mesh", "material", "joint", "contact_point_spacing"});
    StructureSpec structure;
    structure.name = structure_names_.claimName(m);
    if (m.oneOf("prism", "mesh") == 0) {
      const Cursor prism = m.at("prism").map({"profile", "sweep", "from", "to"});
      structure.prism_profile = readProfile(prism.at("profile"), 3);
      structure.profile_line = prism.at("profile").line();
      structure.profile_column = prism.at("profile").column();
      structure.prism_sweep = readSweep(prism.at("sweep"));
      structure.prism_from = prism.at("from").number();
      structure.prism_to =
          prism.at("to").number(above(structure.prism_from), "(to must exceed from)");
    } else {
      structure.mesh = m.at("mesh").existingFile();
    }
    structure.material = material(m.at("material"));
    const std::optional<Cursor> contact = m.get("joint");
    if (contact && contact->isMap()) {
      structure.joint = static_cast<int>(scene_.joints.size());
      scene_.joints.push_back(readJoint(*contact, structure.name + ".joint"));
    } else {
      structure.joint = jointOf(m);
    }
    if (const auto spacing = m.get("contact_point_spacing")) {
      structure.contact_point_spacing_line = spacing->line();
      if (!spacing->is("auto")) {
        if (!spacing->isNumber()) spacing->failExpected("'auto' or a number >= 0 (m)");
        structure.contact_point_spacing = spacing->number(kNonNegative);
      }
    }
    return structure;
  }

  /// A `loads.water` entry.
  WaterLoad readWater(const Cursor& c) const {
    const Cursor m = c.map({"level", "unit_weight", "uplift", "on"});
    WaterLoad water;
    const Cursor level = m.at("level");
    water.level = level.number();
    // Below the domain's bottom the water wets nothing (box domains: a mesh domain's extent
    // is not known here).
    if (scene_.domain_mesh.empty() && water.level < scene_.dfn.domain.min.z()) {
      level.fail("the water level " + formatDouble(water.level) +
                 " m lies below the domain bottom z = " + formatDouble(scene_.dfn.domain.min.z()) +
                 " m and would wet nothing");
    }
    water.unit_weight = m.numberOr("unit_weight", water.unit_weight, kPositive);
    water.uplift = m.valueOr("uplift", false, &Cursor::boolean);
    const Cursor on = m.at("on").map({"structure", "facing", "domain_top", "region"});
    if (on.oneOf("structure", "domain_top") == 0) {
      const Cursor structure = on.at("structure");
      lookupName(structure, namesOf(scene_.structures), "structure");
      water.structure = structure.string();
      water.facing = readDirection(on.at("facing"));
    } else {
      const Cursor top = on.at("domain_top");
      if (!top.boolean()) top.fail("expected true (or an 'on: {structure: ...}' entry), got false");
      if (on.has("facing")) {
        on.at("facing").fail("'facing' selects structure faces; remove it for domain_top");
      }
      water.domain_top = true;
    }
    water.region = on.valueOr("region", water.region, &readRegion);
    return water;
  }

  /// The `loads` section.
  Loads readLoads(const Cursor& c) const {
    const Cursor m = c.map({"gravity", "water", "point_loads"});
    Loads loads;
    if (const auto gravity = m.get("gravity")) {
      if (!gravity->isNumber() && !gravity->isList()) {
        gravity->failExpected("a number > 0 or a list of 3 numbers");
      }
      loads.gravity =
          gravity->isNumber() ? Vec3(0, 0, -gravity->number(kPositive)) : gravity->vec3();
    }
    forEachItem(m, "water", [&](const Cursor& v) { loads.water.push_back(readWater(v)); });
    forEachItem(m, "point_loads",
                [&](const Cursor& v) { loads.point_loads.push_back(readPointLoad(v)); });
    return loads;
  }

  Scene scene_;                            ///< what is being read
  std::vector<std::string> named_joints_;  ///< joints of the `joints` section (referable by name)
  UniqueNames dfn_names_;                  ///< joint sets, fractures files, faults, interlayers
  UniqueNames structure_names_;            ///< structures
};

/// Length of the UTF-8 sequence that starts at text[k] (1-4), or 0 when it is not one: a
/// stray continuation byte, a truncated sequence, an overlong form, a surrogate, or a code
/// point above U+10FFFF (RFC 3629).
std::size_t utf8Length(const std::string& text, std::size_t k) {
  const auto byte = [&](std::size_t i) {
    return i < text.size() ? static_cast<unsigned char>(text[i]) : 0u;
  };
  const unsigned lead = byte(k);
  if (lead < 0x80) return 1;
  const auto continuation = [&](std::size_t i, unsigned low = 0x80, unsigned high = 0xBF) {
    return byte(i) >= low && byte(i) <= high;
  };
  if (lead >= 0xC2 && lead <= 0xDF) return continuation(k + 1) ? 2 : 0;
  if (lead >= 0xE0 && lead <= 0xEF) {
    const unsigned low = lead == 0xE0 ? 0xA0 : 0x80, high = lead == 0xED ? 0x9F : 0xBF;
    return continuation(k + 1, low, high) && continuation(k + 2) ? 3 : 0;
  }
  if (lead >= 0xF0 && lead <= 0xF4) {
    const unsigned low = lead == 0xF0 ? 0x90 : 0x80, high = lead == 0xF4 ? 0x8F : 0xBF;
    return continuation(k + 1, low, high) && continuation(k + 2) && continuation(k + 3) ? 4 : 0;
  }
  return 0;
}

/// An InputError at the first byte of `text` that is not valid UTF-8 (a scene is UTF-8, as
/// YAML and the JSON summary require); checked before anything is read or written.
void checkUtf8(const std::string& text, const fs::path& file) {
  int line = 1;
  std::size_t line_start = 0;
  for (std::size_t k = 0; k < text.size();) {
    const std::size_t length = utf8Length(text, k);
    if (length == 0) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02X", static_cast<unsigned char>(text[k]));
      throw InputError(locate(
          file, line, static_cast<int>(k - line_start) + 1,
          std::string("invalid UTF-8 (byte ") + hex + "); the scene file must be UTF-8 text"));
    }
    if (text[k] == '\n') {
      ++line;
      line_start = k + 1;
    }
    k += length;
  }
}

/// Sees where each document of a YAML stream starts, nothing else.
class DocumentStarts : public YAML::EventHandler {
 public:
  std::vector<YAML::Mark> starts;
  void OnDocumentStart(const YAML::Mark& mark) override { starts.push_back(mark); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

/// The single YAML document of `text`, or an InputError for invalid YAML.
YAML::Node loadDocument(const std::string& text, const fs::path& file) {
  checkUtf8(text, file);
  const auto at = [&](const YAML::Mark& mark, const std::string& what) {
    return InputError(locate(file, std::max(mark.line, 0) + 1, std::max(mark.column, 0) + 1, what));
  };
  const auto invalid = [&](const YAML::Mark& mark, const std::string& what) {
    return at(mark, "invalid YAML: " + what);
  };
  try {
    // The documents are counted first, at most two, with the parser alone: yaml-cpp 0.7's
    // LoadAll never ends on a stray ',' outside [ ] or { } (the parser starts the same empty
    // document again without consuming it, and the list of documents grows until memory
    // runs out: jbeder/yaml-cpp#1040, fixed upstream after 0.8 by PR #1319). Such a document
    // starts where the previous one did.
    std::istringstream stream(text);
    YAML::Parser parser(stream);
    DocumentStarts documents;
    while (documents.starts.size() < 2 && parser.HandleNextDocument(documents)) {
    }
    if (documents.starts.size() == 2) {
      const YAML::Mark& first = documents.starts[0];
      const YAML::Mark& second = documents.starts[1];
      if (second.pos == first.pos) {
        throw invalid(second, "a ',' outside a flow collection ([ ] or { })");
      }
      throw at(second, "expected one YAML document; a second one starts here");
    }
    return documents.starts.empty() ? YAML::Node() : YAML::Load(text);
  } catch (const YAML::Exception& error) {
    throw invalid(error.mark, error.msg);
  }
}

}  // namespace

std::string locate(const Scene& scene, const KeyLocation& key, const std::string& what) {
  return locate(scene.file, key.line, key.column, key.path.empty() ? what : key.path + ": " + what);
}

Scene loadScene(const std::filesystem::path& file) {
  std::error_code error;
  std::ifstream in(file, std::ios::binary);
  if (!in || fs::is_directory(file, error)) {
    throw InputError(file.string() + ": cannot read the scene file");
  }
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(file.string() + ": cannot read the scene file");
  return parseScene(text, file);
}

Scene parseScene(const std::string& text, const std::filesystem::path& file) {
  const Source source{file, fs::absolute(file).parent_path()};
  const Cursor root(source, loadDocument(text, file), "", YAML::Mark());
  return SceneReader().read(root, file);
}

}  // namespace rockmass::io
