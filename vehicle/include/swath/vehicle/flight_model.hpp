#pragma once
// The plant of a simulated flight (docs/swath-control.md): the multirotor, its
// ESCs, the wind and the sensors on one integer-nanosecond event clock. Events at one instant run
// in a fixed order: ESC frames, wind, sensors (in file order); between events the body is
// integrated with RK4 in equal sub-steps of at most max_step_s with the inputs held. The
// controller (control/) reads the delivered sensor samples and commands PWM between calls.

#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "swath/vehicle/multirotor.hpp"
#include "swath/vehicle/sensors.hpp"
#include "swath/vehicle/vehicle_files.hpp"
#include "swath/vehicle/wind.hpp"

namespace swath::vehicle {

struct FlightModelSettings {
  VehiclePhysics physics = default_vehicle();
  Environment environment;
  std::uint64_t seed = 1;
  double max_step_s = 0.001;       ///< (1e-5, 0.002]
  double mission_speed_m_s = 3.0;  ///< Dryden's frozen-field speed V takes it into account
  MultirotorState initial;         ///< rotors at rest unless given
};

/// A sensor sample with the index of its sensor (in file order).
struct DeliveredSample {
  std::size_t sensor = 0;
  SensorSample sample;
};

class FlightModel {
 public:
  explicit FlightModel(const FlightModelSettings& settings);

  SimTime now() const { return now_; }
  const MultirotorState& state() const { return state_; }
  /// Replaces the body's state at now() (a caller's ground contact: control/ardupilot_json).
  void set_state(const MultirotorState& state) {
    state_ = state;
    power_known_ = false;
  }
  const VehiclePhysics& physics() const { return settings_.physics; }
  /// The wind at the body, world ENU (held since the last wind event).
  const Vec3& wind_m_s() const { return wind_; }

  /// The instant of the next ESC frame, wind update or sensor measurement (samples are delivered
  /// only at these instants).
  SimTime next_event() const;
  /// Runs every event up to and including `until` (>= now()).
  void advance_to(SimTime until);
  /// A PWM command for motor `motor` at now(); its ESC applies it at its next frame (with a frame
  /// rate of 0, at once: no frame events are scheduled).
  void command_pwm(std::size_t motor, double pwm_us);
  /// Events run so far (instants at which an ESC frame, wind update or sensor measurement fell):
  /// the simulation's work grows with this count, not with simulated time alone.
  long long events_run() const { return events_run_; }
  /// The samples delivered since the last call, in delivery order (ties in sensor order); valid
  /// until the next call.
  const std::vector<DeliveredSample>& take_samples();

  /// The battery's terminal voltage over the voltage at which the motors reach max_speed_rad_s
  /// (1 without voltage sag): the rotor speed a PWM gives is Ω_cmd × this, from now on.
  void set_supply_ratio(double ratio) {
    supply_ratio_ = ratio;
    power_known_ = false;
  }
  double supply_ratio() const { return supply_ratio_; }

  /// The motors' electrical energy drawn so far (trapezoid per sub-step), J.
  double motor_energy_j() const { return motor_energy_j_; }
  /// The motors' electrical power now, W.
  double motor_power_w() const;
  /// The specific force now (world acceleration without gravity), world ENU.
  Vec3 acceleration_m_s2() const;

 private:
  void integrate_to(SimTime t);
  void run_events(SimTime t);
  void update_wind(double t_s);
  MultirotorInputs inputs() const;

  FlightModelSettings settings_;
  SimTime now_ = 0;
  MultirotorState state_;
  std::vector<Esc> escs_;
  std::vector<double> rotor_commands_;
  std::vector<Sensor> sensors_;
  std::optional<DrydenTurbulence> turbulence_;
  Gusts gusts_;
  SplitMix64 torque_random_;
  SimTime wind_period_ns_;
  SimTime next_wind_ = 0;
  SimTime next_esc_frame_ = 0;
  bool esc_frames_ = true;  ///< false: frame rate 0, commands apply at once
  long long events_run_ = 0;
  Vec3 wind_, torque_noise_;
  double motor_energy_j_ = 0.0;
  double supply_ratio_ = 1.0;
  // motor_power_w() at the end of the last integration, while no input has changed since.
  double power_w_ = 0.0;
  bool power_known_ = false;
  std::array<double, kMaxRotors> drag_factors_{1, 1, 1, 1, 1, 1, 1, 1};
  std::vector<DeliveredSample> delivered_, taken_;
};

}  // namespace swath::vehicle
