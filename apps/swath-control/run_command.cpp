#include "run_command.hpp"

#include <filesystem>
#include <iostream>

#include "control_images.hpp"
#include "data_dir.hpp"
#include "input_text.hpp"
#include "map_furniture.hpp"
#include "progress_bar.hpp"
#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/output_set.hpp"
#include "swath/control/config.hpp"
#include "swath/control/control_files.hpp"
#include "swath/control/simulation.hpp"
#include "swath/energy/sim_config.hpp"

namespace swath::apps {
namespace {

using base::InputError;
namespace fs = std::filesystem;

// A configuration given as a file path or as the name of one in share/<folder>/.
struct ConfigFile {
  std::string name;  ///< as summary.json names it
  std::string source, text;
};

ConfigFile config_file(const std::string& given, const std::string& folder, const std::string& what,
                       const std::string& flag) {
  fs::path path = given;
  std::error_code ec;
  if (!fs::exists(path, ec) && given.find('/') == std::string::npos &&
      fs::path(given).extension().empty())
    path = share_dir() / folder / (given + ".yaml");
  if (!fs::exists(path, ec)) {
    std::string names;
    for (const auto& e : fs::directory_iterator(share_dir() / folder, ec))
      if (e.path().extension() == ".yaml")
        names += (names.empty() ? "" : ", ") + e.path().stem().string();
    throw InputError(flag + " " + given + ": no such " + what + " file, and no bundled " + what +
                     " of that name (bundled: " + names + ")");
  }
  return {path.stem().string(), path.string(),
          base::read_text_file(path, what + " file", base::kMaxConfigFileBytes)};
}

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

void warn(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) std::cerr << "swath-control run: warning: " << w << '\n';
}

// Rows into the streams as they come; a bounded copy for the pictures.
class Recorder : public control::SimulationObserver {
 public:
  Recorder(base::OutputSet::Stream& rows, base::OutputSet::Stream& seconds, ProgressBar& bar)
      : rows_(rows), seconds_(seconds), bar_(bar) {}
  void on_row(const control::TimeseriesRow& row) override {
    rows_ << control::timeseries_csv_row(row);
    kept_.add(row);
  }
  void on_second(const control::RateRow& row) override {
    seconds_ << control::rate_csv_row(row);
    rates_.push_back(row);
  }
  void on_progress(double fraction) override { bar_.update(fraction); }
  const FlightSeries& kept() const { return kept_; }
  const std::vector<control::RateRow>& rates() const { return rates_; }

 private:
  base::OutputSet::Stream& rows_;
  base::OutputSet::Stream& seconds_;
  ProgressBar& bar_;
  FlightSeries kept_;
  std::vector<control::RateRow> rates_;
};

}  // namespace

void ControlRunCommand::setup(CLI::App& app) {
  app.add_option("MISSION", mission_,
                 "swath's mission.geojson, a QGC .plan or .waypoints (one drone: --drone), a stage "
                 "plan (.stages or .yaml), or random:N@WxH (N waypoints in a W by H metre box; the "
                 "paper's missions are random:8@20x20, random:8@100x70, random:8@170x170)")
      ->required();
  app.add_option("-o,--output", output_,
                 "Directory for timeseries.csv, rate.csv, summary.json and the pictures")
      ->required();
  app.add_option("--vehicle", vehicle_,
                 "Vehicle file, or a bundled one: quad-f450, hexa-f550, y6, quad-f450-cc3d")
      ->capture_default_str();
  app.add_option("--scheduler", scheduler_, "Scheduler file, or a bundled one: tt-400")
      ->capture_default_str();
  app.add_option("--environment", environment_,
                 "Wind: calm, lab, rugby, arch (paper 002's places) or an environment file")
      ->capture_default_str();
  app.add_option("--seed", seed_, "Seed of every noise source (wind, sensors, random missions)")
      ->capture_default_str();
  app.add_flag("--loop", loop_,
               "Repeat the mission until the battery reaches its reserve (paper 002 §7)");
  app.add_option("--speed", speed_m_s_,
                 "Cruise speed along the legs, m/s (default: the mission file's, else the "
                 "vehicle's controller.limits.max_speed_m_s)");
  app.add_option("--altitude", altitude_m_,
                 "Fly every point at this height above home, m (default: the file's; random and "
                 "stage plans 5 m)");
  app.add_option("--drone", drone_, "The drone of a fleet plan: its name or number (default: 1)");
  app.add_option("--start", start_,
                 "Stage plans: the take-off point X,Y in the plan's local metres (default 0,0)");
  app.add_option("--max-time", max_time_s_,
                 "Stop after this many simulated seconds (default: the scheduler's "
                 "run.max_time_s, 14400)");
  app.add_option("--set", sets_,
                 "Override a key of the vehicle, scheduler or environment file, e.g. "
                 "vehicle.controller.position_p=1.2, scheduler.rate_hz=200, "
                 "environment.mean_wind.speed_m_s=6 (repeatable)");
  app.add_option("--size", size_, "Size of the pictures, WxH pixels")->capture_default_str();
  app.add_flag("--no-pictures", no_pictures_,
               "Write the CSV files and summary.json only (drawing costs ~0.5 s and ~300 MB of "
               "memory for the OpenGL renderer, whatever the flight's length)");
  app.add_flag("--progress", progress_, "Show a progress bar (only on a terminal)");
}

int ControlRunCommand::run() {
  // 1. Inputs, each checked before anything is written.
  const auto [width_px, height_px] = parse_size(size_);
  control::SimulationSettings settings;
  settings.seed = seed_;
  settings.loop = loop_;
  ConfigFile vehicle = config_file(vehicle_, "vehicles", "vehicle", "--vehicle");
  override_file(vehicle, overrides_for(sets_, "vehicle"));
  settings.physics = vehicle::parse_vehicle(vehicle.text, vehicle.source);
  warn(settings.physics.warnings);
  settings.control = control::parse_vehicle_control(vehicle.text, vehicle.source);
  settings.battery = energy::parse_battery_section(vehicle.text, vehicle.source);
  ConfigFile scheduler = config_file(scheduler_, "schedulers", "scheduler", "--scheduler");
  override_file(scheduler, overrides_for(sets_, "scheduler"));
  settings.scheduler = control::parse_scheduler_config(scheduler.text, scheduler.source);
  if (max_time_s_) {
    if (!(*max_time_s_ > 0 && *max_time_s_ <= 86'400))
      throw InputError("--max-time " + base::shortest_text(*max_time_s_) +
                       ": expected seconds in (0, 86400]");
    settings.scheduler.run.max_time_s = *max_time_s_;
  }
  ConfigFile environment =
      config_file(environment_, "environments", "environment", "--environment");
  override_file(environment, overrides_for(sets_, "environment"));
  settings.environment = vehicle::parse_environment(environment.text, environment.source);
  warn(settings.environment.warnings);

  control::MissionOptions options;
  options.drone = drone_;
  if (altitude_m_ && !(*altitude_m_ > 0 && *altitude_m_ <= 1000))
    throw InputError("--altitude " + base::shortest_text(*altitude_m_) +
                     ": expected metres in (0, 1000]");
  options.altitude_m = altitude_m_.value_or(0.0);
  if (!start_.empty()) {
    const auto xy = parse_number_pair(start_, ',');
    if (!xy) throw InputError("--start " + start_ + ": expected X,Y in metres, e.g. 25,146");
    options.start_m = {xy->first, xy->second};
  }
  if (speed_m_s_ && !(*speed_m_s_ > 0 && *speed_m_s_ <= 30))
    throw InputError("--speed " + base::shortest_text(*speed_m_s_) +
                     ": expected m/s in (0, 30] for a multirotor");
  if (speed_m_s_) options.stage_speed_m_s = *speed_m_s_;
  std::vector<std::string> warnings;
  settings.mission = control::read_flight_mission(mission_, options, seed_, &warnings);
  warn(warnings);
  settings.speed_m_s = speed_m_s_ ? *speed_m_s_
                       : settings.mission.speed_m_s > 0
                           ? settings.mission.speed_m_s
                           : settings.control.controller.limits.max_speed_m_s;
  if (loop_) settings.mission = control::closed_for_loop(std::move(settings.mission));

  // 2. The flight, its rows streamed into the output set's temporaries.
  base::OutputSet set(output_, "control-run");
  base::OutputSet::Stream& rows = set.stream("timeseries.csv");
  base::OutputSet::Stream& seconds = set.stream("rate.csv");
  const std::vector<std::string> triggers = control::trigger_sensor_names(settings.physics);
  rows << control::timeseries_csv_header(settings.physics.airframe.rotors.size());
  seconds << control::rate_csv_header(triggers);
  control::SimulationSummary summary;
  FlightSeries kept;
  {
    ProgressBar bar(progress_, "flying");
    Recorder recorder(rows, seconds, bar);
    summary = control::simulate(settings, &recorder);
    kept = recorder.kept();
  }

  // 3. The summary and the pictures; everything appears at once.
  const control::SummaryInputs inputs{
      settings.mission.name, vehicle.name, scheduler.name, environment.name, seed_,
      settings.speed_m_s,    loop_};
  set.add("summary.json", control::summary_json(summary, inputs, settings));
  if (!no_pictures_) add_control_images(set, settings, summary, kept, width_px, height_px);
  set.commit();

  using base::fixed_text;
  std::cout << "swath-control run: " << control::to_string(summary.status);
  if (!summary.lost_control_reason.empty()) std::cout << " (" << summary.lost_control_reason << ")";
  std::cout << " after " << fixed_text(summary.flight_time_s, 1) << " s, cross-track RMS "
            << fixed_text(summary.cross_track_m.rms, 2) << " m (max "
            << fixed_text(summary.cross_track_m.max, 2) << " m), "
            << fixed_text(summary.executions.per_second_mean, 1) << " executions/s, "
            << fixed_text(summary.total_j / 3600, 2) << " Wh, SoC "
            << fixed_text(100 * summary.final_soc, 1) << " %";
  if (summary.min_clearance_m)
    std::cout << ", least clearance to no-fly zones " << fixed_text(*summary.min_clearance_m, 2)
              << " m";
  std::cout << "; wrote " << output_ << '\n';
  switch (summary.status) {
    case control::FlightStatus::battery_empty:
      return base::kExitNotCompleted;
    case control::FlightStatus::lost_control:
      return base::kExitLostControl;
    default:
      return base::kExitSuccess;
  }
}

}  // namespace swath::apps
