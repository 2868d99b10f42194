#pragma once
// Flying a desired course in wind: the wind triangle.

#include <optional>

#include "swath/geometry/point.hpp"
#include "swath/vehicle/wind.hpp"

namespace swath::energy {

/// Wind as weather reports give it: vehicle::Wind (from a compass bearing, degrees clockwise
/// from north; velocity_m_s() the air's velocity in the local frame, x east, y north).
using vehicle::Wind;

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
