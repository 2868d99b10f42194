#pragma once
// The files swath-energy writes. Numbers have fixed decimals: same input, same bytes.

#include <string>
#include <vector>

#include "swath/energy/budget.hpp"
#include "swath/energy/plan.hpp"
#include "swath/energy/sim_config.hpp"
#include "swath/energy/simulation.hpp"

namespace swath::energy {

/// t_s,x_m,y_m,stage,course_deg,ground_speed_m_s,airspeed_m_s,path_distance_m (stage 1-based,
/// course a compass bearing).
std::string trajectory_csv(const SimulationResult& result);

/// t_s,measured_w,model_w,soc,predicted_total_j,q0..q2r (measured empty where a replayed trace
/// has no value).
std::string energy_csv(const SimulationResult& result);

/// The two files above row by row, for streaming: the header (the energy file's names one
/// column per coefficient of `first`), then one row per sample, each ending in a newline.
std::string trajectory_csv_header();
std::string trajectory_csv_row(const FlightSample& sample);
std::string energy_csv_header(const FlightSample& first);
std::string energy_csv_row(const FlightSample& sample);

/// t_s,c1..,s1..,feasible: the parameters from each time on (at take-off and every change).
std::string control_csv(const SimulationResult& result);

/// completed, status, times, energy, final SoC, reserve, prediction errors, replanning (replans,
/// time-weighted mean parameters), stages, and, when given, the fixed highest / lowest comparison.
std::string simulation_summary_json(const SimulationResult& result, const Plan& plan,
                                    const SimConfig& config,
                                    const FixedComparison* comparison = nullptr);

/// Every drone's budget as JSON (lon/lat of the crossings).
std::string budget_json(const std::vector<DroneBudget>& budgets, const DroneProfile& drone);

/// drone,t_s,lon_deg,lat_deg,altitude_m,soc,energy_j: the timeline of every drone.
std::string budget_csv(const std::vector<DroneBudget>& budgets);

/// A short table for the terminal.
std::string budget_table(const std::vector<DroneBudget>& budgets, const DroneProfile& drone);

}  // namespace swath::energy
