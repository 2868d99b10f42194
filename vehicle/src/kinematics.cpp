#include "swath/vehicle/kinematics.hpp"

#include <algorithm>
#include <cmath>

namespace swath::vehicle {
namespace {

// From `v_in` to `v_out` over `length` with speed ≤ `cap`, acceleration `a`: accelerate, perhaps
// cruise at the cap, brake (v² linear in distance in each phase).
double to_rest_s(double length, double v_in, double v_out, double cap, double a) {
  if (!(length > 0)) return 0;
  const double peak2 = (2 * a * length + v_in * v_in + v_out * v_out) / 2;
  if (peak2 <= cap * cap) {
    const double peak = std::sqrt(peak2);
    return (peak - v_in) / a + (peak - v_out) / a;
  }
  const double up = (cap * cap - v_in * v_in) / (2 * a),
               down = (cap * cap - v_out * v_out) / (2 * a);
  return (cap - v_in) / a + (cap - v_out) / a + (length - up - down) / cap;
}

}  // namespace

double rest_to_rest_s(double length_m, double cruise_m_s, double approach_m_s,
                      double approach_within_m, double accel_m_s2) {
  if (!(length_m > 0)) return 0;
  const double a = accel_m_s2, va = std::min(approach_m_s, cruise_m_s);
  const double zone_b = std::min(approach_within_m, length_m), zone_a = length_m - zone_b;
  if (!(zone_a > 0)) return to_rest_s(zone_b, 0, 0, va, a);
  // The speed at the start of the approach zone: at most va, what it can reach from rest in
  // zone A, and what it can still brake from in zone B.
  const double vb = std::min({va, std::sqrt(2 * a * zone_a), std::sqrt(2 * a * zone_b)});
  return to_rest_s(zone_a, 0, vb, cruise_m_s, a) + to_rest_s(zone_b, vb, 0, va, a);
}

double rest_to_rest_s(double length_m, double cruise_m_s, double accel_m_s2) {
  return rest_to_rest_s(length_m, cruise_m_s, cruise_m_s, 0, accel_m_s2);
}

}  // namespace swath::vehicle
