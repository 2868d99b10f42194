#include "swath/control/control_task.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace swath::control {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kMinDt_s = 1e-4, kMaxDt_s = 0.5;  // the measured Δt is clamped

// Shepperd's method: the unit quaternion of the rotation whose columns are x, y, z.
Quat quat_from_axes(const Vec3& x, const Vec3& y, const Vec3& z) {
  const double trace = x.x + y.y + z.z;
  Quat q;
  if (trace > 0) {
    const double s = 2 * std::sqrt(1 + trace);
    q = {s / 4, (y.z - z.y) / s, (z.x - x.z) / s, (x.y - y.x) / s};
  } else if (x.x > y.y && x.x > z.z) {
    const double s = 2 * std::sqrt(1 + x.x - y.y - z.z);
    q = {(y.z - z.y) / s, s / 4, (y.x + x.y) / s, (z.x + x.z) / s};
  } else if (y.y > z.z) {
    const double s = 2 * std::sqrt(1 + y.y - x.x - z.z);
    q = {(z.x - x.z) / s, (y.x + x.y) / s, s / 4, (z.y + y.z) / s};
  } else {
    const double s = 2 * std::sqrt(1 + z.z - x.x - y.y);
    q = {(x.y - y.x) / s, (z.x + x.z) / s, (z.y + y.z) / s, s / 4};
  }
  return normalized(q);
}

double measured_dt_s(const ControlTaskConfig& c, const TaskState& state, SimTime now_ns) {
  const double nominal = 1.0 / c.nominal_rate_hz;
  if (!state.has_run || c.gains.dt_mode == DtMode::nominal) return nominal;
  return std::clamp(vehicle::seconds(now_ns - state.last_time_ns), kMinDt_s, kMaxDt_s);
}

// Step 2: position P plus the carrot's feed-forward, horizontal and vertical speed limited.
Vec3 velocity_setpoint(const ControllerGains& g, const Vec3& position_m, const Setpoint& sp) {
  Vec3 v = g.position_p_1_s * (sp.position_m - position_m) + sp.velocity_m_s;
  const double horizontal = std::hypot(v.x, v.y);
  if (horizontal > g.limits.max_speed_m_s) {
    v.x *= g.limits.max_speed_m_s / horizontal;
    v.y *= g.limits.max_speed_m_s / horizontal;
  }
  v.z = std::clamp(v.z, -g.limits.max_climb_m_s, g.limits.max_climb_m_s);
  return v;
}

// Step 3a: velocity PIDs, then the tilt limit. The vertical acceleration is kept within ±g/2 so
// that the thrust never reverses; the horizontal part is shortened until the thrust vector leans
// no more than max_tilt from up.
Vec3 acceleration_command(const ControllerGains& g, TaskState& state, const Vec3& v_sp,
                          const Vec3& v, double gravity, double dt) {
  Vec3 a{pid_update(g.velocity_xy, state.velocity_pid[0], v_sp.x, v.x, dt),
         pid_update(g.velocity_xy, state.velocity_pid[1], v_sp.y, v.y, dt),
         pid_update(g.velocity_z, state.velocity_pid[2], v_sp.z, v.z, dt)};
  a.z = std::clamp(a.z, -gravity / 2, gravity / 2);
  const double max_horizontal = (gravity + a.z) * std::tan(g.limits.max_tilt_deg * kDegToRad);
  const double horizontal = std::hypot(a.x, a.y);
  if (horizontal > max_horizontal) {
    a.x *= max_horizontal / horizontal;
    a.y *= max_horizontal / horizontal;
  }
  return a;
}

// Step 4: the attitude error as a rotation vector in body axes, times the P gains, plus the
// setpoint's own yaw rate (world up, in body axes) as feed-forward, limited. Without the
// feed-forward a slewing heading would lag by rate / attitude_p (11° at 45°/s and P 4).
Vec3 rate_setpoint(const ControllerGains& g, const Quat& estimate, const Quat& desired,
                   double yaw_rate_rad_s) {
  const Vec3 error = vehicle::rotation_vector(conjugate(estimate) * desired);
  const Vec3 rate =
      hadamard(g.attitude_p_1_s, error) + rotate_inverse(estimate, Vec3{0, 0, yaw_rate_rad_s});
  const Vec3 limit = g.limits.max_rate_dps * kDegToRad;
  return {std::clamp(rate.x, -limit.x, limit.x), std::clamp(rate.y, -limit.y, limit.y),
          std::clamp(rate.z, -limit.z, limit.z)};
}

}  // namespace

Quat attitude_from_thrust_and_yaw(const Vec3& up_world, double yaw_rad) {
  // PX4's construction: body x ⟂ the horizontal left of the heading, so body x's horizontal part
  // points along yaw_rad whatever the tilt.
  const Vec3 z = up_world / norm(up_world);
  const Vec3 left{-std::sin(yaw_rad), std::cos(yaw_rad), 0};
  Vec3 x = cross(left, z);
  // Thrust along the left axis itself (never within the tilt limit): keep the heading.
  if (norm(x) < 1e-9) x = Vec3{std::cos(yaw_rad), std::sin(yaw_rad), 0};
  x = x / norm(x);
  return quat_from_axes(x, cross(z, x), z);
}

std::optional<ControlTask> ControlTask::create(const ControlTaskConfig& config) {
  const std::optional<MixerMatrices> m = mixer_matrices(config.airframe.rotors);
  if (!m) return std::nullopt;
  return ControlTask(config, *m);
}

TaskState ControlTask::initial_state(const Vec3& position_m, const Quat& attitude) const {
  TaskState s;
  s.estimate = initial_estimate(position_m, attitude);
  s.pwm_us.fill(config_.airframe.rotors.pwm_min_us);
  return s;
}

ExecutionOutput ControlTask::execute(TaskState& state, const TaskInput& in) const {
  const ControllerGains& g = config_.gains;
  const ControlAirframe& air = config_.airframe;
  ExecutionOutput out;
  out.dt_s = measured_dt_s(config_, state, in.time_ns);
  // 1. Estimator.
  estimator_update(config_.estimator, state.estimate, in.sensors);
  const Vec3 p = state.estimate.position_m(), v = state.estimate.velocity_m_s();
  // The setpoint stream is held between updates; the target is advanced to this execution's time
  // so that it moves every loop, not in 50 Hz steps.
  const Setpoint target = extrapolated(in.setpoint, in.time_ns);
  // 2. Position P → velocity setpoint.
  out.velocity_setpoint_m_s = velocity_setpoint(g, p, target);
  // 3. Velocity PID → acceleration → thrust vector: collective along the present body z, and the
  // attitude that would point it where it should go.
  out.acceleration_m_s2 =
      acceleration_command(g, state, out.velocity_setpoint_m_s, v, air.gravity_m_s2, out.dt_s);
  const Vec3 thrust_world = air.mass_kg * (out.acceleration_m_s2 + Vec3{0, 0, air.gravity_m_s2});
  const Vec3 body_up = rotate(state.estimate.attitude, Vec3{0, 0, 1});
  out.request.thrust_n = std::max(dot(thrust_world, body_up), 0.0);
  out.attitude_setpoint = attitude_from_thrust_and_yaw(thrust_world, target.yaw_rad);
  if (norm(in.attitude_injection_rad) > 0)
    out.attitude_setpoint =
        out.attitude_setpoint * vehicle::from_rotation_vector(in.attitude_injection_rad);
  // 4. Attitude P → rate setpoint.
  out.rate_setpoint_rad_s =
      rate_setpoint(g, state.estimate.attitude, out.attitude_setpoint, target.yaw_rate_rad_s);
  // 5. Rate PID → angular acceleration → torque J ⊙ u.
  const Vec3& rate = state.estimate.body_rate_rad_s;
  const Vec3& rsp = out.rate_setpoint_rad_s;
  const Vec3 u{pid_update(g.rate_roll, state.rate_pid[0], rsp.x, rate.x, out.dt_s),
               pid_update(g.rate_pitch, state.rate_pid[1], rsp.y, rate.y, out.dt_s),
               pid_update(g.rate_yaw, state.rate_pid[2], rsp.z, rate.z, out.dt_s)};
  out.controller_torque_nm = hadamard(air.inertia_kg_m2, u);
  out.request.torque_nm = out.controller_torque_nm + in.torque_injection_nm;
  // 6–7. Mixer and quantised pulses; "changed" is a move of some pulse by a level or more.
  out.mix = mix(air.rotors, matrices_, out.request);
  out.rotor_count = matrices_.count;
  out.pwm_us = out.mix.pwm_us;
  out.changed = !state.has_run;
  for (std::size_t i = 0; i < out.rotor_count; ++i)
    out.changed =
        out.changed || std::abs(out.pwm_us[i] - state.pwm_us[i]) >= g.change_threshold_us - 1e-9;
  state.pwm_us = out.pwm_us;
  state.last_time_ns = in.time_ns;
  state.has_run = true;
  return out;
}

}  // namespace swath::control
