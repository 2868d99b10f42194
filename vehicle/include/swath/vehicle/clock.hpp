#pragma once
// Simulation time: integer nanoseconds, so that sensor periods, ESC frames and control releases
// fall on exact instants and events at the same instant are recognised as such (no rounding drift
// over hours of flight; docs/swath-control.md).

#include <cmath>
#include <cstdint>

namespace swath::vehicle {

/// Nanoseconds since the start of a simulation. int64 holds 292 years.
using SimTime = std::int64_t;

inline constexpr SimTime kNanosecondsPerSecond = 1'000'000'000;

/// `t` in seconds.
constexpr double seconds(SimTime t) {
  return static_cast<double>(t) * 1e-9;
}

/// `s` seconds rounded to the nearest nanosecond (|s| below 9.2e9 s).
inline SimTime from_seconds(double s) {
  return static_cast<SimTime>(std::llround(s * 1e9));
}

/// The period of a rate in whole nanoseconds, or 0 when `rate_hz` does not divide a second into
/// whole nanoseconds within 1e-9 relative (callers refuse such rates: docs/swath-control.md).
inline SimTime period_of_rate(double rate_hz) {
  if (!(rate_hz > 0)) return 0;
  const double ns = 1e9 / rate_hz;
  const SimTime whole = static_cast<SimTime>(std::llround(ns));
  return whole > 0 && std::abs(static_cast<double>(whole) - ns) <= 1e-9 * ns ? whole : 0;
}

}  // namespace swath::vehicle
