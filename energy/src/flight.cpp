#include "swath/energy/flight.hpp"

#include <cmath>
#include <numbers>

namespace swath::energy {

using geometry::Point2;

std::optional<double> ground_speed_at_airspeed(Point2 course, Point2 wind, double airspeed_m_s) {
  const double along = course.x * wind.x + course.y * wind.y;
  const double across2 = wind.x * wind.x + wind.y * wind.y - along * along;
  const double disc = airspeed_m_s * airspeed_m_s - across2;
  if (disc < 0.0) return std::nullopt;
  const double s = along + std::sqrt(disc);
  if (!(s > 1e-6)) return std::nullopt;
  return s;
}

std::optional<CourseSpeed> course_speed(Point2 course, Point2 wind, double ground_speed_m_s,
                                        double max_airspeed_m_s) {
  const double ax = ground_speed_m_s * course.x - wind.x;
  const double ay = ground_speed_m_s * course.y - wind.y;
  const double airspeed = std::sqrt(ax * ax + ay * ay);
  if (airspeed <= max_airspeed_m_s) return CourseSpeed{ground_speed_m_s, airspeed};
  const auto s = ground_speed_at_airspeed(course, wind, max_airspeed_m_s);
  if (!s) return std::nullopt;
  return CourseSpeed{*s, max_airspeed_m_s};
}

}  // namespace swath::energy
