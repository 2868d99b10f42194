#include "sweep_command.hpp"

#include <cmath>
#include <iostream>

#include "control_images.hpp"
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

std::string sweep_percent(const control::MeanInterval& m) {
  return fixed_text(100 * m.mean, 1) + " % [" + fixed_text(100 * m.low, 1) + ", " +
         fixed_text(100 * m.high, 1) + "]";
}

control::MeanInterval sweep_scaled(control::MeanInterval m, double factor) {
  m.mean *= factor;
  m.low *= factor;
  m.high *= factor;
  return m;
}

// The figures of `count` flights from `first` (one value's seeds).
std::vector<control::FlightFigures> sweep_figures(const std::vector<BatchFlight>& flights,
                                                  std::size_t first, std::size_t count) {
  std::vector<control::FlightFigures> out;
  for (std::size_t k = first; k < first + count; ++k)
    out.push_back(control::figures_of(flights[k].summary));
  return out;
}

std::string sweep_statuses(const std::vector<BatchFlight>& flights, std::size_t first,
                           std::size_t count) {
  std::string out;
  for (std::size_t k = first; k < first + count; ++k) {
    const std::string s = control::to_string(flights[k].summary.status);
    if (out.find(s) == std::string::npos) out += (out.empty() ? "" : ", ") + s;
  }
  return out;
}

// The value's figures over its seeds: attitude, pitch, cross-track, executions/s, flight time, the
// core's busy share and the background releases completed.
std::string sweep_value_cells(const std::vector<control::FlightFigures>& f) {
  std::vector<double> att, pitch, xt, ex, ft, cpu, bg;
  for (const control::FlightFigures& g : f) {
    cpu.push_back(100 * g.cpu_utilisation);
    bg.push_back(100 * g.background_completed);
    att.push_back(g.attitude_rms_deg);
    pitch.push_back(g.axis_error_deg[1].rms);
    xt.push_back(g.cross_track_rms_m);
    ex.push_back(g.executions_per_s);
    ft.push_back(g.flight_time_s);
  }
  using control::mean_interval;
  return cell(mean_interval(att), 3) + " | " + cell(mean_interval(pitch), 3) + " | " +
         cell(mean_interval(xt), 3) + " | " + cell(mean_interval(ex), 1) + " | " +
         cell(mean_interval(ft), 1) + " | " + cell(mean_interval(cpu), 1) + " | " +
         cell(mean_interval(bg), 1);
}

}  // namespace

void ControlSweepCommand::setup(CLI::App& app) {
  app.add_option("MISSION", request_.mission,
                 "As for run, or `paper`: each environment's mission of paper 002 §7 (as compare)")
      ->required();
  app.add_option("-o,--output", output_, "Directory for runs.csv, sweep.md and sweep.png")
      ->required();
  app.add_option("--param", param_,
                 "The key and its values: FILE.KEY=V1,V2,.. or FILE.KEY=LO:HI:STEP, e.g. "
                 "scheduler.reactive.p_run=0.2:0.8:0.1")
      ->required();
  app.add_option("--vehicle", request_.vehicle, "Vehicle file or bundled name")
      ->capture_default_str();
  app.add_option("--vehicles", vehicles_,
                 "Several vehicles, comma-separated: one curve each (instead of --vehicle)")
      ->delimiter(',');
  app.add_option("--scheduler", request_.scheduler, "Scheduler file or bundled name")
      ->capture_default_str();
  app.add_option("--baseline", baseline_,
                 "A scheduler flown on the same seeds (once per seed for a scheduler key, else at "
                 "each value): the paired improvement of every value over it, e.g. tt-400");
  app.add_option("--environment", request_.environment, "Environment preset or file")
      ->capture_default_str();
  app.add_option("--environments", environments_,
                 "Several environments, comma-separated: one curve each (instead of "
                 "--environment)")
      ->delimiter(',');
  app.add_option("--seeds", seeds_, "Seeds 1..N per value")->capture_default_str();
  app.add_option("--jobs", jobs_, "Flights at once (default: the machine's cores)");
  add_flight_options(app, request_);
  app.add_flag("--no-pictures", no_pictures_, "Do not draw sweep.png");
  app.add_flag("--progress", progress_, "Show a progress bar (only on a terminal)");
}

int ControlSweepCommand::run() {
  if (seeds_ < 1 || seeds_ > 1000)
    throw InputError("--seeds " + std::to_string(seeds_) + ": expected 1 to 1000");
  std::string key;
  const std::vector<std::string> values = values_of(param_, key);
  const std::vector<std::string> vehicles =
      vehicles_.empty() ? std::vector<std::string>{request_.vehicle} : vehicles_;
  const std::vector<std::string> environments =
      environments_.empty() ? std::vector<std::string>{request_.environment} : environments_;
  const bool baseline = !baseline_.empty();
  // Named as the user gave it (the flights below would name --scheduler).
  if (baseline) config_file(baseline_, "schedulers", "scheduler", "--baseline");
  // A scheduler key does not reach another scheduler file: its baseline is the same at every
  // value, flown once per seed. A vehicle or environment key is the baseline's too.
  const bool baseline_per_value = key.rfind("scheduler.", 0) != 0;
  const std::size_t seeds = static_cast<std::size_t>(seeds_);
  const std::size_t base_values = baseline_per_value ? values.size() : 1;

  // Every flight's settings read and checked before anything is flown or written: the swept
  // flights group by group (environment, then vehicle), value by value, seed by seed; then the
  // baseline's in the same order.
  std::vector<BatchFlight> flights;
  auto add = [&](const std::string& env, const std::string& vehicle, const std::string& scheduler,
                 const std::string& value, bool set, int seed) {
    FlightRequest r = request_;
    if (r.mission == "paper") r.mission = paper_mission(env);
    r.environment = env;
    r.vehicle = vehicle;
    r.scheduler = scheduler;
    r.seed = static_cast<std::uint64_t>(seed);
    if (set) r.sets.push_back(key + "=" + value);
    flights.push_back({env, vehicle, scheduler, value, r.seed, prepare_flight(r).settings, {}});
  };
  for (const std::string& env : environments)
    for (const std::string& vehicle : vehicles)
      for (const std::string& v : values)
        for (int seed = 1; seed <= seeds_; ++seed)
          add(env, vehicle, request_.scheduler, v, true, seed);
  const std::size_t base_first = flights.size();
  if (baseline)
    for (const std::string& env : environments)
      for (const std::string& vehicle : vehicles)
        for (std::size_t v = 0; v < base_values; ++v)
          for (int seed = 1; seed <= seeds_; ++seed)
            add(env, vehicle, baseline_, baseline_per_value ? values[v] : "-", baseline_per_value,
                seed);
  // A file of the user's in the way is refused before the flights, not after them.
  std::vector<std::string> written{"runs.csv", "sweep.md"};
  if (!no_pictures_) written.push_back("sweep.png");
  base::check_output_names(output_, "control-sweep", written);
  base::OutputSet set(output_, "control-sweep");
  const unsigned jobs = jobs_ > 0 ? jobs_ : base::machine_threads();
  fly_all(flights, std::min<unsigned>(jobs, static_cast<unsigned>(flights.size())), progress_);

  std::string md = "# swath-control sweep of " + key + "\n\n" + request_.mission + ", " +
                   request_.scheduler + (baseline ? " against " + baseline_ : "") + "; seeds 1.." +
                   std::to_string(seeds_) + "; means with 95 % Student-t intervals" +
                   (baseline ? "; improvements over " + baseline_ +
                                   " paired by seed (positive: smaller error, fewer executions, "
                                   "longer flight)"
                             : "") +
                   ".\n\n| environment | vehicle | " + key +
                   " | status | attitude RMS (deg) | pitch RMS (deg) | cross-track RMS (m) | "
                   "executions/s | flight time (s) | CPU busy (%) | background completed (%) |" +
                   (baseline ? " pitch RMS improvement | attitude RMS improvement | fewer "
                               "executions | flight time |"
                             : "") +
                   "\n|---|---|---|---|---|---|---|---|---|---|---|" +
                   (baseline ? "---|---|---|---|" : "") + "\n";
  std::vector<SweptCurve> curves;
  bool numeric = true;
  std::vector<double> xs;
  for (std::size_t v = 0; v < values.size(); ++v) {
    double x = 0;
    numeric = numeric && base::parse_number(values[v], x);
    xs.push_back(numeric ? x : static_cast<double>(v + 1));
  }
  if (!numeric)
    for (std::size_t v = 0; v < values.size(); ++v) xs[v] = static_cast<double>(v + 1);
  std::size_t group = 0;
  for (const std::string& env : environments)
    for (const std::string& vehicle : vehicles) {
      SweptCurve curve{env + " " + vehicle, xs, {}};
      const auto base_at = [&](std::size_t v) {
        return base_first + (group * base_values + (baseline_per_value ? v : 0)) * seeds;
      };
      if (baseline && !baseline_per_value) {
        const std::size_t b = base_at(0);
        md += "| " + env + " | " + vehicle + " | " + baseline_ + " | " +
              sweep_statuses(flights, b, seeds) + " | " +
              sweep_value_cells(sweep_figures(flights, b, seeds)) + " | | | | |\n";
      }
      for (std::size_t v = 0; v < values.size(); ++v) {
        const std::size_t first = (group * values.size() + v) * seeds;
        const std::vector<control::FlightFigures> f = sweep_figures(flights, first, seeds);
        md += "| " + env + " | " + vehicle + " | " + values[v] + " | " +
              sweep_statuses(flights, first, seeds) + " | " + sweep_value_cells(f) + " |";
        std::vector<double> pitch;
        for (const control::FlightFigures& g : f) pitch.push_back(g.axis_error_deg[1].rms);
        if (baseline) {
          const control::Improvements i =
              control::paired_improvements(sweep_figures(flights, base_at(v), seeds), f);
          for (const control::MeanInterval* m :
               {&i.axis_rms[1], &i.attitude, &i.executions, &i.flight_time})
            md.append(" ").append(sweep_percent(*m)).append(" |");
          curve.y.push_back(sweep_scaled(i.axis_rms[1], 100));
        } else {
          curve.y.push_back(control::mean_interval(pitch));
        }
        md += "\n";
      }
      if (baseline && baseline_per_value) {
        for (std::size_t v = 0; v < values.size(); ++v) {
          const std::size_t b = base_at(v);
          md += "| " + env + " | " + vehicle + " | " + values[v] + " (" + baseline_ + ") | " +
                sweep_statuses(flights, b, seeds) + " | " +
                sweep_value_cells(sweep_figures(flights, b, seeds)) + " | | | | |\n";
        }
      }
      curves.push_back(std::move(curve));
      ++group;
    }
  set.add("runs.csv", runs_csv(flights, "value"));
  set.add("sweep.md", md);
  if (!no_pictures_) {
    const std::string x_label = key + (numeric ? "" : " (the values in order)");
    const ControlPicture p =
        baseline ? sweep_picture(curves,
                                 "Pitch RMS improvement of " + request_.scheduler + " over " +
                                     baseline_ + " (%, + = smaller error; 95 % intervals)",
                                 x_label, "%", 1000, 600)
                 : sweep_picture(curves, "Pitch RMS error (deg; 95 % intervals)", x_label, "deg",
                                 1000, 600);
    set.add("sweep.png", render::encode_png(render::draw(p.scene, p.view)));
  }
  set.commit();
  std::cout << "swath-control sweep: " << flights.size() << " flights (" << values.size()
            << " values of " << key << " x " << seeds_ << " seeds";
  if (curves.size() > 1) std::cout << " x " << curves.size() << " curves";
  if (baseline) std::cout << ", and " << flights.size() - base_first << " of " << baseline_;
  std::cout << "); wrote " << output_ << '\n';
  return base::kExitSuccess;
}

}  // namespace swath::apps
