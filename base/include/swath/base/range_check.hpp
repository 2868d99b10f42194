#pragma once
// Plausibility bounds for the numbers users give: checked before any work that grows with them,
// refused in one sentence that names where the number came from, the value and the range.

#include <string>
#include <string_view>

namespace swath::base {

/// A closed range [lo, hi] of a quantity in `unit` ("m", "m/s", "" for a plain number), with the
/// reason for its ends in `why` (shown in refusals, e.g. "beyond any survey aircraft").
struct Range {
  double lo = 0, hi = 0;
  std::string_view unit;
  std::string_view why;
};

/// Throws InputError "<where> <value> <unit> is outside the range swath accepts, <lo> to <hi>
/// <unit> (<why>)" unless `value` is finite and inside `range`. `where` names the flag or the
/// file and key ("--altitude", "cam.yaml: line 3: focal_length_mm").
void check_range(double value, const Range& range, const std::string& where);

/// The value as text for messages: shortest round-trip form, no locale.
std::string value_text(double value);

}  // namespace swath::base
