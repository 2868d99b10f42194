#include "swath/control/setpoints.hpp"

#include <algorithm>
#include <cmath>

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

CarrotPath::CarrotPath(std::vector<Vec3> waypoints, const CarrotLimits& limits)
    : waypoints_(std::move(waypoints)),
      limits_(limits),
      update_period_ns_(std::max<SimTime>(
          vehicle::from_seconds(1.0 / (limits.update_hz > 0 ? limits.update_hz : 50.0)), 1)) {
  if (waypoints_.empty()) waypoints_.push_back({});
  leg_start_ns_.push_back(0);
  double yaw = 0, start_s = 0;
  for (std::size_t k = 0; k + 1 < waypoints_.size(); ++k) {
    const Vec3 d = waypoints_[k + 1] - waypoints_[k];
    const double length = norm(d);
    double speed = limits_.max_speed_m_s;
    if (length > 0 && std::abs(d.z) * speed > limits_.max_climb_m_s * length)
      speed = limits_.max_climb_m_s * length / std::abs(d.z);
    if (std::hypot(d.x, d.y) > 1e-6) yaw = std::atan2(d.y, d.x);
    speed_m_s_.push_back(speed);
    yaw_rad_.push_back(yaw);
    // Leg ends are kept in seconds and rounded once, so rounding never accumulates over legs.
    start_s += trapezoid_duration_s(length, speed, limits_.max_accel_m_s2);
    leg_start_ns_.push_back(vehicle::from_seconds(start_s));
  }
}

Setpoint CarrotPath::at(SimTime t_ns) const {
  const SimTime sample_ns = std::max<SimTime>(t_ns, 0) / update_period_ns_ * update_period_ns_;
  // The leg in force: the last whose start is at or before the sample.
  const auto it = std::upper_bound(leg_start_ns_.begin(), leg_start_ns_.end(), sample_ns);
  const std::size_t leg = static_cast<std::size_t>(it - leg_start_ns_.begin()) - 1;
  Setpoint sp;
  sp.leg = std::min(leg, legs());
  if (sp.leg >= legs()) {
    sp.position_m = waypoints_.back();
    sp.yaw_rad = yaw_rad_.empty() ? 0.0 : yaw_rad_.back();
    return sp;
  }
  const Vec3 d = waypoints_[sp.leg + 1] - waypoints_[sp.leg];
  const double length = norm(d);
  const double t = vehicle::seconds(sample_ns - leg_start_ns_[sp.leg]);
  const double a = limits_.max_accel_m_s2, v = speed_m_s_[sp.leg];
  const double s = trapezoid_distance_m(t, length, v, a);
  // Speed along the leg: the derivative of the trapezoid's distance.
  const double total = trapezoid_duration_s(length, v, a);
  const double speed = length > 0 ? std::max(0.0, std::min({a * t, v, a * (total - t)})) : 0.0;
  const Vec3 direction = length > 0 ? d / length : Vec3{};
  sp.position_m = waypoints_[sp.leg] + s * direction;
  sp.velocity_m_s = speed * direction;
  sp.yaw_rad = yaw_rad_[sp.leg];
  return sp;
}

}  // namespace swath::control
