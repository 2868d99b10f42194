#pragma once
// Internal: loading a YAML document with errors that name the source and line.

#include <yaml-cpp/yaml.h>

#include <string>

#include "swath/geometry/input_error.hpp"

namespace swath::planning::detail {

inline YAML::Node load_yaml(const std::string& text, const std::string& source) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw geometry::InputError(source + ": line " + std::to_string(e.mark.line + 1) +
                               ": invalid YAML (" + e.msg + ")");
  }
}

}  // namespace swath::planning::detail
