#pragma once
// Option values of two numbers ("LAT,LON", "WxH").

#include <optional>
#include <string>
#include <utility>

namespace swath::apps {

/// "A<separator>B" (spaces around either number allowed, nothing after) as two finite numbers.
std::optional<std::pair<double, double>> parse_number_pair(const std::string& text, char separator);

}  // namespace swath::apps
