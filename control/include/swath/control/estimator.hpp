#pragma once
// The estimator of the control task (docs/swath-control.md): Mahony's complementary filter for
// the attitude, driven by the gyro's accumulated Δθ and corrected towards the accelerometer's
// gravity and the magnetometer's north; and one Kalman filter per world axis for position and
// velocity, predicted with the accelerometer's Δv (rotated to world, gravity removed) and updated
// with the position fix, its velocity and the barometric altitude. The accelerometer's gravity
// reference has the kinematic acceleration of the velocity fixes taken out first (as PX4's
// attitude_estimator_q does), so that a sustained manoeuvre does not tilt the estimate. `truth`
// hands the simulation's state through, for tests of everything after step 1.
//
// Frames: world ENU (x east, y north, z up), body FLU; the attitude maps body to world.

#include <array>
#include <deque>
#include <optional>

#include "swath/vehicle/clock.hpp"
#include "swath/vehicle/vec3.hpp"

namespace swath::control {

using vehicle::Quat;
using vehicle::SimTime;
using vehicle::Vec3;

/// What the inertial driver accumulated since the previous execution (docs/swath-control.md, 'The
/// simulated multirotor'), so that skipped executions lose no inertial data.
struct ImuDelta {
  Vec3 delta_angle_rad;     ///< ∫ω dt, body FLU, rad (coning ignored)
  Vec3 delta_velocity_m_s;  ///< ∫ specific force dt, body FLU, m/s (+g·dt up when at rest)
  double interval_s = 0;    ///< the span of the integrals, s, ≥ 0 (0: no inertial data)
};

/// The latest magnetometer sample, normalised Earth field in body FLU (north and down-dip: its
/// horizontal part is taken as north, +y world).
struct MagReading {
  Vec3 field_body;     ///< unit field, body FLU, any scale > 0 (only its direction is used)
  bool fresh = false;  ///< a sample arrived since the previous execution
};

/// The latest barometric altitude.
struct BaroReading {
  double altitude_m = 0;  ///< above the world origin, m (world z)
  bool fresh = false;
};

/// The latest position fix (GPS or vision) with its velocity.
struct PositionFix {
  Vec3 position_m;    ///< world ENU, m
  Vec3 velocity_m_s;  ///< world ENU, m/s
  bool position_fresh = false;
  bool velocity_fresh = false;
  /// From the fix's arrival to this execution, s, ≥ 0 (the driver's timestamps); added to the
  /// receiver's latency (EstimatorSettings::fix_delay_s) to place the fix in the past.
  double waited_s = 0;
};

/// The simulation's true state, used by `EstimatorType::truth` only.
struct TruthState {
  Vec3 position_m;       ///< world ENU, m
  Vec3 velocity_m_s;     ///< world ENU, m/s
  Quat attitude;         ///< body FLU → world ENU, unit
  Vec3 body_rate_rad_s;  ///< body FLU, rad/s
};

/// The inputs of one execution as the estimator needs them.
struct EstimatorInput {
  ImuDelta imu;
  MagReading mag;
  BaroReading baro;
  PositionFix fix;
  TruthState truth;  ///< read only in truth mode
};

enum class EstimatorType { complementary, truth };

/// `estimator.*` (docs/swath-control.md, 'Vehicle, scheduler and environment files'), plus the
/// measurement noise the Kalman filter assumes (the caller takes it from the sensor descriptions).
struct EstimatorSettings {
  EstimatorType type = EstimatorType::complementary;
  double attitude_gain_1_s = 0.5;  ///< Mahony k_P on the accelerometer's gravity error, 1/s, ≥ 0
  double mag_gain_1_s = 0.2;       ///< k_P on the magnetometer's heading error, 1/s, ≥ 0
  /// Gyro-bias integrator ḃ = −bias_gain · correction, 1/s, ≥ 0; learnt only while the attitude
  /// error is below about 0.05 rad (a start-up error would teach it a bias that is not there).
  double bias_gain_1_s = 0.01;
  /// √q̃, the spectral density of the white acceleration the KF assumes, m/s²/√Hz (its velocity
  /// random walk, m/s/√s), > 0. It stands for what the predicted Δv gets wrong: the
  /// accelerometer's own noise (quad-f450: 0.3 m/s² at 1 kHz, 0.0095 m/s²/√Hz), vibration and
  /// gravity leaking through the attitude error (0.5° of tilt: 0.09 m/s², slowly varying). 0.025
  /// is the filter the old per-execution model (σ = 0.5 m/s² per execution) gave at 400 Hz,
  /// 0.5² / 400 = 6.25e-4 m²/s³, now at every rate: 2.6 times the accelerometer's white noise.
  double process_accel_m_s2_per_sqrt_hz = 0.025;
  double position_noise_m = 0.1;    ///< σ of one position fix, m, > 0
  double velocity_noise_m_s = 0.1;  ///< σ of one velocity fix, m/s, > 0
  double baro_noise_m = 0.1;        ///< σ of one barometric altitude, m, > 0
  /// `estimator.fix_delay_s`: how long before its arrival a position fix was measured, s, [0, 1];
  /// the Kalman filter fuses it against its state at that time and re-propagates to now. Unset:
  /// the position sensor's `latency_s` (with_sensor_noise); 0 fuses a fix as if measured now.
  std::optional<double> fix_delay_s;
  double gravity_m_s2 = 9.80665;  ///< removed from the rotated Δv, m/s²
  /// The accelerometer corrects the attitude only while |specific force| / g lies within this
  /// factor of 1 (a hard manoeuvre tells nothing about where "up" is). (0, 1].
  double accel_gate = 0.5;
};

/// One world axis: position and velocity with their covariance.
struct AxisFilter {
  double position_m = 0;
  double velocity_m_s = 0;
  double p_pp = 1, p_pv = 0, p_vv = 1;  ///< covariance, m², m²/s, m²/s²
  friend bool operator==(const AxisFilter&, const AxisFilter&) = default;
};

/// Predicts `axis` over `dt_s` (≥ 0) under acceleration `accel_m_s2`, with the continuous white
/// noise acceleration model of density `accel_density` (m/s²/√Hz): Q = q̃ [dt³/3, dt²/2; dt²/2,
/// dt], q̃ = accel_density², so that the filter is the same at every execution rate.
void kalman_predict(AxisFilter& axis, double accel_m_s2, double dt_s, double accel_density);
/// Updates with a position measurement `z_m` of standard deviation `sigma_m` (> 0); Joseph form.
void kalman_update_position(AxisFilter& axis, double z_m, double sigma_m);
/// Updates with a velocity measurement `z_m_s` of standard deviation `sigma_m_s` (> 0).
void kalman_update_velocity(AxisFilter& axis, double z_m_s, double sigma_m_s);

/// One execution's step of the position/velocity filters, kept for fusing delayed fixes.
struct FilterStep {
  double dt_s = 0;                     ///< the prediction's interval, s
  std::array<double, 3> accel_m_s2{};  ///< world x, y, z, m/s²
  double baro_m = 0;                   ///< the barometric altitude fused after it, when `baro`
  bool baro = false;
  std::array<AxisFilter, 3> before{};  ///< the filters before the step
  friend bool operator==(const FilterStep&, const FilterStep&) = default;
};

/// The estimate: a copyable value, part of the task state.
struct EstimatorState {
  Quat attitude;                     ///< body FLU → world ENU, unit
  Vec3 gyro_bias_rad_s;              ///< subtracted from the gyro, body FLU, rad/s
  Vec3 body_rate_rad_s;              ///< the latest bias-corrected rate, body FLU, rad/s
  std::array<AxisFilter, 3> axes{};  ///< world x (east), y (north), z (up)
  /// The kinematic acceleration from the last two velocity fixes, world ENU, m/s²: subtracted
  /// from the accelerometer before it corrects the attitude (PX4's attitude_estimator_q), so that
  /// a sustained manoeuvre is not mistaken for a tilt.
  Vec3 fix_acceleration_m_s2;
  Vec3 last_fix_velocity_m_s;  ///< world ENU, m/s
  double since_fix_s = 0;      ///< inertial time since that fix, s
  /// Inertial time since a magnetometer sample last corrected the heading, s: the next sample's
  /// correction stands for this long, so that the heading gain is per second at every rate.
  double since_heading_s = 0;
  bool has_fix_velocity = false;
  /// The filters' last steps covering at least fix_delay_s + 0.1 s, oldest first (empty when
  /// fixes are fused as they arrive), and their total interval, s.
  std::deque<FilterStep> history;
  double history_s = 0;
  friend bool operator==(const EstimatorState&, const EstimatorState&) = default;

  Vec3 position_m() const { return {axes[0].position_m, axes[1].position_m, axes[2].position_m}; }
  Vec3 velocity_m_s() const {
    return {axes[0].velocity_m_s, axes[1].velocity_m_s, axes[2].velocity_m_s};
  }
};

/// A start at a known place and attitude, at rest, with standard deviations `position_sigma_m`
/// and `velocity_sigma_m_s` (> 0).
EstimatorState initial_estimate(const Vec3& position_m, const Quat& attitude,
                                double position_sigma_m = 0.5, double velocity_sigma_m_s = 0.2);

/// One execution's estimator step (the control task's step 1: control_task.hpp).
void estimator_update(const EstimatorSettings& settings, EstimatorState& state,
                      const EstimatorInput& input);

}  // namespace swath::control
