#include "sweep_command.hpp"

#include <cmath>
#include <iostream>

#include "flight_batch.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/output_set.hpp"
#include "swath/base/parallel.hpp"
#include "swath/control/experiment.hpp"

namespace swath::apps {
namespace {

using base::fixed_text;
using base::InputError;

// "KEY=V1,V2,.." or "KEY=LO:HI:STEP" (at most 1,000 values).
std::vector<std::string> values_of(const std::string& spec, std::string& key) {
  const auto eq = spec.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--param " + spec + ": expected FILE.KEY=V1,V2,.. or FILE.KEY=LO:HI:STEP");
  key = spec.substr(0, eq);
  const std::string rest = spec.substr(eq + 1);
  std::vector<std::string> out;
  const auto c1 = rest.find(':');
  if (c1 != std::string::npos) {
    const auto c2 = rest.find(':', c1 + 1);
    double lo = 0, hi = 0, step = 0;
    if (c2 == std::string::npos || !base::parse_number(rest.substr(0, c1), lo) ||
        !base::parse_number(rest.substr(c1 + 1, c2 - c1 - 1), hi) ||
        !base::parse_number(rest.substr(c2 + 1), step) || !(step > 0) || !(hi >= lo) ||
        (hi - lo) / step > 1000)
      throw InputError("--param " + spec +
                       ": LO:HI:STEP needs LO <= HI, STEP > 0 and at most 1000 values");
    const auto n = static_cast<int>(std::floor((hi - lo) / step + 1e-9));
    for (int k = 0; k <= n; ++k) out.push_back(base::shortest_text(lo + k * step));
    return out;
  }
  std::size_t start = 0;
  for (;;) {
    const auto comma = rest.find(',', start);
    out.push_back(rest.substr(start, comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  for (const std::string& v : out)
    if (v.empty()) throw InputError("--param " + spec + ": an empty value");
  if (out.size() > 1000) throw InputError("--param " + spec + ": more than 1000 values");
  return out;
}

std::string cell(const control::MeanInterval& m, int decimals) {
  return fixed_text(m.mean, decimals) + " [" + fixed_text(m.low, decimals) + ", " +
         fixed_text(m.high, decimals) + "]";
}

}  // namespace

void ControlSweepCommand::setup(CLI::App& app) {
  app.add_option("MISSION", request_.mission, "As for run")->required();
  app.add_option("-o,--output", output_, "Directory for runs.csv and sweep.md")->required();
  app.add_option("--param", param_,
                 "The key and its values: FILE.KEY=V1,V2,.. or FILE.KEY=LO:HI:STEP, e.g. "
                 "scheduler.reactive.p_run=0.2:0.8:0.1")
      ->required();
  app.add_option("--vehicle", request_.vehicle, "Vehicle file or bundled name")
      ->capture_default_str();
  app.add_option("--scheduler", request_.scheduler, "Scheduler file or bundled name")
      ->capture_default_str();
  app.add_option("--environment", request_.environment, "Environment preset or file")
      ->capture_default_str();
  app.add_option("--seeds", seeds_, "Seeds 1..N per value")->capture_default_str();
  app.add_option("--jobs", jobs_, "Flights at once (default: the machine's cores)");
  add_flight_options(app, request_);
  app.add_flag("--progress", progress_, "Show a progress bar (only on a terminal)");
}

int ControlSweepCommand::run() {
  if (seeds_ < 1 || seeds_ > 1000)
    throw InputError("--seeds " + std::to_string(seeds_) + ": expected 1 to 1000");
  std::string key;
  const std::vector<std::string> values = values_of(param_, key);
  std::vector<BatchFlight> flights;
  for (const std::string& v : values)
    for (int seed = 1; seed <= seeds_; ++seed) {
      FlightRequest r = request_;
      r.seed = static_cast<std::uint64_t>(seed);
      r.sets.push_back(key + "=" + v);
      flights.push_back(
          {r.environment, r.vehicle, r.scheduler, v, r.seed, prepare_flight(r).settings, {}});
    }
  base::OutputSet set(output_, "control-sweep");
  const unsigned jobs = jobs_ > 0 ? jobs_ : base::machine_threads();
  fly_all(flights, std::min<unsigned>(jobs, static_cast<unsigned>(flights.size())), progress_);

  std::string md = "# swath-control sweep of " + key + "\n\n" + request_.mission + ", " +
                   request_.vehicle + ", " + request_.scheduler + ", " + request_.environment +
                   "; seeds 1.." + std::to_string(seeds_) +
                   "; means with 95 % Student-t intervals.\n\n| " + key +
                   " | status | attitude RMS (deg) | cross-track RMS (m) | executions/s | "
                   "flight time (s) |\n|---|---|---|---|---|---|\n";
  for (std::size_t v = 0; v < values.size(); ++v) {
    std::vector<double> att, xt, ex, ft;
    std::string statuses;
    for (int k = 0; k < seeds_; ++k) {
      const BatchFlight& f =
          flights[v * static_cast<std::size_t>(seeds_) + static_cast<std::size_t>(k)];
      const control::FlightFigures g = control::figures_of(f.summary);
      att.push_back(g.attitude_rms_deg);
      xt.push_back(g.cross_track_rms_m);
      ex.push_back(g.executions_per_s);
      ft.push_back(g.flight_time_s);
      const std::string s = control::to_string(f.summary.status);
      if (statuses.find(s) == std::string::npos) statuses += (statuses.empty() ? "" : ", ") + s;
    }
    md += "| " + values[v] + " | " + statuses + " | " + cell(control::mean_interval(att), 3) +
          " | " + cell(control::mean_interval(xt), 3) + " | " +
          cell(control::mean_interval(ex), 1) + " | " + cell(control::mean_interval(ft), 1) +
          " |\n";
  }
  set.add("runs.csv", runs_csv(flights, "value"));
  set.add("sweep.md", md);
  set.commit();
  std::cout << "swath-control sweep: " << flights.size() << " flights (" << values.size()
            << " values of " << key << " x " << seeds_ << " seeds); wrote " << output_ << '\n';
  return base::kExitSuccess;
}

}  // namespace swath::apps
