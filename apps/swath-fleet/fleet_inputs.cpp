#include "fleet_inputs.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "data_dir.hpp"
#include "input_text.hpp"
#include "seed_option.hpp"
#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/fleet/apps.hpp"
#include "swath/fleet/envelope.hpp"
#include "swath/fleet/faults.hpp"
#include "swath/fleet/fleet_file.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/vehicle/random.hpp"

namespace swath::apps {

using base::InputError;
using json = nlohmann::ordered_json;
namespace fs = std::filesystem;

void add_fleet_options(CLI::App& app, FleetRequest& r, bool with_scheduler, bool required) {
  std::string names;
  for (const fleet::App& a : fleet::all_apps()) names += (names.empty() ? "" : ", ") + a.name;
  app.add_option("APP", r.app,
                 "The application: " + names +
                     " (swath-fleet apps), or a Python file APP.py defining APP(bee) "
                     "(docs/swath-fleet.md; swath-fleet built with Python)")
      ->required(required);
  app.add_option("--world", r.world,
                 "World file, or a bundled world: hotspot, road, rf_field, sites, static, tracking "
                 "(share/worlds/)")
      ->required(required);
  app.add_option("--fleet", r.fleet,
                 "Fleet file (swath plan's fleet format, with optional profile, max_flight_time_s, "
                 "approach_speed_m_s, accel_m_s2, recharge_s per drone)");
  app.add_option("--drones", r.drones,
                 "Instead of --fleet: N default drones (10 m/s, swath-energy's battery and "
                 "power) in a row east of the world's origin, 6 m apart; at most 21 fit under "
                 "the default 120 m ceiling")
      ->check(CLI::Range(1, 100));
  if (with_scheduler) {
    app.add_option("--scheduler", r.scheduler,
                   "sa (simulated annealing), reactive (the paper's baseline: sa without "
                   "forecasts), greedy, round-robin, hungarian")
        ->capture_default_str();
    app.add_option("--forecast", r.forecast,
                   "What forecasts the next requests for speculation and avoid-mutual (sa only): "
                   "gmf (graph matching against --history), constant-velocity, none")
        ->capture_default_str();
    app.add_option("--history", r.history,
                   "Past runs of the same app for gmf and the cancellation model: run "
                   "directories (swath-fleet run -o DIR) or their dtg.json files");
    app.add_flag("--relief", r.relief,
                 "Relief: an idle drone flies ahead to stand by where a drone at work will have "
                 "to leave (flight time or battery) and takes over its next segment");
  }
  app.add_option("--seed", r.seed, "Seed of the scheduler's and the app's random numbers")
      ->check(seed_check())
      ->capture_default_str();
  app.add_option("--faults", r.faults,
                 "Faults file: [{t_s, drone, kind, duration_s, soc}] (link_loss, battery_drop, "
                 "motor_failure, sensor_failure)");
  app.add_option("--weights", r.weights,
                 "Weights file of the sub-utilities (coverage, fairness, avoid_zigzag, commitment, "
                 "speculative, avoid_mutual)");
  app.add_option("--wind", r.wind,
                 "A steady wind E,N in m/s (towards east and north, e.g. 4,-3): the drones keep "
                 "their tracks and times, their rotors work at the airspeed (default: calm)");
  app.add_option("--max-time", r.max_time_s, "Stop a run that has not completed by then, s")
      ->check(CLI::Range(1.0, 604800.0))
      ->capture_default_str();
}

fleet::Dtg read_history(const std::string& path) {
  const std::string file = fs::is_directory(path) ? (fs::path(path) / "dtg.json").string() : path;
  return fleet::parse_dtg(base::read_text_file(file, "history (dtg.json)"), file);
}

std::vector<std::string> comma_names(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream in(list);
  for (std::string s; std::getline(in, s, ',');)
    if (!s.empty()) out.push_back(s);
  return out;
}

std::string world_path(const std::string& name) {
  if (fs::exists(name) || name.find('/') != std::string::npos ||
      name.find('.') != std::string::npos)
    return name;
  const fs::path bundled = share_dir() / "worlds" / (name + ".yaml");
  if (fs::exists(bundled)) return bundled.string();
  throw InputError("--world " + name +
                   ": no such file, and no bundled world of that name (hotspot, road, sites)");
}

std::function<std::unique_ptr<worlds::BaseWorld>(std::unique_ptr<worlds::BaseWorld>)>&
world_wrapper() {
  static std::function<std::unique_ptr<worlds::BaseWorld>(std::unique_ptr<worlds::BaseWorld>)> f;
  return f;
}

PreparedRun prepare_run(const FleetRequest& r, std::optional<std::uint64_t> world_seed) {
  PreparedRun p;
  bool found = false;
  std::string names;
  for (fleet::App& a : fleet::all_apps()) {
    names += (names.empty() ? "" : ", ") + a.name;
    if (a.name == r.app) p.app = std::move(a), found = true;
  }
  if (!found) throw InputError("unknown app \"" + r.app + "\": the apps are " + names);
  p.world_source = world_path(r.world);
  p.world_text = base::read_text_file(p.world_source, "world file", base::kMaxConfigFileBytes);
  p.world = worlds::parse_world(p.world_text, p.world_source, world_seed);
  if (world_wrapper()) p.world = world_wrapper()(std::move(p.world));
  const std::string needs = fleet::app_world_kind(r.app);
  if (p.world->kind() != needs)
    throw InputError(p.world_source + ": a " + p.world->kind() + " world; the " + r.app +
                     " app needs a " + needs + " world");
  if (!r.fleet.empty() && r.drones > 0) throw InputError("give --fleet or --drones, not both");
  // Each file is read once: parsed, and its text kept for config_text.
  std::string fleet_text, weights_text, faults_text;
  fleet::Envelope envelope;  // the fleet file's, else the defaults
  const auto absolute = [](const std::string& f) {
    return f.empty() ? f : fs::absolute(f).lexically_normal().string();
  };
  p.fleet_file = absolute(r.fleet);
  p.weights_file = absolute(r.weights);
  p.faults_file = absolute(r.faults);
  for (const std::string& h : r.history) p.history_files.push_back(absolute(h));
  if (!r.fleet.empty()) {
    fleet_text = base::read_text_file(r.fleet, "fleet file", base::kMaxConfigFileBytes);
    fleet::FleetFileContents contents =
        fleet::parse_fleet_file_contents(fleet_text, r.fleet, p.world->origin);
    p.drones = std::move(contents.drones);
    envelope = std::move(contents.envelope);
  } else {
    const int n = r.drones > 0 ? r.drones : 1;
    p.default_drones = n;
    for (int i = 0; i < n; ++i) {
      fleet::DroneSpec d;
      d.drone.name = "drone-" + std::to_string(i + 1);
      // A row, the separation and a metre (the separation rule's margin) apart: neighbours can
      // climb at once (docs/swath-fleet.md).
      d.home_m = {(envelope.separation_m + 1) * i, 0, 0};
      p.drones.push_back(d);
    }
  }
  p.settings.envelope = fleet::local_envelope(envelope, p.world->origin);
  if (const std::string fence = fleet::fence_size_refusal(p.settings.envelope); !fence.empty())
    throw InputError(r.fleet + ": " + fence);
  if (p.world->has_origin) p.settings.origin = p.world->origin;
  // Checked again by the runtime; here too so that nothing (no vehicle link) is opened first.
  const std::string fit = fleet::layers_refusal(
      static_cast<int>(p.drones.size()), p.settings.layer_base_m,
      std::max(p.settings.layer_step_m, envelope.separation_m), envelope.ceiling_m,
      envelope.fence.max_altitude_m, envelope.separation_m > p.settings.layer_step_m);
  if (!fit.empty())
    throw InputError((r.fleet.empty() ? "--drones " + std::to_string(p.drones.size()) : r.fleet) +
                     ": " + fit);
  for (const fleet::DroneSpec& d : p.drones)
    if (const std::string why = p.settings.envelope.refusal_xy(d.home_m.x, d.home_m.y);
        !why.empty())
      throw InputError(r.fleet + ": " + d.drone.name + "'s home (" +
                       base::fixed_text(d.home_m.x, 1) + ", " + base::fixed_text(d.home_m.y, 1) +
                       ") m is " + why);
  p.settings.app_name = r.app;
  p.settings.scheduler = r.scheduler;
  p.settings.seed = r.seed;
  p.settings.max_time_s = r.max_time_s;
  if (!r.wind.empty()) {
    const auto w = parse_number_pair(r.wind, ',');
    if (!w || !(std::hypot(w->first, w->second) <= 30.0))
      throw InputError("--wind '" + r.wind +
                       "': expected E,N in m/s, at most 30 m/s together (e.g. 4,-3)");
    p.settings.wind = vehicle::Wind::from_velocity(w->first, w->second);  // --wind: E,N
  }
  if (!r.weights.empty()) {
    weights_text = base::read_text_file(r.weights, "weights file", base::kMaxConfigFileBytes);
    p.settings.weights = fleet::parse_weights(weights_text, r.weights);
  }
  if (!r.faults.empty()) {
    std::vector<std::string> drone_names;
    for (const auto& d : p.drones) drone_names.push_back(d.drone.name);
    faults_text = base::read_text_file(r.faults, "faults file", base::kMaxConfigFileBytes);
    p.settings.faults = fleet::parse_faults(faults_text, r.faults, drone_names, r.max_time_s);
  }
  p.settings.relief = r.relief;
  // The forecaster and relief are the scheduler's, as the scheduler itself: not in the hash.
  p.config_text = "app " + r.app + "\nworld\n" + p.world_text + "\nfleet\n" + fleet_text +
                  "\ndrones " + std::to_string(r.drones) + "\nweights\n" + weights_text +
                  "\nfaults\n" + faults_text + "\nwind " + r.wind + "\nmax_time_s " +
                  std::to_string(r.max_time_s) + "\n";
  if (!fleet::make_scheduler(r.scheduler == "reactive" ? "sa" : r.scheduler))
    throw InputError("unknown scheduler \"" + r.scheduler +
                     "\": use sa, reactive, greedy, round-robin or hungarian");
  if (!fleet::make_forecaster(r.forecast, {}))
    throw InputError("--forecast: unknown forecaster \"" + r.forecast +
                     "\": use gmf, constant-velocity or none");
  if (r.forecast != "none" && r.scheduler != "sa")
    throw InputError("--forecast " + r.forecast + " needs --scheduler sa (" + r.scheduler +
                     " does not use forecasts)");
  if (!r.history.empty() && r.forecast == "none")
    throw InputError("--history is read by a forecaster: add --forecast gmf");
  p.settings.forecaster = r.forecast;
  for (const std::string& h : r.history) {
    fleet::Dtg g = read_history(h);
    if (g.app != r.app)
      throw InputError(h + ": a history of the " + g.app + " app, not of " + r.app);
    p.settings.histories.push_back(std::move(g));
  }
  return p;
}

namespace {
double r6(double v) {
  return std::round(v * 1e6) / 1e6;
}
}  // namespace

std::string summary_json(const PreparedRun& p, const fleet::RunRecord& r) {
  json drones = json::array();
  for (const auto& d : r.drones)
    drones.push_back(json{{"name", d.name},
                          {"distance_m", r6(d.distance_m)},
                          {"flight_s", r6(d.flight_s)},
                          {"idle_s", r6(d.idle_s)},
                          {"energy_wh", r6(d.energy_wh)},
                          {"final_soc", r6(d.final_soc)}});
  json tasks = json::object();
  for (const auto& [k, v] : r.tasks_by_outcome) tasks[k] = v;
  // Appended, not looked up: r.metrics' names are unique already, and an ordered_json object
  // looks each key up in a line (quadratic in the number of metrics).
  json metrics = json::object();
  auto& metric_items = metrics.get_ref<json::object_t&>();
  metric_items.reserve(r.metrics.size());
  for (const auto& [k, v] : r.metrics) metric_items.emplace_back(k, r6(v));
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx",
                static_cast<unsigned long long>(vehicle::fnv1a(p.config_text)));
  const geometry::Point2 wind = p.settings.wind.velocity_m_s();
  json out{{"app", p.settings.app_name},
           {"version", SWATH_VERSION},
           {"config_hash", hex},
           {"world", p.world->kind()},
           {"world_file", p.world_source},
           {"backend", p.vehicles.empty() ? "sim" : "mavlink"},
           {"completed", r.completed},
           {"completion_time_s", r6(r.completion_time_s)},
           {"end_s", r6(r.end_s)},
           {"scheduler", p.settings.scheduler},
           {"seed", p.settings.seed},
           {"wind_m_s", {r6(wind.x), r6(wind.y)}},
           {"world_seed", p.world->seed},
           {"drones", drones},
           {"tasks", tasks},
           {"schedules", r.schedules},
           {"forecaster", p.settings.forecaster},
           {"histories", p.settings.histories.size()},
           {"speculation",
            {{"positions", r.speculative_positions},
             {"hits", r.speculative_hits},
             {"misses", r.speculative_misses}}},
           {"relief", p.settings.relief},
           {"reliefs", r.reliefs},
           {"requeued", r.requeued},
           {"duplicate_results", r.duplicate_results},
           {"faults", r.faults_happened},
           {"battery_exhausted", r.battery_exhausted},
           {"faults_scheduled", p.settings.faults.size()},
           {"app_metrics", metrics}};
  if (!r.failure.empty()) out["failure"] = r.failure;
  // Which vehicle flew which drone (a real run): the address as --vehicles spells it.
  if (!p.vehicles.empty()) {
    json vehicles = json::array();
    for (std::size_t i = 0; i < p.vehicles.size() && i < r.drones.size(); ++i)
      vehicles.push_back(json{{"drone", r.drones[i].name},
                              {"url", fleet::vehicle_address_text(p.vehicles[i])},
                              {"sysid", p.vehicles[i].sysid}});
    out["vehicles"] = vehicles;
  }
  // What `replay` needs to run it again (the world is world_file and world_seed above).
  json request{{"max_time_s", p.settings.max_time_s}};
  if (!p.fleet_file.empty()) request["fleet_file"] = p.fleet_file;
  if (p.default_drones > 0) request["default_drones"] = p.default_drones;
  if (!p.weights_file.empty()) request["weights_file"] = p.weights_file;
  if (!p.faults_file.empty()) request["faults_file"] = p.faults_file;
  if (!p.history_files.empty()) request["history_files"] = p.history_files;
  out["request"] = request;
  if (!p.replay_of.empty()) out["replay_of"] = p.replay_of;
  return out.dump(2) + "\n";
}

std::string tracks_geojson(const PreparedRun& p, const fleet::RunRecord& r) {
  const geometry::LocalFrame frame(p.world->origin);
  json features = json::array();
  for (std::size_t i = 0; i < r.drones.size(); ++i) {
    // times_s: seconds since the run's start of each vertex, aligned with the coordinates (a
    // property array GIS tools read as it is; a 4th coordinate most of them drop).
    json coords = json::array(), times_s = json::array();
    for (const auto& s : r.drones[i].track) {
      const geometry::GeoPoint g = frame.to_geo({s[1], s[2]});
      coords.push_back({r6(g.lon_deg * 1e1) / 1e1, r6(g.lat_deg * 1e1) / 1e1, r6(s[3])});
      times_s.push_back(r6(s[0]));
    }
    features.push_back(
        json{{"type", "Feature"},
             {"properties", {{"role", "track"}, {"drone", r.drones[i].name}, {"times_s", times_s}}},
             {"geometry", {{"type", "LineString"}, {"coordinates", coords}}}});
  }
  for (const auto& s : r.served) {
    const geometry::GeoPoint g = frame.to_geo({s[1], s[2]});
    features.push_back(
        json{{"type", "Feature"},
             {"properties", {{"role", "sensed"}, {"t_s", r6(s[0])}}},
             {"geometry",
              {{"type", "Point"},
               {"coordinates", {r6(g.lon_deg * 1e1) / 1e1, r6(g.lat_deg * 1e1) / 1e1}}}}});
  }
  return json{{"type", "FeatureCollection"}, {"features", features}}.dump() + "\n";
}

std::string timing_json(const fleet::RunRecord& r) {
  return json{{"schedules", r.schedules},
              {"decision_s_total", r.decision_s_total},
              {"decision_ms_mean", r.schedules > 0 ? 1e3 * r.decision_s_total / r.schedules : 0.0},
              {"forecasts", r.forecasts},
              {"forecast_s_total", r.forecast_s_total},
              {"forecast_ms_mean", r.forecasts > 0 ? 1e3 * r.forecast_s_total / r.forecasts : 0.0}}
             .dump(2) +
         "\n";
}

std::vector<std::string> run_file_names(bool pictures) {
  std::vector<std::string> names{"events.jsonl", "dtg.json", "summary.json", "tracks.geojson",
                                 "timing.json"};
  if (pictures) names.insert(names.end(), {"tracks.png", "gantt.png"});
  return names;
}

void add_run_files(base::OutputSet& set, const PreparedRun& p, const fleet::RunRecord& r) {
  set.add("events.jsonl", r.events_jsonl);
  set.add("dtg.json", r.dtg_json);
  set.add("summary.json", summary_json(p, r));
  set.add("tracks.geojson", tracks_geojson(p, r));
  set.add("timing.json", timing_json(r));
}

}  // namespace swath::apps
