#include "swath/control/estimator.hpp"

#include <algorithm>
#include <cmath>

namespace swath::control {
namespace {

constexpr Vec3 kUp{0, 0, 1};
// Attitude error (rad, about) below which the gyro bias is learnt.
constexpr double kBiasLearningMaxError_rad = 0.05;
// Low-pass of the velocity fixes' differences, s: a 10-Hz GPS with 0.1 m/s noise differences to
// 1.4 m/s² of noise, which would tilt the estimate by ~1° at rest; manoeuvres last seconds.
constexpr double kFixAccelerationTimeConstant_s = 0.4;

// The scalar measurement z = h·x of variance r: Kalman update with the covariance in Joseph form,
// (I − K h) P (I − K h)ᵀ + K r Kᵀ, which stays symmetric positive definite under rounding (papers
// docs/swath-energy.md: the correct sign of paper 004's update, in its safe form).
void scalar_update(AxisFilter& a, double h0, double h1, double z, double r) {
  const double ph0 = a.p_pp * h0 + a.p_pv * h1;  // P hᵀ
  const double ph1 = a.p_pv * h0 + a.p_vv * h1;
  const double s = h0 * ph0 + h1 * ph1 + r;
  const double k0 = ph0 / s, k1 = ph1 / s;
  const double innovation = z - (h0 * a.position_m + h1 * a.velocity_m_s);
  a.position_m += k0 * innovation;
  a.velocity_m_s += k1 * innovation;
  // A = I − K h.
  const double a00 = 1 - k0 * h0, a01 = -k0 * h1, a10 = -k1 * h0, a11 = 1 - k1 * h1;
  // A P.
  const double b00 = a00 * a.p_pp + a01 * a.p_pv, b01 = a00 * a.p_pv + a01 * a.p_vv;
  const double b10 = a10 * a.p_pp + a11 * a.p_pv, b11 = a10 * a.p_pv + a11 * a.p_vv;
  a.p_pp = b00 * a00 + b01 * a01 + k0 * r * k0;
  a.p_pv = b00 * a10 + b01 * a11 + k0 * r * k1;
  a.p_vv = b10 * a10 + b11 * a11 + k1 * r * k1;
}

// A magnetometer sample left unused this long (a stalled sensor) corrects no more than this much
// heading, s: the impulse k_mag · weight must stay well below 1 (0.2/s · 0.5 s = 0.1).
constexpr double kMaxHeadingWeight_s = 0.5;

// Mahony's correction towards the measured gravity (rad/s, body), applied over the execution's
// interval.
Vec3 gravity_correction(const EstimatorSettings& s, const EstimatorState& state,
                        const EstimatorInput& in) {
  const Vec3 up_estimated = rotate_inverse(state.attitude, kUp);
  const Vec3 specific_force = in.imu.delta_velocity_m_s / in.imu.interval_s -
                              rotate_inverse(state.attitude, state.fix_acceleration_m_s2);
  const double f = norm(specific_force);
  if (f > s.gravity_m_s2 * (1 - s.accel_gate) && f < s.gravity_m_s2 * (1 + s.accel_gate))
    return s.attitude_gain_1_s * cross(specific_force / f, up_estimated);
  return {};
}

// Mahony's correction towards the measured north (rad/s, body), about the estimated up axis only,
// so that the magnetometer never tilts the attitude; zero without a fresh sample.
Vec3 heading_correction(const EstimatorSettings& s, const EstimatorState& state,
                        const EstimatorInput& in) {
  // The heading error is the angle of the measured field's horizontal part from north (+y), as
  // seen through the estimate: a rotation about world up, so it never tilts the attitude. The
  // angle itself rather than its sine keeps the rate 1/mag_gain from any start and any dip.
  const Vec3 h = rotate(state.attitude, in.mag.field_body);
  if (!in.mag.fresh || !(std::hypot(h.x, h.y) > 1e-6 * norm(h))) return {};
  const double heading_error = std::atan2(-h.x, h.y);  // estimate's yaw − true yaw
  return -s.mag_gain_1_s * heading_error * rotate_inverse(state.attitude, kUp);
}

void update_attitude(const EstimatorSettings& s, EstimatorState& state, const EstimatorInput& in) {
  const double dt = in.imu.interval_s;
  const Vec3 gravity = gravity_correction(s, state, in);
  const Vec3 heading = heading_correction(s, state, in);
  // Each correction turns the estimate by its rate times the time its measurement stands for:
  // the accelerometer's Δv spans the execution's interval, a magnetometer sample the time since
  // the previous one was used. Weighting the magnetometer by the execution's interval instead
  // made its gain per second k_mag · (magnetometer rate / execution rate): 0.2/s at 100 Hz, 0.02/s
  // at 1 kHz with a 100-Hz magnetometer, and the heading drifted with the gyro's bias ten times
  // as far (disturbance-only yaw error 0.5° at TT100, 2.4° at TT1000 in LAB).
  state.since_heading_s += dt;
  double heading_weight_s = 0;
  if (in.mag.fresh) {
    heading_weight_s = std::min(state.since_heading_s, kMaxHeadingWeight_s);
    state.since_heading_s = 0;
  }
  const Vec3 correction_rad = dt * gravity + heading_weight_s * heading;
  // The bias is learnt only once the attitude is nearly right: an integrator fed a large start-up
  // error learns a bias that is not there and takes 1 / (bias_gain · gain) seconds to unlearn.
  const double gains = s.attitude_gain_1_s + s.mag_gain_1_s;
  if (gains > 0 && norm(gravity + heading) < kBiasLearningMaxError_rad * gains)
    state.gyro_bias_rad_s -= s.bias_gain_1_s * correction_rad;
  const Vec3 turn = in.imu.delta_angle_rad - dt * state.gyro_bias_rad_s + correction_rad;
  state.body_rate_rad_s = in.imu.delta_angle_rad / dt - state.gyro_bias_rad_s;
  state.attitude = normalized(state.attitude * vehicle::from_rotation_vector(turn));
}

}  // namespace

void kalman_predict(AxisFilter& a, double accel_m_s2, double dt_s, double accel_density) {
  const double dt2 = dt_s * dt_s;
  // Continuous white-noise acceleration of spectral density q̃ integrated exactly over dt
  // (Bar-Shalom, Li, Kirubarajan, section 6.2.2): Q = q̃ [dt³/3, dt²/2; dt²/2, dt]. The noise added
  // per second does not depend on how often the filter predicts.
  const double q = accel_density * accel_density;
  a.position_m += a.velocity_m_s * dt_s + 0.5 * accel_m_s2 * dt2;
  a.velocity_m_s += accel_m_s2 * dt_s;
  a.p_pp += 2 * dt_s * a.p_pv + dt2 * a.p_vv + q * dt2 * dt_s / 3;
  a.p_pv += dt_s * a.p_vv + q * dt2 / 2;
  a.p_vv += q * dt_s;
}

void kalman_update_position(AxisFilter& axis, double z_m, double sigma_m) {
  scalar_update(axis, 1, 0, z_m, sigma_m * sigma_m);
}

void kalman_update_velocity(AxisFilter& axis, double z_m_s, double sigma_m_s) {
  scalar_update(axis, 0, 1, z_m_s, sigma_m_s * sigma_m_s);
}

EstimatorState initial_estimate(const Vec3& position_m, const Quat& attitude,
                                double position_sigma_m, double velocity_sigma_m_s) {
  EstimatorState s;
  s.attitude = normalized(attitude);
  const double p[3] = {position_m.x, position_m.y, position_m.z};
  for (std::size_t k = 0; k < 3; ++k)
    s.axes[k] = AxisFilter{p[k], 0, position_sigma_m * position_sigma_m, 0,
                           velocity_sigma_m_s * velocity_sigma_m_s};
  return s;
}

namespace {

// History kept beyond the receiver's latency, s: a fix waits for the next execution (≤ 0.1 s at
// 10 Hz and above) before the filter reads it.
constexpr double kHistoryMargin_s = 0.1;

// One filter step: the prediction over the step's interval, then its barometric altitude.
void advance(std::array<AxisFilter, 3>& axes, const FilterStep& step, const EstimatorSettings& s) {
  for (std::size_t k = 0; k < 3; ++k)
    kalman_predict(axes[k], step.accel_m_s2[k], step.dt_s, s.process_accel_m_s2_per_sqrt_hz);
  if (step.baro) kalman_update_position(axes[2], step.baro_m, s.baro_noise_m);
}

void fuse_fix(std::array<AxisFilter, 3>& axes, const PositionFix& fix, const EstimatorSettings& s) {
  const double p[3] = {fix.position_m.x, fix.position_m.y, fix.position_m.z};
  const double v[3] = {fix.velocity_m_s.x, fix.velocity_m_s.y, fix.velocity_m_s.z};
  for (std::size_t k = 0; k < 3; ++k) {
    if (fix.position_fresh) kalman_update_position(axes[k], p[k], s.position_noise_m);
    if (fix.velocity_fresh) kalman_update_velocity(axes[k], v[k], s.velocity_noise_m_s);
  }
}

// A fix measured `delay_s` before now: the filters go back to the step holding that instant,
// predict to it, fuse the fix there and re-run every later step (their predictions and barometric
// altitudes) to now, so that the fix meets the state of its own time. Fused now, a fix measured d
// ago on a leg at speed v pulls the position back by v·d (0.3 m at 3 m/s and 0.1 s).
void fuse_delayed_fix(const EstimatorSettings& s, EstimatorState& state, const PositionFix& fix,
                      double delay_s) {
  std::deque<FilterStep>& h = state.history;
  std::size_t j = h.size();
  double back_s = 0;  // from the end of step j − 1 to now
  while (j > 0 && back_s + h[j - 1].dt_s < delay_s) back_s += h[--j].dt_s;
  if (j == 0) {  // older than the history: at its start
    if (h.empty()) return fuse_fix(state.axes, fix, s);
    j = 1, back_s = state.history_s;
  }
  const std::size_t first = j - 1;
  const double before_s = std::max(h[first].dt_s - (delay_s - back_s), 0.0);
  std::array<AxisFilter, 3> axes = h[first].before;
  for (std::size_t k = first; k < h.size(); ++k) {
    FilterStep& step = h[k];
    step.before = axes;
    if (k != first) {
      advance(axes, step, s);
      continue;
    }
    FilterStep part = step;  // to the fix's instant, the fix, then the rest of the step
    part.dt_s = before_s, part.baro = false;
    advance(axes, part, s);
    fuse_fix(axes, fix, s);
    part.dt_s = step.dt_s - before_s, part.baro = step.baro;
    advance(axes, part, s);
  }
  state.axes = axes;
}

void remember(EstimatorState& state, const FilterStep& step, double keep_s) {
  state.history.push_back(step);
  state.history_s += step.dt_s;
  while (state.history.size() > 1 && state.history_s - state.history.front().dt_s >= keep_s) {
    state.history_s -= state.history.front().dt_s;
    state.history.pop_front();
  }
}

}  // namespace

void estimator_update(const EstimatorSettings& s, EstimatorState& state, const EstimatorInput& in) {
  if (s.type == EstimatorType::truth) {
    state.attitude = in.truth.attitude;
    state.body_rate_rad_s = in.truth.body_rate_rad_s;
    const double p[3] = {in.truth.position_m.x, in.truth.position_m.y, in.truth.position_m.z};
    const double v[3] = {in.truth.velocity_m_s.x, in.truth.velocity_m_s.y, in.truth.velocity_m_s.z};
    for (std::size_t k = 0; k < 3; ++k) {
      state.axes[k].position_m = p[k];
      state.axes[k].velocity_m_s = v[k];
    }
    return;
  }
  const double fix_delay_s = s.fix_delay_s.value_or(0.0);
  const double dt = in.imu.interval_s;
  FilterStep step;
  step.baro = in.baro.fresh, step.baro_m = in.baro.altitude_m;
  if (dt > 0 && std::isfinite(dt)) {
    update_attitude(s, state, in);
    // Δv is a specific force: rotated to world, gravity removed, it is the acceleration.
    const Vec3 accel =
        rotate(state.attitude, in.imu.delta_velocity_m_s / dt) - s.gravity_m_s2 * kUp;
    step.dt_s = dt, step.accel_m_s2 = {accel.x, accel.y, accel.z};
    state.since_fix_s += dt;
  }
  if (fix_delay_s > 0) {
    step.before = state.axes;
    remember(state, step, fix_delay_s + kHistoryMargin_s);
  }
  if (in.fix.velocity_fresh) {
    if (state.has_fix_velocity && state.since_fix_s > 0)
      state.fix_acceleration_m_s2 +=
          (1 - std::exp(-state.since_fix_s / kFixAccelerationTimeConstant_s)) *
          ((in.fix.velocity_m_s - state.last_fix_velocity_m_s) / state.since_fix_s -
           state.fix_acceleration_m_s2);
    state.last_fix_velocity_m_s = in.fix.velocity_m_s;
    state.since_fix_s = 0;
    state.has_fix_velocity = true;
  }
  const bool fix = in.fix.position_fresh || in.fix.velocity_fresh;
  if (fix_delay_s > 0) {
    advance(state.axes, step, s);
    if (fix) fuse_delayed_fix(s, state, in.fix, fix_delay_s + std::max(in.fix.waited_s, 0.0));
    return;
  }
  // Fused as they arrive: the prediction, the fix, then the barometer.
  step.baro = false;
  advance(state.axes, step, s);
  fuse_fix(state.axes, in.fix, s);
  if (in.baro.fresh) kalman_update_position(state.axes[2], in.baro.altitude_m, s.baro_noise_m);
}

}  // namespace swath::control
