#pragma once
// What swath-fleet's commands read before anything is written: the app by name, the world file
// (or a bundled one), the fleet file, the faults; and the files a run writes.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "swath/base/output_set.hpp"
#include "swath/fleet/runtime.hpp"
#include "swath/worlds/worlds.hpp"

namespace swath::apps {

/// The options every run shares (run, compare).
struct FleetRequest {
  std::string app, world, fleet, scheduler = "sa", faults, weights;
  std::string wind;  ///< "E,N" m/s, empty: calm
  std::uint64_t seed = 1;
  double max_time_s = 3600;
  int drones = 0;  ///< > 0: that many default drones at the world's origin instead of --fleet
  std::string forecast = "none";     ///< gmf | constant-velocity | none
  std::vector<std::string> history;  ///< past runs: directories holding dtg.json, or the files
  bool relief = false;               ///< stand-bys for drones about to leave (docs/swath-fleet.md)
};
/// `required`: APP and --world must be given (false: the command checks them itself, as
/// `tune`, whose ask and tell subcommands read them from a state file).
void add_fleet_options(CLI::App& app, FleetRequest& r, bool with_scheduler, bool required = true);

struct PreparedRun {
  fleet::App app;
  std::unique_ptr<worlds::BaseWorld> world;
  std::vector<fleet::DroneSpec> drones;
  fleet::RuntimeSettings settings;
  std::string world_text, world_source;
  /// Everything that makes runs comparable but the scheduler and the seed: the app, the world's,
  /// fleet's, weights' and faults' text, wind and time limit (summary.json's config_hash).
  std::string config_text;
  /// What summary.json records for `replay` to run it again: the fleet file (absolute) or the
  /// count of default drones, the weights, faults and history files (absolute), the time limit.
  std::string fleet_file, weights_file, faults_file;
  std::vector<std::string> history_files;
  int default_drones = 0;
  /// A trace replay: the run directory it replays ("" for a run of the app itself).
  std::string replay_of;
  /// The vehicles flying the fleet with `run --backend mavlink`, one per drone in fleet order;
  /// empty: the simulated fleet (summary.json's backend: sim).
  std::vector<fleet::VehicleAddress> vehicles;
};
/// What a program makes of each world it has read before a run sees it (swath-fleet with a
/// Python app: sensors of the app's own, python_app.cpp); unset: the world as read.
std::function<std::unique_ptr<worlds::BaseWorld>(std::unique_ptr<worlds::BaseWorld>)>&
world_wrapper();

/// Reads and checks everything (base::InputError on bad input). `world_seed`: re-draws the
/// world's random parts (compare's scenarios) instead of the file's seed.
PreparedRun prepare_run(const FleetRequest& r, std::optional<std::uint64_t> world_seed = {});

/// A past run's DTG: `path` is dtg.json or a run directory holding one.
fleet::Dtg read_history(const std::string& path);

/// The non-empty names of a comma-separated list ("a,b,,c" → a, b, c).
std::vector<std::string> comma_names(const std::string& list);

/// The world file for a name: a path, or a bundled world (share/worlds/NAME.yaml).
std::string world_path(const std::string& name);

/// summary.json, tracks.geojson and timing.json of a finished run.
std::string summary_json(const PreparedRun& p, const fleet::RunRecord& r);
std::string tracks_geojson(const PreparedRun& p, const fleet::RunRecord& r);
std::string timing_json(const fleet::RunRecord& r);
/// The five files of a run (events.jsonl, dtg.json, summary.json, tracks.geojson, timing.json)
/// added to `set` (run and replay write the same set).
void add_run_files(base::OutputSet& set, const PreparedRun& p, const fleet::RunRecord& r);
/// The names add_run_files() writes, and with `pictures` run --render's tracks.png and gantt.png.
std::vector<std::string> run_file_names(bool pictures);

}  // namespace swath::apps
