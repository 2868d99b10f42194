// parse_json_document against nlohmann's own DOM parser (json::parse) on random documents (fixed
// seed): the same values where the document is valid, a repeated key refused by name (the first in
// the text), and a syntax error reported as one even when a repeated key comes before it.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <iterator>
#include <random>
#include <set>
#include <string>

#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"

namespace swath::base {
namespace {

// Writes random JSON text; objects draw their keys from a few letters (so that some repeat), or
// each key once. Notes the first key, in the text's order, repeated within its object.
class RandomDocument {
 public:
  explicit RandomDocument(std::uint64_t seed) : rng_(seed) {}

  std::string text(bool unique_keys) {
    unique_keys_ = unique_keys;
    first_repeated_.clear();
    std::string out;
    object(out, 0);  // a document as swath reads them: an object at the top
    return out;
  }
  const std::string& first_repeated() const { return first_repeated_; }
  int below(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }

 private:
  void value(std::string& out, int depth) {
    switch (below(depth < 4 ? 9 : 6)) {
      case 0:
        out += "null";
        break;
      case 1:
        out += below(2) ? "true" : "false";
        break;
      case 2:
        out += std::to_string(
            std::uniform_int_distribution<long long>(-1000000000000LL, 1000000000000LL)(rng_));
        break;
      case 3:
        out += below(2) ? "18446744073709551615" : "-0";
        break;
      case 4: {  // a decimal with an exponent: the same double either way it is read
        out += std::to_string(below(2000) - 1000) + "." + std::to_string(below(1000)) + "e" +
               std::to_string(below(40) - 20);
        break;
      }
      case 5:
        string(out);
        break;
      case 6:
      case 7:
        object(out, depth);
        break;
      default:
        array(out, depth);
        break;
    }
  }
  void string(std::string& out) {
    static const char* const pieces[] = {"a", "field", "\\\"", "\\\\", "\\u00e9", "\\n", " ", "é"};
    out += '"';
    for (int k = below(5); k > 0; --k) out += pieces[below(8)];
    out += '"';
  }
  void array(std::string& out, int depth) {
    out += '[';
    for (int k = below(5), first = 1; k > 0; --k, first = 0) {
      if (!first) out += ", ";
      value(out, depth + 1);
    }
    out += ']';
  }
  void object(std::string& out, int depth) {
    static const char* const keys[] = {"a", "b", "c", "type", "é", "a\\u0062", "", "x y"};
    std::set<std::string> used;  // as read: "a\u0062" is "ab"
    out += '{';
    for (int k = below(5), first = 1; k > 0; --k, first = 0) {
      int key = below(8);
      if (unique_keys_)
        while (used.count(read_key(keys[key]))) key = (key + 1) % 8;
      if (!used.insert(read_key(keys[key])).second && first_repeated_.empty())
        first_repeated_ = read_key(keys[key]);
      if (!first) out += ", ";
      out += '"' + std::string(keys[key]) + "\": ";
      value(out, depth + 1);
    }
    out += '}';
  }
  static std::string read_key(const std::string& written) {
    return written == "a\\u0062" ? "ab" : written;
  }

  std::mt19937_64 rng_;
  bool unique_keys_ = false;
  std::string first_repeated_;
};

std::string error_of(const std::string& text) {
  try {
    parse_json_document(text, "doc.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(JsonDocument, ReadsAsNlohmannDoesAndRefusesTheFirstRepeatedKey) {
  RandomDocument doc(52);
  int valid = 0, repeated = 0;
  for (int i = 0; i < 3000; ++i) {
    const std::string text = doc.text(i % 2 == 0);
    if (doc.first_repeated().empty()) {
      const nlohmann::json expected = nlohmann::json::parse(text);
      const nlohmann::json got = parse_json_document(text, "doc.json");
      ASSERT_EQ(got, expected) << text;
      ASSERT_EQ(got.dump(), expected.dump()) << text;  // the same types (1 is not 1.0)
      ++valid;
    } else {
      ASSERT_EQ(error_of(text), "doc.json: the key \"" + doc.first_repeated() +
                                    "\" appears twice in one object; which one holds is ambiguous")
          << text;
      ++repeated;
    }
  }
  EXPECT_GT(valid, 1000);
  EXPECT_GT(repeated, 300);
}

// A document cut short or with a stray byte is a syntax error wherever it is, even after a repeated
// key; the place is json::parse's own (its byte, as line and column).
TEST(JsonDocument, ASyntaxErrorIsReportedBeforeARepeatedKey) {
  RandomDocument doc(53);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    std::string text = doc.text(false);
    if (text.size() < 4) continue;
    const std::size_t at = static_cast<std::size_t>(doc.below(static_cast<int>(text.size())));
    if (doc.below(2))
      text.resize(at);
    else
      text.insert(at, "}");
    std::size_t byte = 0;
    try {
      (void)nlohmann::json::parse(text);
      continue;  // still valid (a "}" closing what was open, a number cut to a shorter one)
    } catch (const nlohmann::json::parse_error& e) {
      byte = e.byte;
    }
    std::size_t line = 1, column = 1;
    for (std::size_t k = 0; k + 1 < byte && k < text.size(); ++k) {
      column = text[k] == '\n' ? 1 : column + 1;
      line += text[k] == '\n';
    }
    const std::string error = error_of(text);
    ASSERT_EQ(error.rfind("doc.json: line " + std::to_string(line) + ", column " +
                              std::to_string(column) + ": invalid JSON (",
                          0),
              0u)
        << text << "\n"
        << error;
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

TEST(JsonDocument, ANumberBeyondADoubleIsRefused) {
  EXPECT_EQ(error_of("{\"a\": [1, 1e999]}"),
            "doc.json: invalid JSON (number overflow parsing '1e999')");
  EXPECT_EQ(error_of("{\"a\": 1, \"a\": 1e999}"),
            "doc.json: invalid JSON (number overflow parsing '1e999')");
}

// The same value, of the same type, bit for bit (-0.0 is not 0.0, 1 is not 1.0, 1u is not 1).
bool same_value(const nlohmann::json& a, const nlohmann::json& b) {
  if (a.type() != b.type()) return false;
  switch (a.type()) {
    case nlohmann::json::value_t::number_float: {
      const double x = a.get<double>(), y = b.get<double>();
      return std::memcmp(&x, &y, sizeof x) == 0;
    }
    case nlohmann::json::value_t::array:
    case nlohmann::json::value_t::object: {
      if (a.size() != b.size()) return false;
      for (auto i = a.begin(), j = b.begin(); i != a.end(); ++i, ++j)
        if ((a.is_object() && i.key() != j.key()) || !same_value(*i, *j)) return false;
      return true;
    }
    default:
      return a == b;
  }
}

// Documents near the plain ones swath writes (printable ASCII strings, indented, numbers in every
// form JSON allows and some it does not), whole or with a byte cut, doubled or changed: the
// document read is nlohmann's (the same values of the same types, bit for bit) and an error is
// its error, word for word, whether the plain documents' parser reads the text or gives up on it.
TEST(JsonDocument, PlainDocumentsReadAsByNlohmannAlone) {
  static const char* const numbers[] = {"0",
                                        "-0",
                                        "7",
                                        "-12",
                                        "0.5",
                                        "-0.0",
                                        "1e5",
                                        "1E+5",
                                        "2.5e-3",
                                        "-1.25E-03",
                                        "123456789012345678",
                                        "-123456789012345678",
                                        "1234567890123456789",
                                        "-9223372036854775808",
                                        "9223372036854775807",
                                        "18446744073709551615",
                                        "18446744073709551616",
                                        "1e400",
                                        "1e-400",
                                        "4.9e-324",
                                        "2.2250738585072011e-308",
                                        "0.1000000000000000055511151231257827",
                                        "150.794131834",
                                        "-34.000106632",
                                        "007",
                                        "1.",
                                        ".5",
                                        "1e",
                                        "+1",
                                        "-",
                                        "1.5e+",
                                        "0x10",
                                        "Infinity",
                                        "NaN"};
  static const char* const strings[] = {"a",       "fileType",  "Plan", "x y",
                                        "",        "tab\there", "\\n",  "\\\"",
                                        "\\u0041", "\xc3\xa9",  "\x7f", "ab\"c"};
  static const char* const spaces[] = {"", " ", "\n    ", "\r\n", "\t", "\n\n  "};
  std::mt19937_64 rng(54);
  auto below = [&](std::size_t n) {
    return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
  };
  auto space = [&] { return std::string(spaces[below(6)]); };
  std::function<void(std::string&, int)> value = [&](std::string& out, int depth) {
    const std::size_t kind = below(depth < 5 ? 7 : 4);
    if (kind == 0)
      out += below(3) == 0 ? "true" : below(2) ? "null" : "false";
    else if (kind == 1 || kind == 2)
      out += below(4) ? numbers[below(24)] : numbers[below(std::size(numbers))];
    else if (kind == 3)
      out += '"' + std::string(below(4) ? strings[below(5)] : strings[below(std::size(strings))]) +
             '"';
    else {
      const bool object = kind != 6;
      out += object ? "{" : "[";
      for (std::size_t k = below(4), first = 1; k > 0; --k, first = 0) {
        out += (first ? "" : ",") + space();
        if (object) out += '"' + std::string(strings[below(below(3) ? 5 : 8)]) + "\":" + space();
        value(out, depth + 1);
      }
      out += space() + (object ? "}" : "]");
    }
  };
  int read = 0, refused = 0, plain = 0;
  for (int i = 0; i < 6000; ++i) {
    std::string text = space();
    value(text, below(3) == 0 ? 4 : 0);
    text += space();
    if (i % 3 == 1 && !text.empty()) {
      const std::size_t at = below(text.size());
      switch (below(3)) {
        case 0:
          text.erase(at, 1);
          break;
        case 1:
          text.insert(at, 1, text[at]);
          break;
        default:
          text[at] = "{}[],:\"0-e. \x01"[below(13)];
      }
    }
    nlohmann::json expected, got;
    std::string expected_error, got_error;
    try {
      expected = detail::parse_json_document_nlohmann(text, "doc.json");
    } catch (const InputError& e) {
      expected_error = e.what();
    }
    try {
      got = parse_json_document(text, "doc.json");
    } catch (const InputError& e) {
      got_error = e.what();
    }
    ASSERT_EQ(got_error, expected_error) << text;
    if (!expected_error.empty()) {
      ++refused;
      continue;
    }
    ASSERT_TRUE(same_value(got, expected)) << text << "\n" << got.dump() << "\n" << expected.dump();
    ++read;
    plain += text.find('\\') == std::string::npos;
  }
  EXPECT_GT(read, 2000);
  EXPECT_GT(refused, 1000);
  EXPECT_GT(plain, 1000);
}

}  // namespace
}  // namespace swath::base
