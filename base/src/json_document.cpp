#include "swath/base/json_document.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string_view>
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
    // Room for a position's two numbers at once (growing one element at a time took two
    // allocations). The values are the same; only an empty or one-element array has room for two.
    open_.back()->get_ref<json::array_t&>().reserve(2);
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

// A parser for the plain documents swath writes (pretty-printed, ASCII, no escapes): the same
// events, in the same order, as nlohmann's parser gives StrictDomBuilder for them, without its
// lexer's per-character reads and strtod. It takes only what it is sure of and gives up (false)
// on anything else: an escape or a byte outside printable ASCII in a string, an integer of more
// than 18 digits (nlohmann's then chooses between int64, uint64 and double), a number from_chars
// does not read exactly, a nesting deeper than 256, or any syntax error; the caller then parses
// the text with nlohmann's parser, whose DOM and errors are the document's. A document given up
// on costs the part read twice; swath's own files are never given up on.
class PlainParser {
 public:
  PlainParser(const std::string& text, StrictDomBuilder& out)
      : p_(text.data()), end_(text.data() + text.size()), out_(out) {}

  // The whole text one value, white space around it.
  bool document() {
    skip_space();
    if (!value(0)) return false;
    skip_space();
    return p_ == end_;
  }

 private:
  void skip_space() {
    while (p_ != end_ && (*p_ == ' ' || *p_ == '\n' || *p_ == '\r' || *p_ == '\t')) ++p_;
  }
  bool literal(std::string_view word) {
    if (static_cast<std::size_t>(end_ - p_) < word.size() ||
        std::string_view(p_, word.size()) != word)
      return false;
    p_ += word.size();
    return true;
  }
  bool value(int depth) {
    if (p_ == end_ || depth > 256) return false;
    switch (*p_) {
      case '{':
        return object(depth);
      case '[':
        return array(depth);
      case '"': {
        std::string s;
        return string(s) && out_.string(s);
      }
      case 't':
        return literal("true") && out_.boolean(true);
      case 'f':
        return literal("false") && out_.boolean(false);
      case 'n':
        return literal("null") && out_.null();
      default:
        return number();
    }
  }
  // Printable ASCII but '"' and '\\' between quotes: the string is its bytes.
  bool string(std::string& s) {
    const char* first = ++p_;
    while (p_ != end_ && *p_ != '"') {
      const auto c = static_cast<unsigned char>(*p_);
      if (c < 0x20 || c > 0x7e || c == '\\') return false;
      ++p_;
    }
    if (p_ == end_) return false;
    s.assign(first, p_);
    ++p_;
    return true;
  }
  // JSON's grammar: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?; an integer without fraction
  // or exponent is nlohmann's number_unsigned (number_integer when negative).
  bool number() {
    const char* first = p_;
    const bool negative = p_ != end_ && *p_ == '-';
    if (negative) ++p_;
    const char* digits = p_;
    if (p_ == end_ || !is_digit(*p_)) return false;
    if (*p_ == '0')
      ++p_;
    else
      skip_digits();
    const std::size_t integer_digits = static_cast<std::size_t>(p_ - digits);
    bool whole = true;
    if (p_ != end_ && *p_ == '.') {
      ++p_;
      if (p_ == end_ || !is_digit(*p_)) return false;
      skip_digits();
      whole = false;
    }
    if (p_ != end_ && (*p_ == 'e' || *p_ == 'E')) {
      ++p_;
      if (p_ != end_ && (*p_ == '+' || *p_ == '-')) ++p_;
      if (p_ == end_ || !is_digit(*p_)) return false;
      skip_digits();
      whole = false;
    }
    if (whole) {
      if (integer_digits > 18) return false;
      std::uint64_t magnitude = 0;
      for (const char* d = digits; d != p_; ++d)
        magnitude = magnitude * 10 + static_cast<std::uint64_t>(*d - '0');
      return negative ? out_.number_integer(-static_cast<std::int64_t>(magnitude))
                      : out_.number_unsigned(magnitude);
    }
    double v = 0.0;
    const auto [at, error] = std::from_chars(first, p_, v);
    if (error != std::errc() || at != p_ || !std::isfinite(v)) return false;
    static const std::string unused;  // StrictDomBuilder does not read the number's text
    return out_.number_float(v, unused);
  }
  bool object(int depth) {
    ++p_;
    out_.start_object(std::size_t(-1));
    skip_space();
    if (p_ != end_ && *p_ == '}') {
      ++p_;
      return out_.end_object();
    }
    std::string key;
    for (;;) {
      if (p_ == end_ || *p_ != '"' || !string(key)) return false;
      out_.key(key);
      skip_space();
      if (p_ == end_ || *p_ != ':') return false;
      ++p_;
      skip_space();
      if (!value(depth + 1)) return false;
      skip_space();
      if (p_ == end_) return false;
      if (*p_ == '}') {
        ++p_;
        return out_.end_object();
      }
      if (*p_ != ',') return false;
      ++p_;
      skip_space();
    }
  }
  bool array(int depth) {
    ++p_;
    out_.start_array(std::size_t(-1));
    skip_space();
    if (p_ != end_ && *p_ == ']') {
      ++p_;
      return out_.end_array();
    }
    for (;;) {
      if (!value(depth + 1)) return false;
      skip_space();
      if (p_ == end_) return false;
      if (*p_ == ']') {
        ++p_;
        return out_.end_array();
      }
      if (*p_ != ',') return false;
      ++p_;
      skip_space();
    }
  }
  static bool is_digit(char c) { return c >= '0' && c <= '9'; }
  void skip_digits() {
    while (p_ != end_ && is_digit(*p_)) ++p_;
  }

  const char* p_;
  const char* end_;
  StrictDomBuilder& out_;
};

}  // namespace

nlohmann::json parse_json_document(const std::string& text, const std::string& source) {
  {
    json root;
    StrictDomBuilder builder(root);
    if (PlainParser(text, builder).document()) {
      if (!builder.repeated().empty())
        throw InputError(source + ": the key \"" + builder.repeated() +
                         "\" appears twice in one object; which one holds is ambiguous");
      return root;
    }
  }
  return detail::parse_json_document_nlohmann(text, source);
}

nlohmann::json detail::parse_json_document_nlohmann(const std::string& text,
                                                    const std::string& source) {
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
