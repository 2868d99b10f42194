#pragma once
// Internal to swath's YAML readers (planning and energy): loading a document, checking a
// mapping's keys, and turning whatever yaml-cpp throws into InputError naming the source and line.

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <set>
#include <string>

#include "swath/base/input_error.hpp"

namespace swath::base {

inline std::string yaml_line(const YAML::Node& node) {
  return "line " + std::to_string(node.Mark().line + 1);
}

/// The most nodes a YAML document may expand to, aliases counted at every use: a 27 KB file can
/// otherwise stand for billions of nodes ("billion laughs") and keep a reader busy for ever.
inline constexpr std::size_t kMaxYamlNodes = 1'000'000;

/// Parses `text`. Throws InputError naming `source` and the line for invalid YAML, and for a
/// document that expands to more than kMaxYamlNodes nodes.
YAML::Node load_yaml(const std::string& text, const std::string& source);

/// Every key of `map` is a plain name given once; throws InputError ("<place>: line N: ...").
inline void check_plain_unique_keys(const YAML::Node& map, const std::string& place) {
  if (!map.IsMap()) return;
  std::set<std::string> seen;
  for (const auto& kv : map) {
    if (!kv.first.IsScalar())
      throw InputError(place + ": " + yaml_line(kv.first) + ": a key must be a plain name");
    if (!seen.insert(kv.first.Scalar()).second)
      throw InputError(place + ": " + yaml_line(kv.first) + ": '" + kv.first.Scalar() +
                       "' is given twice");
  }
}

/// `read()`, with a yaml-cpp exception it lets through (a value of the wrong shape where the
/// reader did not look first) reported as bad input at its line.
template <typename F>
auto yaml_guard(const std::string& source, F&& read) {
  try {
    return read();
  } catch (const YAML::Exception& e) {
    throw InputError(source + ": line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
}

}  // namespace swath::base
