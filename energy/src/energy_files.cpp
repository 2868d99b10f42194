#include "swath/energy/energy_files.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"

namespace swath::energy {
namespace {

using base::fixed_text;
using base::round_to;
using nlohmann::ordered_json;

void cell(std::string& row, double v, int decimals) {
  if (!row.empty() && row.back() != '\n') row += ',';
  if (std::isfinite(v)) row += fixed_text(v, decimals);
}

ordered_json optional_point(const std::optional<BudgetPoint>& p) {
  if (!p) return nullptr;
  return {{"t_s", round_to(p->t_s, 2)},
          {"lon_deg", round_to(p->geo.lon_deg, 9)},
          {"lat_deg", round_to(p->geo.lat_deg, 9)},
          {"altitude_m", round_to(p->altitude_m, 2)},
          {"energy_j", round_to(p->energy_j, 1)}};
}

}  // namespace

std::string trajectory_csv_header() {
  return "t_s,x_m,y_m,stage,course_deg,ground_speed_m_s,airspeed_m_s,path_distance_m\n";
}

std::string trajectory_csv_row(const FlightSample& s) {
  std::string out;
  cell(out, s.t_s, 3);
  cell(out, s.position.x, 3);
  cell(out, s.position.y, 3);
  out += ',' + std::to_string(s.stage + 1);
  cell(out, s.course_deg, 2);
  cell(out, s.ground_speed_m_s, 3);
  cell(out, s.airspeed_m_s, 3);
  cell(out, s.path_distance_m, 3);
  out += '\n';
  return out;
}

std::string trajectory_csv(const SimulationResult& result) {
  std::string out = trajectory_csv_header();
  for (const FlightSample& s : result.samples) out += trajectory_csv_row(s);
  return out;
}

std::string energy_csv_header(const FlightSample& first) {
  std::string out = "t_s,measured_w,model_w,soc,predicted_total_j";
  for (std::size_t i = 0; i < first.coefficients.size(); ++i) out += ",q" + std::to_string(i);
  return out + '\n';
}

std::string energy_csv_row(const FlightSample& s) {
  std::string out;
  cell(out, s.t_s, 3);
  out += ',';
  if (std::isfinite(s.measured_w)) out += fixed_text(s.measured_w, 3);
  cell(out, s.model_w, 3);
  cell(out, s.soc, 6);
  cell(out, s.predicted_total_j, 1);
  for (double q : s.coefficients) cell(out, q, 3);
  out += '\n';
  return out;
}

std::string energy_csv(const SimulationResult& result) {
  std::string out =
      energy_csv_header(result.samples.empty() ? FlightSample{} : result.samples.front());
  for (const FlightSample& s : result.samples) out += energy_csv_row(s);
  return out;
}

std::string control_csv(const SimulationResult& result) {
  std::string out = "t_s";
  const std::size_t nt = result.control.empty() ? 0 : result.control.front().trajectory.size();
  const std::size_t nc = result.control.empty() ? 0 : result.control.front().computations.size();
  for (std::size_t i = 0; i < nt; ++i) out += ",c" + std::to_string(i + 1);
  for (std::size_t j = 0; j < nc; ++j) out += ",s" + std::to_string(j + 1);
  out += ",feasible\n";
  for (const ControlSample& c : result.control) {
    cell(out, c.t_s, 3);
    for (double v : c.trajectory) cell(out, v, 4);
    for (double v : c.computations) cell(out, v, 4);
    out += c.feasible ? ",true\n" : ",false\n";
  }
  return out;
}

namespace {

ordered_json rounded(const std::vector<double>& values, int decimals) {
  ordered_json out = ordered_json::array();
  for (double v : values) out.push_back(round_to(v, decimals));
  return out;
}

ordered_json fixed_run(const SimulationResult& r) {
  return {{"completed", r.status == SimulationEnd::completed},
          {"status", to_string(r.status)},
          {"flight_time_s", round_to(r.flight_time_s, 2)},
          {"final_soc", round_to(r.final_soc, 6)},
          {"mean_power_w", round_to(r.mean_power_w, 3)},
          {"computations", rounded(r.mean_computations, 4)}};
}

}  // namespace

std::string simulation_summary_json(const SimulationResult& r, const Plan& plan,
                                    const SimConfig& config, const FixedComparison* comparison) {
  ordered_json stages = ordered_json::array();
  for (const StageEntry& e : r.stages)
    stages.push_back({{"stage", e.stage + 1},
                      {"line", plan.stages[e.stage].line},
                      {"entered_s", round_to(e.t_s, 2)},
                      {"x_m", round_to(e.position.x, 3)},
                      {"y_m", round_to(e.position.y, 3)}});
  ordered_json j;
  j["swath_version"] = "0.1.0";
  j["plan"] = plan.source;
  j["config"] = config.source;
  j["completed"] = r.status == SimulationEnd::completed;
  j["status"] = to_string(r.status);
  j["flight_time_s"] = round_to(r.flight_time_s, 2);
  j["planned_time_s"] = round_to(r.planned_time_s, 2);
  j["energy_j"] = round_to(r.energy_j, 1);
  j["final_soc"] = round_to(r.final_soc, 6);
  j["reserve_soc"] = round_to(config.battery.reserve_soc, 6);
  j["reserve_crossed_s"] =
      r.reserve_crossed_s ? ordered_json(round_to(*r.reserve_crossed_s, 2)) : ordered_json();
  j["prediction"] = {{"from_s", round_to(r.first_period_s, 2)},
                     {"mean_relative_error", round_to(r.mean_relative_error, 6)},
                     {"max_relative_error", round_to(r.max_relative_error, 6)},
                     {"kalman_corrections", r.corrections},
                     {"steps", r.steps},
                     {"final_period_s", round_to(r.final_period_s, 3)}};
  j["replanning"] = {{"enabled", config.replan},
                     {"replans", r.replans},
                     {"infeasible_replans", r.infeasible_replans},
                     {"changes", r.control.empty() ? 0 : r.control.size() - 1},
                     {"mean_trajectory", rounded(r.mean_trajectory, 4)},
                     {"mean_computations", rounded(r.mean_computations, 4)},
                     {"mean_power_w", round_to(r.mean_power_w, 3)}};
  if (comparison) {
    ordered_json high = fixed_run(comparison->highest), low = fixed_run(comparison->lowest);
    j["fixed"] = {{"highest", high},
                  {"lowest", low},
                  {"lowest_gains_min_per_hour", round_to(comparison->minutes_per_hour, 2)}};
  }
  j["stages"] = stages;
  return base::json_text(j, 1) + "\n";
}

std::string budget_json(const std::vector<DroneBudget>& budgets, const DroneProfile& drone) {
  ordered_json list = ordered_json::array();
  for (const DroneBudget& b : budgets) {
    ordered_json soc = ordered_json::array();
    for (const BudgetPoint& p : b.timeline) soc.push_back({round_to(p.t_s, 2), round_to(p.soc, 6)});
    list.push_back({{"drone", b.drone},
                    {"can_finish", b.can_finish()},
                    {"distance_m", round_to(b.distance_m, 2)},
                    {"flight_time_s", round_to(b.flight_time_s, 2)},
                    {"energy_j", round_to(b.energy_j, 1)},
                    {"energy_wh", round_to(b.energy_j / 3600.0, 3)},
                    {"landing_soc", round_to(b.landing_soc, 6)},
                    {"reserve_margin", round_to(b.reserve_margin, 6)},
                    {"reserve_crossed", optional_point(b.reserve_crossed)},
                    {"battery_empty", optional_point(b.battery_empty)},
                    {"soc_over_time", soc}});
  }
  ordered_json j;
  j["swath_version"] = "0.1.0";
  j["drone_profile"] = drone.source;
  j["reserve_soc"] = round_to(drone.battery.reserve_soc, 6);
  j["drones"] = list;
  return base::json_text(j, 1) + "\n";
}

std::string budget_csv(const std::vector<DroneBudget>& budgets) {
  std::string out = "drone,t_s,lon_deg,lat_deg,altitude_m,soc,energy_j\n";
  for (const DroneBudget& b : budgets)
    for (const BudgetPoint& p : b.timeline) {
      out += b.drone;
      cell(out, p.t_s, 2);
      cell(out, p.geo.lon_deg, 9);
      cell(out, p.geo.lat_deg, 9);
      cell(out, p.altitude_m, 2);
      cell(out, p.soc, 6);
      cell(out, p.energy_j, 1);
      out += '\n';
    }
  return out;
}

std::string budget_table(const std::vector<DroneBudget>& budgets, const DroneProfile& drone) {
  std::string out = "drone        time      energy     landing SoC  reserve margin\n";
  for (const DroneBudget& b : budgets) {
    std::string name = b.drone;
    name.resize(std::max<std::size_t>(name.size(), 12), ' ');
    out += name + ' ';
    std::string time = fixed_text(b.flight_time_s / 60.0, 1) + " min";
    time.resize(std::max<std::size_t>(time.size(), 10), ' ');
    std::string energy = fixed_text(b.energy_j / 3600.0, 1) + " Wh";
    energy.resize(std::max<std::size_t>(energy.size(), 11), ' ');
    std::string soc = b.landing_soc > 0 ? fixed_text(100.0 * b.landing_soc, 1) + " %" : "empty";
    soc.resize(std::max<std::size_t>(soc.size(), 13), ' ');
    out += time + energy + soc + fixed_text(100.0 * b.reserve_margin, 1) + " points\n";
    if (b.reserve_crossed) {
      const BudgetPoint& p = *b.reserve_crossed;
      out += "  " + b.drone + " reaches the " + fixed_text(100.0 * drone.battery.reserve_soc, 0) +
             " % reserve at t = " + fixed_text(p.t_s, 0) + " s, at lat " +
             fixed_text(p.geo.lat_deg, 6) + ", lon " + fixed_text(p.geo.lon_deg, 6) + "\n";
    }
    if (b.battery_empty)
      out += "  " + b.drone + " runs out of battery at t = " + fixed_text(b.battery_empty->t_s, 0) +
             " s\n";
  }
  return out;
}

}  // namespace swath::energy
