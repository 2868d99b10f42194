#pragma once
// `swath plan --config mission.yaml`: a mission YAML holding any of the command's options.

#include <CLI/CLI.hpp>

#include <string>

namespace swath::apps {

/// Sets the options of `app` (a parsed `swath plan` command) from a mission YAML mapping: keys are
/// the long option names, `field` is FIELD. Options given on the command line win. Throws
/// base::InputError naming `source`, the line and the key for invalid YAML, a non-mapping, a
/// key that is not a plain name, an unknown or repeated key, a non-scalar value, or a value the
/// option refuses.
void apply_mission_config(CLI::App& app, const std::string& yaml_text, const std::string& source);

}  // namespace swath::apps
