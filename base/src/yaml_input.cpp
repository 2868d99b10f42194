#include "swath/base/yaml_input.hpp"

#include <vector>

namespace swath::base {

YAML::Node load_yaml(const std::string& text, const std::string& source) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(source + ": line " + std::to_string(e.mark.line + 1) + ": invalid YAML (" +
                     e.msg + ")");
  }
  // Count the nodes as a reader would visit them (an alias once per use), iteratively, and stop
  // at the limit: the count costs at most kMaxYamlNodes steps whatever the document.
  std::vector<YAML::Node> stack{root};
  std::size_t count = 0;
  while (!stack.empty()) {
    const YAML::Node node = stack.back();
    stack.pop_back();
    if (++count > kMaxYamlNodes)
      throw InputError(source + ": the YAML document expands to more than " +
                       std::to_string(kMaxYamlNodes) +
                       " nodes (aliases count at every use); swath refuses it");
    if (node.IsSequence()) {
      for (const YAML::Node& child : node) stack.push_back(child);
    } else if (node.IsMap()) {
      for (const auto& kv : node) {
        stack.push_back(kv.first);
        stack.push_back(kv.second);
      }
    }
  }
  return root;
}

}  // namespace swath::base
