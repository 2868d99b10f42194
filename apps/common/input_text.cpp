#include "input_text.hpp"

#include <cmath>
#include <cstdio>

#include "swath/base/input_error.hpp"

namespace swath::apps {

std::optional<std::pair<double, double>> parse_number_pair(const std::string& text,
                                                           char separator) {
  const std::string format = std::string(" %lf ") + separator + " %lf %c";
  double a = 0, b = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), format.c_str(), &a, &b, &tail) != 2 || !std::isfinite(a) ||
      !std::isfinite(b))
    return std::nullopt;
  return std::pair{a, b};
}

}  // namespace swath::apps
