// Readers of the control keys (docs/swath-control.md): every key lands in its field, the
// shipped files read back, and bad input is one InputError naming the file, line and key.

#include <gtest/gtest.h>

#include <string>

#include "swath/base/input_error.hpp"
#include "swath/control/config.hpp"
#include "swath/control/driver.hpp"

namespace swath::control {
namespace {

std::string error_of(const std::function<void()>& read) {
  try {
    read();
  } catch (const base::InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ControlConfig, EveryKeyLandsInItsField) {
  const VehicleControlConfig c = parse_vehicle_control(R"(
frame: {mass_kg: 2}
estimator: {type: truth, attitude_gain: 0.7, mag_gain: 0.3, bias_gain: 0.02, process_accel_m_s2_per_sqrt_hz: 0.9, fix_delay_s: 0.25}
controller:
  position_p: 1.1
  velocity_xy: {p: 2.1, i: 0.6, d: 0.1, i_limit: 2.2, d_lpf_hz: 6}
  velocity_z: {p: 4.1, i: 1.1, d: 0.2, i_limit: 3.1, d_lpf_hz: 7}
  attitude_p: [9, 10, 5]
  rate:
    roll: {p: 41, i: 21, d: 0.6, i_limit: 6, d_lpf_hz: 31}
    pitch: {p: 42, i: 22, d: 0.7, i_limit: 7, d_lpf_hz: 32}
    yaw: {p: 23, i: 6, d: 0.1, i_limit: 3, d_lpf_hz: 10}
  limits: {max_speed_m_s: 4, max_climb_m_s: 2, max_accel_m_s2: 1.5, max_tilt_deg: 25,
           max_rate_dps: [200, 210, 100], crash_tilt_deg: 70}
  dt_mode: nominal
  change_threshold_us: 2
computer:
  clock_hz: 72e6
  control_cycles: 170000
  dispatch_cycles: 3000
  driver_cycles: 1600
  trigger_check_cycles: 110
  refit_cycles_per_point: 310
  idle_w: 0.1
  active_w: 0.5
  control_preempts_background: false
  background: [{name: log, rate_hz: 25, cycles: 1000}]
)",
                                                       "v.yaml");
  EXPECT_EQ(c.estimator.type, EstimatorType::truth);
  EXPECT_EQ(c.estimator.attitude_gain_1_s, 0.7);
  EXPECT_EQ(c.estimator.mag_gain_1_s, 0.3);
  EXPECT_EQ(c.estimator.bias_gain_1_s, 0.02);
  EXPECT_EQ(c.estimator.process_accel_m_s2_per_sqrt_hz, 0.9);
  EXPECT_EQ(c.estimator.fix_delay_s, 0.25);
  const ControllerGains& g = c.controller;
  EXPECT_EQ(g.position_p_1_s, 1.1);
  EXPECT_EQ(g.velocity_xy.p, 2.1);
  EXPECT_EQ(g.velocity_xy.i, 0.6);
  EXPECT_EQ(g.velocity_xy.d, 0.1);
  EXPECT_EQ(g.velocity_xy.i_limit, 2.2);
  EXPECT_EQ(g.velocity_xy.d_lpf_hz, 6);
  EXPECT_EQ(g.velocity_z.p, 4.1);
  EXPECT_EQ(g.velocity_z.d_lpf_hz, 7);
  EXPECT_EQ(g.attitude_p_1_s, (Vec3{9, 10, 5}));
  EXPECT_EQ(g.rate_roll.p, 41);
  EXPECT_EQ(g.rate_pitch.i, 22);
  EXPECT_EQ(g.rate_pitch.d, 0.7);
  EXPECT_EQ(g.rate_yaw.i_limit, 3);
  EXPECT_EQ(g.rate_yaw.d_lpf_hz, 10);
  EXPECT_EQ(g.limits.max_speed_m_s, 4);
  EXPECT_EQ(g.limits.max_climb_m_s, 2);
  EXPECT_EQ(g.limits.max_accel_m_s2, 1.5);
  EXPECT_EQ(g.limits.max_tilt_deg, 25);
  EXPECT_EQ(g.limits.max_rate_dps, (Vec3{200, 210, 100}));
  EXPECT_EQ(g.limits.crash_tilt_deg, 70);
  EXPECT_EQ(g.dt_mode, DtMode::nominal);
  EXPECT_EQ(g.change_threshold_us, 2);
  const ComputerSettings& k = c.computer;
  EXPECT_EQ(k.clock_hz, 72e6);
  EXPECT_EQ(k.control_cycles, 170000);
  EXPECT_EQ(k.dispatch_cycles, 3000);
  EXPECT_EQ(k.driver_cycles, 1600);
  EXPECT_EQ(k.trigger_check_cycles, 110);
  EXPECT_EQ(k.refit_cycles_per_point, 310);
  EXPECT_EQ(k.idle_w, 0.1);
  EXPECT_EQ(k.active_w, 0.5);
  EXPECT_FALSE(k.control_preempts_background);
  ASSERT_EQ(k.background.size(), 1u);
  EXPECT_EQ(k.background[0].name, "log");
  EXPECT_EQ(k.background[0].rate_hz, 25);
  EXPECT_EQ(k.background[0].cycles, 1000);
}

TEST(ControlConfig, ShippedFilesReadBackAtTheDefaults) {
  const VehicleControlConfig v =
      read_vehicle_control(SWATH_SOURCE_DIR "/tests/bad-input/seeds/vehicle-control.yaml");
  const ControllerGains defaults;
  EXPECT_EQ(v.controller.rate_roll.d, defaults.rate_roll.d);
  EXPECT_EQ(v.controller.limits.max_rate_dps, defaults.limits.max_rate_dps);
  EXPECT_EQ(v.computer.clock_hz, 168e6);
  ASSERT_EQ(v.computer.background.size(), 3u);
  EXPECT_EQ(v.computer.background[1].name, "telemetry");
  const SchedulerConfig s = read_scheduler_config(SWATH_SOURCE_DIR "/share/schedulers/tt-400.yaml");
  EXPECT_EQ(s.mode, SchedulerMode::time_triggered);
  EXPECT_EQ(s.rate_hz, 400);
  EXPECT_EQ(s.run.metrics_from_s, 30);
  EXPECT_EQ(s.run.max_step_s, 0.001);
}

TEST(ControlConfig, TheFixDelayIsThePositionSensorsLatencyUnlessGiven) {
  vehicle::SensorSettings gps;
  gps.type = vehicle::SensorType::position;
  gps.latency_s = 0.15;
  EXPECT_EQ(with_sensor_noise(EstimatorSettings{}, {gps}).fix_delay_s, 0.15);
  EstimatorSettings given;
  given.fix_delay_s = 0.0;
  EXPECT_EQ(with_sensor_noise(given, {gps}).fix_delay_s, 0.0);
  EXPECT_FALSE(parse_vehicle_control("estimator: {}\n", "v.yaml").estimator.fix_delay_s);
}

TEST(ControlConfig, ReactiveKeysAreRead) {
  const SchedulerConfig s = parse_scheduler_config(R"(
mode: reactive
rate_hz: 500
reactive:
  p_run: 0.4
  boot_s: 10
  boot_rate_hz: 200
  failsafe_s: 0.05
  failsafe_mode: periodic
  delta_reference: last_sample
  trigger_signal: raw
  setpoint_forces_execution: false
  accumulation: {min_rate_hz: 0, max_wait_s: 0.004}
  fit: {method: mle, bins: 10, min_per_bin: 5, refit_period_s: 2, feedback: all, dataset_capacity: 100}
  initial_models: {gyro: [-3, 2], baro: [-1, 0.5]}
  oracle: true
  graph_execution: partial
run: {max_time_s: 600}
)",
                                                   "s.yaml");
  const ReactiveSettings& r = s.reactive;
  EXPECT_EQ(s.mode, SchedulerMode::reactive);
  EXPECT_EQ(s.rate_hz, 500);
  EXPECT_EQ(r.p_run, 0.4);
  EXPECT_EQ(r.boot_s, 10);
  EXPECT_EQ(r.boot_rate_hz, 200);
  EXPECT_EQ(r.failsafe_s, 0.05);
  EXPECT_EQ(r.failsafe_mode, FailsafeMode::periodic);
  EXPECT_EQ(r.delta_reference, DeltaReference::last_sample);
  EXPECT_EQ(r.trigger_signal, TriggerSignal::raw);
  EXPECT_FALSE(r.setpoint_forces_execution);
  EXPECT_EQ(r.accumulation_min_rate_hz, 0);
  EXPECT_EQ(r.accumulation_max_wait_s, 0.004);
  EXPECT_EQ(r.fit_method, FitMethod::mle);
  EXPECT_EQ(r.fit_bins, 10);
  EXPECT_EQ(r.fit_min_per_bin, 5);
  EXPECT_EQ(r.fit_refit_period_s, 2);
  EXPECT_EQ(r.fit_feedback, FeedbackRule::all);
  EXPECT_EQ(r.fit_dataset_capacity, 100);
  ASSERT_EQ(r.initial_models.size(), 2u);
  EXPECT_EQ(r.initial_models[0].sensor, "gyro");
  EXPECT_EQ(r.initial_models[0].beta1, -3);
  EXPECT_EQ(r.initial_models[1].beta2, 0.5);
  EXPECT_TRUE(r.oracle);
  EXPECT_EQ(r.graph_execution, GraphExecution::partial);
  EXPECT_EQ(s.run.max_time_s, 600);
}

TEST(ControlConfig, BadInputIsOneSentenceNamingTheKey) {
  struct Case {
    const char* text;
    const char* fragment;
  };
  const Case scheduler_cases[] = {
      {"rate_hz: 400\n", "'mode' (time_triggered or reactive) is required"},
      {"mode: sometimes\n", "line 1: mode must be one of time_triggered, reactive"},
      {"mode: time_triggered\nrate_hz: 300\n", "rate_hz must divide a second into a whole"},
      {"mode: time_triggered\nrate: 400\n", "unknown key 'rate'"},
      {"mode: reactive\nreactive: {p_run: 1}\n", "reactive.p_run must lie in (0, 1)"},
      {"mode: reactive\nreactive: {graph_execution: half}\n",
       "reactive.graph_execution must be one of whole, partial"},
      {"mode: reactive\nreactive: {boot_s: 700}\nrun: {max_time_s: 600}\n",
       "boot_s must be below run.max_time_s"},
      {"mode: reactive\nreactive: {boot_s: 0}\n", "boot_s 0 needs initial_models"},
      {"mode: time_triggered\nrun: {max_time_s: 90000}\n", "run.max_time_s must be in"},
      {"mode: time_triggered\nrun: {max_step_s: 0.003}\n", "run.max_step_s must be in"},
      {"mode: reactive\nreactive: {initial_models: {gyro: [1]}}\n", "must be [beta1, beta2]"},
      {"mode: reactive\nreactive: {fit: {bins: 2.5}}\n", "reactive.fit.bins must be a whole"},
      {"mode: [", "s.yaml: line"},
  };
  for (const Case& c : scheduler_cases)
    EXPECT_NE(error_of([&] { parse_scheduler_config(c.text, "s.yaml"); }).find(c.fragment),
              std::string::npos)
        << c.text << " → " << error_of([&] { parse_scheduler_config(c.text, "s.yaml"); });
  const Case vehicle_cases[] = {
      {"wheels: 4\n", "unknown key 'wheels'"},
      {"controller: {velocity_xy: {p: -1}}\n", "controller.velocity_xy.p must be in"},
      {"controller: {attitude_p: [1, 2]}\n", "controller.attitude_p must be a list of 3"},
      {"controller: {limits: {max_tilt_deg: 30, crash_tilt_deg: 20}}\n",
       "crash_tilt_deg must exceed max_tilt_deg"},
      {"controller: {rate: {rol: {}}}\n", "unknown key 'controller.rate.rol'"},
      {"estimator: {type: kalman}\n", "estimator.type must be one of complementary, truth"},
      {"estimator: {fix_delay_s: 1.5}\n", "estimator.fix_delay_s must be in"},
      {"estimator: {fix_delay_s: -0.1}\n", "estimator.fix_delay_s must be in"},
      {"computer: {control_cycles: 1.5}\n", "computer.control_cycles must be a whole number"},
      {"computer: {idle_w: 1, active_w: 0.5}\n", "active_w must be at least idle_w"},
      {"computer: {background: 3}\n", "computer.background must be a list"},
      {"computer: {background: [{name: a, rate_hz: 0}]}\n",
       "computer.background[0].rate_hz must be in"},
      {"controller: {position_p: 1, position_p: 2}\n", "'position_p' is given twice"},
  };
  for (const Case& c : vehicle_cases)
    EXPECT_NE(error_of([&] { parse_vehicle_control(c.text, "v.yaml"); }).find(c.fragment),
              std::string::npos)
        << c.text << " → " << error_of([&] { parse_vehicle_control(c.text, "v.yaml"); });
}

}  // namespace
}  // namespace swath::control
