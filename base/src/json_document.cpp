#include "swath/base/json_document.hpp"

#include <set>
#include <vector>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"

namespace swath::base {

using nlohmann::json;

nlohmann::json parse_json_document(const std::string& text, const std::string& source) {
  // One set of keys per open object; a callback sees every key as it is read.
  std::vector<std::set<std::string>> open_objects;
  std::string repeated;
  const json::parser_callback_t check_keys = [&](int, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::object_start) {
      open_objects.emplace_back();
    } else if (event == json::parse_event_t::object_end) {
      if (!open_objects.empty()) open_objects.pop_back();
    } else if (event == json::parse_event_t::key && !open_objects.empty()) {
      const std::string& key = parsed.get_ref<const std::string&>();
      if (!open_objects.back().insert(key).second && repeated.empty()) repeated = key;
    }
    return true;
  };
  json root;
  try {
    root = json::parse(text, check_keys);
  } catch (const json::parse_error& e) {
    const auto [line, column] = line_column(text, e.byte == 0 ? 0 : e.byte - 1);
    std::string reason = e.what();
    const auto colon = reason.find(": ", reason.find("column"));
    reason = colon == std::string::npos ? reason : reason.substr(colon + 2);
    throw InputError(source + ": line " + std::to_string(line) + ", column " +
                     std::to_string(column) + ": invalid JSON (" + reason + ")");
  } catch (const json::exception& e) {
    // Not a syntax error but a value JSON cannot hold as a double (e.g. 1e999).
    std::string reason = e.what();
    const auto bracket = reason.find("] ");
    throw InputError(source + ": invalid JSON (" +
                     (bracket == std::string::npos ? reason : reason.substr(bracket + 2)) + ")");
  }
  if (!repeated.empty())
    throw InputError(source + ": the key \"" + repeated +
                     "\" appears twice in one object; which one holds is ambiguous");
  return root;
}

}  // namespace swath::base
