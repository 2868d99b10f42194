#include "swath/vehicle/flight_model.hpp"

#include <algorithm>
#include <cmath>

namespace swath::vehicle {

FlightModel::FlightModel(const FlightModelSettings& s)
    : settings_(s),
      state_(s.initial),
      gusts_(s.environment.gusts, SplitMix64::stream(s.seed, "gusts")),
      torque_random_(SplitMix64::stream(s.seed, "torque_noise")),
      wind_period_ns_(std::max<SimTime>(1, from_seconds(1.0 / s.environment.update_hz))),
      esc_frames_(s.physics.esc.frame_rate_hz > 0) {
  const Airframe& a = s.physics.airframe;
  for (std::size_t i = 0; i < a.rotors.size(); ++i) {
    escs_.emplace_back(s.physics.esc, a.propulsion.max_speed_rad_s);
    rotor_commands_.push_back(state_.rotor_rad_s[i]);
  }
  // The ESCs start holding the speed the rotors have (a flight may start in hover).
  for (std::size_t i = 0; i < escs_.size(); ++i) {
    const double u = std::pow(state_.rotor_rad_s[i] / a.propulsion.max_speed_rad_s,
                              s.physics.esc.thrust_linear ? 2.0 : 1.0);
    escs_[i].command(
        s.physics.esc.pwm_min_us + u * (s.physics.esc.pwm_max_us - s.physics.esc.pwm_min_us), 0);
    rotor_commands_[i] = escs_[i].speed_command_rad_s(escs_[i].next_frame(0));
  }
  for (std::size_t i = 0; i < s.physics.sensors.size(); ++i)
    sensors_.emplace_back(s.physics.sensors[i],
                          SplitMix64::stream(s.seed, "sensor:" + s.physics.sensors[i].name));
  const Environment& e = s.environment;
  if (e.dryden && e.w20_m_s > 0) {
    const double height = std::max(1.0, state_.position_m.z);
    const double v = e.reference_speed_m_s > 0
                         ? e.reference_speed_m_s
                         : std::max({e.mean_wind.speed_m_s, s.mission_speed_m_s, 1.0});
    turbulence_.emplace(dryden_scales(height, e.w20_m_s), v, seconds(wind_period_ns_),
                        SplitMix64::stream(s.seed, "turbulence"));
  }
  run_events(0);
}

MultirotorInputs FlightModel::inputs() const {
  MultirotorInputs in;
  // The ESCs drive the motors from the battery: the speed a PWM gives scales with its voltage.
  for (std::size_t i = 0; i < rotor_commands_.size(); ++i)
    in.command_rad_s[i] = rotor_commands_[i] * supply_ratio_;
  in.wind_m_s = wind_;
  in.torque_noise_nm = torque_noise_;
  in.drag_torque_factor = drag_factors_;
  return in;
}

double FlightModel::motor_power_w() const {
  return motors_power_w(settings_.physics.airframe, state_, inputs());
}

Vec3 FlightModel::acceleration_m_s2() const {
  return applied_force_world_n(settings_.physics.airframe, state_, inputs()) /
             settings_.physics.airframe.frame.mass_kg -
         Vec3{0, 0, kStandardGravity_m_s2};
}

void FlightModel::update_wind(double t_s) {
  const Environment& e = settings_.environment;
  const Vec3 mean = mean_wind_m_s(e.mean_wind, state_.position_m.z, t_s);
  Vec3 turbulence{};
  if (turbulence_) {
    // u along the mean wind (east when calm), v to its left, w up.
    const auto s = turbulence_->step();
    const double n = std::hypot(mean.x, mean.y);
    const Vec3 along = n > 0 ? Vec3{mean.x / n, mean.y / n, 0} : Vec3{1, 0, 0};
    const Vec3 left{-along.y, along.x, 0};
    turbulence = along * s[0] + left * s[1] + Vec3{0, 0, s[2]};
  }
  wind_ = mean + turbulence + gusts_.at(t_s) + region_wind_m_s(e.regions, state_.position_m);
  // Torque noise: Gauss–Markov per axis, discretised exactly at the wind's rate.
  const Frame& f = settings_.physics.airframe.frame;
  if (f.torque_noise_sigma_nm > 0) {
    const double a = std::exp(-seconds(wind_period_ns_) / f.torque_noise_time_constant_s);
    const double k = f.torque_noise_sigma_nm * std::sqrt(1 - a * a);
    torque_noise_ =
        torque_noise_ * a +
        Vec3{torque_random_.normal(), torque_random_.normal(), torque_random_.normal()} * k;
  }
}

SimTime FlightModel::next_event() const {
  SimTime t = next_wind_;
  if (esc_frames_ && !escs_.empty()) t = std::min(t, next_esc_frame_);
  for (const Sensor& s : sensors_) t = std::min(t, s.next_measurement());
  return t;
}

void FlightModel::run_events(SimTime t) {
  // ESC frames: every ESC shares the frame schedule.
  ++events_run_;
  if (esc_frames_ && !escs_.empty() && next_esc_frame_ <= t) {
    power_known_ = false;
    for (std::size_t i = 0; i < escs_.size(); ++i)
      rotor_commands_[i] = escs_[i].speed_command_rad_s(t);
    next_esc_frame_ = escs_.front().next_frame(t + 1);
  }
  if (next_wind_ <= t) {
    power_known_ = false;
    update_wind(seconds(t));
    next_wind_ = t + wind_period_ns_;
    // Translational lift from the airflow now, held until the next wind update like the wind
    // (solving Glauert's equation at every event would cost more than the rest of the plant).
    drag_factors_ = drag_torque_factors(settings_.physics.airframe, state_, wind_);
  }
  Truth truth;
  bool have_truth = false;
  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    if (sensors_[i].next_measurement() > t) continue;
    if (!have_truth) {
      truth = {state_.position_m, state_.velocity_m_s, acceleration_m_s2(), state_.attitude,
               state_.rate_rad_s};
      have_truth = true;
    }
    sensors_[i].measure(t, truth);
  }
  for (std::size_t i = 0; i < sensors_.size(); ++i)
    sensors_[i].deliver_each(t, [&](const SensorSample& s) { delivered_.push_back({i, s}); });
}

void FlightModel::integrate_to(SimTime t) {
  if (t <= now_) return;
  const double duration = seconds(t - now_);
  const auto steps = static_cast<long>(std::ceil(duration / settings_.max_step_s - 1e-9));
  const double h = duration / static_cast<double>(std::max(1L, steps));
  const MultirotorInputs in = inputs();
  // The power at the start is the last sub-step's end unless an input changed since.
  double p0 = power_known_ ? power_w_ : motor_power_w();
  for (long k = 0; k < std::max(1L, steps); ++k) {
    state_ = integrate(settings_.physics.airframe, state_, in, h, h);
    const double p1 = motor_power_w();
    motor_energy_j_ += 0.5 * (p0 + p1) * h;
    p0 = p1;
  }
  power_w_ = p0;
  power_known_ = true;
  now_ = t;
}

void FlightModel::advance_to(SimTime until) {
  while (true) {
    const SimTime t = next_event();
    if (t > until) break;
    integrate_to(t);
    run_events(t);
  }
  integrate_to(until);
}

void FlightModel::command_pwm(std::size_t motor, double pwm_us) {
  if (motor >= escs_.size()) return;
  escs_[motor].command(pwm_us, now_);
  power_known_ = false;
  // Without frames the command reaches the rotor now; a frame schedule of one event per
  // nanosecond would cost 10⁹ events per simulated second.
  if (!esc_frames_) rotor_commands_[motor] = escs_[motor].speed_command_rad_s(now_);
}

const std::vector<DeliveredSample>& FlightModel::take_samples() {
  // Two buffers in turn: no allocation per event once both have grown.
  taken_.clear();
  taken_.swap(delivered_);
  return taken_;
}

}  // namespace swath::vehicle
