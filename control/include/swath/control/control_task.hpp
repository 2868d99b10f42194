#pragma once
// The control task (docs/swath-control.md): one execution, identical in every scheduling
// mode, in seven steps — estimator; position P → velocity setpoint; velocity PID → tilt-limited
// acceleration → collective thrust and desired attitude; quaternion attitude P → rate setpoint;
// rate PID → angular acceleration → torque J ⊙ u; mixer A⁺[T; τ]; quantised PWM. The task's
// memory is a copyable value (TaskState), so a copy can be run on other inputs (part 2's oracle)
// without touching the original.

#include <array>
#include <cstddef>
#include <optional>

#include "swath/control/estimator.hpp"
#include "swath/control/mixer.hpp"
#include "swath/control/pid.hpp"
#include "swath/control/setpoints.hpp"

namespace swath::control {

/// `controller.limits` (docs/swath-control.md, 'Vehicle, scheduler and environment files').
struct ControlLimits {
  double max_speed_m_s = 3.0;        ///< horizontal velocity setpoint, m/s, > 0
  double max_climb_m_s = 1.5;        ///< vertical velocity setpoint, m/s, > 0
  double max_accel_m_s2 = 1.0;       ///< the carrot's acceleration (setpoints), m/s², > 0
  double max_tilt_deg = 30.0;        ///< tilt of the thrust vector from up, degrees, (0, 80]
  Vec3 max_rate_dps{220, 220, 120};  ///< |rate setpoint| per body axis, °/s, > 0
  double crash_tilt_deg = 80.0;      ///< the simulation declares lost control above it, degrees
  double yaw_slew_dps = 45.0;        ///< the heading turns to a new leg's at this rate, °/s, ≥ 0
};

/// Whether Δt is measured since the previous execution or taken as 1 / nominal rate.
enum class DtMode { measured, nominal };

/// `controller.*` (docs/swath-control.md, 'Vehicle, scheduler and environment files').
struct ControllerGains {
  double position_p_1_s = 1.0;                    ///< velocity setpoint per metre, 1/s, ≥ 0
  PidGains velocity_xy{2.0, 0.5, 0.0, 2.0, 5.0};  ///< m/s → m/s² (1/s, 1/s², 1, m/s², Hz)
  PidGains velocity_z{4.0, 1.0, 0.0, 3.0, 5.0};   ///< the same for the vertical
  Vec3 attitude_p_1_s{8, 8, 4};                   ///< rate setpoint per radian, 1/s, ≥ 0
  PidGains rate_roll{40, 20, 0.5, 5, 30};  ///< rad/s → rad/s² (1/s, 1/s², 1, rad/s², Hz)
  PidGains rate_pitch{40, 20, 0.5, 5, 30};
  PidGains rate_yaw{20, 5, 0, 2, 0};
  ControlLimits limits;
  DtMode dt_mode = DtMode::measured;
  double change_threshold_us = 1.0;  ///< "output changed": some PWM moved by ≥ this, µs, > 0
};

/// The airframe as the controller believes it to be.
struct ControlAirframe {
  double mass_kg = 1.5;                     ///< > 0
  Vec3 inertia_kg_m2{0.015, 0.015, 0.027};  ///< principal, body FLU, kg m², > 0
  double gravity_m_s2 = 9.80665;            ///< > 0
  MixerRotors rotors = standard_layout(vehicle::RotorLayout::quad_x, 0.225);
};

/// Everything fixed about the task.
struct ControlTaskConfig {
  ControllerGains gains;
  EstimatorSettings estimator;
  ControlAirframe airframe;
  double nominal_rate_hz = 400.0;  ///< Δt of the first execution and of dt_mode nominal, Hz, > 0
};

/// The snapshot one execution reads (taken when it starts).
struct TaskInput {
  SimTime time_ns = 0;  ///< when the execution starts
  EstimatorInput sensors;
  Setpoint setpoint;
  /// Added to the rate loop's torque before mixing, body FLU, N m: the injection point of step,
  /// sine or chirp tests of the rate loop (loop_response.hpp); 0 in flight.
  Vec3 torque_injection_nm;
  /// A rotation vector in body axes composed onto step 3's attitude setpoint, rad: the injection
  /// point of step tests of the attitude loop (swath-control response); 0 in flight.
  Vec3 attitude_injection_rad;
};

/// The task's memory: a copyable value.
struct TaskState {
  EstimatorState estimate;
  std::array<PidState, 3> velocity_pid{};   ///< world x, y, z
  std::array<PidState, 3> rate_pid{};       ///< body roll, pitch, yaw
  std::array<double, kMaxRotors> pwm_us{};  ///< the previous execution's pulses, µs
  SimTime last_time_ns = 0;
  bool has_run = false;
  friend bool operator==(const TaskState&, const TaskState&) = default;
};

/// What one execution decided, with the intermediate values for logs and tests.
struct ExecutionOutput {
  std::array<double, kMaxRotors> pwm_us{};  ///< per rotor, µs, quantised
  std::size_t rotor_count = 0;
  bool changed = false;        ///< some pulse moved by ≥ change_threshold_us (first: true)
  double dt_s = 0;             ///< the Δt the loops used, s
  Vec3 velocity_setpoint_m_s;  ///< step 2, world ENU
  Vec3 acceleration_m_s2;      ///< step 3, world ENU, tilt-limited
  Quat attitude_setpoint;      ///< step 3, body FLU → world ENU
  Vec3 rate_setpoint_rad_s;    ///< step 4, body FLU
  Wrench request;              ///< step 5: collective and torque J ⊙ u, injection included
  Vec3 controller_torque_nm;   ///< step 5's torque J ⊙ u before the injection, body FLU
  MixerOutput mix;             ///< step 6–7
};

/// The control task of one vehicle.
class ControlTask {
 public:
  /// The task, or nullopt when the rotor layout cannot be mixed (count outside [4, 8], a
  /// coefficient not positive, rank < 4).
  static std::optional<ControlTask> create(const ControlTaskConfig& config);

  /// A state at rest at `position_m` with `attitude`, pulses at pwm_min.
  TaskState initial_state(const Vec3& position_m, const Quat& attitude = {}) const;

  /// One execution (the seven steps above).
  /// Deterministic: the same state and input give the same output and state.
  ExecutionOutput execute(TaskState& state, const TaskInput& input) const;

  const ControlTaskConfig& config() const { return config_; }
  const MixerMatrices& matrices() const { return matrices_; }

 private:
  ControlTask(const ControlTaskConfig& config, const MixerMatrices& m)
      : config_(config), matrices_(m) {}
  ControlTaskConfig config_;
  MixerMatrices matrices_;
};

/// The attitude that points body +z along `up_world` (any length > 0) with body +x's horizontal
/// part along the heading `yaw_rad` (counter-clockwise from east, rad).
Quat attitude_from_thrust_and_yaw(const Vec3& up_world, double yaw_rad);

}  // namespace swath::control
