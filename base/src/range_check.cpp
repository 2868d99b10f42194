#include "swath/base/range_check.hpp"

#include <charconv>
#include <cmath>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"

namespace swath::base {

std::string value_text(double value) {
  // A number as the user typed it has a few digits and is shown as it reads; one computed from
  // others (the altitude a GSD gives) has 16 or 17, shown to 6 ("0.376276 m", not
  // "0.3762758620689655 m").
  const std::string shortest = shortest_text(value);
  int digits = 0;
  bool leading = true;
  for (const char c : shortest) {
    if (c == 'e') break;
    if (c < '0' || c > '9' || (leading && c == '0')) continue;
    leading = false;
    ++digits;
  }
  if (digits <= 12) return shortest;
  char buffer[64];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 6);
  return result.ec == std::errc() ? std::string(buffer, result.ptr) : shortest;
}

void check_range(double value, const Range& range, const std::string& where) {
  if (std::isfinite(value) && value >= range.lo && value <= range.hi) return;
  // Built by append(): GCC 12 warns falsely (-Wrestrict, its bug 105329) on "x" + string here.
  std::string unit;
  if (!range.unit.empty()) unit.append(" ").append(range.unit);
  // Rounded for the message, a value just outside would read as inside (or on an end): not then.
  std::string shown = value_text(value);
  double back = 0;
  if (parse_number(shown, back) && back >= range.lo && back <= range.hi)
    shown = shortest_text(value);
  std::string message = where;
  message.append(" ").append(shown).append(unit);
  message.append(" is outside the range swath accepts, ").append(value_text(range.lo));
  message.append(" to ").append(value_text(range.hi)).append(unit);
  if (!range.why.empty()) message.append(" (").append(range.why).append(")");
  throw InputError(message);
}

}  // namespace swath::base
