#include "swath/control/setpoints.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace swath::control {

double trapezoid_duration_s(double length_m, double speed_m_s, double accel_m_s2) {
  if (!(length_m > 0)) return 0;
  // Triangle when the leg is too short to reach the speed: v_peak = √(L a).
  if (length_m < speed_m_s * speed_m_s / accel_m_s2) return 2 * std::sqrt(length_m / accel_m_s2);
  return length_m / speed_m_s + speed_m_s / accel_m_s2;
}

double trapezoid_distance_m(double t_s, double length_m, double speed_m_s, double accel_m_s2) {
  if (!(length_m > 0) || t_s <= 0) return 0;
  const double total = trapezoid_duration_s(length_m, speed_m_s, accel_m_s2);
  if (t_s >= total) return length_m;
  const double peak = std::min(speed_m_s, std::sqrt(length_m * accel_m_s2));
  const double ramp = peak / accel_m_s2;
  if (t_s < ramp) return 0.5 * accel_m_s2 * t_s * t_s;
  const double left = total - t_s;  // braking mirrors the start
  if (left < ramp) return length_m - 0.5 * accel_m_s2 * left * left;
  return 0.5 * peak * ramp + peak * (t_s - ramp);
}

namespace {

std::vector<std::vector<Vec3>> pairs(const std::vector<Vec3>& waypoints) {
  std::vector<std::vector<Vec3>> legs;
  for (std::size_t k = 0; k + 1 < waypoints.size(); ++k)
    legs.push_back({waypoints[k], waypoints[k + 1]});
  if (legs.empty()) legs.push_back({waypoints.empty() ? Vec3{} : waypoints.front()});
  return legs;
}

}  // namespace

CarrotPath::CarrotPath(const std::vector<Vec3>& waypoints, const CarrotLimits& limits)
    : CarrotPath(pairs(waypoints), limits) {}

CarrotPath::CarrotPath(std::vector<std::vector<Vec3>> legs, const CarrotLimits& limits)
    : limits_(limits),
      update_period_ns_(std::max<SimTime>(
          vehicle::from_seconds(1.0 / (limits.update_hz > 0 ? limits.update_hz : 50.0)), 1)) {
  if (legs.empty()) legs.push_back({Vec3{}});
  leg_start_ns_.push_back(0);
  double yaw = 0, start_s = 0;
  for (std::vector<Vec3>& points : legs) {
    if (points.empty()) points.push_back(legs_.empty() ? Vec3{} : legs_.back().points.back());
    Leg leg;
    leg.points = std::move(points);
    leg.arc_m.push_back(0);
    leg.speed_m_s = limits_.max_speed_m_s;
    for (std::size_t k = 0; k + 1 < leg.points.size(); ++k) {
      const Vec3 d = leg.points[k + 1] - leg.points[k];
      const double length = norm(d);
      if (length > 0 && std::abs(d.z) * leg.speed_m_s > limits_.max_climb_m_s * length)
        leg.speed_m_s = limits_.max_climb_m_s * length / std::abs(d.z);
      if (std::hypot(d.x, d.y) > 1e-6) yaw = std::atan2(d.y, d.x);
      leg.yaw_rad.push_back(yaw);
      leg.arc_m.push_back(leg.arc_m.back() + length);
    }
    if (leg.yaw_rad.empty()) leg.yaw_rad.push_back(yaw);
    for (std::size_t k = 0; k < leg.yaw_rad.size(); ++k) {
      leg.from_yaw_rad.push_back(k > 0           ? leg.yaw_rad[k - 1]
                                 : legs_.empty() ? leg.yaw_rad[0]
                                                 : legs_.back().yaw_rad.back());
      leg.enter_s.push_back(k == 0 ? 0.0 : time_at_distance(leg.arc_m[k], leg));
    }
    // Leg ends are kept in seconds and rounded once, so rounding never accumulates over legs.
    start_s += trapezoid_duration_s(leg.arc_m.back(), leg.speed_m_s, limits_.max_accel_m_s2);
    leg_start_ns_.push_back(vehicle::from_seconds(start_s));
    legs_.push_back(std::move(leg));
  }
}

double CarrotPath::time_at_distance(double s_m, const Leg& leg) const {
  // The trapezoid's distance is monotone in time: bisection to a nanosecond.
  const double a = limits_.max_accel_m_s2, v = leg.speed_m_s, length = leg.arc_m.back();
  double lo = 0, hi = trapezoid_duration_s(length, v, a);
  while (hi - lo > 1e-9) {
    const double mid = 0.5 * (lo + hi);
    (trapezoid_distance_m(mid, length, v, a) < s_m ? lo : hi) = mid;
  }
  return hi;
}

void CarrotPath::slew(Setpoint& sp, double from_rad, double to_rad, double since_s) const {
  const double turn = std::remainder(to_rad - from_rad, 2 * std::numbers::pi);  // shorter way
  const double rate = limits_.yaw_slew_rad_s;
  if (!(rate > 0) || std::abs(turn) <= rate * std::max(since_s, 0.0)) {
    sp.yaw_rad = to_rad;
    return;
  }
  const double done = std::copysign(rate * std::max(since_s, 0.0), turn);
  sp.yaw_rad = std::remainder(from_rad + done, 2 * std::numbers::pi);
  sp.yaw_rate_rad_s = std::copysign(rate, turn);
}

Setpoint extrapolated(const Setpoint& sp, SimTime t_ns) {
  if (t_ns <= sp.sampled_ns) return sp;
  const double ahead_s = vehicle::seconds(t_ns - sp.sampled_ns);
  Setpoint out = sp;
  out.position_m = sp.position_m + ahead_s * sp.velocity_m_s;
  if (sp.yaw_rate_rad_s != 0)
    out.yaw_rad = std::remainder(sp.yaw_rad + ahead_s * sp.yaw_rate_rad_s, 2 * std::numbers::pi);
  return out;
}

double CarrotPath::length_m() const {
  double sum = 0;
  for (const Leg& leg : legs_) sum += leg.arc_m.back();
  return sum;
}

Setpoint CarrotPath::at(SimTime t_ns) const {
  const SimTime sample_ns = std::max<SimTime>(t_ns, 0) / update_period_ns_ * update_period_ns_;
  // The leg in force: the last whose start is at or before the sample.
  const auto it = std::upper_bound(leg_start_ns_.begin(), leg_start_ns_.end(), sample_ns);
  const std::size_t index = static_cast<std::size_t>(it - leg_start_ns_.begin()) - 1;
  Setpoint sp;
  sp.sampled_ns = sample_ns;
  sp.leg = std::min(index, legs());
  if (sp.leg >= legs()) {
    const Leg& last = legs_.back();
    sp.position_m = last.points.back();
    sp.yaw_rad = last.yaw_rad.back();
    sp.segment = last.yaw_rad.size() - 1;
    return sp;
  }
  const Leg& leg = legs_[sp.leg];
  const double length = leg.arc_m.back();
  const double t = vehicle::seconds(sample_ns - leg_start_ns_[sp.leg]);
  const double a = limits_.max_accel_m_s2, v = leg.speed_m_s;
  const double s = trapezoid_distance_m(t, length, v, a);
  // Speed along the leg: the derivative of the trapezoid's distance.
  const double total = trapezoid_duration_s(length, v, a);
  const double speed = length > 0 ? std::max(0.0, std::min({a * t, v, a * (total - t)})) : 0.0;
  // The segment holding arc length s (the first when s = 0, the last at the end).
  std::size_t k = 0;
  if (leg.points.size() > 1) {
    k = static_cast<std::size_t>(std::upper_bound(leg.arc_m.begin(), leg.arc_m.end(), s) -
                                 leg.arc_m.begin());
    k = std::clamp<std::size_t>(k, 1, leg.points.size() - 1) - 1;
  }
  sp.segment = k;
  const std::size_t y = std::min(k, leg.yaw_rad.size() - 1);
  slew(sp, leg.from_yaw_rad[y], leg.yaw_rad[y], t - leg.enter_s[y]);
  if (leg.points.size() < 2) {
    sp.position_m = leg.points.front();
    return sp;
  }
  const Vec3 d = leg.points[k + 1] - leg.points[k];
  const double segment = leg.arc_m[k + 1] - leg.arc_m[k];
  const Vec3 direction = segment > 0 ? d / segment : Vec3{};
  sp.position_m = leg.points[k] + (s - leg.arc_m[k]) * direction;
  sp.velocity_m_s = speed * direction;
  return sp;
}

}  // namespace swath::control
