#pragma once
// PID with the derivative on the measurement (no kick when the setpoint steps), a first-order
// low-pass on that derivative, and an integrator whose contribution is clamped
// (docs/swath-control.md step 5). Units follow the loop: for the velocity loop e is m/s and the
// output m/s²; for the rate loop e is rad/s and the output rad/s².

namespace swath::control {

/// Gains of one loop (`controller.velocity_xy`, `.velocity_z`, `.rate.*`; docs/swath-control.md,
/// 'Vehicle, scheduler and environment files').
struct PidGains {
  double p = 0;         ///< output per unit error, ≥ 0
  double i = 0;         ///< output per unit error and second, ≥ 0
  double d = 0;         ///< output per unit error rate (error/s), ≥ 0
  double i_limit = 0;   ///< |integral contribution| ≤ i_limit, output units, ≥ 0
  double d_lpf_hz = 0;  ///< cut-off of the derivative's low-pass, Hz, ≥ 0 (0: unfiltered)
};

/// The loop's memory: a copyable value.
struct PidState {
  double integral = 0;          ///< the integral contribution, output units, |·| ≤ i_limit
  double derivative = 0;        ///< the filtered derivative of the measurement, measurement/s
  double last_measurement = 0;  ///< at the previous update
  bool started = false;         ///< false until the first update (no derivative yet)
  friend bool operator==(const PidState&, const PidState&) = default;
};

/// One update after `dt_s` seconds (> 0):
///   I ← clamp(I + i · e · dt, ±i_limit),  e = setpoint − measurement (backward Euler),
///   D ← D + α (ẏ − D),  ẏ = (y − y_prev) / dt,  α = dt / (dt + 1 / (2π d_lpf_hz)),
///   output = p · e + I − d · D.
/// The first update has no derivative (D = 0).
double pid_update(const PidGains& gains, PidState& state, double setpoint, double measurement,
                  double dt_s);

}  // namespace swath::control
