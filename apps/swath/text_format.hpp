#pragma once
// Number formatting for reports: fixed decimals for text, rounded doubles for JSON.

#include <string>

namespace swath::apps {

/// `value` with exactly `decimals` digits after the point ("-0.00" printed as "0.00").
std::string fixed(double value, int decimals);
/// `value` rounded to `decimals` decimal places, for JSON output.
double rounded(double value, int decimals);

}  // namespace swath::apps
