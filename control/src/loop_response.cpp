#include "swath/control/loop_response.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace swath::control {
namespace {

constexpr double kPi = std::numbers::pi;

// ∠L(jω) in radians, summed factor by factor so that it is continuous (it starts near −270°
// at low frequencies, where P·I and the attitude loop make a triple integrator).
double rate_loop_phase_rad(const RateLoopModel& m, double omega) {
  const std::complex<double> s(0, omega);
  const std::complex<double> derivative =
      m.d_lpf_hz > 0 ? m.d * s / (1.0 + s / (2 * kPi * m.d_lpf_hz)) : m.d * s;
  double phase = std::arg(m.p + m.i / s + derivative) - kPi / 2 -
                 std::atan(m.motor_time_constant_s * omega) - omega * m.delay_s;
  if (m.attitude_p_1_s > 0) phase += std::arg(1.0 + m.attitude_p_1_s / s);
  if (m.gyro_lpf_hz > 0) phase -= std::atan(omega / (2 * kPi * m.gyro_lpf_hz));
  return phase;
}

template <typename F>
double bisect(F f, double lo, double hi) {
  const bool lo_positive = f(lo) > 0;
  for (int k = 0; k < 80; ++k) {
    const double mid = std::sqrt(lo * hi);
    ((f(mid) > 0) == lo_positive ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

}  // namespace

double rate_loop_delay_s(double rate_hz, double execution_s, double gyro_rate_hz,
                         double esc_frame_rate_hz) {
  const double period = 1 / rate_hz;
  const double esc = esc_frame_rate_hz > 0 ? 0.5 / esc_frame_rate_hz : 0.0;
  return 0.5 * period + 0.5 / gyro_rate_hz + execution_s + 0.5 * period + esc;
}

std::complex<double> rate_loop_gain(const RateLoopModel& m, double omega) {
  const std::complex<double> s(0, omega);
  const std::complex<double> derivative =
      m.d_lpf_hz > 0 ? m.d * s / (1.0 + s / (2 * kPi * m.d_lpf_hz)) : m.d * s;
  const std::complex<double> pid = m.p + m.i / s + derivative;
  const std::complex<double> attitude = 1.0 + m.attitude_p_1_s / s;
  const std::complex<double> gyro =
      m.gyro_lpf_hz > 0 ? 1.0 / (1.0 + s / (2 * kPi * m.gyro_lpf_hz)) : 1.0;
  return pid * attitude / s / (1.0 + m.motor_time_constant_s * s) * gyro * std::exp(-s * m.delay_s);
}

LoopMargins loop_margins(const RateLoopModel& model, double from_rad_s, double to_rad_s) {
  LoopMargins out;
  auto magnitude_db = [&](double w) { return 20 * std::log10(std::abs(rate_loop_gain(model, w))); };
  auto phase_deg = [&](double w) { return rate_loop_phase_rad(model, w) * 180 / kPi; };
  const int steps = 2000;
  double previous = from_rad_s;
  for (int k = 1; k <= steps; ++k) {
    const double w = from_rad_s * std::pow(to_rad_s / from_rad_s, static_cast<double>(k) / steps);
    if (out.gain_crossover_rad_s == 0 && magnitude_db(previous) > 0 && magnitude_db(w) <= 0) {
      out.gain_crossover_rad_s = bisect(magnitude_db, previous, w);
      out.phase_margin_deg = 180 + phase_deg(out.gain_crossover_rad_s);
    }
    if (out.gain_crossover_rad_s > 0 && w > out.gain_crossover_rad_s &&
        phase_deg(previous) > -180 && phase_deg(w) <= -180) {
      out.phase_crossover_rad_s = bisect([&](double x) { return phase_deg(x) + 180; }, previous, w);
      out.gain_margin_db = -magnitude_db(out.phase_crossover_rad_s);
      break;
    }
    previous = w;
  }
  if (out.gain_crossover_rad_s == 0) out.phase_margin_deg = std::numeric_limits<double>::infinity();
  if (out.phase_crossover_rad_s == 0) out.gain_margin_db = std::numeric_limits<double>::infinity();
  return out;
}

}  // namespace swath::control
