#pragma once
// Numbers for reports and files: rounded to a fixed number of decimals, same bytes every run.

#include <string>

namespace swath::base {

/// `value` rounded half away from zero to `decimals` places (0..10); never "-0".
double round_to(double value, int decimals);

/// `value` with exactly `decimals` digits after the point (std::to_chars: no locale).
std::string fixed_text(double value, int decimals);

/// The shortest text that reads back as exactly `value` (std::to_chars: no locale); never "-0".
std::string shortest_text(double value);

}  // namespace swath::base
