#include "swath/base/number_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

namespace swath::base {
namespace {

// Room for any double in fixed notation: 309 integer digits, a sign, a point and 10 decimals.
constexpr std::size_t kFixedBuffer = 352;

}  // namespace

double round_to(double value, int decimals) {
  static constexpr double kScale[] = {1, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10};
  const double scale = kScale[std::clamp(decimals, 0, 10)];
  const double scaled = value * scale;
  // Beyond 2^53 a double has no fraction to round, and scaling could overflow to infinity.
  if (!std::isfinite(scaled) || std::abs(scaled) >= 0x1p53) return value;
  const double r = std::round(scaled) / scale;
  return r == 0.0 ? 0.0 : r;
}

std::string fixed_text(double value, int decimals) {
  decimals = std::clamp(decimals, 0, 10);
  char buffer[kFixedBuffer];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, round_to(value, decimals),
                                    std::chars_format::fixed, decimals);
  if (result.ec != std::errc()) return shortest_text(value);  // cannot happen: the buffer fits all
  return std::string(buffer, result.ptr);
}

void append_fixed_text(std::string& out, double value, int decimals) {
  static constexpr double kScale[] = {1, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10};
  decimals = std::clamp(decimals, 0, 10);
  const double scaled = value * kScale[decimals];
  // round_to gives r = round(scaled) / 10^d, which fixed_text prints to d decimals. Below 10^15
  // the double r lies within 0.11 of a unit of the last decimal from round(scaled) × 10^-d, so
  // its d-decimal text is the digits of the integer round(scaled) with the point put in.
  if (!(std::abs(scaled) < 1e15)) {
    out += fixed_text(value, decimals);
    return;
  }
  const double rounded = std::round(scaled);
  // |rounded| < 10^15: exact as an integer. Unsigned, two digits a division where it can.
  auto units = static_cast<unsigned long long>(std::abs(static_cast<long long>(rounded)));
  static constexpr char kPairs[] =
      "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
      "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
      "8081828384858687888990919293949596979899";
  // Written from the right: the decimals, the point, at least one digit before it, the sign.
  char text[32];
  char* first = text + sizeof text;
  int left = decimals;
  for (; left >= 2; left -= 2, units /= 100) {
    const char* pair = kPairs + 2 * (units % 100);
    *--first = pair[1];
    *--first = pair[0];
  }
  if (left == 1) {
    *--first = static_cast<char>('0' + units % 10);
    units /= 10;
  }
  if (decimals > 0) *--first = '.';
  for (; units >= 100; units /= 100) {
    const char* pair = kPairs + 2 * (units % 100);
    *--first = pair[1];
    *--first = pair[0];
  }
  if (units >= 10) {
    *--first = kPairs[2 * units + 1];
    *--first = kPairs[2 * units];
  } else {
    *--first = static_cast<char>('0' + units);
  }
  if (rounded < 0) *--first = '-';  // never a minus zero
  out.append(first, text + sizeof text);
}

std::string shortest_text(double value) {
  char buffer[64];  // the shortest form of any double is at most 24 characters
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value == 0.0 ? 0.0 : value);
  return result.ec == std::errc() ? std::string(buffer, result.ptr) : std::string("nan");
}

bool parse_number(std::string_view text, double& value) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return false;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

}  // namespace swath::base
