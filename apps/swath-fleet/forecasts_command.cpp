#include "forecasts_command.hpp"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>

#include "intervals.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/output_set.hpp"
#include "swath/fleet/forecaster.hpp"

namespace swath::apps {

using base::InputError;
using json = nlohmann::ordered_json;

void FleetForecastsCommand::setup(CLI::App& app) {
  add_fleet_options(app, request_, true);
  request_.scheduler = "reactive";
  app.add_option("--forecasters", forecasters_,
                 "Comma-separated forecasters to score: gmf, constant-velocity, none")
      ->capture_default_str();
  app.add_option("--seeds", seeds_, "Runs (seeds, each also a scenario of the world)")
      ->check(CLI::Range(2, 1000))
      ->capture_default_str();
  app.add_option("--p-min", p_min_, "Forecasts at least this likely count")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--within", within_m_, "Recall radius, m")
      ->check(CLI::Range(0.0, 1e6))
      ->capture_default_str();
  app.add_option("--gmf-depth", gmf_.max_depth,
                 "GMF: deepest signature compared (Weisfeiler-Lehman iterations; the paper's 10)")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  app.add_option("--gmf-top", gmf_.top_k, "GMF: best-fitting matches whose next is forecast")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_option("-o,--output", output_, "Directory for forecasts.csv and summary.json")
      ->required();
}

namespace {

// Median with infinities (no confident forecast) counted as the largest values.
double median(std::vector<double> x) {
  if (x.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(x.begin(), x.end());
  const std::size_t n = x.size();
  return n % 2 ? x[n / 2] : (x[n / 2 - 1] + x[n / 2]) / 2;
}

std::string number_text(double v, int digits) {
  if (std::isnan(v)) return "";
  if (std::isinf(v)) return "inf";
  return base::fixed_text(v, digits);
}

json number_json(double v, int digits) {
  if (!std::isfinite(v)) return nullptr;
  const double scale = std::pow(10.0, digits);
  return std::round(v * scale) / scale;
}

// One forecaster over every held-out run.
struct Pooled {
  std::vector<double> distances_m, recall_per_run, brier_per_run;
  double brier_sum = 0;
  std::size_t pairs = 0;
};

}  // namespace

int FleetForecastsCommand::run() {
  const std::vector<std::string> names = comma_names(forecasters_);
  if (names.empty()) throw InputError("--forecasters names no forecaster");
  for (const std::string& n : names)
    if (!fleet::make_forecaster(n, {}))
      throw InputError("--forecasters: unknown forecaster \"" + n +
                       "\": use gmf, constant-velocity or none");
  const PreparedRun check = prepare_run(request_);  // every input read before any run
  // A file of the user's in the way is refused before the runs, not after them.
  base::check_output_names(output_, "fleet-forecasts", {"forecasts.csv", "summary.json"});
  std::vector<fleet::Dtg> runs;
  std::vector<std::uint64_t> seeds;
  for (int k = 0; k < seeds_; ++k) {
    FleetRequest r = request_;
    r.seed = request_.seed + static_cast<std::uint64_t>(k);
    PreparedRun p = prepare_run(r, r.seed);
    const fleet::RunRecord rec = fleet::run_app(p.app, *p.world, p.drones, p.settings);
    runs.push_back(fleet::parse_dtg(rec.dtg_json, "run of seed " + std::to_string(r.seed)));
    seeds.push_back(r.seed);
  }
  std::string csv =
      "forecaster,seed,next_tasks,median_distance_m,recall,cancellation_pairs,brier\n";
  std::vector<Pooled> pooled(names.size());
  for (std::size_t h = 0; h < runs.size(); ++h) {
    std::vector<fleet::Dtg> others;
    for (std::size_t o = 0; o < runs.size(); ++o)
      if (o != h) others.push_back(runs[o]);
    for (std::size_t f = 0; f < names.size(); ++f) {
      auto forecaster = fleet::make_forecaster(names[f], others, gmf_);
      const fleet::ForecastScore s = fleet::score_forecasts(*forecaster, runs[h], p_min_);
      const auto within = std::count_if(s.distances_m.begin(), s.distances_m.end(),
                                        [&](double d) { return d <= within_m_; });
      const double recall = s.distances_m.empty() ? std::numeric_limits<double>::quiet_NaN()
                                                  : static_cast<double>(within) /
                                                        static_cast<double>(s.distances_m.size());
      const double brier = s.cancellation_pairs == 0
                               ? std::numeric_limits<double>::quiet_NaN()
                               : s.brier_sum / static_cast<double>(s.cancellation_pairs);
      csv += names[f] + "," + std::to_string(seeds[h]) + "," +
             std::to_string(s.distances_m.size()) + "," + number_text(median(s.distances_m), 3) +
             "," + number_text(recall, 4) + "," + std::to_string(s.cancellation_pairs) + "," +
             number_text(brier, 5) + "\n";
      Pooled& p = pooled[f];
      p.distances_m.insert(p.distances_m.end(), s.distances_m.begin(), s.distances_m.end());
      if (!std::isnan(recall)) p.recall_per_run.push_back(recall);
      if (!std::isnan(brier)) p.brier_per_run.push_back(brier);
      p.brier_sum += s.brier_sum;
      p.pairs += s.cancellation_pairs;
    }
  }
  json rows = json::array();
  for (std::size_t f = 0; f < names.size(); ++f) {
    const Pooled& p = pooled[f];
    json row{{"forecaster", names[f]},
             {"next_tasks", p.distances_m.size()},
             {"median_distance_m", number_json(median(p.distances_m), 3)}};
    std::cout << names[f] << ": " << p.distances_m.size() << " next tasks";
    if (p.recall_per_run.size() >= 2) {
      const Interval i = mean_interval95(p.recall_per_run);
      row["recall"] = number_json(i.mean, 4);
      row["recall_ci95"] = number_json(i.half, 4);
      std::cout << ", median distance " << number_text(median(p.distances_m), 2)
                << " m, recall within " << base::fixed_text(within_m_, 1) << " m "
                << base::fixed_text(100 * i.mean, 1) << " ± " << base::fixed_text(100 * i.half, 1)
                << " %";
    }
    row["cancellation_pairs"] = p.pairs;
    if (p.pairs > 0) {
      row["brier"] = number_json(p.brier_sum / static_cast<double>(p.pairs), 5);
      std::cout << ", cancellation Brier "
                << base::fixed_text(p.brier_sum / static_cast<double>(p.pairs), 4) << " over "
                << p.pairs << " pairs";
    }
    if (p.brier_per_run.size() >= 2)
      row["brier_ci95"] = number_json(mean_interval95(p.brier_per_run).half, 5);
    std::cout << "\n";
    rows.push_back(row);
  }
  base::OutputSet set(output_, "fleet-forecasts");
  set.add("forecasts.csv", csv);
  set.add("summary.json", json{{"app", request_.app},
                               {"world", check.world->kind()},
                               {"scheduler", request_.scheduler},
                               {"runs", seeds_},
                               {"first_seed", request_.seed},
                               {"p_min", p_min_},
                               {"within_m", within_m_},
                               {"gmf_depth", gmf_.max_depth},
                               {"gmf_top", gmf_.top_k},
                               {"forecasters", rows}}
                                  .dump(2) +
                              "\n");
  set.commit();
  return base::kExitSuccess;
}

}  // namespace swath::apps
