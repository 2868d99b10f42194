#pragma once
// Readers of the control keys of docs/swath-control.md: the `estimator`, `controller` and
// `computer` sections of a vehicle file, and the scheduler file (`share/schedulers/*.yaml`). Every
// key is optional unless said otherwise, units are in the key names or documented there, and
// unknown keys, wrong types and out-of-range values are refused with base::InputError naming the
// file, the line and the key.

#include <string>
#include <vector>

#include "swath/control/computer.hpp"
#include "swath/control/control_task.hpp"

namespace swath::control {

/// The control sections of a vehicle file.
struct VehicleControlConfig {
  EstimatorSettings estimator;  ///< `estimator.*` (measurement noise is the sensors', not read)
  ControllerGains controller;   ///< `controller.*`
  ComputerSettings computer;    ///< `computer.*`
};

/// Reads `estimator`, `controller` and `computer` of a vehicle file (docs/swath-control.md,
/// 'Vehicle, scheduler and environment files'). The vehicle's other top-level keys (name, frame,
/// rotors, propeller, motor, esc, sensors, avionics_w, battery) are passed over here and checked by
/// the vehicle reader; any other top-level key is refused.
VehicleControlConfig parse_vehicle_control(const std::string& text, const std::string& source);
VehicleControlConfig read_vehicle_control(const std::string& path);

enum class SchedulerMode { time_triggered, reactive };
enum class FailsafeMode { watchdog, periodic };
enum class DeltaReference { last_execution, last_sample };
enum class TriggerSignal { filtered, raw };
enum class FitMethod { logit_ols, logit_wls, mle };
enum class FeedbackRule { errors, all, none };
/// What a reactive execution costs the flight computer: every node of the control graph (`whole`,
/// a plain C/C++ task) or only the nodes downstream of the inputs that triggered it (`partial`,
/// paper 002's RP-Embedded; scheduler.hpp's control_graph()).
enum class GraphExecution { whole, partial };

/// A trigger model given in the file: L(x) = 1 / (1 + e^−(β1 + β2 x)) for one sensor.
struct InitialModel {
  std::string sensor;
  double beta1 = 0, beta2 = 0;
};

/// `reactive.*` (docs/swath-control.md, 'Reactive control and paper 002's experiment'; used by part
/// 2's reactive scheduler).
struct ReactiveSettings {
  double p_run = 0.6;       ///< (0, 1)
  double boot_s = 30;       ///< T_boot, s, ≥ 0, < run.max_time_s
  double boot_rate_hz = 0;  ///< TT rate during the boot, Hz; 0: the file's rate_hz
  double failsafe_s = 0.1;  ///< T_failsafe, s, (0, 10]
  FailsafeMode failsafe_mode = FailsafeMode::watchdog;
  DeltaReference delta_reference = DeltaReference::last_execution;
  TriggerSignal trigger_signal = TriggerSignal::filtered;
  bool setpoint_forces_execution = true;
  double accumulation_min_rate_hz = 400;    ///< sensors at or above it set the hyperperiod; 0: all
  double accumulation_max_wait_s = 0.0025;  ///< cap on the wait for the hyperperiod, s, [0, 1]
  FitMethod fit_method = FitMethod::logit_ols;
  int fit_bins = 20;                ///< [2, 1000]
  int fit_min_per_bin = 25;         ///< [1, 1e6]
  double fit_refit_period_s = 1.0;  ///< s, (0, 3600]
  /// `all` (every outcome, for each sensor that triggered it), `errors` (paper 002's: false
  /// positives and negatives only, a baseline that ratchets x* upwards), `none` (boot fit only).
  FeedbackRule fit_feedback = FeedbackRule::all;
  int fit_dataset_capacity = 8192;           ///< points per sensor, [16, 1e7]
  std::vector<InitialModel> initial_models;  ///< required when boot_s is 0
  bool oracle = false;
  GraphExecution graph_execution = GraphExecution::whole;
};

/// `run.*`.
struct RunSettings {
  double metrics_from_s = 30;       ///< s, ≥ 0
  double output_interval_s = 0.02;  ///< s, (0, 3600]
  double max_time_s = 14'400;       ///< s, (0, 86,400]
  double setpoint_rate_hz = 50;     ///< Hz, (0, 1e4], a whole number of ns per period
  double max_step_s = 0.001;        ///< integration sub-step, s, (1e-5, 0.002]
};

/// A scheduler file.
struct SchedulerConfig {
  SchedulerMode mode = SchedulerMode::time_triggered;  ///< `mode`, required
  double rate_hz = 400;  ///< TT rate, Hz, (0, 1e5], a whole number of ns per period
  ReactiveSettings reactive;
  RunSettings run;
};

/// One `--set KEY=VALUE`: a dotted key into a YAML file ("controller.position_p",
/// "run.max_time_s", "mean_wind.speed_m_s") and its value as YAML text ("1.2", "[8, 8, 4]").
struct Override {
  std::string key, value;
};

/// `text` (a YAML mapping) with `overrides` applied, as YAML text: each key's mappings are created
/// when absent; the value replaces what was there. The file's own reader then checks every key,
/// so a misspelt key is refused as in the file. Throws base::InputError naming `source` and the
/// override when the value is not YAML or a key runs into a value that is not a mapping.
std::string apply_overrides(const std::string& text, const std::string& source,
                            const std::vector<Override>& overrides);

SchedulerConfig parse_scheduler_config(const std::string& text, const std::string& source);
SchedulerConfig read_scheduler_config(const std::string& path);

}  // namespace swath::control
