#include "text_format.hpp"

#include <cmath>
#include <cstdio>

namespace swath::apps {

double rounded(double value, int decimals) {
  const double scale = std::pow(10.0, decimals);
  const double r = std::round(value * scale) / scale;
  return r == 0.0 ? 0.0 : r;  // no "-0"
}

std::string fixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, rounded(value, decimals));
  return buffer;
}

}  // namespace swath::apps
