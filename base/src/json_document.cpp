#include "swath/base/json_document.hpp"

#include <cmath>
#include <set>
#include <vector>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"

namespace swath::base {

using nlohmann::json;

namespace {

// A key repeated in one object, found by a SAX pass: one set of keys per open object. (Not
// nlohmann's parser callback: its DOM builder then scans the enclosing container at every
// object's end, quadratic in an array's length — a 93,000-item .plan took 22 s to read.)
class RepeatedKeyFinder : public nlohmann::json_sax<json> {
 public:
  const std::string& repeated() const { return repeated_; }
  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override {
    open_objects_.emplace_back();
    return true;
  }
  bool key(string_t& key) override {
    if (!open_objects_.back().insert(key).second && repeated_.empty()) repeated_ = key;
    return true;
  }
  bool end_object() override {
    open_objects_.pop_back();
    return true;
  }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
    return false;  // json::parse has already read the same text without error
  }

 private:
  std::vector<std::set<std::string>> open_objects_;
  std::string repeated_;
};

}  // namespace

nlohmann::json parse_json_document(const std::string& text, const std::string& source) {
  json root;
  try {
    root = json::parse(text);
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
  RepeatedKeyFinder keys;
  json::sax_parse(text, &keys);
  if (!keys.repeated().empty())
    throw InputError(source + ": the key \"" + keys.repeated() +
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
