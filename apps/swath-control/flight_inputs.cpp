#include "flight_inputs.hpp"

#include <algorithm>
#include <filesystem>

#include "data_dir.hpp"
#include "input_text.hpp"
#include "seed_option.hpp"
#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/control/config.hpp"
#include "swath/energy/sim_config.hpp"

namespace swath::apps {
namespace {

using base::InputError;
namespace fs = std::filesystem;

// The file's text with its overrides; messages then name "FILE (with --set)", since line numbers
// refer to the text as rewritten.
void override_file(ConfigFile& file, const std::vector<control::Override>& overrides) {
  if (overrides.empty()) return;
  file.text = control::apply_overrides(file.text, file.source, overrides);
  file.source += " (with --set)";
}

// --set vehicle.KEY=V, scheduler.KEY=V, environment.KEY=V, sorted to their files.
std::vector<control::Override> overrides_for(const std::vector<std::string>& sets,
                                             const std::string& file) {
  std::vector<control::Override> out;
  for (const std::string& s : sets) {
    const auto eq = s.find('='), dot = s.find('.');
    if (eq == std::string::npos || dot == std::string::npos || dot > eq)
      throw InputError("--set " + s +
                       ": expected FILE.KEY=VALUE with FILE vehicle, scheduler or environment "
                       "(e.g. --set vehicle.controller.position_p=1.2)");
    const std::string prefix = s.substr(0, dot);
    if (prefix != "vehicle" && prefix != "scheduler" && prefix != "environment")
      throw InputError("--set " + s + ": " + prefix + " is not vehicle, scheduler or environment");
    if (prefix == file) out.push_back({s.substr(dot + 1, eq - dot - 1), s.substr(eq + 1)});
  }
  return out;
}

}  // namespace

ConfigFile config_file(const std::string& given, const std::string& folder, const std::string& what,
                       const std::string& flag) {
  fs::path path = given;
  std::error_code ec;
  if (!fs::exists(path, ec) && given.find('/') == std::string::npos &&
      fs::path(given).extension().empty())
    path = share_dir() / folder / (given + ".yaml");
  if (!fs::exists(path, ec)) {
    std::vector<std::string> bundled;  // sorted: the directory's order is the file system's
    for (const auto& e : fs::directory_iterator(share_dir() / folder, ec))
      if (e.path().extension() == ".yaml") bundled.push_back(e.path().stem().string());
    std::sort(bundled.begin(), bundled.end());
    std::string names;
    for (const std::string& n : bundled) names += (names.empty() ? "" : ", ") + n;
    throw InputError(flag + " " + given + ": no such " + what + " file, and no bundled " + what +
                     " of that name (bundled: " + names + ")");
  }
  return {path.stem().string(), path.string(),
          base::read_text_file(path, what + " file", base::kMaxConfigFileBytes)};
}

void add_flight_options(CLI::App& app, FlightRequest& r) {
  app.add_option("--seed", r.seed, "Seed of every noise source (wind, sensors, random missions)")
      ->check(seed_check())
      ->capture_default_str();
  app.add_flag("--loop", r.loop,
               "Repeat the mission until the battery reaches its reserve (paper 002 §7)");
  app.add_option("--speed", r.speed_m_s,
                 "Cruise speed along the legs, m/s (default: the mission file's, else the "
                 "vehicle's controller.limits.max_speed_m_s)");
  app.add_option("--altitude", r.altitude_m,
                 "Fly every point at this height above home, m (default: the file's; random and "
                 "stage plans 5 m)");
  app.add_option("--drone", r.drone, "The drone of a fleet plan: its name or number (default: 1)");
  app.add_option("--start", r.start,
                 "Stage plans: the take-off point X,Y in the plan's local metres (default 0,0)");
  app.add_option("--max-time", r.max_time_s,
                 "Stop after this many simulated seconds (default: the scheduler's "
                 "run.max_time_s, 14400)");
  app.add_option("--set", r.sets,
                 "Override a key of the vehicle, scheduler or environment file, e.g. "
                 "vehicle.controller.position_p=1.2, scheduler.rate_hz=200, "
                 "environment.mean_wind.speed_m_s=6 (repeatable)");
}

PreparedFlight prepare_flight(const FlightRequest& r) {
  PreparedFlight out;
  control::SimulationSettings& settings = out.settings;
  settings.seed = r.seed;
  settings.loop = r.loop;
  ConfigFile vehicle = config_file(r.vehicle, "vehicles", "vehicle", "--vehicle");
  override_file(vehicle, overrides_for(r.sets, "vehicle"));
  settings.physics = vehicle::parse_vehicle(vehicle.text, vehicle.source);
  out.warnings.insert(out.warnings.end(), settings.physics.warnings.begin(),
                      settings.physics.warnings.end());
  settings.control = control::parse_vehicle_control(vehicle.text, vehicle.source);
  settings.battery = energy::parse_battery_section(vehicle.text, vehicle.source);
  ConfigFile scheduler = config_file(r.scheduler, "schedulers", "scheduler", "--scheduler");
  override_file(scheduler, overrides_for(r.sets, "scheduler"));
  settings.scheduler = control::parse_scheduler_config(scheduler.text, scheduler.source);
  if (r.max_time_s) {
    if (!(*r.max_time_s > 0 && *r.max_time_s <= 86'400))
      throw InputError("--max-time " + base::shortest_text(*r.max_time_s) +
                       ": expected seconds in (0, 86400]");
    settings.scheduler.run.max_time_s = *r.max_time_s;
  }
  ConfigFile environment =
      config_file(r.environment, "environments", "environment", "--environment");
  override_file(environment, overrides_for(r.sets, "environment"));
  settings.environment = vehicle::parse_environment(environment.text, environment.source);
  out.warnings.insert(out.warnings.end(), settings.environment.warnings.begin(),
                      settings.environment.warnings.end());

  control::MissionOptions options;
  options.drone = r.drone;
  if (r.altitude_m && !(*r.altitude_m > 0 && *r.altitude_m <= 1000))
    throw InputError("--altitude " + base::shortest_text(*r.altitude_m) +
                     ": expected metres in (0, 1000]");
  options.altitude_m = r.altitude_m.value_or(0.0);
  if (!r.start.empty()) {
    const auto xy = parse_number_pair(r.start, ',');
    if (!xy) throw InputError("--start " + r.start + ": expected X,Y in metres, e.g. 25,146");
    options.start_m = {xy->first, xy->second};
  }
  if (r.speed_m_s && !(*r.speed_m_s > 0 && *r.speed_m_s <= 30))
    throw InputError("--speed " + base::shortest_text(*r.speed_m_s) +
                     ": expected m/s in (0, 30] for a multirotor");
  if (r.speed_m_s) options.stage_speed_m_s = *r.speed_m_s;
  settings.mission = control::read_flight_mission(r.mission, options, r.seed, &out.warnings);
  settings.speed_m_s = r.speed_m_s ? *r.speed_m_s
                       : settings.mission.speed_m_s > 0
                           ? settings.mission.speed_m_s
                           : settings.control.controller.limits.max_speed_m_s;
  if (r.loop) settings.mission = control::closed_for_loop(std::move(settings.mission));

  out.inputs = {settings.mission.name, vehicle.name, scheduler.name, environment.name, r.seed,
                settings.speed_m_s,    r.loop};
  return out;
}

}  // namespace swath::apps
