#include "swath/base/json_document.hpp"

#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"

namespace swath::base {

using nlohmann::json;

namespace {

// nlohmann's DOM builder (json_sax_dom_parser) that also notes the first key repeated in one
// object, found as the member is made: one pass over the text. (A second SAX pass with a set of
// keys per object cost as much as the parse itself; nlohmann's parser callback was worse: its DOM
// builder then scans the enclosing container at every object's end, quadratic in an array's
// length — a 93,000-item .plan took 22 s to read.)
class StrictDomBuilder {
 public:
  using number_integer_t = json::number_integer_t;
  using number_unsigned_t = json::number_unsigned_t;
  using number_float_t = json::number_float_t;
  using string_t = json::string_t;
  using binary_t = json::binary_t;

  explicit StrictDomBuilder(json& root) : root_(root) {}
  const std::string& repeated() const { return repeated_; }

  bool null() { return add(nullptr); }
  bool boolean(bool v) { return add(v); }
  bool number_integer(number_integer_t v) { return add(v); }
  bool number_unsigned(number_unsigned_t v) { return add(v); }
  bool number_float(number_float_t v, const string_t&) { return add(v); }
  // The lexer clears its token before reading the next: its text can be moved.
  bool string(string_t& v) { return add(std::move(v)); }
  bool binary(binary_t&) { return true; }  // not in JSON text
  bool start_object(std::size_t) {
    open_.push_back(place(json::value_t::object));
    return true;
  }
  bool key(string_t& k) {
    auto& members = open_.back()->get_ref<json::object_t&>();
    const auto [it, added] = members.try_emplace(std::move(k));
    if (!added && repeated_.empty()) repeated_ = it->first;
    member_ = &it->second;
    return true;
  }
  bool end_object() {
    open_.pop_back();
    return true;
  }
  bool start_array(std::size_t) {
    open_.push_back(place(json::value_t::array));
    return true;
  }
  bool end_array() {
    open_.pop_back();
    return true;
  }
  // The exception as json::parse throws it (its own type: a syntax error, or 1e999's range).
  template <class Exception>
  bool parse_error(std::size_t, const std::string&, const Exception& e) {
    throw e;
  }

 private:
  template <typename Value>
  bool add(Value&& v) {
    place(std::forward<Value>(v));
    return true;
  }
  template <typename Value>
  json* place(Value&& v) {
    if (open_.empty()) {
      root_ = json(std::forward<Value>(v));
      return &root_;
    }
    if (open_.back()->is_array()) {
      auto& items = open_.back()->get_ref<json::array_t&>();
      items.emplace_back(std::forward<Value>(v));
      return &items.back();
    }
    *member_ = json(std::forward<Value>(v));
    return member_;
  }

  json& root_;
  std::vector<json*> open_;  // the open arrays and objects, outermost first
  json* member_ = nullptr;   // the object member whose key was read last
  std::string repeated_;
};

}  // namespace

nlohmann::json parse_json_document(const std::string& text, const std::string& source) {
  json root;
  StrictDomBuilder builder(root);
  try {
    json::sax_parse(text, &builder);
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
  // Only a document without syntax errors is refused for a repeated key.
  if (!builder.repeated().empty())
    throw InputError(source + ": the key \"" + builder.repeated() +
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

void append_json_number(std::string& out, double x) {
  if (!std::isfinite(x)) {
    out += "null";
    return;
  }
  std::array<char, 64> text{};
  out.append(text.data(), nlohmann::detail::to_chars(text.data(), text.data() + text.size(), x));
}

}  // namespace swath::base
