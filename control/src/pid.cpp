#include "swath/control/pid.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace swath::control {

double pid_update(const PidGains& gains, PidState& state, double setpoint, double measurement,
                  double dt_s) {
  const double error = setpoint - measurement;
  state.integral =
      std::clamp(state.integral + gains.i * error * dt_s, -gains.i_limit, gains.i_limit);
  if (state.started) {
    const double rate = (measurement - state.last_measurement) / dt_s;
    const double alpha =
        gains.d_lpf_hz > 0 ? dt_s / (dt_s + 1.0 / (2.0 * std::numbers::pi * gains.d_lpf_hz)) : 1.0;
    state.derivative += alpha * (rate - state.derivative);
  }
  state.last_measurement = measurement;
  state.started = true;
  return gains.p * error + state.integral - gains.d * state.derivative;
}

}  // namespace swath::control
