#include "tune_command.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "intervals.hpp"
#include "progress_bar.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/output_set.hpp"
#include "swath/fleet/dtg.hpp"
#include "swath/fleet/runtime.hpp"
#include "swath/vehicle/random.hpp"

namespace swath::apps {

using base::InputError;
using json = nlohmann::ordered_json;

void FleetTuneCommand::setup(CLI::App& app) {
  add_fleet_options(app, request_, false);
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
      ->required();
}

namespace {

// The weights a trial may change; coverage stays (it keeps "serve what is visible" above the
// rest) and closest is fixed at 1 (the argmax ignores scale).
struct FreeWeight {
  const char* name;
  double fleet::Weights::*member;
};
constexpr FreeWeight kFree[] = {{"fairness", &fleet::Weights::fairness},
                                {"avoid_zigzag", &fleet::Weights::avoid_zigzag},
                                {"commitment", &fleet::Weights::commitment},
                                {"speculative", &fleet::Weights::speculative},
                                {"avoid_mutual", &fleet::Weights::avoid_mutual}};

// 0 with probability 1/5, else log-uniform in [1e-3, 1e3], kept to 4 significant digits so that
// weights.yaml holds exactly the weights that were scored.
double draw_weight(vehicle::SplitMix64& rng) {
  if (rng.uniform() < 0.2) return 0.0;
  const double v = std::pow(10.0, rng.uniform(-3.0, 3.0));
  // Rounded through its text: 43.41, not 43.410000000000004.
  const int decimals = std::max(0, 3 - static_cast<int>(std::floor(std::log10(v))));
  double rounded = 0;
  base::parse_number(base::fixed_text(v, decimals), rounded);
  return std::min(1000.0, rounded);
}

std::vector<fleet::Weights> draw_trials(const fleet::Weights& start, int count,
                                        std::uint64_t seed) {
  std::vector<fleet::Weights> out{start};
  fleet::Weights reactive = start;  // the paper's baseline weights: no forecast terms
  reactive.speculative = reactive.avoid_mutual = 0;
  out.push_back(reactive);
  auto rng = vehicle::SplitMix64::stream(seed, "tune");
  while (static_cast<int>(out.size()) < count) {
    fleet::Weights w = start;
    for (const FreeWeight& f : kFree) w.*f.member = draw_weight(rng);
    out.push_back(w);
  }
  return out;
}

std::string weights_yaml(const fleet::Weights& w, const std::string& comment) {
  std::ostringstream out;
  out << "# " << comment << "\n";
  out << "coverage: " << base::shortest_text(w.coverage) << "\n";
  for (const FreeWeight& f : kFree)
    out << f.name << ": " << base::shortest_text(w.*f.member) << "\n";
  return out.str();
}

struct Trial {
  fleet::Weights weights;
  std::vector<double> times_s;  // per tuning seed evaluated, in order
  double mean_s() const {
    double sum = 0;
    for (double t : times_s) sum += t;
    return sum / static_cast<double>(times_s.size());
  }
};

// Completion times on the held-out seeds, per configuration.
struct HeldOut {
  std::vector<double> reactive, start, tuned;
  std::string csv = "seed,reactive_s,predictive_default_s,predictive_tuned_s\n";
};

// The tuning's steps over one request: seeds in three disjoint ranges from --seed (histories,
// tuning, held out), every run a world replay of the app.
class Tuning {
 public:
  Tuning(const FleetRequest& r, std::size_t histories, int tuning_seeds, int held_out)
      : request_(r),
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

  // Every trial alive runs the next tuning seed; then the better half (ties: lower trial) goes
  // on. The winner: the best of those that ran every tuning seed.
  std::size_t halve(std::vector<Trial>& trials) {
    std::vector<std::size_t> alive(trials.size());
    for (std::size_t i = 0; i < alive.size(); ++i) alive[i] = i;
    expected_runs_ = 3.0 * held_out_;
    for (double a = static_cast<double>(alive.size()), k = 0; k < tuning_seeds_;
         ++k, a = std::ceil(a / 2))
      expected_runs_ += a;
    auto by_mean = [&](std::size_t a, std::size_t b) {
      const double ma = trials[a].mean_s(), mb = trials[b].mean_s();
      return ma != mb ? ma < mb : a < b;
    };
    for (int k = 0; k < tuning_seeds_; ++k) {
      if (k > 0) {
        std::sort(alive.begin(), alive.end(), by_mean);
        alive.resize((alive.size() + 1) / 2);
      }
      for (std::size_t i : alive)
        trials[i].times_s.push_back(time_of(
            run_once("predictive", &trials[i].weights, tune0_ + static_cast<std::uint64_t>(k))));
    }
    return *std::min_element(alive.begin(), alive.end(), by_mean);
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
    }
    fleet::RunRecord rec = fleet::run_app(p.app, *p.world, p.drones, p.settings);
    if (expected_runs_ > 0) progress_.update(++done_runs_ / expected_runs_);
    return rec;
  }
  // A run that does not complete counts as twice the time limit.
  double time_of(const fleet::RunRecord& r) const {
    return r.completed ? r.completion_time_s : 2 * request_.max_time_s;
  }

  const FleetRequest& request_;
  std::size_t history_count_;
  int tuning_seeds_, held_out_;
  std::uint64_t tune0_, held0_;
  std::vector<fleet::Dtg> histories_;
  ProgressBar progress_;  // drawn only on a terminal
  double expected_runs_ = 0, done_runs_ = 0;
};

std::string tune_csv(const std::vector<Trial>& trials) {
  std::string csv = "trial,coverage";
  for (const FreeWeight& f : kFree) csv += std::string(",") + f.name;
  csv += ",tuning_seeds,mean_completion_time_s\n";
  for (std::size_t i = 0; i < trials.size(); ++i) {
    csv += std::to_string(i) + "," + base::shortest_text(trials[i].weights.coverage);
    for (const FreeWeight& f : kFree) csv += "," + base::shortest_text(trials[i].weights.*f.member);
    csv += "," + std::to_string(trials[i].times_s.size()) + "," +
           base::fixed_text(trials[i].mean_s(), 3) + "\n";
  }
  return csv;
}

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
  for (const FreeWeight& f : kFree) out[f.name] = w.*f.member;
  return out;
}

}  // namespace

int FleetTuneCommand::run() {
  const PreparedRun check = prepare_run(request_, request_.seed);  // every input checked first
  Tuning tuning(request_, histories_, tuning_seeds_, held_out_);
  tuning.learn_histories();
  std::vector<Trial> trials;
  for (const fleet::Weights& w : draw_trials(check.settings.weights, trials_, request_.seed))
    trials.push_back({w, {}});
  const std::size_t winner = tuning.halve(trials);
  const HeldOut held = tuning.score(trials[0].weights, trials[winner].weights);

  const json summary{
      {"app", request_.app},
      {"world", check.world->kind()},
      {"drones", check.drones.size()},
      {"trials", trials.size()},
      {"seeds", tuning.seeds_json()},
      {"winner", {{"trial", winner}, {"weights", weights_json(trials[winner].weights)}}},
      {"held_out", held_out_json(held)}};
  base::OutputSet set(output_, "fleet-tune");
  set.add("weights.yaml",
          weights_yaml(trials[winner].weights,
                       "swath-fleet tune " + request_.app + ": trial " + std::to_string(winner) +
                           " of " + std::to_string(trials.size()) + ", mean " +
                           base::fixed_text(trials[winner].mean_s(), 3) + " s over " +
                           std::to_string(trials[winner].times_s.size()) + " tuning seeds"));
  set.add("tune.csv", tune_csv(trials));
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

}  // namespace swath::apps
