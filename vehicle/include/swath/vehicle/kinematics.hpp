#pragma once
// How long a multirotor takes over a horizontal leg flown from rest to rest: the one closed form
// swath plan's flight-time estimate and swath-fleet's scheduler share. The acceleration is the
// drone's (vehicle::Drone::accel_m_s2; each program's default documented with it).

namespace swath::vehicle {

/// The default horizontal acceleration and braking of a multirotor, m/s²: ArduCopter's
/// WPNAV_ACCEL, 250 cm/s² (ArduPilot, libraries/AC_WPNav/AC_WPNav.cpp, parameter ACCEL; the
/// Copter parameter list, ardupilot.org/copter/docs/parameters.html#wpnav-accel). The one value
/// behind vehicle::Drone::accel_m_s2, swath plan's FleetFileRules, the stopping margin
/// (missions/stopping.hpp) and swath verify's flight model.
inline constexpr double kDefaultAccel_m_s2 = 2.5;

/// The default vertical speeds of a multirotor, m/s: ArduCopter's WPNAV_SPEED_UP (250 cm/s) and
/// WPNAV_SPEED_DN (150 cm/s), what an autopilot flies when nothing says otherwise (a mission file
/// carries no climb rate). The values behind vehicle::Drone, FleetFileRules, the planner's
/// mission settings and swath verify's flight model.
inline constexpr double kDefaultClimb_m_s = 2.5;
inline constexpr double kDefaultDescent_m_s = 1.5;

/// Rest to rest over `length_m` at ≤ `cruise_m_s`, ≤ `approach_m_s` within `approach_within_m`
/// of the end, accelerating and braking at `accel_m_s2` (> 0), s (v² linear in distance in each
/// phase: a trapezoid, or a triangle when a phase is too short to reach its cap). 0 for
/// length_m ≤ 0.
double rest_to_rest_s(double length_m, double cruise_m_s, double approach_m_s,
                      double approach_within_m, double accel_m_s2);

/// The same with no approach phase: a trapezoid at ≤ `cruise_m_s` (length / v + v / a), or a
/// triangle (2 √(length / a)) when the leg is too short to reach it.
double rest_to_rest_s(double length_m, double cruise_m_s, double accel_m_s2);

}  // namespace swath::vehicle
