// The control task flying the simulated multirotor (vehicle::FlightModel) at 400 Hz, time
// triggered: the plant's sensors through the driver's accumulation into the estimator, PWM back to
// the ESCs. Hover holds in calm air and in ARCH's wind; a square at 3 m/s is tracked; the motor
// energy is what the power says.
#include <gtest/gtest.h>

#include <iostream>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "swath/control/control_task.hpp"
#include "swath/control/driver.hpp"
#include "swath/control/loop_response.hpp"
#include "swath/control/setpoints.hpp"
#include "swath/vehicle/flight_model.hpp"
#include "swath/vehicle/sensors.hpp"

namespace swath::control {
namespace {

using vehicle::FlightModel;
using vehicle::FlightModelSettings;

class Loop {
 public:
  Loop(const FlightModelSettings& plant, const Vec3& start)
      : plant_(plant), task_(*ControlTask::create(config_of(plant))) {
    state_ = task_.initial_state(start);
  }

  static ControlTaskConfig config_of(const FlightModelSettings& plant) {
    ControlTaskConfig c;
    const vehicle::Airframe& a = plant.physics.airframe;
    c.airframe.mass_kg = a.frame.mass_kg;
    c.airframe.inertia_kg_m2 = a.frame.inertia_kg_m2;
    c.airframe.rotors = layout_of(a, plant.physics.esc);
    c.nominal_rate_hz = 400;
    return c;
  }

  // One execution at `t`: the plant up to t, the samples into the driver, the task, the PWM out.
  ExecutionOutput execute(SimTime t, const Setpoint& setpoint, const Vec3& injection_nm = {}) {
    plant_.advance_to(t);
    for (const vehicle::DeliveredSample& d : plant_.take_samples()) driver_.deliver(d);
    input_.sensors = driver_.take(t);
    input_.time_ns = t;
    input_.setpoint = setpoint;
    input_.torque_injection_nm = injection_nm;
    const ExecutionOutput out = task_.execute(state_, input_);
    for (std::size_t i = 0; i < out.rotor_count; ++i) plant_.command_pwm(i, out.pwm_us[i]);
    return out;
  }

  const FlightModel& plant() const { return plant_; }
  const TaskState& state() const { return state_; }

 private:
  FlightModel plant_;
  ControlTask task_;
  TaskState state_;
  SensorDriver driver_{plant_.physics().sensors};
  TaskInput input_;
};

double tilt_deg(const Quat& q) {
  const Vec3 up = vehicle::rotate(q, {0, 0, 1});
  return std::acos(std::clamp(up.z, -1.0, 1.0)) * 180 / M_PI;
}

FlightModelSettings hovering(const char* environment, std::uint64_t seed) {
  FlightModelSettings s;
  s.environment = vehicle::environment_preset(environment);
  s.seed = seed;
  s.initial.position_m = {0, 0, 10};
  s.initial.rotor_rad_s = vehicle::hover(s.physics.airframe).rotor_rad_s;
  return s;
}

struct Held {
  double rms_m = 0, max_m = 0, max_tilt_deg = 0;
};

Held hold(const char* environment, std::uint64_t seed, double seconds) {
  const Vec3 target{0, 0, 10};
  Loop loop(hovering(environment, seed), target);
  Setpoint sp;
  sp.position_m = target;
  double sum = 0;
  int n = 0;
  Held h;
  const auto steps = static_cast<long>(seconds * 400);
  for (long k = 1; k <= steps; ++k) {
    const SimTime t = k * 2'500'000;
    loop.execute(t, sp);
    if (t < 5 * vehicle::kNanosecondsPerSecond) continue;  // settled after 5 s
    const double e = norm(loop.plant().state().position_m - target);
    sum += e * e;
    ++n;
    h.max_m = std::max(h.max_m, e);
    h.max_tilt_deg = std::max(h.max_tilt_deg, tilt_deg(loop.plant().state().attitude));
  }
  h.rms_m = std::sqrt(sum / n);
  return h;
}

TEST(ClosedLoop, HoverHoldsInCalmAir) {
  const Held h = hold("calm", 1, 30);
  // Sensor noise only (GPS 0.1 m white + 0.5 m Gauss–Markov over 60 s, baro 0.1 m).
  EXPECT_LT(h.rms_m, 0.5) << h.rms_m;
  EXPECT_LT(h.max_m, 1.0) << h.max_m;
  EXPECT_LT(h.max_tilt_deg, 5.0) << h.max_tilt_deg;
}

TEST(ClosedLoop, HoverHoldsInArchWind) {
  const Held h = hold("arch", 3, 30);
  EXPECT_LT(h.rms_m, 1.5) << h.rms_m;
  EXPECT_LT(h.max_tilt_deg, 30.0) << h.max_tilt_deg;  // the tilt limit
}

TEST(ClosedLoop, ASquareAtThreeMetresASecondIsTracked) {
  const std::vector<Vec3> square{{0, 0, 10}, {20, 0, 10}, {20, 20, 10}, {0, 20, 10}, {0, 0, 10}};
  const CarrotPath path(square, CarrotLimits{});
  Loop loop(hovering("calm", 5), square.front());
  double worst = 0;
  const SimTime end = path.end_ns() + 5 * vehicle::kNanosecondsPerSecond;
  for (SimTime t = 2'500'000; t <= end; t += 2'500'000) {
    const Setpoint sp = path.at(t);
    loop.execute(t, sp);
    worst = std::max(worst, norm(loop.plant().state().position_m - sp.position_m));
  }
  // The carrot is 3 m/s at most with 1 m/s²: the drone follows it within 1.5 m all the way and
  // ends at the last corner.
  EXPECT_LT(worst, 1.5) << worst;
  EXPECT_LT(norm(loop.plant().state().position_m - square.back()), 0.6);
  // 20 m legs at 3 m/s with 1 m/s² ramps: 4 x (20/3 + 3) s, and the motors drew about hover power.
  EXPECT_NEAR(vehicle::seconds(path.end_ns()), 4 * (20.0 / 3 + 3), 0.1);
  const double hover_w = vehicle::hover(loop.plant().physics().airframe).motor_power_w;
  EXPECT_NEAR(loop.plant().motor_energy_j() / vehicle::seconds(end), hover_w, 0.1 * hover_w);
}

// The roll rate loop's gain measured on the simulated plant: a sine of `omega` injected at the
// torque input (u = c + d), L(jω) = −C/U from the controller's torque c and the plant's input u
// over whole periods after a settling time (single-frequency DFT).
std::complex<double> measured_roll_loop_gain(double omega) {
  const Vec3 target{0, 0, 10};
  FlightModelSettings plant = hovering("calm", 7);
  Loop loop(plant, target);
  Setpoint sp;
  sp.position_m = target;
  const double period = 2 * std::numbers::pi / omega;
  const double settle = 2.0 + 2 * period, measure = std::max(8.0, 20 * period);
  const double amplitude_nm = 0.05;
  std::complex<double> c_sum, u_sum;
  const double end = settle + std::floor(measure / period) * period;
  for (SimTime t = 2'500'000; vehicle::seconds(t) < end; t += 2'500'000) {
    const double ts = vehicle::seconds(t);
    const double d = ts > 1.0 ? amplitude_nm * std::sin(omega * (ts - 1.0)) : 0.0;
    const ExecutionOutput out = loop.execute(t, sp, Vec3{d, 0, 0});
    if (ts < settle) continue;
    const std::complex<double> phasor = std::exp(std::complex<double>(0, -omega * ts));
    c_sum += out.controller_torque_nm.x * phasor;
    u_sum += out.request.torque_nm.x * phasor;
  }
  return -c_sum / u_sum;
}

TEST(ClosedLoop, RateLoopMarginsFromTheSimulationMatchTheClosedForm) {
  // The closed form for this harness: 400 Hz, the task's outputs applied at once (no execution
  // time), the gyro at 1 kHz, the ESCs at 490 Hz; quad-f450's roll gains.
  RateLoopModel model;
  model.delay_s = rate_loop_delay_s(400, 0, 1000, 490);
  const LoopMargins closed = loop_margins(model);
  // Measured on a logarithmic grid; margins interpolated between its points (log ω, dB and
  // degrees, the phase continued from the lowest frequency).
  std::vector<double> omega, db, deg;
  for (double w = 6; w < 700; w *= 1.18) {
    const std::complex<double> l = measured_roll_loop_gain(w);
    double phase = std::arg(l) * 180 / std::numbers::pi;
    while (!deg.empty() && phase - deg.back() > 180) phase -= 360;
    while (!deg.empty() && phase - deg.back() < -180) phase += 360;
    omega.push_back(w);
    db.push_back(20 * std::log10(std::abs(l)));
    deg.push_back(phase);
    // The closed form at the same frequency, from where the velocity loop no longer adds to the
    // attitude loop (~2 rad/s: 1.8 dB at 10 rad/s) to the phase crossover: within 1.5 dB.
    const std::complex<double> expected = rate_loop_gain(model, w);
    if (w > 15 && w < closed.phase_crossover_rad_s) {
      EXPECT_NEAR(db.back(), 20 * std::log10(std::abs(expected)), 1.5) << w << " rad/s";
    }
  }
  auto crossing = [&](const std::vector<double>& y, double level, const std::vector<double>& z) {
    for (std::size_t k = 0; k + 1 < y.size(); ++k)
      if ((y[k] - level) * (y[k + 1] - level) <= 0) {
        const double f = (level - y[k]) / (y[k + 1] - y[k]);
        return std::pair{std::exp(std::log(omega[k]) + f * std::log(omega[k + 1] / omega[k])),
                         z[k] + f * (z[k + 1] - z[k])};
      }
    return std::pair{0.0, 0.0};
  };
  const auto [gain_crossover, phase_there] = crossing(db, 0, deg);
  const auto [phase_crossover, db_there] = crossing(deg, -180, db);
  const double phase_margin = 180 + phase_there, gain_margin = -db_there;
  std::cout << "closed form: crossover " << closed.gain_crossover_rad_s << " rad/s, PM "
            << closed.phase_margin_deg << " deg, phase crossover " << closed.phase_crossover_rad_s
            << " rad/s, GM " << closed.gain_margin_db << " dB\nsimulated:   crossover "
            << gain_crossover << " rad/s, PM " << phase_margin << " deg, phase crossover "
            << phase_crossover << " rad/s, GM " << gain_margin << " dB\n";
  // Tolerances: the closed form is continuous (no sampling beyond its half-period delays, no PWM
  // quantisation, the velocity and position loops left out) and the measurement has sensor noise.
  EXPECT_NEAR(gain_crossover / closed.gain_crossover_rad_s, 1, 0.1);
  EXPECT_NEAR(phase_margin, closed.phase_margin_deg, 5);
  EXPECT_NEAR(phase_crossover / closed.phase_crossover_rad_s, 1, 0.2);
  EXPECT_NEAR(gain_margin, closed.gain_margin_db, 3);
}

}  // namespace
}  // namespace swath::control
