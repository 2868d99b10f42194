#include "swath/control/voltage_compensation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace swath::control {

namespace {
constexpr double kFilter_hz = 0.5;  // AP_MOTORS_BATT_VOLT_FILT_HZ
}

ThrustCompensation::ThrustCompensation(const vehicle::Battery& b, double initial_voltage_v)
    : on_(b.cells > 0 && b.thrust_compensation),
      volt_min_v_(b.volt_min_v),
      volt_max_v_(b.volt_max_v),
      filtered_v_(initial_voltage_v) {}

void ThrustCompensation::measure(double voltage_v, double dt_s) {
  const double alpha = 1.0 - std::exp(-2.0 * std::numbers::pi * kFilter_hz * dt_s);
  filtered_v_ += alpha * (voltage_v - filtered_v_);
}

double ThrustCompensation::gain() const {
  if (!on_) return 1.0;
  const double ratio = volt_max_v_ / std::clamp(filtered_v_, volt_min_v_, volt_max_v_);
  return ratio * ratio;
}

double ThrustCompensation::pwm_us(double pwm_us, const MixerRotors& r) const {
  const double g = gain();
  if (g == 1.0) return pwm_us;
  const double span = r.pwm_max_us - r.pwm_min_us;
  const double u = std::max(pwm_us - r.pwm_min_us, 0.0) / span;
  // Thrust ∝ u (thrust_linear) or u² (linear).
  const double scaled = r.mapping == EscMapping::thrust_linear ? u * g : u * std::sqrt(g);
  return r.pwm_min_us + std::min(scaled, 1.0) * span;
}

}  // namespace swath::control
