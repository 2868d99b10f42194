#pragma once
// Numbers for reports and files: rounded to a fixed number of decimals, same bytes every run.

#include <charconv>
#include <string>
#include <string_view>

namespace swath::base {

/// `value` rounded half away from zero to `decimals` places (0..10); never "-0".
double round_to(double value, int decimals);

/// `value` with exactly `decimals` digits after the point (std::to_chars: no locale).
std::string fixed_text(double value, int decimals);

/// Appends fixed_text(value, decimals) to `out` (the same bytes), without a temporary string
/// and, for |value| below 10^15 / 10^decimals, without std::to_chars (the CSV writers' hot path).
void append_fixed_text(std::string& out, double value, int decimals);

/// Appends an integer's decimal digits (std::to_string's, and nlohmann's for a JSON integer)
/// without a temporary string.
template <typename Integer>
void append_integer_text(std::string& out, Integer value) {
  char text[24];
  out.append(text, std::to_chars(text, text + sizeof text, value).ptr);
}

/// The shortest text that reads back as exactly `value` (std::to_chars: no locale); never "-0".
std::string shortest_text(double value);

/// Reads a whole decimal number from `text` (std::from_chars: no locale; an optional leading '+'
/// is accepted); false when `text` is not entirely one number.
bool parse_number(std::string_view text, double& value);

}  // namespace swath::base
