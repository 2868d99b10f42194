#include "swath/vehicle/random.hpp"

#include <cmath>

namespace swath::vehicle {

__extension__ typedef unsigned __int128 Uint128;

std::uint64_t SplitMix64::below(std::uint64_t n) {
  // Lemire (2019): multiply-shift with rejection of the biased low products.
  Uint128 m = static_cast<Uint128>(next()) * n;
  auto low = static_cast<std::uint64_t>(m);
  if (low < n) {
    const std::uint64_t threshold = (0 - n) % n;
    while (low < threshold) {
      m = static_cast<Uint128>(next()) * n;
      low = static_cast<std::uint64_t>(m);
    }
  }
  return static_cast<std::uint64_t>(m >> 64);
}

double SplitMix64::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  double u = 0, v = 0, s = 0;
  do {
    u = 2.0 * uniform() - 1.0;
    v = 2.0 * uniform() - 1.0;
    s = u * u + v * v;
  } while (s >= 1.0 || s == 0.0);
  const double f = std::sqrt(-2.0 * std::log(s) / s);
  spare_ = v * f;
  has_spare_ = true;
  return u * f;
}

double SplitMix64::exponential(double rate_per_s) {
  return -std::log1p(-uniform()) / rate_per_s;
}

}  // namespace swath::vehicle
