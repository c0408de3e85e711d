// The `uncertainty` section of a scene: the inputs an ensemble varies (docs/ensemble.md),
// each a number of the scene named by its key path, with the distribution it is drawn from.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "io/scene_sections.h"

namespace rockmass::io::scene_detail {

namespace {

/// One segment of a key path: a map key, optionally followed by a list index ("water[0]").
struct Segment {
  std::string name;
  std::optional<std::size_t> index;
};

/// The segments of "a.b[2].c", or an empty optional for a malformed path.
std::optional<std::vector<Segment>> splitKey(const std::string& key) {
  std::vector<Segment> segments;
  std::size_t at = 0;
  while (at <= key.size()) {
    const std::size_t dot = key.find('.', at);
    std::string part = key.substr(at, dot == std::string::npos ? std::string::npos : dot - at);
    Segment segment;
    if (const std::size_t open = part.find('['); open != std::string::npos) {
      if (part.back() != ']' || open + 2 > part.size() - 1) return std::nullopt;
      const std::string digits = part.substr(open + 1, part.size() - open - 2);
      const std::optional<std::size_t> index = parseInteger<std::size_t>(digits);
      if (!index) return std::nullopt;
      segment.index = index;
      part.resize(open);
    }
    if (part.empty() && !segment.index) return std::nullopt;
    segment.name = part;
    segments.push_back(segment);
    if (dot == std::string::npos) break;
    at = dot + 1;
  }
  return segments;
}

/// The item of a list whose `name` is `name`.
std::optional<YAML::Node> namedItem(const YAML::Node& list, const std::string& name) {
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node item = list[i];  // list is const: no key is added
    if (item.IsMap() && item["name"] && item["name"].IsScalar() && item["name"].Scalar() == name) {
      return item;
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<YAML::Node> resolveKey(const YAML::Node& root, const std::string& key,
                                     std::string& why) {
  const std::optional<std::vector<Segment>> segments = splitKey(key);
  if (!segments) {
    why = "expected a key path such as joints.soft.friction or loads.water[0].level, got '" + key +
          "'";
    return std::nullopt;
  }
  if (segments->front().name == "uncertainty" || segments->front().name == "seed" ||
      segments->front().name == "version") {
    why = "'" + segments->front().name + "' cannot vary in an ensemble";
    return std::nullopt;
  }
  // Node::reset rebinds; Node::operator= would assign through to the tree (yaml-cpp), and the
  // non-const operator[] would add missing keys: lookups go through a const view.
  YAML::Node node;
  node.reset(root);
  std::string path;
  for (const Segment& segment : *segments) {
    if (!segment.name.empty()) {
      const std::string at = path.empty() ? segment.name : path + "." + segment.name;
      const YAML::Node& view = node;
      if (view.IsMap() && view[segment.name]) {
        node.reset(view[segment.name]);
      } else if (view.IsSequence()) {
        const std::optional<YAML::Node> item = namedItem(view, segment.name);
        if (!item) {
          why = "the scene has no item named '" + segment.name + "' in " + path;
          return std::nullopt;
        }
        node.reset(*item);
      } else {
        why = "the scene has no key " + at;
        return std::nullopt;
      }
      path = at;
    }
    if (segment.index) {
      if (!node.IsSequence() || *segment.index >= node.size()) {
        why = "the scene has no item [" + std::to_string(*segment.index) + "] in " + path;
        return std::nullopt;
      }
      const YAML::Node& view = node;
      node.reset(view[*segment.index]);
      path += "[" + std::to_string(*segment.index) + "]";
    }
  }
  if (!node.IsScalar() || !parseNumber(node.Scalar())) {
    why = "the scene's " + key + " is not a number";
    return std::nullopt;
  }
  return node;
}

namespace {

/// The `std` next to the key (the std of the same distribution map), for sample_mean.
std::optional<double> siblingStd(const YAML::Node& root, const std::string& key) {
  const std::size_t dot = key.rfind('.');
  if (dot == std::string::npos) return std::nullopt;
  std::string why;
  const std::optional<YAML::Node> node = resolveKey(root, key.substr(0, dot) + ".std", why);
  if (!node) return std::nullopt;
  return parseNumber(node->Scalar());
}

UncertainInput readInput(const Cursor& c, const YAML::Node& root) {
  const Cursor m =
      c.map({"key", "distribution", "mean", "std", "min", "max", "mode", "count", "values"});
  UncertainInput input;
  const Cursor key = m.at("key");
  input.key = key.string();
  input.location = locationOf(key);
  std::string why;
  const std::optional<YAML::Node> node = resolveKey(root, input.key, why);
  if (!node) key.fail(why);
  input.value = *parseNumber(node->Scalar());
  const std::vector<std::string> kinds{"normal",     "lognormal",   "uniform",
                                       "triangular", "sample_mean", "list"};
  const Cursor kind = m.at("distribution");
  input.distribution = kinds[kind.choice("distribution", kinds)];
  // Keys each kind takes; any other is an error (a typo would silently change nothing).
  const std::vector<std::string> takes =
      input.distribution == "normal"       ? std::vector<std::string>{"mean", "std", "min", "max"}
      : input.distribution == "lognormal"  ? std::vector<std::string>{"mean", "std"}
      : input.distribution == "uniform"    ? std::vector<std::string>{"min", "max"}
      : input.distribution == "triangular" ? std::vector<std::string>{"min", "mode", "max"}
      : input.distribution == "list"       ? std::vector<std::string>{"values"}
                                           : std::vector<std::string>{"count", "std", "min", "max"};
  for (const std::string name : {"mean", "std", "min", "max", "mode", "count", "values"}) {
    if (const auto given = m.get(name);
        given && std::find(takes.begin(), takes.end(), name) == takes.end()) {
      given->fail("a " + input.distribution + " distribution takes " + joined(takes) + ", not " +
                  name);
    }
  }
  if (input.distribution == "normal" || input.distribution == "lognormal") {
    input.mean = m.numberOr("mean", input.value, kAnyNumber);
    input.std = m.at("std").number(above(0.0));
    if (input.distribution == "lognormal" && !(input.mean > 0.0)) {
      (m.has("mean") ? m.at("mean") : key)
          .fail("a lognormal distribution needs a mean > 0, got " + formatDouble(input.mean));
    }
    if (input.distribution == "normal") {
      input.min = m.numberOr("min", input.min, kAnyNumber);
      input.max = m.numberOr("max", input.max, kAnyNumber);
      if (!(input.min < input.max)) {
        m.at("max").fail("expected max > min (" + formatDouble(input.min) + "), got " +
                         formatDouble(input.max));
      }
    }
  } else if (input.distribution == "uniform" || input.distribution == "triangular") {
    input.min = m.at("min").number();
    input.max = m.at("max").number();
    if (!(input.min < input.max)) {
      m.at("max").fail("expected max > min (" + formatDouble(input.min) + "), got " +
                       formatDouble(input.max));
    }
    if (input.distribution == "triangular") {
      input.mode = m.numberOr("mode", input.value, kAnyNumber);
      if (input.mode < input.min || input.mode > input.max) {
        (m.has("mode") ? m.at("mode") : key)
            .fail("the mode " + formatDouble(input.mode) + " is outside [min, max] = [" +
                  formatDouble(input.min) + ", " + formatDouble(input.max) + "]");
      }
    }
  } else if (input.distribution == "list") {
    const Cursor values = m.at("values");
    for (const Cursor& item : values.items()) input.values.push_back(item.number());
    if (input.values.empty()) values.failExpected("a list of at least one number");
  } else {  // sample_mean: the mean of `count` samples of standard deviation `std`
    const int count = m.at("count").integer(atLeast(2));
    double std = 0.0;
    if (const auto given = m.get("std")) {
      std = given->number(above(0.0));
    } else if (const std::optional<double> sibling = siblingStd(root, input.key);
               sibling && *sibling > 0.0) {
      std = *sibling;
    } else {
      m.fail("a sample_mean distribution needs `std`: the scene has no std > 0 next to " +
             input.key);
    }
    input.mean = input.value;
    input.std = std / std::sqrt(static_cast<double>(count));
    input.min = m.numberOr("min", input.min, kAnyNumber);
    input.max = m.numberOr("max", input.max, kAnyNumber);
    if (!(input.min < input.max)) {
      m.at("max").fail("expected max > min (" + formatDouble(input.min) + "), got " +
                       formatDouble(input.max));
    }
  }
  return input;
}

}  // namespace

Uncertainty readUncertainty(const Cursor& c, const YAML::Node& root) {
  const Cursor m = c.map({"sampling", "size", "targets", "inputs"});
  Uncertainty u;
  if (const auto sampling = m.get("sampling")) {
    const std::vector<std::string> methods{"monte_carlo", "latin_hypercube"};
    u.latin_hypercube = sampling->choice("sampling", methods) == 1;
    u.size_location = locationOf(*sampling);
  }
  if (const auto size = m.get("size")) {
    if (!u.latin_hypercube)
      size->fail("size is the Latin hypercube's: give sampling: latin_hypercube");
    // At most the largest ensemble (--realizations): each input keeps a permutation of size.
    u.size = size->integer(closed(1, 1e6));
    u.size_location = locationOf(*size);
  } else if (u.latin_hypercube) {
    m.at("sampling")
        .fail(
            "latin_hypercube needs `size`, the number of strata of each input (the largest "
            "ensemble it samples)");
  }
  if (const auto targets = m.get("targets")) {
    const Cursor t = targets->map({"overload", "strength_reduction"});
    if (t.has("overload")) u.overload_target = t.at("overload").number(above(0.0));
    if (t.has("strength_reduction")) {
      u.strength_target = t.at("strength_reduction").number(above(0.0));
    }
  }
  std::vector<std::string> keys;
  forEachItem(m, "inputs", [&](const Cursor& item) {
    UncertainInput input = readInput(item, root);
    if (std::find(keys.begin(), keys.end(), input.key) != keys.end()) {
      item.at("key").fail("the key " + input.key + " is already an input");
    }
    keys.push_back(input.key);
    u.inputs.push_back(std::move(input));
  });
  return u;
}

}  // namespace rockmass::io::scene_detail
