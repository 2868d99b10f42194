#include "replay_command.hpp"

#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "seed_option.hpp"
#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/output_set.hpp"
#include "swath/fleet/trace_replay.hpp"

namespace swath::apps {

using base::InputError;
namespace fs = std::filesystem;

namespace {

struct RecordedRun {
  nlohmann::json summary;
  std::string summary_path, dtg_path, dtg_text;
};

RecordedRun read_recorded(const std::string& run) {
  RecordedRun r;
  if (!fs::is_directory(run))
    throw InputError(run + ": not a run directory (swath-fleet run -o DIR makes one)");
  r.summary_path = (fs::path(run) / "summary.json").string();
  r.dtg_path = (fs::path(run) / "dtg.json").string();
  if (!fs::exists(r.summary_path) || !fs::exists(r.dtg_path))
    throw InputError(run + ": not a run directory: no summary.json or dtg.json in it");
  r.summary = base::parse_json_document(
      base::read_text_file(r.summary_path, "run summary", base::kMaxConfigFileBytes),
      r.summary_path);
  r.dtg_text = base::read_text_file(r.dtg_path, "task graph (dtg.json)");
  return r;
}

std::string text_of(const nlohmann::json& j, const char* key, const std::string& where) {
  return base::json_string(base::json_member(j, key, where), where + ": " + key);
}

}  // namespace

PreparedRun prepare_replay(const std::string& run, const ReplayOverrides& o) {
  const RecordedRun rec = read_recorded(run);
  const std::string& where = rec.summary_path;
  const nlohmann::json& s = rec.summary;
  FleetRequest r;
  r.app = text_of(s, "app", where);
  if (const std::string why = fleet::schedule_dependence(r.app); !why.empty() && !o.force)
    throw InputError(run + ": not replayed: " + why +
                     " (--force replays the recorded graph "
                     "anyway)");
  r.world = text_of(s, "world_file", where);
  const auto seed_of = [&](const char* key) {
    return static_cast<std::uint64_t>(base::json_integer(base::json_member(s, key, where), 0,
                                                         9007199254740992LL, where + ": " + key));
  };
  const std::uint64_t world_seed = seed_of("world_seed");
  r.seed = o.seed_given ? o.seed : seed_of("seed");
  r.scheduler = o.scheduler.empty() ? text_of(s, "scheduler", where) : o.scheduler;
  const nlohmann::json* request = base::json_find(s, "request");
  if (!request)
    throw InputError(where +
                     ": no request (fleet, time limit): a run of a swath-fleet older "
                     "than replay; run it again");
  const auto file_of = [&](const char* key) -> std::string {
    const nlohmann::json* f = base::json_find(*request, key);
    return f ? base::json_string(*f, where + ": request: " + key) : "";
  };
  if (!o.fleet.empty() || o.drones > 0) {
    r.fleet = o.fleet;
    r.drones = o.drones;
  } else {
    r.fleet = file_of("fleet_file");
    if (const nlohmann::json* n = base::json_find(*request, "default_drones"))
      r.drones = static_cast<int>(base::json_integer(*n, 1, 100, where + ": default_drones"));
  }
  r.weights = o.weights.empty() ? file_of("weights_file") : o.weights;
  r.faults = file_of("faults_file");
  r.max_time_s = base::json_number(base::json_member(*request, "max_time_s", where),
                                   where + ": request: max_time_s");
  const auto& wind = base::json_array(base::json_member(s, "wind_m_s", where), where, 2);
  const double east = base::json_number(wind[0], where + ": wind_m_s");
  const double north = base::json_number(wind[1], where + ": wind_m_s");
  if (east != 0 || north != 0)
    r.wind = base::shortest_text(east) + "," + base::shortest_text(north);
  // Forecasts: the options', else the run's own (its history files, as it read them).
  r.forecast = o.forecast.empty() ? text_of(s, "forecaster", where) : o.forecast;
  if (!o.history.empty()) {
    r.history = o.history;
  } else if (o.forecast.empty() || o.forecast == text_of(s, "forecaster", where)) {
    if (const nlohmann::json* h = base::json_find(*request, "history_files"))
      for (std::size_t i = 0; i < h->size(); ++i)
        r.history.push_back(base::json_string((*h)[i], where + ": history_files"));
  }
  if (r.forecast != "none" && r.scheduler != "sa") r.forecast = "none", r.history.clear();
  const nlohmann::json* relief = base::json_find(s, "relief");
  r.relief = o.relief || (relief && relief->is_boolean() && relief->get<bool>());

  PreparedRun p = prepare_run(r, world_seed);
  fleet::Dtg dtg = fleet::parse_dtg(rec.dtg_text, rec.dtg_path);
  if (dtg.app != r.app)
    throw InputError(rec.dtg_path + ": a graph of the " + dtg.app + " app in a run of " + r.app);
  try {
    p.app = fleet::make_trace_app(dtg);
  } catch (const InputError& why) {
    throw InputError(rec.dtg_path + ": " + why.what());
  }
  p.replay_of = fs::absolute(run).lexically_normal().string();
  p.config_text += "\ntrace replay\n" + rec.dtg_text;
  return p;
}

void FleetReplayCommand::setup(CLI::App& app) {
  app.add_option("RUN", runs_,
                 "Run directories (swath-fleet run -o DIR), each with dtg.json and "
                 "summary.json")
      ->required();
  app.add_option("-o,--output", output_,
                 "Directory for the replay's files (several runs: a directory per run in it, "
                 "named as the run's)")
      ->required();
  app.add_option("--scheduler", o_.scheduler,
                 "sa, reactive, greedy, round-robin, hungarian (default: the run's)");
  app.add_option("--weights", o_.weights, "Weights file (default: the run's)");
  app.add_option("--fleet", o_.fleet, "Fleet file (default: the run's fleet)");
  app.add_option("--drones", o_.drones, "Instead of --fleet: N default drones")
      ->check(CLI::Range(1, 100));
  seed_option_ = app.add_option("--seed", o_.seed, "The scheduler's seed (default: the run's)")
                     ->check(seed_check());
  app.add_option("--forecast", o_.forecast, "gmf, constant-velocity or none (default: the run's)");
  app.add_option("--history", o_.history, "Past runs for gmf (default: the run's)");
  app.add_flag("--relief", o_.relief, "Relief on (default: as the run had it)");
  app.add_flag("--force", o_.force,
               "Replay also a run whose graph depends on the schedule (case 2 wifi): its "
               "recorded cancels are played as recorded");
}

// Where the replay of runs_[i] goes: -o, or with several runs a directory in it named as the run.
fs::path FleetReplayCommand::output_directory(std::size_t i) const {
  fs::path dir = output_;
  if (runs_.size() > 1) {
    const fs::path run = fs::path(runs_[i]).lexically_normal();
    dir /= run.filename().empty() ? run.parent_path().filename() : run.filename();
  }
  return dir;
}

int FleetReplayCommand::run() {
  o_.seed_given = seed_option_->count() > 0;
  if (!o_.fleet.empty() && o_.drones > 0) throw InputError("give --fleet or --drones, not both");
  // Every run read and checked before any is replayed: one swath version, one name each.
  std::vector<PreparedRun> prepared;
  std::map<std::string, std::string> version_of, name_of;
  std::string first_version;
  for (const std::string& run : runs_) {
    const std::string path = (fs::path(run) / "summary.json").string();
    prepared.push_back(prepare_replay(run, o_));
    const nlohmann::json s = base::parse_json_document(
        base::read_text_file(path, "run summary", base::kMaxConfigFileBytes), path);
    const std::string version = text_of(s, "version", path);
    if (first_version.empty()) first_version = version;
    if (version != first_version)
      throw InputError(run + ": made by swath-fleet " + version + ", " + runs_.front() + " by " +
                       first_version + ": replay runs of one version together");
    const std::string name =
        fs::path(run).lexically_normal().filename().string().empty()
            ? fs::path(run).lexically_normal().parent_path().filename().string()
            : fs::path(run).lexically_normal().filename().string();
    if (runs_.size() > 1 && !name_of.emplace(name, run).second)
      throw InputError(run + ": the same directory name as " + name_of[name] +
                       ": their replays would share " + output_ + "/" + name);
  }
  // Every replay's directory checked before the first is written: a refusal writes nothing.
  for (std::size_t i = 0; i < runs_.size(); ++i)
    base::check_output_names(output_directory(i), "fleet-run", run_file_names(false));
  int incomplete = 0;
  for (std::size_t i = 0; i < runs_.size(); ++i) {
    PreparedRun& p = prepared[i];
    const fleet::RunRecord r = fleet::run_app(p.app, *p.world, p.drones, p.settings);
    const fs::path dir = output_directory(i);
    base::OutputSet set(dir, "fleet-run");
    add_run_files(set, p, r);
    set.commit();
    std::cout << runs_[i] << ": trace replay ";
    if (r.completed)
      std::cout << "completed in " << base::fixed_text(r.completion_time_s, 1) << " s";
    else
      std::cout << "did not complete (" << r.failure << ")", ++incomplete;
    std::cout << " with " << p.drones.size() << " drone" << (p.drones.size() == 1 ? "" : "s")
              << " (" << p.settings.scheduler << ") -> " << dir.string() << "\n";
  }
  return incomplete > 0 ? base::kExitNotCompleted : base::kExitSuccess;
}

}  // namespace swath::apps
