#pragma once
// Step and chirp tests of one body axis of the simulated multirotor in hover
// (docs/swath-control.md, `swath-control response`): the plant (vehicle::FlightModel), the sensor
// driver and the control task executed time-triggered at a fixed rate with the pulses applied at
// once, the horizontal position and velocity loops switched off (attitude hold, the height loop
// still on) so that the attitude loop is seen alone, as on a test stand.
//
// step: the attitude setpoint of the axis steps by the amplitude (the task's attitude injection);
// rise time, overshoot and settling time of the true attitude.
// chirp: a logarithmic sine sweep added to the axis' torque at the rate loop's output (u = c + d);
// the loop broken there has L = −C/U, estimated from the simulated signals with Hann-windowed,
// half-overlapping segments as L = −Σ D̄·C / Σ D̄·U (cross-spectra with the injection d, so that
// noise uncorrelated with d averages out), and its gain and phase margins, beside the closed form
// of loop_response.hpp for the same rate, gyro and ESCs.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "swath/control/loop_response.hpp"
#include "swath/control/simulation.hpp"

namespace swath::control {

enum class ResponseAxis { roll, pitch, yaw };
enum class ResponseInput { step, chirp };
/// The loop under test: the attitude loop closed around the rate loop, or the rate loop alone (the
/// tested axis' attitude_p set to 0: a rate hold at 0, as in acro mode).
enum class ResponseLoop { attitude, rate };
const char* to_string(ResponseAxis axis);

struct ResponseSettings {
  ResponseAxis axis = ResponseAxis::roll;
  ResponseInput input = ResponseInput::step;
  ResponseLoop loop = ResponseLoop::attitude;  ///< step: attitude only
  double amplitude_deg = 10;  ///< step: the attitude setpoint's step, degrees, ≠ 0
  double amplitude_nm = 0.2;  ///< chirp: the torque sweep's amplitude, N m, > 0
  double from_hz = 0.5;  ///< chirp: the band analysed, Hz, > 0 (the sweep starts at from_hz / 1.25)
  double to_hz = 40;     ///< chirp: … up to to_hz, > from_hz (the sweep ends at to_hz · 1.25)
  double duration_s = 2;       ///< the test after the settling time, s
  double rate_hz = 400;        ///< the task's execution rate, Hz
  double settle_s = 2;         ///< hover before the input starts, s
  int points_per_decade = 40;  ///< chirp: frequencies of the estimate per decade
};

/// One execution (response.csv). Angles: roll right wing down, pitch nose up, yaw clockwise from
/// north, degrees; rates and torques about the axis in the same sense.
struct ResponseSample {
  double t_s = 0;
  double setpoint_deg = 0, response_deg = 0, error_deg = 0;
  double estimate_deg = 0;  ///< the task's estimate of the attitude
  double rate_setpoint_dps = 0, rate_dps = 0;
  double injection_nm = 0, controller_torque_nm = 0;
  std::size_t rotors = 0;
  std::array<double, vehicle::kMaxRotors> pwm_us{};
};

/// Step figures of an attitude y(t) (minus its mean over the last 0.5 s before the step) against
/// the step A.
struct StepMetrics {
  double rise_time_s = 0;        ///< from y = 0.1 A to y = 0.9 A (first crossings)
  double overshoot_percent = 0;  ///< (max y / A − 1) · 100, 0 when y never passes A
  double settling_time_s = 0;    ///< from the step to the last time |y − A| > 5 % |A|
  double final_deg = 0;          ///< y's mean over the last 0.5 s
  bool settled = false;          ///< |y − A| ≤ 5 % |A| over the last 0.5 s
};

/// L(j 2π f) at one frequency.
struct BodePoint {
  double frequency_hz = 0, magnitude_db = 0, phase_deg = 0;
  double coherence = 0;  ///< γ² of the injection d and the controller's torque c, [0, 1]
  double closed_form_magnitude_db = 0, closed_form_phase_deg = 0;
};

/// Margins in Hz for the user (loop_margins' crossovers are in rad/s).
struct MarginFigures {
  double gain_crossover_hz = 0, phase_margin_deg = 0;
  double phase_crossover_hz = 0, gain_margin_db = 0;  ///< 0 Hz: not found (margin +∞)
};

struct ResponseResult {
  std::vector<ResponseSample> samples;
  std::optional<StepMetrics> step;           ///< of the true attitude
  std::optional<StepMetrics> step_estimate;  ///< of the task's estimate (what the loop controls)
  std::vector<BodePoint> bode;               ///< chirp
  MarginFigures measured, closed_form;
  RateLoopModel model;  ///< the closed form's loop
};

/// The closed-form loop of `axis` for these settings' gains, motors, gyro and ESCs at `rate_hz`.
RateLoopModel response_model(const SimulationSettings& settings, ResponseAxis axis,
                             ResponseLoop loop, double rate_hz);

/// Runs the test. Throws base::InputError for settings that cannot be run (a rate that does not
/// divide a second into whole nanoseconds, a layout that cannot be mixed).
ResponseResult run_response(const SimulationSettings& settings, const ResponseSettings& test);

/// Step figures of `samples` (the true attitude, or the estimate) for a step of `amplitude_deg` at
/// `step_s`.
StepMetrics step_metrics(const std::vector<ResponseSample>& samples, double step_s,
                         double amplitude_deg, bool of_estimate = false);

/// Gain and phase margins read off a measured response (ascending frequencies): the phase
/// unwrapped from the lowest frequency and shifted by whole turns so that it lies in (−360°, 0°]
/// at the gain crossover. Each crossing is first bracketed between neighbours, then read off a
/// least-squares parabola (value against ln f) through the points within a factor 1.25 of it, which
/// averages the estimate's noise over about 8 points at 40 per decade.
MarginFigures margins_of(const std::vector<BodePoint>& bode);

std::string response_csv(const std::vector<ResponseSample>& samples);
std::string bode_csv(const std::vector<BodePoint>& bode);
std::string margins_csv(const MarginFigures& measured, const MarginFigures& closed_form);
std::string step_csv(const StepMetrics& truth, const StepMetrics& estimate);

}  // namespace swath::control
