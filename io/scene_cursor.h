// The scene reader's cursor: a YAML node with its key path and typed getters that throw an
// InputError located at the node ("file:line:column: key.path: expected ..., got ..."), with
// the text helpers, ranges and name tables the readers share. Internal to io (io/scene.cpp,
// io/scene_sections.cpp).
#pragma once

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "io/atomic_file.h"
#include "io/input_error.h"
#include "io/scene.h"

namespace rockmass::io::scene_detail {

namespace fs = std::filesystem;

constexpr double kInf = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------------------
// Text helpers
// ---------------------------------------------------------------------------------------------

/// Items joined by ", ".
inline std::string joined(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return text;
}

/// The number a plain YAML scalar spells ("-0.5", "+3", "2.6e4"), if it is a finite one.
inline std::optional<double> parseNumber(std::string_view text) {
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

  /// The YAML node itself (the uncertainty section resolves key paths on the root's).
  const YAML::Node& node() const { return node_; }

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
inline KeyLocation locationOf(const Cursor& c) {
  return {c.path(), c.line(), c.column()};
}

/// Index of the name at `c` among `names`; `noun` ("joint") words the error.
inline int lookupName(const Cursor& c, const std::vector<std::string>& names,
                      const std::string& noun) {
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

}  // namespace rockmass::io::scene_detail
