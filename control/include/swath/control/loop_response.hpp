#pragma once
// The rate loop's frequency response in closed form (docs/swath-control.md), from the loop model
// of the code: broken at the plant's torque input, the loop gain of one body axis is
//   L(s) = (P + I/s + D s / (1 + s/ω_D)) · (1 + K_att/s) · 1/s · 1/(1 + τ_m s) · G(s) · e^(−s T)
// with the rate PID of controller.rate (derivative on the measurement, low-passed at ω_D), the
// attitude P loop K_att closed around it (rate setpoint K_att·(θ_sp − θ), θ the integral of the
// rate), the body 1/(J s) cancelling the task's J ⊙ u, the motors' first-order lag τ_m (thrust ∝ Ω²
// linearised about hover has Ω's time constant), the gyro's first-order low-pass G, and a pure
// delay T: half the execution period (Δθ averaged over it), half the gyro's sample period, the
// execution's own time, half the execution period again (the pulse held until the next one) and
// half the ESC's frame period (the pulse waits for the next frame).

#include <complex>

namespace swath::control {

struct RateLoopModel {
  double p = 40, i = 20, d = 0.5;  ///< controller.rate.<axis>: 1/s, 1/s², 1
  double d_lpf_hz = 30;            ///< the derivative's low-pass, Hz (0: none)
  double attitude_p_1_s = 8;       ///< controller.attitude_p of the axis, 1/s (0: rate loop only)
  double motor_time_constant_s = 0.03;
  double gyro_lpf_hz = 80;  ///< 0: none
  double delay_s = 0;       ///< the pure delay T, s
};

/// The delay T of a loop executing at `rate_hz`, each execution taking `execution_s`, reading a
/// gyro sampled at `gyro_rate_hz` and commanding ESCs that latch at `esc_frame_rate_hz` (0: at
/// once).
double rate_loop_delay_s(double rate_hz, double execution_s, double gyro_rate_hz,
                         double esc_frame_rate_hz);

/// L(jω) of `model` (ω in rad/s, > 0).
std::complex<double> rate_loop_gain(const RateLoopModel& model, double omega_rad_s);

/// Gain and phase margins of `model`: the gain crossover (|L| = 1, the first above `from_rad_s`)
/// with the phase margin 180° + ∠L there, and the phase crossover (∠L = −180°, the first above
/// the gain crossover) with the gain margin −20 log10 |L| there. Searched on a logarithmic grid of
/// `from_rad_s`…`to_rad_s` and refined by bisection; a crossover not found is reported as 0 rad/s
/// (margin +∞). quad-f450 at 400 Hz in flight (T = 4.73 ms): the rate loop alone (attitude_p 0)
/// crosses over at 32.4 rad/s with 52.8° and 15.6 dB; with the attitude loop closed around it,
/// 33.2 rad/s, 38.7° and 14.9 dB.
struct LoopMargins {
  double gain_crossover_rad_s = 0, phase_margin_deg = 0;
  double phase_crossover_rad_s = 0, gain_margin_db = 0;
};
LoopMargins loop_margins(const RateLoopModel& model, double from_rad_s = 1, double to_rad_s = 2000);

}  // namespace swath::control
