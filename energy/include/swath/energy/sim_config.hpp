#pragma once
// Configuration of the flight simulation (docs/swath-energy.md) and of a drone for mission budgets.

#include <string>
#include <vector>

#include "swath/energy/battery.hpp"
#include "swath/energy/energy_estimator.hpp"
#include "swath/energy/flight.hpp"
#include "swath/energy/power_model.hpp"
#include "swath/geometry/point.hpp"
#include "swath/vehicle/drone.hpp"

namespace swath::energy {

/// A measured power signal to replay: rows "t_s, watts" (a header line is allowed), t increasing.
struct PowerTrace {
  std::vector<double> t_s, power_w;
  /// Linear interpolation; NaN outside the recorded span (no measurement).
  double at(double t) const;
};

PowerTrace parse_power_trace(const std::string& text, const std::string& source);

/// `swath-energy run --config`. Positions are local metres (x east, y north) like the plan's.
struct SimConfig {
  std::string source;
  double time_step_s = 0.01;       ///< (0, 1]
  double speed_m_s = 12.0;         ///< commanded ground speed, > 0
  double max_airspeed_m_s = 25.0;  ///< >= speed_m_s would be flown in calm air
  Wind wind;
  double trigger_radius_m = 5.0;   ///< > 0
  geometry::Point2 start;          ///< take-off point, local metres
  double max_time_s = 4 * 3600.0;  ///< the simulation gives up after this
  double stall_time_s = 300.0;     ///< no approach to the triggering point for this long: stall
  double output_interval_s = 0.1;  ///< rows of trajectory.csv and energy.csv, >= time_step_s
  std::vector<double> trajectory_parameters;   ///< c1.. at take-off (default: upper bounds)
  std::vector<double> computation_parameters;  ///< at take-off (default: upper bounds)
  std::vector<double> trajectory_gains_w;      ///< nu: W per unit of each c (eq. 8), default 0
  int fourier_order = 3;                       ///< r, 0..20
  double initial_period_s = 60.0;              ///< T before re-estimation, > 0
  bool estimate_period = true;  ///< re-estimate T each period from the measured signal
  KalmanSettings kalman;
  bool replan = true;                   ///< false: the parameters stay at their initial values
  double mpc_period_s = 1.0;            ///< the parameters are re-chosen this often, s (> 0)
  double mpc_horizon_s = 6.0;           ///< a raised choice is held at least this long, s (>= 0)
  double mpc_margin = 0.02;             ///< share of the available energy kept unused, [0, 0.5]
  std::vector<double> quality_weights;  ///< per computation (empty: all 1)
  Battery battery;
  PowerProfile power;
  std::string replay_csv;             ///< measured power to replay instead of the power model
  PowerTrace replay;                  ///< its contents (read with the config; empty: model)
  std::vector<std::string> warnings;  ///< from reading the file (old key spellings)
};

/// Parses the YAML configuration; `source` names it in errors. Unknown keys, wrong types and out
/// of range values throw base::InputError naming the file, the line and the key.
SimConfig parse_sim_config(const std::string& text, const std::string& source);
/// The `battery` section of a YAML mapping whose other keys belong to someone else (a vehicle
/// file of swath-control); the defaults when it has none. Keys and ranges as in a sim config.
Battery parse_battery_section(const std::string& text, const std::string& source);
SimConfig read_sim_config(const std::string& path);

/// A drone for `swath-energy budget`: how it flies a waypoint mission and what that costs.
struct DroneProfile {
  std::string source;
  /// The drone: name and speeds (`speed_m_s` absent: each leg at the mission's own speed).
  vehicle::Drone drone;
  Wind wind;
  Battery battery;
  PowerProfile power;
  std::vector<double> computation_parameters;  ///< one per power.computations entry
  std::vector<std::string> warnings;           ///< from reading the file (old key spellings)
};

DroneProfile parse_drone_profile(const std::string& text, const std::string& source);
DroneProfile read_drone_profile(const std::string& path);

}  // namespace swath::energy
