#include "swath/energy/power_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace swath::energy {

double level_flight_power_w(const MechanicalPower& m, double airspeed_m_s) {
  const double ratio = airspeed_m_s / m.cruise_airspeed_m_s;
  return m.cruise_w * ((1.0 - m.parasitic_share) + m.parasitic_share * ratio * ratio * ratio);
}

double mechanical_power_w(const MechanicalPower& m, double airspeed_m_s,
                          double lateral_accel_m_s2) {
  constexpr double kGravity = 9.80665;
  const double a = lateral_accel_m_s2 / kGravity;
  const double level = level_flight_power_w(m, airspeed_m_s);
  if (a == 0.0) return level;  // straight flight: skip the pow
  const double n2 = 1.0 + a * a;
  return level * std::sqrt(n2) * std::sqrt(std::sqrt(n2));  // n^1.5 = (n^2)^0.75
}

double computation_power_w(const PowerCurve& curve, double parameter) {
  if (parameter == 0.0 || curve.points.empty()) return 0.0;
  const auto& p = curve.points;
  if (p.size() == 1) return std::max(0.0, p[0].second);
  // The segment that holds the parameter, or the end segment it extends.
  std::size_t i = 1;
  while (i + 1 < p.size() && parameter > p[i].first) ++i;
  const auto [c0, w0] = p[i - 1];
  const auto [c1, w1] = p[i];
  return std::max(0.0, w0 + (w1 - w0) * (parameter - c0) / (c1 - c0));
}

double computations_power_w(const std::vector<PowerCurve>& curves,
                            const std::vector<double>& parameters) {
  double sum = 0.0;
  for (std::size_t j = 0; j < curves.size() && j < parameters.size(); ++j)
    sum += computation_power_w(curves[j], parameters[j]);
  return sum;
}

double climbing_power_w(const PowerProfile& p) {
  return p.climb_w > 0 ? p.climb_w : kClimbPowerFactor * p.mechanical.cruise_w;
}

double descending_power_w(const PowerProfile& p) {
  return p.descent_w > 0 ? p.descent_w : kDescentPowerFactor * p.mechanical.cruise_w;
}

double GaussianNoise::uniform() {
  // The open interval (0, 1): Box-Muller takes its logarithm (SplitMix64::uniform is [0, 1)).
  return (static_cast<double>(bits_.next() >> 11) + 0.5) * 0x1.0p-53;
}

double GaussianNoise::next() {
  if (sigma_ == 0.0) return 0.0;
  if (has_spare_) {
    has_spare_ = false;
    return sigma_ * spare_;
  }
  const double r = std::sqrt(-2.0 * std::log(uniform()));
  const double angle = 2.0 * std::numbers::pi * uniform();
  spare_ = r * std::sin(angle);
  has_spare_ = true;
  return sigma_ * r * std::cos(angle);
}

}  // namespace swath::energy
