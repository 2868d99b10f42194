#include "swath/control/control_files.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"

namespace swath::control {
namespace {

using base::fixed_text;
using base::round_to;
using nlohmann::ordered_json;

void add(std::string& line, double value, int decimals) {
  if (!line.empty()) line += ',';
  base::append_fixed_text(line, value, decimals);
}

void add_vec(std::string& line, const Vec3& v, int decimals) {
  add(line, v.x, decimals);
  add(line, v.y, decimals);
  add(line, v.z, decimals);
}

ordered_json stat(const ErrorStat& e, int decimals) {
  return {{"rms", round_to(e.rms, decimals)}, {"max", round_to(e.max, decimals)}};
}

ordered_json axes(const std::array<ErrorStat, 3>& e) {
  return {{"roll", stat(e[0], 4)}, {"pitch", stat(e[1], 4)}, {"yaw", stat(e[2], 4)}};
}

constexpr const char* kCauses[] = {"time_triggered", "boot", "trigger", "failsafe", "setpoint"};

}  // namespace

std::string timeseries_csv_header(std::size_t rotors) {
  std::string h =
      "t_s,x_m,y_m,z_m,vx_m_s,vy_m_s,vz_m_s,roll_deg,pitch_deg,yaw_deg,roll_sp_deg,pitch_sp_deg,"
      "yaw_sp_deg,roll_est_deg,pitch_est_deg,yaw_est_deg,sp_x_m,sp_y_m,sp_z_m,cross_track_m,"
      "wind_e_m_s,wind_n_m_s,wind_u_m_s";
  for (std::size_t i = 1; i <= rotors; ++i) h += ",pwm_" + std::to_string(i) + "_us";
  for (std::size_t i = 1; i <= rotors; ++i) h += ",omega_" + std::to_string(i) + "_rad_s";
  return h + ",motors_w,cpu_w,avionics_w,soc,executions_last_s\n";
}

std::string timeseries_csv_row(const TimeseriesRow& r) {
  std::string line;
  line.reserve(320);  // a row of 8 rotors is ~300 bytes: one allocation
  add(line, r.t_s, 3);
  add_vec(line, r.position_m, 3);
  add_vec(line, r.velocity_m_s, 3);
  add_vec(line, r.attitude_deg, 3);
  add_vec(line, r.setpoint_deg, 3);
  add_vec(line, r.estimate_deg, 3);
  add_vec(line, r.carrot_m, 3);
  add(line, r.cross_track_m, 3);
  add_vec(line, r.wind_m_s, 3);
  for (std::size_t i = 0; i < r.rotors; ++i) add(line, r.pwm_us[i], 1);
  for (std::size_t i = 0; i < r.rotors; ++i) add(line, r.rotor_rad_s[i], 2);
  add(line, r.motors_w, 2);
  add(line, r.cpu_w, 4);
  add(line, r.avionics_w, 2);
  add(line, r.soc, 6);
  line += ',';
  line += std::to_string(r.executions_last_s);
  line += '\n';
  return line;
}

std::string rate_csv_header(const std::vector<std::string>& trigger_sensors) {
  std::string h = "second,executions,tt,boot,trigger,failsafe,setpoint,unchanged";
  for (const std::string& s : trigger_sensors) h += ",triggers_" + s;
  return h + ",cpu_busy,overruns,latency_mean_ms,attitude_rms_deg\n";
}

std::string rate_csv_row(const RateRow& r) {
  std::string line = std::to_string(r.second) + ',' + std::to_string(r.executions);
  for (int n : r.by_cause) line += ',' + std::to_string(n);
  line += ',' + std::to_string(r.unchanged);
  for (int n : r.triggers) line += ',' + std::to_string(n);
  add(line, r.cpu_busy, 6);
  line += ',' + std::to_string(r.overruns);
  add(line, r.latency_mean_ms, 4);
  add(line, r.attitude_rms_deg, 4);
  return line + '\n';
}

std::string executions_csv_header(const std::vector<std::string>& trigger_sensors) {
  std::string h =
      "t_request_s,t_start_s,t_end_s,cause,sensors,changed,false_positive,false_negative";
  for (const std::string& s : trigger_sensors) h += ",x_" + s;
  return h + '\n';
}

std::string executions_csv_row(const ExecutionRow& r, std::size_t trigger_sensors) {
  std::string line;
  add(line, r.request_s, 6);
  add(line, r.start_s, 6);
  add(line, r.end_s, 6);
  line += ',' + std::string(kCauses[static_cast<int>(r.cause)]) + ',' + r.sensors + ',' +
          (r.changed ? "1" : "0") + ',' + (r.false_positive ? "1" : "0") + ',' +
          (r.false_negative ? "1" : "0");
  for (std::size_t k = 0; k < trigger_sensors; ++k) add(line, k < r.x.size() ? r.x[k] : 0.0, 6);
  return line + '\n';
}

std::string fits_csv_header() {
  return "t_s,sensor,n,beta1,beta2,threshold,method\n";
}

std::string fits_csv_row(const FitRow& r, FitMethod method) {
  static constexpr const char* kMethods[] = {"logit_ols", "logit_wls", "mle"};
  std::string line;
  add(line, r.t_s, 3);
  line += ',' + r.sensor + ',' + std::to_string(r.points);
  add(line, r.beta1, 6);
  add(line, r.beta2, 6);
  line += ',' + (std::isfinite(r.threshold) ? fixed_text(r.threshold, 6) : std::string("inf"));
  line += ',' + std::string(kMethods[static_cast<int>(method)]);
  return line + '\n';
}

std::string summary_json(const SimulationSummary& s, const SummaryInputs& in,
                         const SimulationSettings& settings) {
  ordered_json j;
  j["inputs"] = {{"mission", in.mission},
                 {"vehicle", in.vehicle},
                 {"scheduler", in.scheduler},
                 {"environment", in.environment},
                 {"seed", in.seed},
                 {"speed_m_s", round_to(in.speed_m_s, 3)},
                 {"loop", in.loop}};
  j["status"] = to_string(s.status);
  if (!s.lost_control_reason.empty()) j["lost_control"] = s.lost_control_reason;
  j["flight_time_s"] = round_to(s.flight_time_s, 3);
  j["reserve_time_s"] = s.reserve_time_s ? ordered_json(round_to(*s.reserve_time_s, 3)) : nullptr;
  j["distance_m"] = round_to(s.distance_m, 2);
  j["laps"] = s.laps;
  j["metrics_from_s"] = round_to(s.metrics_from_s, 3);
  j["attitude_error_deg"] = axes(s.attitude_error_deg);
  j["attitude_error_estimated_deg"] = axes(s.attitude_error_estimated_deg);
  j["attitude_error_disturbance_deg"] = axes(s.attitude_error_disturbance_deg);
  j["attitude_error_disturbance_deg"]["share_of_samples"] = round_to(s.disturbance_share, 4);
  j["max_tilt_deg"] = round_to(s.max_tilt_deg, 3);
  j["tracking"] = {{"cross_track_rms_m", round_to(s.cross_track_m.rms, 4)},
                   {"cross_track_max_m", round_to(s.cross_track_m.max, 4)},
                   {"position_error_rms_m", round_to(s.position_error_m.rms, 4)},
                   {"position_error_max_m", round_to(s.position_error_m.max, 4)}};
  const auto& e = s.executions;
  ordered_json causes;
  for (std::size_t k = 0; k < e.by_cause.size(); ++k) causes[kCauses[k]] = e.by_cause[k];
  j["executions"] = {{"total", e.total},
                     {"by_cause", causes},
                     {"per_second",
                      {{"mean", round_to(e.per_second_mean, 3)},
                       {"p5", round_to(e.per_second_p5, 3)},
                       {"p95", round_to(e.per_second_p95, 3)},
                       {"max", round_to(e.per_second_max, 3)}}},
                     {"share_seconds_above_rate", round_to(e.share_seconds_above_rate, 6)},
                     {"unchanged_fraction", round_to(e.unchanged_fraction, 6)},
                     {"latency_ms",
                      {{"mean", round_to(e.latency_mean_ms, 4)},
                       {"p95", round_to(e.latency_p95_ms, 4)},
                       {"max", round_to(e.latency_max_ms, 4)}}},
                     {"overruns", e.overruns}};
  ordered_json triggers = ordered_json::object();
  for (const auto& t : s.triggers) {
    ordered_json one = {{"samples", t.samples}, {"triggers", t.triggers}};
    if (s.reactive) {
      one["beta1"] = round_to(t.beta1, 6);
      one["beta2"] = round_to(t.beta2, 6);
      one["threshold"] = std::isfinite(t.threshold) ? ordered_json(round_to(t.threshold, 6))
                                                    : ordered_json("never");
      one["refits"] = t.refits;
      one["dataset"] = t.dataset;
    }
    triggers[t.sensor] = one;
  }
  j["triggers"] = triggers;
  if (s.reactive) {
    j["feedback"] = {{"fp_share_after_boot", round_to(s.feedback.fp_share_after_boot, 6)},
                     {"fp_share_steady", round_to(s.feedback.fp_share_steady, 6)},
                     {"false_positives", s.feedback.false_positives},
                     {"false_negatives", s.feedback.false_negatives},
                     {"multi_cause_excluded", s.feedback.multi_cause_excluded}};
  }
  if (s.oracle) {
    const auto& o = *s.oracle;
    auto ratio = [](std::int64_t a, std::int64_t b) {
      return b > 0 ? round_to(static_cast<double>(a) / static_cast<double>(b), 6) : 0.0;
    };
    j["oracle"] = {{"tp", o.tp},
                   {"fp", o.fp},
                   {"tn", o.tn},
                   {"fn", o.fn},
                   {"precision", ratio(o.tp, o.tp + o.fp)},
                   {"recall", ratio(o.tp, o.tp + o.fn)}};
  }
  j["cpu"] = {{"utilisation", round_to(s.cpu_utilisation, 6)},
              {"energy_j", round_to(s.cpu_j, 3)},
              {"energy_per_execution_mj", round_to(s.cpu_energy_per_execution_mj, 6)},
              {"background_completed", s.background_completed},
              {"background",
               {{"released", s.background_released},
                {"completed", s.background_completed},
                {"skipped", s.background_skipped},
                {"completed_share", s.background_released > 0
                                        ? round_to(static_cast<double>(s.background_completed) /
                                                       static_cast<double>(s.background_released),
                                                   6)
                                        : 0.0},
                {"latency_mean_ms", round_to(s.background_latency_mean_ms, 4)},
                {"latency_max_ms", round_to(s.background_latency_max_ms, 4)}}}};
  j["energy"] = {{"total_j", round_to(s.total_j, 2)},
                 {"motors_j", round_to(s.motors_j, 2)},
                 {"cpu_j", round_to(s.cpu_j, 3)},
                 {"avionics_j", round_to(s.avionics_j, 2)},
                 {"mean_power_w", round_to(s.mean_power_w, 3)},
                 {"final_soc", round_to(s.final_soc, 6)},
                 {"reserve_soc", round_to(settings.battery.reserve_soc, 6)},
                 {"balance_residual", s.balance_residual}};
  if (s.checked_against_plan) {
    j["plan_check"] = {
        {"outside_area_m", round_to(s.outside_area_m, 2)},
        {"inside_no_fly_m", round_to(s.inside_no_fly_m, 2)},
        {"min_clearance_m",
         s.min_clearance_m ? ordered_json(round_to(*s.min_clearance_m, 3)) : nullptr}};
  }
  return base::json_text(j, 1) + "\n";
}

}  // namespace swath::control
