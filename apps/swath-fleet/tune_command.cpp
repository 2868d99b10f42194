#include "tune_command.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "intervals.hpp"
#include "progress_bar.hpp"
#include "seed_option.hpp"
#include "shell_text.hpp"
#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/output_set.hpp"
#include "swath/fleet/dtg.hpp"
#include "swath/fleet/runtime.hpp"
#include "swath/fleet/trace_replay.hpp"
#include "swath/fleet/tuning.hpp"

namespace swath::apps {

using base::InputError;
using json = nlohmann::ordered_json;

void FleetTuneCommand::add_tune_options(CLI::App& app, bool required) {
  add_fleet_options(app, request_, false, required);
  app.add_option("--trials", trials_,
                 "Weight sets to try (the defaults, or --weights, and reactive's among them)")
      ->check(CLI::Range(2, 4096))
      ->capture_default_str();
  app.add_option("--tuning-seeds", tuning_seeds_,
                 "Seeds of the successive halving: after each, the better half of the trials "
                 "goes on to the next")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  app.add_option("--held-out", held_out_,
                 "Seeds the winner, the defaults and reactive are scored on (never tuned on)")
      ->check(CLI::Range(2, 1000))
      ->capture_default_str();
  app.add_option("--histories", histories_, "Reactive runs GMF learns from, on seeds of their own")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_option("-o,--output", output_,
                 "Directory for weights.yaml, tune.csv, held_out.csv and summary.json")
      ->required(required);
}

void FleetTuneCommand::setup(CLI::App& app) {
  // APP, --world and -o are checked in run(): ask and tell read them from their state file.
  add_tune_options(app, false);
  app.add_option("--replay", replay_,
                 "How a trial is scored: world (the app re-run in its world) or trace (the "
                 "tuning seed's reactive run replayed from its dtg.json; not for wifi)")
      ->check(CLI::IsMember({"world", "trace"}))
      ->capture_default_str();
  ask_ = app.add_subcommand(
      "ask",
      "Print the next rung's runs as swath-fleet command lines, one per line (creating STATE, "
      "a JSON file, from APP and the options when it does not exist)");
  ask_->add_option("STATE", state_, "The tuning's state file (JSON)")->required();
  add_tune_options(*ask_, false);
  ask_->add_option("--runs", runs_dir_,
                   "Directory the runs go into (default: STATE's name with -runs)");
  ask_->add_option("--program", program_,
                   "The swath-fleet to name in the lines (default: this one's absolute path)");
  tell_ = app.add_subcommand("tell",
                             "Feed finished runs (directories ask named) back into STATE; after "
                             "the last rung write weights.yaml and tune.csv to the output, after "
                             "the held-out runs held_out.csv and summary.json");
  tell_->add_option("STATE", state_, "The tuning's state file (JSON)")->required();
  tell_->add_option("RUN", told_runs_, "Run directories of the lines ask printed")->required();
}

namespace {

using fleet::FreeWeight;
using fleet::Trial;

// The files a tuning writes into its -o directory (the last step of tune ask/tell too).
std::vector<std::string> tune_file_names() {
  return {"weights.yaml", "tune.csv", "held_out.csv", "summary.json"};
}

// Completion times on the held-out seeds, per configuration.
struct HeldOut {
  std::vector<double> reactive, start, tuned;
  std::string csv = "seed,reactive_s,predictive_default_s,predictive_tuned_s\n";
};

// The tuning's steps over one request: seeds in three disjoint ranges from --seed (histories,
// tuning, held out), every run a world replay of the app.
class Tuning {
 public:
  Tuning(const FleetRequest& r, std::size_t histories, int tuning_seeds, int held_out, bool trace)
      : request_(r),
        trace_(trace),
        history_count_(histories),
        tuning_seeds_(tuning_seeds),
        held_out_(held_out),
        tune0_(r.seed + histories),
        held0_(tune0_ + static_cast<std::uint64_t>(tuning_seeds)),
        progress_(true, "tune " + r.app) {}

  void learn_histories() {
    for (std::size_t k = 0; k < history_count_; ++k)
      histories_.push_back(fleet::parse_dtg(
          run_once("reactive", nullptr, request_.seed + k).dtg_json, "history dtg.json"));
  }

  // Successive halving (fleet::successive_halving) over the tuning seeds, each trial's run a
  // predictive world replay (or trace replay) of the app.
  std::size_t halve(std::vector<Trial>& trials) {
    expected_runs_ = 3.0 * held_out_;
    for (double a = static_cast<double>(trials.size()), k = 0; k < tuning_seeds_;
         ++k, a = std::ceil(a / 2))
      expected_runs_ += a;
    return fleet::successive_halving(trials, tuning_seeds_, [&](std::size_t i, int k) {
      return time_of(
          run_once("predictive", &trials[i].weights, tune0_ + static_cast<std::uint64_t>(k)));
    });
  }

  // Reactive, predictive with the starting weights and with the winner's, on the held-out seeds.
  HeldOut score(const fleet::Weights& start, const fleet::Weights& tuned) {
    HeldOut h;
    for (int k = 0; k < held_out_; ++k) {
      const std::uint64_t seed = held0_ + static_cast<std::uint64_t>(k);
      h.reactive.push_back(time_of(run_once("reactive", nullptr, seed)));
      h.start.push_back(time_of(run_once("predictive", &start, seed)));
      h.tuned.push_back(time_of(run_once("predictive", &tuned, seed)));
      h.csv += std::to_string(seed) + "," + base::fixed_text(h.reactive.back(), 3) + "," +
               base::fixed_text(h.start.back(), 3) + "," + base::fixed_text(h.tuned.back(), 3) +
               "\n";
    }
    return h;
  }

  json seeds_json() const {
    return json{{"histories_first", request_.seed},
                {"tuning_first", tune0_},
                {"tuning", tuning_seeds_},
                {"held_out_first", held0_},
                {"held_out", held_out_}};
  }

 private:
  // One run: reactive, or predictive (sa + GMF over the histories + relief) with `w`.
  fleet::RunRecord run_once(const std::string& mode, const fleet::Weights* w, std::uint64_t seed) {
    FleetRequest r = request_;
    r.scheduler = mode == "reactive" ? "reactive" : "sa";
    r.seed = seed;
    PreparedRun p = prepare_run(r, seed);
    if (w) p.settings.weights = *w;
    if (mode == "predictive") {
      p.settings.forecaster = "gmf";
      p.settings.histories = histories_;
      p.settings.relief = true;
      if (trace_) p.app = fleet::make_trace_app(trace_of(seed));
    }
    fleet::RunRecord rec = fleet::run_app(p.app, *p.world, p.drones, p.settings);
    if (expected_runs_ > 0) progress_.update(++done_runs_ / expected_runs_);
    return rec;
  }
  // The trace a trial replays on `seed`: reactive's world run there, made once.
  const fleet::Dtg& trace_of(std::uint64_t seed) {
    auto it = traces_.find(seed);
    if (it == traces_.end()) {
      FleetRequest r = request_;
      r.scheduler = "reactive";
      r.seed = seed;
      PreparedRun p = prepare_run(r, seed);
      it = traces_
               .emplace(seed, fleet::parse_dtg(
                                  fleet::run_app(p.app, *p.world, p.drones, p.settings).dtg_json,
                                  "trace dtg.json"))
               .first;
    }
    return it->second;
  }
  // A run that does not complete counts as twice the time limit.
  double time_of(const fleet::RunRecord& r) const {
    return r.completed ? r.completion_time_s : 2 * request_.max_time_s;
  }

  const FleetRequest& request_;
  bool trace_;
  std::map<std::uint64_t, fleet::Dtg> traces_;
  std::size_t history_count_;
  int tuning_seeds_, held_out_;
  std::uint64_t tune0_, held0_;
  std::vector<fleet::Dtg> histories_;
  ProgressBar progress_;  // drawn only on a terminal
  double expected_runs_ = 0, done_runs_ = 0;
};

json held_out_json(const HeldOut& h) {
  auto summary_of = [](const std::vector<double>& x) {
    const Interval i = mean_interval95(x);
    return json{{"completion_time_s_mean", base::round_to(i.mean, 3)},
                {"completion_time_s_ci95", base::round_to(i.half, 3)}};
  };
  auto paired = [](const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> d;
    for (std::size_t i = 0; i < a.size(); ++i) d.push_back(b[i] / a[i] - 1.0);
    const Interval i = mean_interval95(d);
    return json{{"relative_change_mean", base::round_to(i.mean, 5)},
                {"relative_change_ci95", base::round_to(i.half, 5)}};
  };
  return json{{"reactive", summary_of(h.reactive)},
              {"predictive_default", summary_of(h.start)},
              {"predictive_tuned", summary_of(h.tuned)},
              {"tuned_vs_reactive", paired(h.reactive, h.tuned)},
              {"tuned_vs_default", paired(h.start, h.tuned)}};
}

json weights_json(const fleet::Weights& w) {
  json out{{"coverage", w.coverage}};
  for (const FreeWeight& f : fleet::free_weights()) out[f.name] = w.*f.member;
  return out;
}

}  // namespace

// The tuning's seeds run from --seed over histories, tuning and held-out seeds: the last one is
// a seed too.
void FleetTuneCommand::check_last_seed() const {
  const std::uint64_t span = histories_ + static_cast<std::uint64_t>(tuning_seeds_ + held_out_);
  if (request_.seed > kMaxSeed - span)
    throw InputError("--seed " + std::to_string(request_.seed) +
                     ": the tuning's last seed (--seed + --histories + --tuning-seeds + "
                     "--held-out) would be beyond 9007199254740991");
}

int FleetTuneCommand::run() {
  try {
    if (ask_->parsed()) return ask();
    if (tell_->parsed()) return tell();
  } catch (const nlohmann::json::exception& e) {  // a state file edited or cut short
    throw InputError(state_ + ": not a tune state file of this swath-fleet (" + e.what() + ")");
  }
  if (request_.app.empty() || request_.world.empty() || output_.empty())
    throw InputError(
        "tune needs APP, --world and -o DIR (or: tune ask STATE, tune tell STATE "
        "RUN..)");
  check_last_seed();
  const PreparedRun check = prepare_run(request_, request_.seed);  // every input checked first
  // Refused before the trials are flown, not after.
  base::check_output_names(output_, "fleet-tune", tune_file_names());
  if (replay_ == "trace")
    if (const std::string why = fleet::schedule_dependence(request_.app); !why.empty())
      throw InputError("--replay trace: " + why);
  Tuning tuning(request_, histories_, tuning_seeds_, held_out_, replay_ == "trace");
  tuning.learn_histories();
  std::vector<Trial> trials;
  for (const fleet::Weights& w : fleet::draw_trials(check.settings.weights, trials_, request_.seed))
    trials.push_back({w, {}});
  const std::size_t winner = tuning.halve(trials);
  const HeldOut held = tuning.score(trials[0].weights, trials[winner].weights);

  json summary{{"app", request_.app},
               {"world", check.world->kind()},
               {"drones", check.drones.size()},
               {"trials", trials.size()},
               {"seeds", tuning.seeds_json()},
               {"winner", {{"trial", winner}, {"weights", weights_json(trials[winner].weights)}}},
               {"held_out", held_out_json(held)}};
  base::OutputSet set(output_, "fleet-tune");
  if (replay_ == "trace") summary["replay"] = "trace";
  set.add(
      "weights.yaml",
      fleet::weights_yaml(trials[winner].weights,
                          "swath-fleet tune " + request_.app + ": trial " + std::to_string(winner) +
                              " of " + std::to_string(trials.size()) + ", mean " +
                              base::fixed_text(trials[winner].mean_s(), 3) + " s over " +
                              std::to_string(trials[winner].times_s.size()) + " tuning seeds"));
  set.add("tune.csv", fleet::tune_csv(trials));
  set.add("held_out.csv", held.csv);
  set.add("summary.json", summary.dump(2) + "\n");
  set.commit();
  const Interval r = mean_interval95(held.reactive), t = mean_interval95(held.tuned);
  std::cout << request_.app << ": trial " << winner << " of " << trials.size()
            << " wins; held out (" << held_out_ << " seeds): reactive "
            << base::fixed_text(r.mean, 1) << " ± " << base::fixed_text(r.half, 1)
            << " s, tuned predictive " << base::fixed_text(t.mean, 1) << " ± "
            << base::fixed_text(t.half, 1) << " s\n";
  return base::kExitSuccess;
}

// ---- tune ask / tell: the same search as command lines (docs/swath-fleet.md) -------------------

namespace {

namespace fs = std::filesystem;

std::string absolute_path(const std::string& f) {
  if (f.empty()) return f;
  std::string out = fs::absolute(f).lexically_normal().string();
  while (out.size() > 1 && out.back() == '/') out.pop_back();  // "runs/x/" is "runs/x"
  return out;
}

// Checked fields of a state file (edited, cut short or of another swath-fleet): each refusal a
// sentence naming the file and the field, before any field is used.
class StateFields {
 public:
  StateFields(const json& st, const std::string& path) : st_(st), path_(path) {}

  const json& member(const char* key) const {
    const auto it = st_.find(key);
    if (it == st_.end()) throw InputError(path_ + ": no " + key + " (not a complete tune state)");
    return *it;
  }
  void text(const char* key, bool non_empty = false) const {
    const json& v = member(key);
    if (!v.is_string() || (non_empty && v.get_ref<const std::string&>().empty()))
      throw InputError(path_ + ": " + key + " must be a" + (non_empty ? " non-empty" : "") +
                       " string");
  }
  double number(const json& v, const std::string& what, double lo, double hi) const {
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < lo ||
        v.get<double>() > hi)
      throw InputError(path_ + ": " + what + " must be a number from " + base::shortest_text(lo) +
                       " to " + base::shortest_text(hi) + ", found " + v.dump());
    return v.get<double>();
  }
  long long whole(const json& v, const std::string& what, long long lo, long long hi) const {
    const bool ok = v.is_number() && std::isfinite(v.get<double>()) &&
                    v.get<double>() == std::floor(v.get<double>()) &&
                    v.get<double>() >= static_cast<double>(lo) &&
                    v.get<double>() <= static_cast<double>(hi);
    if (!ok)
      throw InputError(path_ + ": " + what + " must be a whole number from " + std::to_string(lo) +
                       " to " + std::to_string(hi) + ", found " + v.dump());
    return v.is_number_float() ? static_cast<long long>(v.get<double>()) : v.get<long long>();
  }
  long long whole(const char* key, long long lo, long long hi) const {
    return whole(member(key), key, lo, hi);
  }
  const json& array(const char* key, std::size_t lo, std::size_t hi) const {
    const json& v = member(key);
    if (!v.is_array() || v.size() < lo || v.size() > hi)
      throw InputError(path_ + ": " + key + " must be a list of " + std::to_string(lo) + " to " +
                       std::to_string(hi) + " entries");
    return v;
  }

 private:
  const json& st_;
  const std::string& path_;
};

// Every field tune ask and tell read, with tune's own ranges (a done state needs only its app
// and output).
void check_state(const json& st, const std::string& path) {
  const StateFields f(st, path);
  if (f.whole("tune_state", 0, 1000) != 1)
    throw InputError(path + ": tune_state " + st["tune_state"].dump() +
                     ": a tune state of another swath-fleet");
  f.text("version", true);
  f.text("app", true);
  f.text("output", true);
  f.text("phase", true);
  const std::string phase = st["phase"].get<std::string>();
  if (phase != "histories" && phase != "rung" && phase != "held_out" && phase != "done")
    throw InputError(path + ": phase \"" + phase +
                     "\" is none of histories, rung, held_out and done");
  if (phase == "done") return;
  for (const char* key : {"world", "runs", "program", "world_kind"}) f.text(key, true);
  for (const char* key : {"fleet", "weights", "faults", "wind"}) f.text(key);
  f.whole("drones", 0, 100);
  f.whole("drone_count", 1, 100);
  f.number(f.member("max_time_s"), "max_time_s", 1, 604800);
  f.whole("seed", 0, 9007199254740991LL);
  f.whole("histories", 1, 1000);
  const long long tuning_seeds = f.whole("tuning_seeds", 1, 100);
  if (phase == "held_out" || st.contains("held_out")) f.whole("held_out", 2, 1000);
  const json& trials = f.array("trials", 2, 4096);
  const long long n = static_cast<long long>(trials.size());
  for (std::size_t i = 0; i < trials.size(); ++i) {
    const std::string at = "trials[" + std::to_string(i) + "]";
    if (!trials[i].is_object()) throw InputError(path + ": " + at + " must be a weights object");
    f.number(StateFields(trials[i], path).member("coverage"), at + ".coverage", 0, 1000);
    for (const FreeWeight& w : fleet::free_weights())
      f.number(StateFields(trials[i], path).member(w.name), at + "." + w.name, 0, 1000);
  }
  f.whole("rung", 0, tuning_seeds - 1);
  std::vector<bool> seen(trials.size(), false);
  for (const json& i : f.array("alive", 0, trials.size())) {
    const auto k = static_cast<std::size_t>(f.whole(i, "alive", 0, n - 1));
    if (seen[k]) throw InputError(path + ": alive names trial " + std::to_string(k) + " twice");
    seen[k] = true;
  }
  const json& times = f.array("times_s", trials.size(), trials.size());
  for (const json& t : times) {
    if (!t.is_array() || t.size() > static_cast<std::size_t>(tuning_seeds))
      throw InputError(path + ": times_s must hold a list of at most tuning_seeds times per trial");
    for (const json& v : t) f.number(v, "times_s", 0, 2 * 604800);
  }
  const json& told = f.member("told");
  if (!told.is_object()) throw InputError(path + ": told must be an object (run: time)");
  for (const auto& [dir, t] : told.items()) f.number(t, "told[" + dir + "]", 0, 2 * 604800);
  if (phase == "held_out" || st.contains("winner")) f.whole("winner", 0, n - 1);
}

json read_state(const std::string& path) {
  const json j = json::parse(base::read_text_file(path, "tune state", base::kMaxConfigFileBytes),
                             nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("tune_state"))
    throw InputError(path + ": not a tune state file (tune ask STATE makes one)");
  check_state(j, path);
  return j;
}

void write_state(const std::string& path, const json& state) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << state.dump(1) << "\n";
    if (!out) throw InputError(path + ": cannot write the tune state");
  }
  fs::rename(tmp, path);
}

fleet::Weights weights_of(const json& j) {
  fleet::Weights w;
  w.coverage = j.at("coverage").get<double>();
  for (const FreeWeight& f : fleet::free_weights()) w.*f.member = j.at(f.name).get<double>();
  return w;
}

std::string trial_weights_file(const json& st, std::size_t i) {
  return st["runs"].get<std::string>() + "/weights/trial-" + std::to_string(i) + ".yaml";
}

// The run directories the state's current phase waits for, with the seed of each.
std::vector<std::pair<std::string, std::uint64_t>> expected_runs(const json& st) {
  std::vector<std::pair<std::string, std::uint64_t>> out;
  const std::string runs = st["runs"].get<std::string>();
  const std::uint64_t seed = st["seed"].get<std::uint64_t>();
  const std::string phase = st["phase"].get<std::string>();
  if (phase == "histories") {
    for (std::uint64_t k = 0; k < st["histories"].get<std::uint64_t>(); ++k)
      out.push_back({runs + "/history-seed" + std::to_string(seed + k), seed + k});
  } else if (phase == "rung") {
    const int rung = st["rung"].get<int>();
    const std::uint64_t s =
        seed + st["histories"].get<std::uint64_t>() + static_cast<std::uint64_t>(rung);
    for (const auto& i : st["alive"])
      out.push_back(
          {runs + "/rung" + std::to_string(rung) + "-trial" + std::to_string(i.get<std::size_t>()),
           s});
  } else if (phase == "held_out") {  // tune's score(): reactive, the defaults, the winner
    const std::uint64_t h0 =
        seed + st["histories"].get<std::uint64_t>() + st["tuning_seeds"].get<std::uint64_t>();
    for (std::uint64_t k = 0; k < st["held_out"].get<std::uint64_t>(); ++k)
      for (const char* which : {"reactive", "default", "tuned"})
        out.push_back({runs + "/held-seed" + std::to_string(h0 + k) + "-" + which, h0 + k});
  }
  return out;
}

// The weights file of an expected run ("" for a reactive run: the starting weights).
std::string weights_file_of(const json& st, const std::string& dir) {
  const std::string name = fs::path(dir).filename().string();
  const std::string phase = st["phase"].get<std::string>();
  if (phase == "rung")
    return trial_weights_file(st, std::stoul(name.substr(name.find("-trial") + 6)));
  if (phase == "held_out") {
    if (name.size() >= 8 && name.compare(name.size() - 8, 8, "-default") == 0)
      return trial_weights_file(st, 0);  // trial 0: the starting weights
    if (name.size() >= 6 && name.compare(name.size() - 6, 6, "-tuned") == 0)
      return trial_weights_file(st, st["winner"].get<std::size_t>());
  }
  return "";
}

std::string run_line(const json& st, const std::string& out_dir, std::uint64_t seed,
                     const std::string& weights_file) {
  std::ostringstream line;
  line << shell_word(st["program"].get<std::string>()) << " run "
       << shell_word(st["app"].get<std::string>()) << " --world "
       << shell_word(st["world"].get<std::string>()) << " --world-seed " << seed;
  if (!st["fleet"].get<std::string>().empty())
    line << " --fleet " << shell_word(st["fleet"].get<std::string>());
  if (st["drones"].get<int>() > 0) line << " --drones " << st["drones"].get<int>();
  line << " --seed " << seed;
  if (weights_file.empty()) {  // a history: reactive with the starting weights
    line << " --scheduler reactive";
    if (!st["weights"].get<std::string>().empty())
      line << " --weights " << shell_word(st["weights"].get<std::string>());
  } else {  // a trial: predictive (sa + GMF over the histories + relief) with its weights
    line << " --scheduler sa --forecast gmf";
    for (const auto& [dir, s] : expected_runs(json{{"phase", "histories"},
                                                   {"runs", st["runs"]},
                                                   {"seed", st["seed"]},
                                                   {"histories", st["histories"]}}))
      line << " --history " << shell_word(dir);
    line << " --relief --weights " << shell_word(weights_file);
  }
  if (!st["faults"].get<std::string>().empty())
    line << " --faults " << shell_word(st["faults"].get<std::string>());
  if (!st["wind"].get<std::string>().empty())
    line << " --wind " << shell_word(st["wind"].get<std::string>());
  line << " --max-time " << base::shortest_text(st["max_time_s"].get<double>()) << " -o "
       << shell_word(out_dir);
  return line.str();
}

}  // namespace

int FleetTuneCommand::ask() {
  json st;
  if (fs::exists(state_)) {
    st = read_state(state_);
    if (!request_.app.empty() && request_.app != st["app"].get<std::string>())
      throw InputError(state_ + ": the state of a tuning of " + st["app"].get<std::string>() +
                       ", not of " + request_.app + " (another STATE file, or drop APP)");
  } else {
    if (request_.app.empty() || request_.world.empty() || output_.empty())
      throw InputError(state_ + " does not exist: to start a tuning give APP, --world and -o DIR");
    check_last_seed();
    const PreparedRun check = prepare_run(request_, request_.seed);  // every input checked
    base::check_output_names(output_, "fleet-tune", tune_file_names());
    const std::string runs = absolute_path(
        runs_dir_.empty() ? fs::path(state_).replace_extension("").string() + "-runs" : runs_dir_);
    st = json{{"tune_state", 1},
              {"version", SWATH_VERSION},
              {"app", request_.app},
              {"world", absolute_path(check.world_source)},
              {"fleet", absolute_path(request_.fleet)},
              {"drones", request_.fleet.empty() ? check.default_drones : 0},
              {"weights", absolute_path(request_.weights)},
              {"faults", absolute_path(request_.faults)},
              {"wind", request_.wind},
              {"max_time_s", request_.max_time_s},
              {"seed", request_.seed},
              {"histories", histories_},
              {"tuning_seeds", tuning_seeds_},
              {"held_out", held_out_},
              {"world_kind", check.world->kind()},
              {"drone_count", check.drones.size()},
              {"runs", runs},
              {"output", absolute_path(output_)},
              {"program", program_.empty() ? own_program_path("swath-fleet") : program_}};
    json sets = json::array();
    std::vector<std::pair<std::string, std::string>> files;
    const auto trials = fleet::draw_trials(check.settings.weights, trials_, request_.seed);
    for (std::size_t i = 0; i < trials.size(); ++i) {
      sets.push_back(weights_json(trials[i]));
      files.push_back(
          {"trial-" + std::to_string(i) + ".yaml",
           fleet::weights_yaml(trials[i], "swath-fleet tune ask: trial " + std::to_string(i) +
                                              " of " + std::to_string(trials.size()))});
    }
    st["trials"] = sets;
    st["phase"] = "histories";
    st["rung"] = 0;
    st["alive"] = json::array();
    st["times_s"] = json::array();
    for (std::size_t i = 0; i < trials.size(); ++i) st["times_s"].push_back(json::array());
    st["told"] = json::object();
    base::write_files_atomically(runs + "/weights", files, "fleet-tune-weights");
    write_state(state_, st);
  }
  const std::string phase = st["phase"].get<std::string>();
  if (phase == "done") {
    std::cerr << state_ << ": the tuning is done: " << st["output"].get<std::string>()
              << "/weights.yaml\n";
    return base::kExitSuccess;
  }
  std::ostringstream out;
  for (const auto& [dir, seed] : expected_runs(st)) {
    if (st["told"].contains(dir)) continue;
    out << run_line(st, dir, seed, weights_file_of(st, dir)) << "\n";
  }
  std::cout << out.str();
  return base::kExitSuccess;
}

int FleetTuneCommand::tell() {
  json st = read_state(state_);
  if (st["phase"] == "done")
    throw InputError(state_ + ": the tuning is done; nothing more to tell");
  const auto expected = expected_runs(st);
  const std::string app = st["app"].get<std::string>();
  const double max_time_s = st["max_time_s"].get<double>();
  for (const std::string& run : told_runs_) {
    const std::string dir = absolute_path(run);
    const auto it = std::find_if(expected.begin(), expected.end(),
                                 [&](const auto& e) { return e.first == dir; });
    const std::string summary_path = (fs::path(run) / "summary.json").string();
    if (!fs::is_directory(run) || !fs::exists(summary_path))
      throw InputError(run +
                       ": not a run directory (no summary.json): run the line tune ask "
                       "printed for it first");
    if (it == expected.end())
      throw InputError(run + ": not one of the runs " + state_ + " waits for now (tune ask " +
                       state_ + " prints them)");
    const nlohmann::json s = base::parse_json_document(
        base::read_text_file(summary_path, "run summary", base::kMaxConfigFileBytes), summary_path);
    const std::string run_app =
        base::json_string(base::json_member(s, "app", summary_path), summary_path + ": app");
    if (run_app != app)
      throw InputError(run + ": a run of " + run_app + "; " + state_ + " tunes " + app);
    const std::string version = base::json_string(base::json_member(s, "version", summary_path),
                                                  summary_path + ": version");
    if (version != st["version"].get<std::string>())
      throw InputError(run + ": made by swath-fleet " + version + ", " + state_ + " by " +
                       st["version"].get<std::string>() + ": one version per tuning");
    const auto seed = base::json_integer(base::json_member(s, "seed", summary_path), 0,
                                         9007199254740992LL, summary_path + ": seed");
    if (static_cast<std::uint64_t>(seed) != it->second)
      throw InputError(run + ": seed " + std::to_string(seed) + ", expected " +
                       std::to_string(it->second));
    const nlohmann::json& completed = base::json_member(s, "completed", summary_path);
    const double t =
        completed.is_boolean() && completed.get<bool>()
            ? base::json_number(base::json_member(s, "completion_time_s", summary_path),
                                summary_path + ": completion_time_s")
            : 2 * max_time_s;  // as tune counts a run that does not complete
    st["told"][dir] = t;
  }
  std::size_t told = 0;
  for (const auto& e : expected) told += st["told"].contains(e.first) ? 1 : 0;
  if (told < expected.size()) {
    write_state(state_, st);
    std::cout << state_ << ": " << told << " of " << expected.size() << " runs told\n";
    return base::kExitSuccess;
  }
  // The phase is complete: on to the next rung, or the winner.
  std::vector<Trial> trials;
  for (std::size_t i = 0; i < st["trials"].size(); ++i) {
    trials.push_back({weights_of(st["trials"][i]), {}});
    for (const auto& t : st["times_s"][i]) trials[i].times_s.push_back(t.get<double>());
  }
  const int tuning_seeds = st["tuning_seeds"].get<int>();
  std::vector<std::size_t> alive;
  if (st["phase"] == "histories") {
    for (std::size_t i = 0; i < trials.size(); ++i) alive.push_back(i);
    st["phase"] = "rung";
    st["rung"] = 0;
  } else if (st["phase"] == "held_out") {
    // tune's score(): per held-out seed reactive, the starting weights, the winner's; then tune's
    // held_out.csv and summary.json next to weights.yaml and tune.csv.
    HeldOut h;
    for (std::size_t j = 0; j + 2 < expected.size(); j += 3) {
      h.reactive.push_back(st["told"][expected[j].first].get<double>());
      h.start.push_back(st["told"][expected[j + 1].first].get<double>());
      h.tuned.push_back(st["told"][expected[j + 2].first].get<double>());
      h.csv += std::to_string(expected[j].second) + "," + base::fixed_text(h.reactive.back(), 3) +
               "," + base::fixed_text(h.start.back(), 3) + "," +
               base::fixed_text(h.tuned.back(), 3) + "\n";
    }
    const std::size_t winner = st["winner"].get<std::size_t>();
    const std::uint64_t seed = st["seed"].get<std::uint64_t>();
    const std::uint64_t tune0 = seed + st["histories"].get<std::uint64_t>();
    const json seeds{{"histories_first", seed},
                     {"tuning_first", tune0},
                     {"tuning", tuning_seeds},
                     {"held_out_first", tune0 + static_cast<std::uint64_t>(tuning_seeds)},
                     {"held_out", st["held_out"].get<int>()}};
    const json summary{
        {"app", app},
        {"world", st["world_kind"].get<std::string>()},
        {"drones", st["drone_count"].get<std::size_t>()},
        {"trials", trials.size()},
        {"seeds", seeds},
        {"winner", {{"trial", winner}, {"weights", weights_json(trials[winner].weights)}}},
        {"held_out", held_out_json(h)}};
    base::OutputSet set(st["output"].get<std::string>(), "fleet-tune",
                        {base::OutputSet::Mode::amend});
    set.add("held_out.csv", h.csv);
    set.add("summary.json", summary.dump(2) + "\n");
    set.commit();
    st["phase"] = "done";
    const Interval r = mean_interval95(h.reactive), t = mean_interval95(h.tuned);
    std::cout << state_ << ": held out (" << h.reactive.size() << " seeds): reactive "
              << base::fixed_text(r.mean, 1) << " ± " << base::fixed_text(r.half, 1)
              << " s, tuned predictive " << base::fixed_text(t.mean, 1) << " ± "
              << base::fixed_text(t.half, 1) << " s -> " << st["output"].get<std::string>()
              << "/held_out.csv, summary.json\n";
  } else {
    for (const auto& e : expected) {
      const std::string name = fs::path(e.first).filename().string();
      const std::size_t i = std::stoul(name.substr(name.find("-trial") + 6));
      trials[i].times_s.push_back(st["told"][e.first].get<double>());
      st["times_s"][i].push_back(st["told"][e.first]);
      alive.push_back(i);
    }
    const int rung = st["rung"].get<int>();
    if (rung + 1 < tuning_seeds) {  // the better half goes on (tune's halving)
      alive = fleet::better_half(trials, std::move(alive));
      std::sort(alive.begin(), alive.end());
      st["rung"] = rung + 1;
    } else {
      const std::size_t winner = fleet::best_trial(trials, alive);
      base::OutputSet set(st["output"].get<std::string>(), "fleet-tune");
      set.add(
          "weights.yaml",
          fleet::weights_yaml(trials[winner].weights,
                              "swath-fleet tune " + app + ": trial " + std::to_string(winner) +
                                  " of " + std::to_string(trials.size()) + ", mean " +
                                  base::fixed_text(trials[winner].mean_s(), 3) + " s over " +
                                  std::to_string(trials[winner].times_s.size()) + " tuning seeds"));
      set.add("tune.csv", fleet::tune_csv(trials));
      set.commit();
      // Then the held-out rung (tune's score); a state from before it had none.
      st["phase"] = st.contains("held_out") ? "held_out" : "done";
      st["winner"] = winner;
      alive.clear();
      std::cout << state_ << ": trial " << winner << " of " << trials.size() << " wins -> "
                << st["output"].get<std::string>() << "/weights.yaml, tune.csv\n";
    }
  }
  st["alive"] = alive;
  st["told"] = json::object();
  write_state(state_, st);
  if (st["phase"] == "rung")
    std::cout << state_ << ": rung " << st["rung"].get<int>() << " next (" << alive.size()
              << " runs): tune ask " << state_ << "\n";
  if (st["phase"] == "held_out")
    std::cout << state_ << ": the held-out runs next (" << expected_runs(st).size()
              << " runs): tune ask " << state_ << "\n";
  return base::kExitSuccess;
}

}  // namespace swath::apps
