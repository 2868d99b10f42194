// base's text helpers: numbers that always fit, ranges refused in one sentence, files read with a
// cap, YAML documents that expand without bound refused.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/range_check.hpp"
#include "swath/base/yaml_input.hpp"

namespace swath::base {
namespace {

// Property: for any double (random bit patterns, fixed seed), fixed_text is printable ASCII of a
// number (or inf/nan) and reads back within half a unit of its last decimal.
TEST(NumberText, FixedTextIsAlwaysANumberThatReadsBack) {
  std::uint64_t state = 12345;
  for (int i = 0; i < 20000; ++i) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    double value = 0;
    const std::uint64_t bits = state;
    std::memcpy(&value, &bits, sizeof value);
    const int decimals = static_cast<int>(state >> 60) % 11;
    const std::string text = fixed_text(value, decimals);
    ASSERT_FALSE(text.empty());
    for (const char c : text)
      ASSERT_TRUE((c >= '0' && c <= '9') || c == '.' || c == '-' || c == 'e' || c == '+' ||
                  c == 'i' || c == 'n' || c == 'f' || c == 'a')
          << "byte " << int(static_cast<unsigned char>(c)) << " in '" << text << "'";
    if (!std::isfinite(value)) continue;
    double back = 0;
    std::from_chars(text.data(), text.data() + text.size(), back);
    EXPECT_LE(std::abs(back - value), 0.5 * std::pow(10.0, -decimals) + 1e-15 * std::abs(value))
        << value << " -> " << text;
  }
  EXPECT_EQ(fixed_text(1e308, 1).size(), 311u);  // 309 digits, the point, one decimal
  EXPECT_EQ(fixed_text(-0.0001, 2), "0.00");
  EXPECT_EQ(fixed_text(2.5, 0), "3");
  EXPECT_EQ(shortest_text(0.1), "0.1");
}

// append_fixed_text (the CSV writers' fast path) writes fixed_text's bytes: random values of every
// magnitude from 1e-12 to 1e17 (both sides of its 1e15 switch), halves that round away from zero,
// numbers that round to zero from below, and the specials (fixed seed).
TEST(NumberText, AppendFixedTextIsFixedTextsBytes) {
  std::uint64_t state = 777;
  auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return state;
  };
  std::vector<double> values = {0.0,
                                -0.0,
                                0.5,
                                -0.5,
                                2.5,
                                0.125,
                                -0.125,
                                1e15,
                                -1e15,
                                999999.5,
                                1e-11,
                                -4e-4,
                                123.45,
                                0.0049999,
                                1e300,
                                -1e-300,
                                9.9999999,
                                -0.9995,
                                1.0005,
                                std::nan(""),
                                std::numeric_limits<double>::infinity(),
                                -std::numeric_limits<double>::infinity()};
  for (int i = 0; i < 200000; ++i) {
    const double unit = static_cast<double>(next() >> 11) * 0x1.0p-53;  // [0, 1)
    const double magnitude = std::pow(10.0, -12.0 + 29.0 * unit);
    values.push_back((next() & 1 ? -1 : 1) * magnitude);
    // A tie at some decimals: k / 2 / 10^d.
    values.push_back(static_cast<double>(next() % 100000) / 2.0 /
                     std::pow(10.0, static_cast<double>(next() % 7)));
  }
  int fast = 0;
  for (const double v : values)
    for (int d = 0; d <= 10; ++d) {
      std::string line = "x,";
      append_fixed_text(line, v, d);
      ASSERT_EQ(line, "x," + fixed_text(v, d)) << v << " at " << d << " decimals";
      fast += std::abs(v * std::pow(10.0, d)) < 1e15;
    }
  EXPECT_GT(fast, 2000000);  // most went through the fast path
}

TEST(RangeCheck, NamesWhereTheValueAndTheRange) {
  const Range r{0.5, 100, "m/s", "a reason"};
  EXPECT_NO_THROW(check_range(0.5, r, "--speed"));
  EXPECT_NO_THROW(check_range(100, r, "--speed"));
  try {
    check_range(1e-300, r, "--speed");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(
        e.what(),
        "--speed 1e-300 m/s is outside the range swath accepts, 0.5 to 100 m/s (a reason)");
  }
  // A computed value is shown to 6 digits, a typed one as typed; never rounded into the range.
  auto said = [&](double value) {
    try {
      check_range(value, {1, 5000, "m", ""}, "the altitude");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(said(0.3762758620689655),
            "the altitude 0.376276 m is outside the range swath "
            "accepts, 1 to 5000 m");
  EXPECT_EQ(value_text(0.3762758620689655), "0.376276");
  EXPECT_EQ(value_text(0.9999999), "0.9999999");
  EXPECT_EQ(value_text(123456.789), "123456.789");
  EXPECT_NE(said(5000.000000000001).find("altitude 5000.000000000001 m is outside"),
            std::string::npos);
  EXPECT_NE(said(0.99999999999999989).find("altitude 0.9999999999999999 m is outside"),
            std::string::npos);
  EXPECT_THROW(check_range(std::nan(""), r, "x"), InputError);
  EXPECT_THROW(check_range(std::numeric_limits<double>::infinity(), r, "x"), InputError);
}

TEST(FileText, EndlessAndLargeFilesAreRefusedAtTheCap) {
  try {
    read_text_file("/dev/zero", "fleet file", 1 << 20);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "/dev/zero: the fleet file is larger than swath's limit of 1 MiB");
  }
  EXPECT_THROW(read_text_file("/", "area file"), InputError);
  EXPECT_THROW(read_text_file("/nonexistent/x", "area file"), InputError);
}

TEST(Yaml, AnAliasBombIsRefusedAtTheNodeLimit) {
  // Each level repeats the one before ten times: 10^7 nodes from a few hundred bytes.
  std::string doc = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int i = 1; i <= 6; ++i) {
    const std::string n = std::to_string(i), previous = "*a" + std::to_string(i - 1);
    doc.append("a").append(n).append(": &a").append(n).append(" [").append(previous);
    for (int k = 1; k < 10; ++k) doc.append(", ").append(previous);
    doc.append("]\n");
  }
  try {
    load_yaml(doc, "bomb.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bomb.yaml: the YAML document expands to more than"),
              std::string::npos)
        << e.what();
  }
  // Three levels (about 1,100 nodes) are fine.
  std::string small = doc.substr(0, doc.find("a3:"));
  EXPECT_NO_THROW(load_yaml(small, "small.yaml"));
}

}  // namespace
}  // namespace swath::base
