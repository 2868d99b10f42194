#include "swath/base/json_document.hpp"

#include <cmath>
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
    // nlohmann's "; last read: '...'" quotes the file's bytes (a symlink to /etc/passwd would
    // show its first line); the line and column say where.
    reason = reason.substr(0, reason.find("; last read:"));
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

const nlohmann::json* json_find(const nlohmann::json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

const nlohmann::json& json_member(const nlohmann::json& object, const char* key,
                                  const std::string& where) {
  if (!object.is_object()) throw InputError(where + ": expected a JSON object");
  const nlohmann::json* member = json_find(object, key);
  if (member == nullptr) throw InputError(where + ": no \"" + key + "\"");
  return *member;
}

double json_number(const nlohmann::json& value, const std::string& where) {
  if (!value.is_number()) throw InputError(where + " must be a number");
  const double v = value.get<double>();
  if (!std::isfinite(v)) throw InputError(where + " must be a finite number");
  return v;
}

long long json_integer(const nlohmann::json& value, long long lo, long long hi,
                       const std::string& where) {
  const double v = json_number(value, where);
  if (v != std::floor(v) || v < static_cast<double>(lo) || v > static_cast<double>(hi))
    throw InputError(where + " must be a whole number from " + std::to_string(lo) + " to " +
                     std::to_string(hi));
  return static_cast<long long>(v);
}

const std::string& json_string(const nlohmann::json& value, const std::string& where) {
  if (!value.is_string()) throw InputError(where + " must be a string");
  return value.get_ref<const std::string&>();
}

const nlohmann::json& json_array(const nlohmann::json& value, const std::string& where,
                                 std::size_t min_size) {
  if (!value.is_array()) throw InputError(where + " must be an array");
  if (value.size() < min_size)
    throw InputError(where + " must have at least " + std::to_string(min_size) + " elements");
  return value;
}

}  // namespace swath::base
