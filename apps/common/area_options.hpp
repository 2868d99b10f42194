#pragma once
// The options that choose one area from a GIS file holding several (docs/swath-plan.md): shared by
// every command that reads an area.

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

#include "swath/geometry/field.hpp"

namespace swath::apps {

struct AreaChoice {
  std::optional<std::string> layer, feature, name_field;

  void add_options(CLI::App& app) {
    app.add_option("--layer", layer,
                   "GIS files with several layers: the layer to read (name or 0-based index)");
    app.add_option("--feature", feature,
                   "Files with several areas: the area to plan (its name, or its 0-based "
                   "position among the layer's areas)");
    app.add_option("--name-field", name_field,
                   "The attribute that names areas (default: name, Name, NAME or id)");
  }
  void apply(geometry::FieldReadOptions& o) const {
    o.layer = layer;
    o.feature = feature;
    o.name_field = name_field;
  }
};

}  // namespace swath::apps
