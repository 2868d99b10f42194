#include "scale_out_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "fleet_inputs.hpp"
#include "shell_text.hpp"
#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/output_set.hpp"
#include "swath/base/yaml_input.hpp"
#include "swath/base/yaml_map.hpp"

namespace swath::apps {

using base::InputError;
namespace fs = std::filesystem;

namespace {

// What a sweep file asks for: one run per (scheduler, seed), everything else shared.
struct SweepSpec {
  FleetRequest base;
  std::vector<std::string> schedulers{"sa"};
  std::uint64_t seed_from = 1, seed_to = 1;
  std::uint64_t histories = 5;  ///< predictive: reactive runs of the other seeds it learns from
};

// A path of the sweep file, relative to the file's folder, made absolute so that the printed
// lines run from any directory; bundled world names stay names.
std::string resolve(const std::string& path, const fs::path& folder) {
  if (path.empty()) return path;
  const fs::path p(path);
  if (p.is_absolute()) return path;
  const fs::path there = folder / p;
  if (fs::exists(there) || path.find('/') != std::string::npos) return fs::absolute(there).string();
  return path;
}

SweepSpec read_sweep(const std::string& source) {
  const std::string text = base::read_text_file(source, "sweep file", base::kMaxConfigFileBytes);
  const YAML::Node doc = base::load_yaml(text, source);
  if (!doc.IsMap()) throw InputError(source + ": a sweep file is a mapping (app, world, ...)");
  base::check_plain_unique_keys(doc, source);
  const base::YamlMap m(doc, source, "");
  m.allow({"app", "world", "fleet", "drones", "schedulers", "seeds", "wind", "weights", "faults",
           "max_time_s", "histories"});
  const fs::path folder = fs::absolute(source).parent_path();
  SweepSpec s;
  s.base.app = m.text("app", "");
  if (s.base.app.empty()) throw InputError(m.where("app") + ": the app to run is missing");
  s.base.world = resolve(m.text("world", ""), folder);
  if (s.base.world.empty()) throw InputError(m.where("world") + ": the world is missing");
  s.base.fleet = resolve(m.text("fleet", ""), folder);
  s.base.drones = static_cast<int>(m.number("drones", 0, 1, 100));
  s.base.wind = m.text("wind", "");
  s.base.weights = resolve(m.text("weights", ""), folder);
  s.base.faults = resolve(m.text("faults", ""), folder);
  s.base.max_time_s = m.number("max_time_s", 3600, 1, 604800);
  if (const YAML::Node list = doc["schedulers"]) {
    if (!list.IsSequence() || list.size() == 0)
      throw InputError(m.where("schedulers") + ": a list of schedulers, e.g. [sa, reactive]");
    s.schedulers.clear();
    for (const auto& n : list) {
      if (!n.IsScalar()) throw InputError(m.where("schedulers") + ": a scheduler is a name");
      // Each scheduler's runs go to their own directories: twice would write one -o twice.
      if (std::find(s.schedulers.begin(), s.schedulers.end(), n.Scalar()) != s.schedulers.end())
        throw InputError(m.where("schedulers") + ": \"" + n.Scalar() + "\" appears twice");
      s.schedulers.push_back(n.Scalar());
    }
  }
  const base::YamlMap seeds = m.map("seeds");
  seeds.allow({"from", "to"});
  s.seed_from = static_cast<std::uint64_t>(seeds.number("from", 1, 0, 9007199254740991.0));
  s.seed_to =
      static_cast<std::uint64_t>(seeds.number("to", double(s.seed_from), 0, 9007199254740991.0));
  if (s.seed_to < s.seed_from)
    throw InputError(seeds.where("to") + ": the last seed comes before the first");
  if (s.seed_to - s.seed_from >= 100000)
    throw InputError(seeds.where("to") + ": more than 100,000 seeds in one sweep");
  s.histories = static_cast<std::uint64_t>(m.number("histories", 5, 1, 1000));
  const bool predictive =
      std::find(s.schedulers.begin(), s.schedulers.end(), "predictive") != s.schedulers.end();
  if (predictive && s.seed_to == s.seed_from)
    throw InputError(seeds.where("to") +
                     ": predictive learns from the reactive runs of the other seeds: give at "
                     "least two seeds");
  return s;
}

}  // namespace

void FleetSweepCommand::setup(CLI::App& app) {
  app.add_option(
         "SPEC", spec_,
         "Sweep file (YAML): app, world, fleet or drones, schedulers [list], seeds "
         "{from, to}, and optionally wind, weights, faults, max_time_s, histories (predictive's "
         "reactive runs, default 5); paths relative to the file; each line's world is "
         "drawn from its seed (--world-seed)")
      ->required();
  app.add_option("--runs", runs_dir_,
                 "Directory the runs' own directories go into (written absolute in the lines)")
      ->capture_default_str();
  app.add_option("--part", part_,
                 "all: every line; histories: the reactive runs predictive learns from; runs: "
                 "every other line (with predictive, print and run histories first, then runs)")
      ->check(CLI::IsMember({"all", "histories", "runs"}))
      ->capture_default_str();
  app.add_option("--program", program_,
                 "The swath-fleet to name in the lines (default: this one's absolute path; give "
                 "the remote path for --sshloginfile hosts)");
}

namespace {

// A run's directory in the sweep: --runs DIR/<app>-<scheduler>-seed<N>.
std::string run_dir(const std::string& runs, const std::string& app, const std::string& scheduler,
                    std::uint64_t seed) {
  return runs + "/" + app + "-" + scheduler + "-seed" + std::to_string(seed);
}

// The reactive runs predictive's `seed` learns from: the next `histories` seeds of the sweep
// (cyclic), never its own, as compare's predictive.
std::vector<std::uint64_t> history_seeds(const SweepSpec& spec, std::uint64_t seed) {
  const std::uint64_t count = spec.seed_to - spec.seed_from + 1;
  std::vector<std::uint64_t> out;
  for (std::uint64_t i = 1; i < count && out.size() < spec.histories; ++i)
    out.push_back(spec.seed_from + (seed - spec.seed_from + i) % count);
  return out;
}

// One `swath-fleet run` line: the world drawn from the run's seed (--world-seed, as compare's
// scenarios), predictive as sa + GMF over its history runs + relief.
std::string run_line(const SweepSpec& spec, const std::string& program, const std::string& runs,
                     const std::string& scheduler, std::uint64_t seed) {
  const FleetRequest& r = spec.base;
  std::ostringstream out;
  out << shell_word(program) << " run " << shell_word(r.app) << " --world " << shell_word(r.world)
      << " --world-seed " << seed;
  if (!r.fleet.empty()) out << " --fleet " << shell_word(r.fleet);
  if (r.drones > 0) out << " --drones " << r.drones;
  if (scheduler == "predictive") {
    out << " --scheduler sa --seed " << seed << " --forecast gmf";
    for (const std::uint64_t h : history_seeds(spec, seed))
      out << " --history " << shell_word(run_dir(runs, r.app, "reactive", h));
    out << " --relief";
  } else {
    out << " --scheduler " << shell_word(scheduler) << " --seed " << seed;
  }
  if (!r.wind.empty()) out << " --wind " << shell_word(r.wind);
  if (!r.weights.empty()) out << " --weights " << shell_word(r.weights);
  if (!r.faults.empty()) out << " --faults " << shell_word(r.faults);
  out << " --max-time " << base::shortest_text(r.max_time_s);
  out << " -o " << shell_word(run_dir(runs, r.app, scheduler, seed)) << "\n";
  return out.str();
}

}  // namespace

int FleetSweepCommand::run() {
  const SweepSpec spec = read_sweep(spec_);
  for (const std::string& scheduler : spec.schedulers) {  // everything checked before a line
    FleetRequest r = spec.base;
    r.scheduler = scheduler == "predictive" ? "sa" : scheduler;
    prepare_run(r);
  }
  const bool predictive = std::find(spec.schedulers.begin(), spec.schedulers.end(), "predictive") !=
                          spec.schedulers.end();
  if (predictive && part_ == "all")
    throw InputError(spec_ +
                     ": predictive learns from reactive runs that must have finished first: "
                     "print them with --part histories, run them, then --part runs");
  if (!predictive && part_ != "all")
    throw InputError("--part " + part_ + ": only a sweep with predictive comes in parts");
  // The histories are reactive's runs: with predictive, reactive's lines are the histories part.
  std::vector<std::string> schedulers;
  if (part_ == "histories") schedulers.push_back("reactive");
  for (const std::string& s : spec.schedulers)
    if (part_ == "all" || (part_ == "runs" && s != "reactive")) schedulers.push_back(s);
  const std::string program = program_.empty() ? own_program_path("swath-fleet") : program_;
  std::string runs = fs::absolute(runs_dir_).lexically_normal().string();
  while (runs.size() > 1 && runs.back() == '/') runs.pop_back();
  std::ostringstream out;
  for (const std::string& scheduler : schedulers)
    for (std::uint64_t seed = spec.seed_from; seed <= spec.seed_to; ++seed)
      out << run_line(spec, program, runs, scheduler, seed);
  std::cout << out.str();
  return base::kExitSuccess;
}

void FleetCollectCommand::setup(CLI::App& app) {
  app.add_option("RUN", runs_, "Run directories (or their summary.json)")->required();
  app.add_option("-o,--output", output_, "Directory for collect.csv")->required();
}

namespace {

struct CollectedRun {
  std::string run, app, scheduler, version, config_hash;
  std::string backend = "sim";  ///< summary.json's backend (absent before it was recorded: sim)
  std::uint64_t seed = 0;
  bool completed = false;
  double completion_time_s = 0, energy_wh = 0, distance_m = 0;
  long long done = 0, cancelled = 0, failed = 0, requeued = 0, duplicates = 0;
};

CollectedRun read_run(const std::string& run) {
  const std::string path = fs::is_directory(run) ? (fs::path(run) / "summary.json").string() : run;
  const nlohmann::json j = base::parse_json_document(
      base::read_text_file(path, "run summary", base::kMaxConfigFileBytes), path);
  CollectedRun c;
  c.run = run;
  const auto text = [&](const char* key) {
    return base::json_string(base::json_member(j, key, path), path + ": " + key);
  };
  const auto number = [&](const nlohmann::json& o, const char* key) {
    return base::json_number(base::json_member(o, key, path), path + ": " + key);
  };
  if (!base::json_find(j, "version") || !base::json_find(j, "config_hash"))
    throw InputError(path +
                     ": no version or config_hash: a run of a swath-fleet older than "
                     "collect; run it again");
  c.version = text("version");
  c.config_hash = text("config_hash");
  c.app = text("app");
  c.scheduler = text("scheduler");
  if (base::json_find(j, "backend")) c.backend = text("backend");
  c.seed = static_cast<std::uint64_t>(base::json_integer(base::json_member(j, "seed", path), 0,
                                                         9007199254740992LL, path + ": seed"));
  const nlohmann::json& completed = base::json_member(j, "completed", path);
  if (!completed.is_boolean()) throw InputError(path + ": completed: expected true or false");
  c.completed = completed.get<bool>();
  c.completion_time_s = number(j, "completion_time_s");
  for (const auto& d : base::json_array(base::json_member(j, "drones", path), path + ": drones")) {
    c.energy_wh += number(d, "energy_wh");
    c.distance_m += number(d, "distance_m");
  }
  // Each finite, the sums may still overflow: refused rather than written as inf.
  if (!std::isfinite(c.energy_wh) || !std::isfinite(c.distance_m))
    throw InputError(path +
                     ": drones: the drones' energy_wh or distance_m add up to more than "
                     "a finite number");
  // A predictive run (sa + GMF + relief) is a scheduler of its own in the table, as in compare.
  const nlohmann::json* forecaster = base::json_find(j, "forecaster");
  const nlohmann::json* relief = base::json_find(j, "relief");
  const std::string forecast =
      forecaster ? base::json_string(*forecaster, path + ": forecaster") : "none";
  const bool relieved = relief && relief->is_boolean() && relief->get<bool>();
  if (c.scheduler == "sa" && forecast == "gmf" && relieved)
    c.scheduler = "predictive";
  else
    c.scheduler += (forecast == "none" ? "" : "+" + forecast) + (relieved ? "+relief" : "");
  const nlohmann::json& tasks = base::json_member(j, "tasks", path);
  const auto count = [&](const nlohmann::json& o, const char* key) -> long long {
    const nlohmann::json* v = base::json_find(o, key);
    return v ? base::json_integer(*v, 0, 1LL << 53, path + ": " + key) : 0;
  };
  c.done = count(tasks, "done");
  c.cancelled = count(tasks, "cancelled");
  c.failed = count(tasks, "failed");
  c.requeued = count(j, "requeued");
  c.duplicates = count(j, "duplicate_results");
  return c;
}

}  // namespace

int FleetCollectCommand::run() {
  base::check_output_names(output_, "fleet-collect", {"collect.csv"});
  std::vector<CollectedRun> runs;
  for (const std::string& r : runs_) runs.push_back(read_run(r));
  const CollectedRun& first = runs.front();
  std::map<std::pair<std::string, std::uint64_t>, std::string> seen;
  for (const CollectedRun& r : runs) {
    if (r.version != first.version)
      throw InputError(r.run + ": made by swath-fleet " + r.version + ", " + first.run + " by " +
                       first.version + ": collect merges runs of one version");
    if (r.config_hash != first.config_hash || r.app != first.app)
      throw InputError(r.run + ": another configuration than " + first.run + " (config_hash " +
                       r.config_hash + " vs " + first.config_hash +
                       ": app, world, fleet, weights, faults, wind or time limit differ)");
    // A real flight's time is not a simulated one's: one backend per table.
    if (r.backend != first.backend)
      throw InputError(r.run + ": flown with the " + r.backend + " backend, " + first.run +
                       " with " + first.backend + ": collect merges runs of one backend");
    const auto [it, fresh] = seen.emplace(std::make_pair(r.scheduler, r.seed), r.run);
    if (!fresh)
      throw InputError(r.run + ": the same scheduler (" + r.scheduler + ") and seed (" +
                       std::to_string(r.seed) + ") as " + it->second);
  }
  std::sort(runs.begin(), runs.end(), [](const CollectedRun& a, const CollectedRun& b) {
    return std::tie(a.scheduler, a.seed) < std::tie(b.scheduler, b.seed);
  });
  std::ostringstream csv;
  csv << "run,app,scheduler,seed,completed,completion_time_s,energy_wh,distance_m,tasks_done,"
         "tasks_cancelled,tasks_failed,requeued,duplicate_results\n";
  std::map<std::string, int> per_scheduler;
  for (const CollectedRun& r : runs) {
    ++per_scheduler[r.scheduler];
    csv << csv_field(r.run) << "," << r.app << "," << r.scheduler << "," << r.seed << ","
        << (r.completed ? "true" : "false") << "," << base::fixed_text(r.completion_time_s, 3)
        << "," << base::fixed_text(r.energy_wh, 6) << "," << base::fixed_text(r.distance_m, 3)
        << "," << r.done << "," << r.cancelled << "," << r.failed << "," << r.requeued << ","
        << r.duplicates << "\n";
  }
  base::OutputSet set(output_, "fleet-collect");
  set.add("collect.csv", csv.str());
  set.commit();
  std::cout << "collect: " << runs.size() << " runs of " << first.app << " (";
  bool comma = false;
  for (const auto& [s, n] : per_scheduler) {
    std::cout << (comma ? ", " : "") << s << " " << n;
    comma = true;
  }
  std::cout << "), swath-fleet " << first.version << " -> " << output_ << "/collect.csv\n";
  return base::kExitSuccess;
}

}  // namespace swath::apps
