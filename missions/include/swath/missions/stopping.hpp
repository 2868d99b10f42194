#pragma once
// The stopping margin (issue 45): how far past a waypoint a multirotor can end up where the path
// turns sharply or holds. Header-only so that the planner (which draws line ends back by it) and
// the preflight check (which checks it against zones and fences) use one formula.

#include "swath/vehicle/kinematics.hpp"

namespace swath::missions {

/// The distance, metres, a vehicle flying at `speed_m_s` needs to stop at a constant
/// `deceleration_m_s2` (by default ArduCopter's WPNAV_ACCEL, the horizontal deceleration the
/// autopilot plans its stops with: vehicle::kDefaultAccel_m_s2): v^2 / (2 a). Where braking starts
/// at the waypoint instead of before it (a late or missed braking point, a pause, a position
/// estimate that lags), the vehicle overruns the waypoint along its incoming direction by this
/// much; the check treats it as the envelope the flight may reach.
constexpr double stopping_distance_m(double speed_m_s,
                                     double deceleration_m_s2 = vehicle::kDefaultAccel_m_s2) {
  return speed_m_s * speed_m_s / (2.0 * deceleration_m_s2);
}

}  // namespace swath::missions
