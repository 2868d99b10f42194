#include "swath/energy/sim_config.hpp"
#include "swath/base/file_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "swath/base/input_error.hpp"
#include "swath/base/yaml_map.hpp"

namespace swath::energy {
namespace {

using base::InputError;
using base::kInf;
using base::YamlMap;

Wind parse_wind(const YamlMap& m) {
  m.allow({"speed_m_s", "from_deg"});
  const double speed_m_s = m.number("speed_m_s", 0.0, 0.0, 100.0);
  return Wind(speed_m_s, m.number("from_deg", 0.0, -360.0, 360.0));
}

// swath-control's voltage sag (vehicle/battery.hpp); the other programs read and ignore it.
void read_sag(const YamlMap& m, Battery& b) {
  const double cells_read = m.number("cells", b.cells, 0.0, 24.0);
  if (cells_read != std::floor(cells_read))
    throw InputError(m.where("cells") + " must be a whole number of cells in series");
  b.cells = static_cast<int>(cells_read);
  b.internal_resistance_ohm =
      m.number("internal_resistance_ohm", b.internal_resistance_ohm, 0.0, 1.0);
  // The defaults follow the cell count: 4.2 V and 3.3 V a cell (ArduPilot's usual settings).
  const double cells = std::max(b.cells, 1);
  b.volt_max_v = m.number("volt_max_v", 4.2 * cells, 0.0, 1000.0, true);
  b.volt_min_v = m.number("volt_min_v", 3.3 * cells, 0.0, 1000.0, true);
  if (!(b.volt_min_v < b.volt_max_v))
    throw InputError(m.where("volt_min_v") + " must be below battery.volt_max_v");
  b.thrust_compensation = m.flag("thrust_compensation", b.thrust_compensation);
}

Battery parse_battery(const YamlMap& m) {
  m.allow({"voltage_v", "stabilised_voltage_v", "resistance_ohm", "capacity_ah", "initial_soc",
           "reserve_soc", "cells", "internal_resistance_ohm", "volt_max_v", "volt_min_v",
           "thrust_compensation"});
  Battery b;
  b.voltage_v = m.number("voltage_v", b.voltage_v, 0.0, 1000.0, true);
  b.stabilised_voltage_v =
      m.number("stabilised_voltage_v", b.stabilised_voltage_v, 0.0, 1000.0, true);
  b.resistance_ohm = m.number("resistance_ohm", b.resistance_ohm, 0.0, 10.0, true);
  b.capacity_ah = m.number("capacity_ah", b.capacity_ah, 0.0, 1000.0, true);
  b.initial_soc = m.number("initial_soc", b.initial_soc, 0.0, 1.0, true);
  b.reserve_soc = m.number("reserve_soc", b.reserve_soc, 0.0, 1.0);
  if (b.reserve_soc >= b.initial_soc)
    throw InputError(m.where("reserve_soc") + " must be below battery.initial_soc");
  read_sag(m, b);
  return b;
}

PowerProfile parse_power(const YamlMap& m) {
  m.allow({"mechanical", "payload_w", "climb_w", "descent_w", "computations", "noise_w", "seed"});
  PowerProfile p;
  const YamlMap mech = m.map("mechanical");
  mech.allow({"cruise_w", "cruise_airspeed_m_s", "parasitic_share", "max_bank_deg"});
  p.mechanical.cruise_w = mech.number("cruise_w", p.mechanical.cruise_w, 0.0, 1e6, true);
  p.mechanical.cruise_airspeed_m_s =
      mech.number("cruise_airspeed_m_s", p.mechanical.cruise_airspeed_m_s, 0.0, 200.0, true);
  p.mechanical.parasitic_share =
      mech.number("parasitic_share", p.mechanical.parasitic_share, 0.0, 1.0);
  p.mechanical.max_bank_deg =
      mech.number("max_bank_deg", p.mechanical.max_bank_deg, 0.0, 80.0, true);
  p.payload_w = m.number("payload_w", 0.0, 0.0, 1e5);
  p.climb_w = m.number("climb_w", 0.0, 0.0, 1e6);
  p.descent_w = m.number("descent_w", 0.0, 0.0, 1e6);
  p.noise_w = m.number("noise_w", 0.0, 0.0, 1e5);
  p.seed = static_cast<std::uint64_t>(m.number("seed", 1.0, 0.0, 9007199254740992.0));
  if (m.has("computations")) {
    const YAML::Node list = m.node()["computations"];
    if (!list.IsSequence()) throw InputError(m.where("computations") + " must be a list");
    for (std::size_t j = 0; j < list.size(); ++j) {
      const std::string where = m.where("computations") + "[" + std::to_string(j) + "]";
      if (!list[j].IsMap() || !list[j]["points"] || !list[j]["points"].IsSequence() ||
          list[j]["points"].size() == 0)
        throw InputError(where + " must be {name: TEXT, points: [[parameter, W], ..]}");
      PowerCurve curve;
      curve.name = list[j]["name"] ? list[j]["name"].as<std::string>()
                                   : "computation " + std::to_string(j + 1);
      for (const YAML::Node& pt : list[j]["points"]) {
        double c1 = 0.0, w = 0.0;
        try {
          if (!pt.IsSequence() || pt.size() != 2) throw YAML::Exception(pt.Mark(), "pair");
          c1 = pt[0].as<double>();
          w = pt[1].as<double>();
        } catch (const YAML::Exception&) {
          throw InputError(where + ": every point is [parameter, W]");
        }
        if (!std::isfinite(c1) || !std::isfinite(w) || w < 0)
          throw InputError(where + ": a point's power must be a finite number >= 0 W");
        if (!curve.points.empty() && c1 <= curve.points.back().first)
          throw InputError(where + ": points must have increasing parameters");
        curve.points.emplace_back(c1, w);
      }
      p.computations.push_back(std::move(curve));
    }
  }
  return p;
}

}  // namespace

double PowerTrace::at(double t) const {
  if (t_s.empty() || t < t_s.front() || t > t_s.back())
    return std::numeric_limits<double>::quiet_NaN();
  const auto it = std::upper_bound(t_s.begin(), t_s.end(), t);
  if (it == t_s.end()) return power_w.back();
  const std::size_t i = static_cast<std::size_t>(it - t_s.begin());
  const double f = (t - t_s[i - 1]) / (t_s[i] - t_s[i - 1]);
  return power_w[i - 1] + f * (power_w[i] - power_w[i - 1]);
}

PowerTrace parse_power_trace(const std::string& text, const std::string& source) {
  PowerTrace trace;
  std::istringstream in(text);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos || line[0] == '#') continue;
    const auto comma = line.find(',');
    auto parse = [&](std::string s, double& v) {
      s.erase(0, s.find_first_not_of(" \t"));
      s.erase(s.find_last_not_of(" \t") + 1);
      const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
      return r.ec == std::errc() && r.ptr == s.data() + s.size() && std::isfinite(v);
    };
    double t = 0.0, w = 0.0;
    const bool ok = comma != std::string::npos && parse(line.substr(0, comma), t) &&
                    parse(line.substr(comma + 1), w);
    if (!ok) {
      if (trace.t_s.empty() && n == 1) continue;  // a header
      // The line itself is not echoed: a config pointed at the wrong file (/etc/passwd) must not
      // print that file's content.
      throw InputError(source + ": line " + std::to_string(n) +
                       ": expected 't_s, watts' (two numbers separated by a comma)");
    }
    if (!trace.t_s.empty() && t <= trace.t_s.back())
      throw InputError(source + ": line " + std::to_string(n) + ": times must increase");
    trace.t_s.push_back(t);
    trace.power_w.push_back(w);
  }
  if (trace.t_s.size() < 2) throw InputError(source + ": a power trace needs at least two rows");
  return trace;
}

namespace {

SimConfig sim_config_from_yaml(const std::string& text, const std::string& source) {
  const YAML::Node root = base::load_yaml(text, source);
  if (!root.IsMap()) throw InputError(source + ": a simulation config is a mapping of keys");
  const YamlMap m(root, source, "");
  m.allow({"time_step_s", "speed_m_s", "max_airspeed_m_s", "wind", "trigger_radius_m", "start_m",
           "max_time_s", "stall_time_s", "output_interval_s", "parameters", "gains", "model", "mpc",
           "battery", "power", "replay_csv"});
  SimConfig c;
  c.source = source;
  // Below 1 ms the guidance field gains nothing and a day's flight would take 10^8+ steps.
  c.time_step_s = m.number("time_step_s", c.time_step_s, 1e-3, 1.0);
  c.speed_m_s = m.number("speed_m_s", c.speed_m_s, 0.0, 200.0, true);
  c.max_airspeed_m_s =
      m.number("max_airspeed_m_s", std::max(c.max_airspeed_m_s, c.speed_m_s), 0.0, 300.0, true);
  c.wind = parse_wind(m.map("wind"));
  c.trigger_radius_m = m.number("trigger_radius_m", c.trigger_radius_m, 0.0, 1e4, true);
  const auto start = m.numbers("start_m");
  if (!start.empty() && start.size() != 2)
    throw InputError(m.where("start_m") + " must be [x, y] in local metres");
  if (start.size() == 2) c.start = {start[0], start[1]};
  c.max_time_s = m.number("max_time_s", c.max_time_s, 0.0, 86400.0, true);  // a day at most
  c.stall_time_s = m.number("stall_time_s", c.stall_time_s, 0.0, 1e7, true);
  c.output_interval_s = m.number("output_interval_s", c.output_interval_s, c.time_step_s, 1e5);
  const YamlMap params = m.map("parameters");
  params.allow({"trajectory", "computations"});
  c.trajectory_parameters = params.numbers("trajectory");
  c.computation_parameters = params.numbers("computations");
  const YamlMap gains = m.map("gains");
  gains.allow({"trajectory_w_per_unit"});
  c.trajectory_gains_w = gains.numbers("trajectory_w_per_unit");
  const YamlMap model = m.map("model");
  model.allow({"fourier_order", "initial_period_s", "estimate_period", "kalman"});
  const double order = model.number("fourier_order", c.fourier_order, 0, 20);
  if (order != std::floor(order))
    throw InputError(model.where("fourier_order") + " must be a whole number");
  c.fourier_order = static_cast<int>(order);
  c.initial_period_s = model.number("initial_period_s", c.initial_period_s, 0.0, 1e6, true);
  if (c.initial_period_s < 10 * c.time_step_s)
    throw InputError(model.where("initial_period_s") + " must span at least 10 time steps");
  c.estimate_period = model.flag("estimate_period", c.estimate_period);
  const YamlMap k = model.map("kalman");
  k.allow({"process_w", "measurement_w", "initial_w", "gate_w"});
  c.kalman.process_w = k.number("process_w", c.kalman.process_w, 0.0, 1e6);
  c.kalman.measurement_w = k.number("measurement_w", c.kalman.measurement_w, 0.0, 1e6, true);
  c.kalman.initial_w = k.number("initial_w", c.kalman.initial_w, 0.0, 1e6, true);
  c.kalman.gate_w = k.number("gate_w", c.kalman.gate_w, 0.0, 1e6);
  const YamlMap mpc = m.map("mpc");
  mpc.allow({"replan", "horizon_s", "period_s", "margin", "quality_weights"});
  c.replan = mpc.flag("replan", c.replan);
  c.mpc_horizon_s = mpc.number("horizon_s", c.mpc_horizon_s, 0.0, 1e6);
  c.mpc_period_s = mpc.number("period_s", c.mpc_period_s, 0.0, 1e6, true);
  c.mpc_margin = mpc.number("margin", c.mpc_margin, 0.0, 0.5);
  c.quality_weights = mpc.numbers("quality_weights");
  for (double w : c.quality_weights)
    if (w < 0) throw InputError(mpc.where("quality_weights") + " must be >= 0");
  c.battery = parse_battery(m.map("battery"));
  c.power = parse_power(m.map("power"));
  c.replay_csv = m.text("replay_csv", "");
  c.warnings = m.warnings();
  return c;
}

}  // namespace

SimConfig parse_sim_config(const std::string& text, const std::string& source) {
  return base::yaml_guard(source, [&] { return sim_config_from_yaml(text, source); });
}

Battery parse_battery_section(const std::string& text, const std::string& source) {
  return base::yaml_guard(source, [&] {
    const YAML::Node root = base::load_yaml(text, source);
    if (!root.IsMap()) throw InputError(source + ": expected a mapping of keys");
    return parse_battery(YamlMap(root, source, "").map("battery"));
  });
}

SimConfig read_sim_config(const std::string& path) {
  SimConfig c = parse_sim_config(
      base::read_text_file(path, "simulation config", base::kMaxConfigFileBytes), path);
  if (!c.replay_csv.empty()) {
    std::filesystem::path csv(c.replay_csv);
    if (csv.is_relative()) csv = std::filesystem::path(path).parent_path() / csv;
    c.replay = parse_power_trace(base::read_text_file(csv, "power trace"), csv.string());
  }
  return c;
}

namespace {

DroneProfile drone_profile_from_yaml(const std::string& text, const std::string& source) {
  const YAML::Node root = base::load_yaml(text, source);
  if (!root.IsMap()) throw InputError(source + ": a drone profile is a mapping of keys");
  const YamlMap m(root, source, "");
  m.allow({"name", "speed_m_s", "climb_speed_m_s", "descent_speed_m_s", "max_airspeed_m_s", "wind",
           "battery", "power", "parameters"});
  DroneProfile d;
  d.source = source;
  vehicle::Drone& drone = d.drone;
  drone.name = m.text("name", "drone");
  // 0 (as absence): each leg at the mission's own speed.
  if (const double speed = m.number("speed_m_s", 0.0, 0.0, 200.0); speed > 0)
    drone.speed_m_s = speed;
  drone.climb_speed_m_s = m.number("climb_speed_m_s", drone.climb_speed_m_s, 0.0, 100.0, true);
  drone.descent_speed_m_s =
      m.number("descent_speed_m_s", drone.descent_speed_m_s, 0.0, 100.0, true);
  drone.max_airspeed_m_s = m.number("max_airspeed_m_s", drone.max_airspeed_m_s, 0.0, 300.0, true);
  d.wind = parse_wind(m.map("wind"));
  d.battery = parse_battery(m.map("battery"));
  d.power = parse_power(m.map("power"));
  const YamlMap params = m.map("parameters");
  params.allow({"computations"});
  d.computation_parameters = params.numbers("computations");
  if (d.computation_parameters.size() != d.power.computations.size())
    throw InputError(source + ": parameters.computations gives " +
                     std::to_string(d.computation_parameters.size()) + " values for " +
                     std::to_string(d.power.computations.size()) + " power.computations curves");
  d.warnings = m.warnings();
  return d;
}

}  // namespace

DroneProfile parse_drone_profile(const std::string& text, const std::string& source) {
  return base::yaml_guard(source, [&] { return drone_profile_from_yaml(text, source); });
}

DroneProfile read_drone_profile(const std::string& path) {
  return parse_drone_profile(base::read_text_file(path, "drone profile", base::kMaxConfigFileBytes),
                             path);
}

}  // namespace swath::energy
