#pragma once
// Flying a desired course in wind: the wind triangle.

#include <optional>

#include "swath/geometry/point.hpp"

namespace swath::energy {

/// Wind as weather reports give it. `from_bearing_deg` is a compass bearing (0 = from north,
/// 90 = from east, clockwise): the air moves towards from_bearing_deg + 180.
struct Wind {
  double speed_m_s = 0.0;         ///< >= 0
  double from_bearing_deg = 0.0;  ///< compass degrees
};

/// The wind's velocity in the local frame (x east, y north), m/s.
geometry::Point2 wind_velocity(const Wind& wind);

/// Ground speed along the unit course `course` when the drone flies at `airspeed_m_s` through
/// `wind` (m/s, local frame): the positive s with |s course - wind| = airspeed. Empty when no
/// positive ground speed exists (the wind is too strong across or against the course).
std::optional<double> ground_speed_at_airspeed(geometry::Point2 course, geometry::Point2 wind,
                                               double airspeed_m_s);

/// How the drone holds a course: the commanded ground speed when its airspeed needs stay within
/// `max_airspeed_m_s`, else the ground speed that the maximum airspeed gives.
struct CourseSpeed {
  double ground_speed_m_s = 0.0;
  double airspeed_m_s = 0.0;
};

std::optional<CourseSpeed> course_speed(geometry::Point2 course, geometry::Point2 wind,
                                        double ground_speed_m_s, double max_airspeed_m_s);

}  // namespace swath::energy
