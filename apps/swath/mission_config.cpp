#include "mission_config.hpp"

#include <yaml-cpp/yaml.h>

#include <set>

#include "swath/base/input_error.hpp"
#include "swath/base/yaml_input.hpp"

namespace swath::apps {

using base::InputError;

void apply_mission_config(CLI::App& app, const std::string& yaml_text, const std::string& source) {
  const YAML::Node root = base::load_yaml(yaml_text, source);  // aliases bounded too
  if (root.IsNull()) return;
  if (!root.IsMap()) throw InputError(source + ": a mission config is a mapping of option: value");
  std::set<std::string> seen;
  for (const auto& kv : root) {
    const std::string where = source + ": line " + std::to_string(kv.first.Mark().line + 1);
    if (!kv.first.IsScalar()) throw InputError(where + ": a key must be an option name");
    const std::string key = kv.first.Scalar();
    if (!seen.insert(key).second) throw InputError(where + ": '" + key + "' is given twice");
    CLI::Option* option = key == "field"                     ? app.get_option_no_throw("FIELD")
                          : key == "config" || key == "help" ? nullptr
                                                             : app.get_option_no_throw("--" + key);
    if (option == nullptr)
      throw InputError(where + ": unknown key '" + key +
                       "' (keys are the long options of swath plan)");
    if (option->count() > 0) continue;  // the command line wins
    if (!kv.second.IsScalar()) throw InputError(where + ": " + key + " must be a single value");
    try {
      option->add_result(kv.second.Scalar());
      option->run_callback();
    } catch (const CLI::Error& e) {
      throw InputError(where + ": " + key + ": " + e.what());
    }
  }
}

}  // namespace swath::apps
