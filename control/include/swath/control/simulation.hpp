#pragma once
// A simulated flight (docs/swath-control.md): the plant (vehicle::FlightModel: the multirotor, its
// ESCs, wind and sensors) and the flight computer running the control task when the scheduler
// releases it, on one integer-nanosecond clock, with the battery fed by motors + CPU + avionics
// (paper 004 eq. 12, energy::Battery). The parts are composed in simulation.cpp as named steps:
// the sensor driver, the computer's events (an execution reads its snapshot when it starts and
// its pulses reach the ESCs when it ends), the battery, the metrics and the recorder.
//
// Deterministic: the same settings and seed give the same rows and summary, bit for bit.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "swath/control/computer.hpp"
#include "swath/control/config.hpp"
#include "swath/control/control_task.hpp"
#include "swath/control/mission.hpp"
#include "swath/control/setpoints.hpp"
#include "swath/energy/battery.hpp"
#include "swath/vehicle/drone.hpp"
#include "swath/vehicle/flight_model.hpp"

namespace swath::control {

/// A flight's settings. The drone it flies is one vehicle::Drone, as planning, energy and fleet see
/// a drone (drone()): its name is the airframe's, its cruise speed `speed_m_s`, its climb and
/// descent the controller's max_climb_m_s and its acceleration the carrot's max_accel_m_s2. Each
/// figure is held once, where the vehicle file and the command line put it; drone() composes
/// them. Beside it, what only a rigid-body flight needs: the physics (airframe, ESCs, sensors),
/// the environment, the control task and scheduler, the battery (docs/architecture.md).
struct SimulationSettings {
  vehicle::VehiclePhysics physics = vehicle::default_vehicle();
  vehicle::Environment environment;
  std::uint64_t seed = 1;
  VehicleControlConfig control;  ///< estimator, controller, computer of the vehicle file
  SchedulerConfig scheduler;     ///< mode, rate and run settings
  energy::Battery battery;       ///< paper 004 eq. 12; reserve_soc ends a --loop flight
  FlightMission mission;         ///< already closed for loop when `loop`
  double speed_m_s = 3.0;        ///< the carrot's cruise speed along the legs, m/s, > 0
  bool loop = false;             ///< repeat the mission until the reserve (paper 002 §7)

  /// The drone this flight flies: the carrot takes its speed, climb and acceleration from it.
  vehicle::Drone drone() const;
};

/// How a flight ended (its status; docs/swath-control.md, opening section).
enum class FlightStatus {
  completed,        ///< the mission was flown to its end (without --loop)
  reserve_reached,  ///< --loop: flown until the state of charge reached the reserve
  battery_empty,    ///< the battery could not deliver the power before the end
  time_limit,       ///< run.max_time_s reached first
  lost_control,     ///< tilt beyond crash_tilt_deg, below the ground, or 50 m off for 5 s
};
const char* to_string(FlightStatus status);

/// One row of timeseries.csv (every run.output_interval_s). Angles in degrees: roll positive
/// right wing down, pitch positive nose up, yaw a compass heading (clockwise from north, [0, 360)).
struct TimeseriesRow {
  double t_s = 0;
  Vec3 position_m, velocity_m_s;                  ///< world ENU
  Vec3 attitude_deg, setpoint_deg, estimate_deg;  ///< roll, pitch, yaw
  Vec3 carrot_m;                                  ///< the setpoint's position, world ENU
  double cross_track_m = 0;
  Vec3 wind_m_s;  ///< at the body, world ENU
  std::size_t rotors = 0;
  std::array<double, vehicle::kMaxRotors> pwm_us{}, rotor_rad_s{};
  double motors_w = 0, cpu_w = 0, avionics_w = 0;  ///< means over the last interval
  double soc = 0;
  int executions_last_s = 0;  ///< executions that ended in the preceding second
};

/// One row of rate.csv (every whole second).
struct RateRow {
  int second = 0;  ///< the row covers [second − 1, second)
  int executions = 0;
  std::array<int, 5> by_cause{};  ///< indexed by ReleaseCause
  int unchanged = 0;
  std::vector<int> triggers;  ///< per trigger sensor (time-triggered: 0)
  double cpu_busy = 0;        ///< fraction of the second
  std::int64_t overruns = 0;
  double latency_mean_ms = 0;   ///< release to pulses out
  double attitude_rms_deg = 0;  ///< true vs setpoint, roll and pitch together
};

struct ErrorStat {
  double rms = 0, max = 0;
};

/// summary.json's figures (docs/formats.md, 'Outputs of swath-control and swath-fleet'); metrics
/// over [metrics_from_s, end].
struct SimulationSummary {
  FlightStatus status = FlightStatus::completed;
  std::string lost_control_reason;  ///< what was lost, when status is lost_control
  double flight_time_s = 0;
  std::optional<double> reserve_time_s;  ///< when the SoC reached the reserve
  double distance_m = 0;                 ///< flown, 3-D
  int laps = 0;                          ///< missions completed
  double metrics_from_s = 0;
  std::array<ErrorStat, 3> attitude_error_deg{};            ///< roll, pitch, yaw: setpoint − true
  std::array<ErrorStat, 3> attitude_error_estimated_deg{};  ///< setpoint − estimate (the paper's)
  /// Setpoint − true, roll, pitch, yaw, over the samples when nothing was commanded: the carrot
  /// at constant velocity and the heading not slewing for the last second (what the disturbances
  /// and the sensors' noise cause, without the transients of commanded turns and stops).
  std::array<ErrorStat, 3> attitude_error_disturbance_deg{};
  double disturbance_share = 0;  ///< the share of the metrics' samples that counted for it
  double max_tilt_deg = 0;
  ErrorStat cross_track_m, position_error_m;  ///< to the path; to the carrot (3-D)
  struct Executions {
    std::int64_t total = 0;
    std::array<std::int64_t, 5> by_cause{};
    double per_second_mean = 0, per_second_p5 = 0, per_second_p95 = 0, per_second_max = 0;
    double share_seconds_above_rate = 0;  ///< seconds with more executions than rate_hz
    double unchanged_fraction = 0;
    double latency_mean_ms = 0, latency_p95_ms = 0, latency_max_ms = 0;
    std::int64_t overruns = 0;
  } executions;
  struct Trigger {
    std::string sensor;
    std::int64_t samples = 0, triggers = 0, refits = 0;
    double beta1 = 0, beta2 = 0;  ///< the model in force at the end (reactive)
    double threshold = 0;         ///< x* in force at the end (+∞: never triggers)
    std::size_t dataset = 0;      ///< points of the last fit
  };
  std::vector<Trigger> triggers;  ///< per trigger sensor
  bool reactive = false;
  /// Reactive: feedback figures (docs/swath-control.md, 'Reactive control and paper 002's
  /// experiment'); shares are of single-trigger executions.
  struct Feedback {
    std::int64_t false_positives = 0, false_negatives = 0, multi_cause_excluded = 0;
    double fp_share_after_boot = 0, fp_share_steady = 0;
  } feedback;
  /// Reactive with `oracle: true`: every trigger-sensor sample after the boot, whether it fired
  /// against whether the task, run on the last snapshot with that sample, would have changed
  /// its output (the true label by the paper's own definition of a trigger).
  struct Oracle {
    std::int64_t tp = 0, fp = 0, tn = 0, fn = 0;
  };
  std::optional<Oracle> oracle;
  double cpu_utilisation = 0, cpu_energy_per_execution_mj = 0;
  std::int64_t background_completed = 0;
  std::int64_t background_released = 0;  ///< background releases (completed + skipped + pending)
  std::int64_t background_skipped = 0;   ///< releases that found their previous job unfinished
  double background_latency_mean_ms = 0, background_latency_max_ms = 0;  ///< release → done
  double total_j = 0, motors_j = 0, cpu_j = 0, avionics_j = 0, mean_power_w = 0, final_soc = 0;
  /// |Σ (V I − R I²) V/V~ dt − E| / E: the battery's integrated current against the energy
  /// drawn (eq. 12 solved for I must give back the power).
  double balance_residual = 0;
  /// For a swath plan (the mission has an area): the horizontal track outside the area's outer
  /// ring and inside no-fly zones, m; the least horizontal distance to a no-fly zone (negative:
  /// depth inside one), m.
  bool checked_against_plan = false;
  double outside_area_m = 0, inside_no_fly_m = 0;
  std::optional<double> min_clearance_m;
};

/// Receives what a flight produces as it happens; every method optional.
/// One execution (executions.csv, `--log-executions`).
struct ExecutionRow {
  double request_s = 0, start_s = 0, end_s = 0;
  ReleaseCause cause = ReleaseCause::time_triggered;  ///< the first cause of its request
  std::string sensors;  ///< reactive: the trigger sensors that caused it, '+'-joined
  bool changed = false;
  bool false_positive = false;  ///< one sensor's trigger, output unchanged (the paper's rule)
  bool false_negative = false;  ///< failsafe alone, output changed
  std::vector<double> x;        ///< reactive: each trigger sensor's change at the start
  unsigned causes =
      0;  ///< reactive: every cause, bits 1 tt, 2 boot, 4 trigger, 8 failsafe, 16 setpoint
  std::int64_t cycles = 0;  ///< what the computer was charged for it (graph_execution)
};

/// One sensor's model after a refit (fits.csv).
struct FitRow {
  double t_s = 0;  ///< when the refit finished (its models apply from then)
  std::string sensor;
  std::size_t points = 0;
  double beta1 = 0, beta2 = 0;
  double threshold = 0;  ///< x* (+∞: never)
};

class SimulationObserver {
 public:
  virtual ~SimulationObserver() = default;
  virtual void on_row(const TimeseriesRow& /*row*/) {}
  virtual void on_second(const RateRow& /*row*/) {}
  /// Every execution as it ends.
  virtual void on_execution(const ExecutionRow& /*row*/) {}
  /// Every trigger (reactive): when, and the trigger sensor's index in trigger_sensor_names().
  virtual void on_trigger(double /*t_s*/, std::size_t /*trigger_sensor*/) {}
  /// Every sensor's model after each refit (reactive).
  virtual void on_fit(const FitRow& /*row*/) {}
  /// About every simulated second: the fraction of the expected flight done, [0, 1].
  virtual void on_progress(double /*fraction*/) {}
};

/// The names of the vehicle's trigger sensors, in file order (rate.csv's triggers_<name>).
std::vector<std::string> trigger_sensor_names(const vehicle::VehiclePhysics& physics);

/// Flies the mission. Throws base::InputError for settings that cannot fly (the scheduler's mode
/// is not available, the rotors cannot be mixed, the rotors cannot lift 1.2 × the weight, a
/// mission without two points) before anything is simulated; every outcome of the flight itself is
/// a status.
SimulationSummary simulate(const SimulationSettings& settings, SimulationObserver* observer);

}  // namespace swath::control
