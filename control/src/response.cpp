#include "swath/control/response.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/control/driver.hpp"
#include "swath/control/rotor_layout.hpp"
#include "swath/vehicle/flight_model.hpp"

namespace swath::control {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = 180 / kPi;
constexpr double kBand = 0.05;          // the settling band, a share of the step
constexpr double kFinalWindow_s = 0.5;  // the mean that gives the final value and the baseline
constexpr double kHoverHeight_m = 10;

constexpr double kSweepMargin = 1.25;  // the sweep runs this far beyond the band analysed

std::size_t axis_index(ResponseAxis a) {
  return static_cast<std::size_t>(a);
}

// Roll (right wing down), pitch (nose up), compass yaw of a body FLU → world ENU attitude, deg.
Vec3 euler_deg(const Quat& q) {
  const Vec3 x = vehicle::rotate(q, {1, 0, 0}), y = vehicle::rotate(q, {0, 1, 0}),
             z = vehicle::rotate(q, {0, 0, 1});
  return {std::atan2(y.z, z.z) * kDeg, std::asin(std::clamp(x.z, -1.0, 1.0)) * kDeg,
          90.0 - std::atan2(x.y, x.x) * kDeg};
}

double wrap_deg(double a) {
  a = std::fmod(a + 180.0, 360.0);
  if (a < 0) a += 360.0;
  return a - 180.0;
}

// The body axis of each Euler angle's positive sense: roll about +x (forward), pitch nose up
// about −y (left), compass yaw clockwise about −z (up).
Vec3 body_sense(ResponseAxis a) {
  switch (a) {
    case ResponseAxis::roll:
      return {1, 0, 0};
    case ResponseAxis::pitch:
      return {0, -1, 0};
    default:
      return {0, 0, -1};
  }
}

double component(const Vec3& v, std::size_t k) {
  return k == 0 ? v.x : k == 1 ? v.y : v.z;
}

// As simulate() builds it, with the horizontal position and velocity loops off.
ControlTaskConfig test_task_config(const SimulationSettings& s, const ResponseSettings& r) {
  ControlTaskConfig c;
  c.gains = s.control.controller;
  c.gains.velocity_xy = PidGains{};  // no tilt asked by the outer loops: attitude hold
  if (r.loop == ResponseLoop::rate) {
    Vec3& p = c.gains.attitude_p_1_s;
    (r.axis == ResponseAxis::roll ? p.x : r.axis == ResponseAxis::pitch ? p.y : p.z) = 0;
  }
  c.estimator = with_sensor_noise(s.control.estimator, s.physics.sensors);
  c.estimator.gravity_m_s2 = s.environment.gravity_m_s2;
  const vehicle::Airframe& a = s.physics.airframe;
  c.airframe.mass_kg = a.frame.mass_kg;
  c.airframe.inertia_kg_m2 = a.frame.inertia_kg_m2;
  c.airframe.gravity_m_s2 = s.environment.gravity_m_s2;
  c.airframe.rotors = layout_of(a, s.physics.esc);
  c.nominal_rate_hz = r.rate_hz;
  return c;
}

// The plant, the driver and the task, one execution at a time, pulses applied at once.
class TestLoop {
 public:
  TestLoop(const SimulationSettings& s, const ResponseSettings& r)
      : plant_(plant_settings(s)), driver_(s.physics.sensors) {
    const std::optional<ControlTask> task = ControlTask::create(test_task_config(s, r));
    if (!task)
      throw base::InputError(
          "the vehicle's rotors cannot be mixed (4 to 8 rotors with positive "
          "coefficients giving rank 4 are needed)");
    task_ = *task;
    state_ = task_->initial_state({0, 0, kHoverHeight_m});
    input_.setpoint.position_m = {0, 0, kHoverHeight_m};
  }

  ExecutionOutput execute(SimTime t, const Vec3& attitude_rad, const Vec3& torque_nm) {
    plant_.advance_to(t);
    for (const vehicle::DeliveredSample& d : plant_.take_samples()) driver_.deliver(d);
    input_.sensors = driver_.take(t);
    input_.time_ns = t;
    input_.attitude_injection_rad = attitude_rad;
    input_.torque_injection_nm = torque_nm;
    const ExecutionOutput out = task_->execute(state_, input_);
    for (std::size_t i = 0; i < out.rotor_count; ++i) plant_.command_pwm(i, out.pwm_us[i]);
    return out;
  }
  const vehicle::MultirotorState& truth() const { return plant_.state(); }
  const Quat& estimate() const { return state_.estimate.attitude; }

 private:
  static vehicle::FlightModelSettings plant_settings(const SimulationSettings& s) {
    vehicle::FlightModelSettings p;
    p.physics = s.physics;
    p.environment = s.environment;
    p.seed = s.seed;
    p.max_step_s = s.scheduler.run.max_step_s;
    p.mission_speed_m_s = 0;
    p.initial.position_m = {0, 0, kHoverHeight_m};
    p.initial.rotor_rad_s = vehicle::hover(s.physics.airframe).rotor_rad_s;
    return p;
  }
  vehicle::FlightModel plant_;
  SensorDriver driver_;
  std::optional<ControlTask> task_;
  TaskState state_;
  TaskInput input_;
};

// The logarithmic sweep's phase at t (0 ≤ t ≤ T): instantaneous frequency f0·(f1/f0)^(t/T), from
// f0 = from_hz / kSweepMargin to f1 = to_hz · kSweepMargin, so that the band asked for is not under
// the taper of the first and last segments.
double chirp_phase_rad(const ResponseSettings& r, double t) {
  const double f0 = r.from_hz / kSweepMargin, f1 = r.to_hz * kSweepMargin;
  const double k = std::log(f1 / f0) / r.duration_s;
  return 2 * kPi * f0 * (std::exp(k * t) - 1) / k;
}

struct Recorded {
  std::vector<double> t, d, c;  // time, injection, controller torque (u = c + d)
};

// L = −Σ D̄C / Σ D̄U over Hann-windowed segments overlapping by half, at each frequency.
std::vector<BodePoint> estimate_bode(const Recorded& rec, const ResponseSettings& r) {
  const std::size_t n = rec.t.size();
  const std::size_t segment = std::max<std::size_t>(16, n / 6);
  const std::size_t hop = segment / 2;
  std::vector<double> window(segment);
  for (std::size_t k = 0; k < segment; ++k)
    window[k] = 0.5 - 0.5 * std::cos(2 * kPi * static_cast<double>(k) /
                                     (static_cast<double>(segment) - 1.0));
  const double decades = std::log10(r.to_hz / r.from_hz);
  const int count = std::max(2, static_cast<int>(std::ceil(decades * r.points_per_decade)) + 1);
  std::vector<BodePoint> out;
  for (int j = 0; j < count; ++j) {
    const double f = r.from_hz * std::pow(r.to_hz / r.from_hz, j / (count - 1.0));
    const double omega = 2 * kPi * f;
    std::complex<double> dc, du;
    double dd = 0, cc = 0;
    for (std::size_t start = 0; start + segment <= n; start += hop) {
      std::complex<double> D, C;
      for (std::size_t k = 0; k < segment; ++k) {
        const double t = rec.t[start + k] - rec.t[start];
        const std::complex<double> e = window[k] * std::polar(1.0, -omega * t);
        D += rec.d[start + k] * e;
        C += rec.c[start + k] * e;
      }
      const std::complex<double> U = C + D;
      dc += std::conj(D) * C;
      du += std::conj(D) * U;
      dd += std::norm(D);
      cc += std::norm(C);
    }
    const std::complex<double> l = -dc / du;
    BodePoint p;
    p.frequency_hz = f;
    p.magnitude_db = 20 * std::log10(std::abs(l));
    p.phase_deg = std::arg(l) * kDeg;
    p.coherence = dd > 0 && cc > 0 ? std::norm(dc) / (dd * cc) : 0;
    out.push_back(p);
  }
  return out;
}

// Unwraps a sequence of angles (degrees) so that neighbours differ by less than 180°.
void unwrap_deg(std::vector<double>& a) {
  for (std::size_t k = 1; k < a.size(); ++k) {
    while (a[k] - a[k - 1] > 180) a[k] -= 360;
    while (a[k] - a[k - 1] < -180) a[k] += 360;
  }
}

MarginFigures in_hz(const LoopMargins& m) {
  return {m.gain_crossover_rad_s / (2 * kPi), m.phase_margin_deg,
          m.phase_crossover_rad_s / (2 * kPi), m.gain_margin_db};
}

}  // namespace

const char* to_string(ResponseAxis axis) {
  switch (axis) {
    case ResponseAxis::roll:
      return "roll";
    case ResponseAxis::pitch:
      return "pitch";
    default:
      return "yaw";
  }
}

RateLoopModel response_model(const SimulationSettings& s, ResponseAxis axis, ResponseLoop loop,
                             double rate_hz) {
  const ControllerGains& g = s.control.controller;
  const PidGains& pid = axis == ResponseAxis::roll    ? g.rate_roll
                        : axis == ResponseAxis::pitch ? g.rate_pitch
                                                      : g.rate_yaw;
  RateLoopModel m;
  m.p = pid.p;
  m.i = pid.i;
  m.d = pid.d;
  m.d_lpf_hz = pid.d_lpf_hz;
  m.attitude_p_1_s =
      loop == ResponseLoop::rate ? 0.0 : component(g.attitude_p_1_s, axis_index(axis));
  m.motor_time_constant_s = s.physics.airframe.propulsion.time_constant_s;
  double gyro_rate_hz = rate_hz;
  m.gyro_lpf_hz = 0;
  for (const vehicle::SensorSettings& sensor : s.physics.sensors)
    if (sensor.type == vehicle::SensorType::gyro) {
      gyro_rate_hz = 1.0 / vehicle::seconds(sensor.period_ns);
      m.gyro_lpf_hz = sensor.lpf_hz;
      break;
    }
  m.delay_s = rate_loop_delay_s(rate_hz, 0, gyro_rate_hz, s.physics.esc.frame_rate_hz);
  return m;
}

StepMetrics step_metrics(const std::vector<ResponseSample>& samples, double step_s,
                         double amplitude_deg, bool of_estimate) {
  auto value = [&](const ResponseSample& s) {
    return of_estimate ? s.estimate_deg : s.response_deg;
  };
  StepMetrics m;
  double before = 0, final_sum = 0;
  int n_before = 0, n_final = 0;
  const double end_s = samples.empty() ? 0 : samples.back().t_s;
  for (const ResponseSample& s : samples) {
    if (s.t_s < step_s && s.t_s >= step_s - kFinalWindow_s) before += value(s), ++n_before;
    if (s.t_s > end_s - kFinalWindow_s) final_sum += value(s), ++n_final;
  }
  const double base = n_before ? before / n_before : 0;
  m.final_deg = (n_final ? final_sum / n_final : 0) - base;
  const double a = amplitude_deg;
  double peak = 0;
  double t10 = -1, t90 = -1, last_out = step_s;
  m.settled = true;
  for (const ResponseSample& s : samples) {
    if (s.t_s < step_s) continue;
    const double y = (value(s) - base) / a;  // the response as a share of the step
    if (t10 < 0 && y >= 0.1) t10 = s.t_s;
    if (t90 < 0 && y >= 0.9) t90 = s.t_s;
    peak = std::max(peak, y);
    if (std::abs(y - 1) > kBand) {
      last_out = s.t_s;
      if (s.t_s > end_s - kFinalWindow_s) m.settled = false;
    }
  }
  m.rise_time_s = t10 >= 0 && t90 >= 0 ? t90 - t10 : 0;
  m.overshoot_percent = std::max(0.0, (peak - 1) * 100);
  m.settling_time_s = last_out - step_s;
  return m;
}

MarginFigures margins_of(const std::vector<BodePoint>& bode) {
  MarginFigures out;
  out.phase_margin_deg = out.gain_margin_db = std::numeric_limits<double>::infinity();
  std::vector<double> lf, db, deg;
  for (const BodePoint& p : bode) {
    lf.push_back(std::log(p.frequency_hz));
    db.push_back(p.magnitude_db);
    deg.push_back(p.phase_deg);
  }
  unwrap_deg(deg);
  // The least-squares parabola of y against ln f through the points within ln 1.25 of `at`, as
  // coefficients of (ln f − at)^0, ^1, ^2 (a parabola: the curvature of the phase and the
  // magnitude over ±25 % would bias a line's crossing by ~1 %).
  auto local_fit = [&](const std::vector<double>& y, double at) {
    double m[3][4] = {};
    for (std::size_t j = 0; j < y.size(); ++j) {
      const double x = lf[j] - at;
      if (std::abs(x) > std::log(1.25)) continue;
      const double p[3] = {1, x, x * x};
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) m[r][c] += p[r] * p[c];
        m[r][3] += p[r] * y[j];
      }
    }
    for (int c = 0; c < 3; ++c)  // Gauss–Jordan; the matrix is positive definite with ≥ 3 points
      for (int r = 0; r < 3; ++r) {
        if (r == c) continue;
        const double k = m[r][c] / m[c][c];
        for (int q = 0; q < 4; ++q) m[r][q] -= k * m[c][q];
      }
    return std::array<double, 3>{m[0][3] / m[0][0], m[1][3] / m[1][1], m[2][3] / m[2][2]};
  };
  // Where y first falls through `level` (from index `from`): ln f, refined on the local fit
  // (Newton from the bracket), or NaN.
  auto crossing = [&](const std::vector<double>& y, double level, std::size_t from) {
    for (std::size_t k = from; k + 1 < y.size(); ++k)
      if (y[k] > level && y[k + 1] <= level) {
        const double bracket = lf[k] + (level - y[k]) / (y[k + 1] - y[k]) * (lf[k + 1] - lf[k]);
        const auto c = local_fit(y, bracket);
        double x = 0;
        for (int i = 0; i < 20; ++i) {
          const double slope = c[1] + 2 * c[2] * x;
          if (!(slope < 0)) return bracket;
          x -= (c[0] + c[1] * x + c[2] * x * x - level) / slope;
        }
        return std::abs(x) < std::log(1.25) ? bracket + x : bracket;
      }
    return std::numeric_limits<double>::quiet_NaN();
  };
  auto value_at = [&](const std::vector<double>& y, double x) { return local_fit(y, x)[0]; };
  const double gain_crossover = crossing(db, 0, 0);
  if (std::isnan(gain_crossover)) return out;
  const double phase_there = value_at(deg, gain_crossover);
  const double turns = std::ceil(phase_there / 360.0);  // phase in (−360, 0] there
  for (double& d : deg) d -= 360 * turns;
  out.gain_crossover_hz = std::exp(gain_crossover);
  out.phase_margin_deg = 180 + phase_there - 360 * turns;
  std::size_t from = 0;
  while (from + 1 < lf.size() && lf[from] < gain_crossover) ++from;
  const double phase_crossover = crossing(deg, -180, from);
  if (std::isnan(phase_crossover)) return out;
  out.phase_crossover_hz = std::exp(phase_crossover);
  out.gain_margin_db = -value_at(db, phase_crossover);
  return out;
}

ResponseResult run_response(const SimulationSettings& settings, const ResponseSettings& r) {
  const SimTime period_ns = vehicle::period_of_rate(r.rate_hz);
  if (period_ns == 0)
    throw base::InputError("--rate-hz " + base::shortest_text(r.rate_hz) +
                           ": expected a rate that divides a second into whole nanoseconds");
  ResponseResult out;
  out.model = response_model(settings, r.axis, r.loop, r.rate_hz);
  const std::size_t k = axis_index(r.axis);
  const Vec3 sense = body_sense(r.axis);
  TestLoop loop(settings, r);
  Recorded rec;
  const double end_s = r.settle_s + r.duration_s;
  for (SimTime t = period_ns; vehicle::seconds(t) <= end_s + 1e-12; t += period_ns) {
    const double ts = vehicle::seconds(t), since = ts - r.settle_s;
    Vec3 attitude_rad, torque_nm;
    if (since >= 0 && r.input == ResponseInput::step)
      attitude_rad = sense * (r.amplitude_deg / kDeg);
    if (since >= 0 && r.input == ResponseInput::chirp)
      torque_nm = sense * (r.amplitude_nm * std::sin(chirp_phase_rad(r, since)));
    const ExecutionOutput o = loop.execute(t, attitude_rad, torque_nm);
    const vehicle::MultirotorState& x = loop.truth();
    ResponseSample s;
    s.t_s = ts;
    s.setpoint_deg = component(euler_deg(o.attitude_setpoint), k);
    s.response_deg = component(euler_deg(x.attitude), k);
    s.estimate_deg = component(euler_deg(loop.estimate()), k);
    if (r.axis == ResponseAxis::yaw) s.estimate_deg = wrap_deg(s.estimate_deg);
    if (r.axis == ResponseAxis::yaw) s.setpoint_deg = wrap_deg(s.setpoint_deg);
    if (r.axis == ResponseAxis::yaw) s.response_deg = wrap_deg(s.response_deg);
    s.error_deg = wrap_deg(s.setpoint_deg - s.response_deg);
    s.rate_setpoint_dps = dot(o.rate_setpoint_rad_s, sense) * kDeg;
    s.rate_dps = dot(x.rate_rad_s, sense) * kDeg;
    s.injection_nm = dot(torque_nm, sense);
    s.controller_torque_nm = dot(o.controller_torque_nm, sense);
    s.rotors = o.rotor_count;
    s.pwm_us = o.pwm_us;
    out.samples.push_back(s);
    if (since >= 0 && r.input == ResponseInput::chirp) {
      rec.t.push_back(ts);
      rec.d.push_back(s.injection_nm);
      rec.c.push_back(s.controller_torque_nm);
    }
  }
  const LoopMargins closed = loop_margins(out.model, 2 * kPi * r.from_hz, 2 * kPi * r.to_hz);
  out.closed_form = in_hz(closed);
  if (r.input == ResponseInput::step) {
    out.step = step_metrics(out.samples, r.settle_s, r.amplitude_deg, false);
    out.step_estimate = step_metrics(out.samples, r.settle_s, r.amplitude_deg, true);
    return out;
  }
  out.bode = estimate_bode(rec, r);
  std::vector<double> closed_deg;
  for (BodePoint& p : out.bode) {
    const std::complex<double> l = rate_loop_gain(out.model, 2 * kPi * p.frequency_hz);
    p.closed_form_magnitude_db = 20 * std::log10(std::abs(l));
    closed_deg.push_back(std::arg(l) * kDeg);
  }
  unwrap_deg(closed_deg);
  out.measured = margins_of(out.bode);
  // Both phase curves on the branch the margins use: (−360°, 0°] at their gain crossovers.
  std::vector<double> measured_deg;
  for (const BodePoint& p : out.bode) measured_deg.push_back(p.phase_deg);
  unwrap_deg(measured_deg);
  auto shift_to_branch = [&](std::vector<double>& deg, double crossover_hz) {
    std::size_t j = 0;
    while (j + 1 < out.bode.size() && out.bode[j].frequency_hz < crossover_hz) ++j;
    const double turns = std::ceil(deg[j] / 360.0);
    for (double& d : deg) d -= 360 * turns;
  };
  shift_to_branch(measured_deg, out.measured.gain_crossover_hz);
  shift_to_branch(closed_deg, out.closed_form.gain_crossover_hz);
  for (std::size_t j = 0; j < out.bode.size(); ++j) {
    out.bode[j].phase_deg = measured_deg[j];
    out.bode[j].closed_form_phase_deg = closed_deg[j];
  }
  return out;
}

namespace {
void add(std::string& line, double v, int decimals) {
  if (!line.empty() && line.back() != '\n') line += ',';
  line += base::fixed_text(v, decimals);
}
std::string margin_text(double v, int decimals) {
  return std::isfinite(v) ? base::fixed_text(v, decimals) : "inf";
}
}  // namespace

std::string response_csv(const std::vector<ResponseSample>& samples) {
  std::string out =
      "time_s,setpoint_deg,response_deg,error_deg,estimate_deg,rate_setpoint_dps,rate_dps,"
      "injection_nm,controller_torque_nm";
  const std::size_t rotors = samples.empty() ? 0 : samples.front().rotors;
  for (std::size_t i = 1; i <= rotors; ++i) out += ",pwm_" + std::to_string(i) + "_us";
  out += '\n';
  for (const ResponseSample& s : samples) {
    std::string line;
    add(line, s.t_s, 4);
    add(line, s.setpoint_deg, 4);
    add(line, s.response_deg, 4);
    add(line, s.error_deg, 4);
    add(line, s.estimate_deg, 4);
    add(line, s.rate_setpoint_dps, 3);
    add(line, s.rate_dps, 3);
    add(line, s.injection_nm, 5);
    add(line, s.controller_torque_nm, 5);
    for (std::size_t i = 0; i < s.rotors; ++i) add(line, s.pwm_us[i], 1);
    out += line + '\n';
  }
  return out;
}

std::string bode_csv(const std::vector<BodePoint>& bode) {
  std::string out =
      "frequency_hz,magnitude_db,phase_deg,coherence,closed_form_magnitude_db,"
      "closed_form_phase_deg\n";
  for (const BodePoint& p : bode) {
    std::string line;
    add(line, p.frequency_hz, 4);
    add(line, p.magnitude_db, 3);
    add(line, p.phase_deg, 2);
    add(line, p.coherence, 4);
    add(line, p.closed_form_magnitude_db, 3);
    add(line, p.closed_form_phase_deg, 2);
    out += line + '\n';
  }
  return out;
}

std::string margins_csv(const MarginFigures& measured, const MarginFigures& closed_form) {
  std::string out = "source,gain_crossover_hz,phase_margin_deg,phase_crossover_hz,gain_margin_db\n";
  for (const auto& [name, m] : {std::pair{"simulated", measured}, {"closed_form", closed_form}})
    out += std::string(name) + ',' + base::fixed_text(m.gain_crossover_hz, 3) + ',' +
           margin_text(m.phase_margin_deg, 2) + ',' + base::fixed_text(m.phase_crossover_hz, 3) +
           ',' + margin_text(m.gain_margin_db, 2) + '\n';
  return out;
}

std::string step_csv(const StepMetrics& truth, const StepMetrics& estimate) {
  std::string out = "attitude,rise_time_s,overshoot_percent,settling_time_s,final_deg,settled\n";
  for (const auto& [name, m] : {std::pair{"true", truth}, {"estimate", estimate}})
    out += std::string(name) + ',' + base::fixed_text(m.rise_time_s, 4) + ',' +
           base::fixed_text(m.overshoot_percent, 2) + ',' + base::fixed_text(m.settling_time_s, 4) +
           ',' + base::fixed_text(m.final_deg, 3) + ',' + (m.settled ? "true" : "false") + '\n';
  return out;
}

}  // namespace swath::control
