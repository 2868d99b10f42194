#include "swath/base/number_text.hpp"

#include <charconv>
#include <cmath>

namespace swath::base {

double round_to(double value, int decimals) {
  static constexpr double kScale[] = {1, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10};
  const double scale = kScale[decimals];
  const double r = std::round(value * scale) / scale;
  return r == 0.0 ? 0.0 : r;
}

std::string fixed_text(double value, int decimals) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, round_to(value, decimals),
                                    std::chars_format::fixed, decimals);
  return std::string(buffer, result.ptr);
}

std::string shortest_text(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value == 0.0 ? 0.0 : value);
  return std::string(buffer, result.ptr);
}

}  // namespace swath::base
