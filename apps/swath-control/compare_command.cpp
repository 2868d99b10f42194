#include "compare_command.hpp"

#include <iostream>
#include <nlohmann/json.hpp>

#include "control_images.hpp"
#include "flight_batch.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/base/output_set.hpp"
#include "swath/base/parallel.hpp"
#include "swath/control/experiment.hpp"

namespace swath::apps {
namespace {

using base::fixed_text;
using base::InputError;
using base::round_to;
using nlohmann::ordered_json;

struct Mode {
  std::string name, scheduler;
  std::vector<std::string> sets;
};

std::string stem(const std::string& name) {
  const auto slash = name.find_last_of('/');
  std::string s = slash == std::string::npos ? name : name.substr(slash + 1);
  const auto dot = s.rfind(".yaml");
  return dot == std::string::npos ? s : s.substr(0, dot);
}

ordered_json interval(const control::MeanInterval& m) {
  return {{"mean", round_to(m.mean, 6)},
          {"low", round_to(m.low, 6)},
          {"high", round_to(m.high, 6)},
          {"n", m.n}};
}

std::string percent(const control::MeanInterval& m) {
  return fixed_text(100 * m.mean, 1) + " % [" + fixed_text(100 * m.low, 1) + ", " +
         fixed_text(100 * m.high, 1) + "]";
}

double mean_of(const std::vector<control::FlightFigures>& f, double control::FlightFigures::*x) {
  double sum = 0;
  for (const auto& v : f) sum += v.*x;
  return f.empty() ? 0 : sum / static_cast<double>(f.size());
}

// The mean over seeds of one axis' RMS or max error: `axes` picks all-samples or
// disturbance-only, `max` the statistic.
double axis_mean(const std::vector<control::FlightFigures>& f,
                 std::array<control::ErrorStat, 3> control::FlightFigures::*axes, std::size_t axis,
                 bool max) {
  double sum = 0;
  for (const auto& v : f) sum += max ? (v.*axes)[axis].max : (v.*axes)[axis].rms;
  return f.empty() ? 0 : sum / static_cast<double>(f.size());
}

// comparison.md's by-axis rows: one mode's means (degrees), all samples and disturbance only.
std::string axis_row(const std::string& environment, const std::string& vehicle,
                     const std::string& mode, const std::vector<control::FlightFigures>& f) {
  using F = control::FlightFigures;
  std::string row = "| " + environment + " | " + vehicle + " | " + mode + " |";
  for (std::size_t a = 0; a < 3; ++a)
    row += " " + fixed_text(axis_mean(f, &F::axis_error_deg, a, false), 2) + "° / " +
           fixed_text(axis_mean(f, &F::axis_error_deg, a, true), 1) + "° |";
  for (std::size_t a = 0; a < 3; ++a)
    row += " " + fixed_text(axis_mean(f, &F::axis_disturbance_error_deg, a, false), 2) + "°" +
           (a < 2 ? " /" : "");
  return row + " (" + fixed_text(100 * mean_of(f, &F::disturbance_share), 0) + " %) |\n";
}

ordered_json axes_json(const control::Improvements& imp) {
  ordered_json j;
  const char* names[] = {"roll", "pitch", "yaw"};
  for (std::size_t a = 0; a < 3; ++a)
    j[names[a]] = {{"rms", interval(imp.axis_rms[a])}, {"max", interval(imp.axis_max[a])}};
  return j;
}

}  // namespace

void ControlCompareCommand::setup(CLI::App& app) {
  app.add_option("MISSION", request_.mission,
                 "As for run, or `paper`: each environment's mission of paper 002 §7 (lab "
                 "random:8@20x20, rugby random:8@100x70, arch random:8@170x170)")
      ->required();
  app.add_option("-o,--output", output_, "Directory for runs.csv, comparison.json, comparison.md")
      ->required();
  app.add_option("--vehicles", vehicles_, "Vehicles, comma-separated (files or bundled names)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--schedulers", schedulers_,
                 "Scheduling modes, comma-separated; the first is the baseline the others are "
                 "compared with")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--environments", environments_, "Environments, comma-separated")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--tt-rates", tt_rates_,
                 "Also time-triggered at these rates, Hz (the first scheduler's file with its "
                 "rate_hz replaced), e.g. 100,200,1000")
      ->delimiter(',');
  app.add_option("--seeds", seeds_, "Seeds 1..N per environment, vehicle and mode")
      ->capture_default_str();
  app.add_option("--jobs", jobs_, "Flights at once (default: the machine's cores)");
  app.add_flag("--quick", quick_,
               "A check, not a result: 2 seeds, 20 s flights, a 5 s boot and metrics from 5 s");
  add_flight_options(app, request_);
  app.add_flag("--no-pictures", no_pictures_,
               "Write the tables only (no improvement.png, rate.png)");
  app.add_flag("--progress", progress_, "Show a progress bar (only on a terminal)");
}

namespace {

// The comparison of every mode with the first one, paired by seed: comparison.json's groups,
// comparison.md and the pictures' groups.
struct Comparison {
  ordered_json groups = ordered_json::array();
  std::vector<ComparedGroup> picture_groups;
  std::string md;
};

const char* kAxesIntro =
    "\n## Attitude error by axis\n\nThe paper's Figs. 9-10 report roll, pitch and yaw "
    "separately. Means over seeds of the true attitude against its setpoint; \"disturbance "
    "only\": the samples when nothing was commanded (the carrot at constant velocity, the heading "
    "not slewing for the last second), with their share of the samples.\n\n"
    "| environment | vehicle | mode | roll RMS / max | pitch RMS / max | yaw RMS / max | roll / "
    "pitch / yaw RMS, disturbance only |\n|---|---|---|---|---|---|---|\n";

const char* kAxesImprovementIntro =
    "\nImprovements by axis over the baseline, paired by seed (positive = smaller error), with "
    "95 % intervals; the last column is roll and pitch together over the disturbance-only "
    "samples.\n\n| environment | vehicle | mode | roll RMS | pitch RMS | yaw RMS | roll max | "
    "pitch max | yaw max | attitude RMS, disturbance only |\n"
    "|---|---|---|---|---|---|---|---|---|---|\n";

Comparison compare_pairs(const std::vector<BatchFlight>& runs, const std::vector<Mode>& modes,
                         int seeds) {
  Comparison c;
  c.md =
      "# swath-control compare\n\nPaired by seed (the same wind and sensor noise in every mode); "
      "improvements of each mode over `" +
      modes.front().name +
      "` with 95 % Student-t intervals over seeds. Errors and executions: (baseline − mode) / "
      "baseline, positive = fewer. Flight time (to the reserve when reached): (mode − baseline) / "
      "baseline, positive = longer.\n\nPaper 002's claims (real flights): attitude and tracking "
      "error 22 to 41 % lower (Figs. 9-10), flight time 11 to 24 % longer (Fig. 12).\n\n"
      "| environment | vehicle | mode | attitude RMS | attitude RMS (estimate) | cross-track RMS "
      "| executions/s (baseline → mode) | unchanged outputs (baseline) | flight time |\n"
      "|---|---|---|---|---|---|---|---|---|\n";
  std::string axes_md = kAxesIntro, axes_improvement_md = kAxesImprovementIntro;
  const std::size_t per_mode = static_cast<std::size_t>(seeds);
  for (std::size_t g = 0; g < runs.size(); g += per_mode * modes.size()) {
    auto figures = [&](std::size_t m) {
      std::vector<control::FlightFigures> f;
      for (std::size_t k = 0; k < per_mode; ++k)
        f.push_back(control::figures_of(runs[g + m * per_mode + k].summary));
      return f;
    };
    const auto baseline = figures(0);
    axes_md += axis_row(runs[g].environment, runs[g].vehicle, modes.front().name, baseline);
    ComparedGroup picture_group;
    picture_group.label = runs[g].environment + " " + runs[g].vehicle;
    picture_group.executions_per_s.push_back(
        mean_of(baseline, &control::FlightFigures::executions_per_s));
    for (std::size_t m = 1; m < modes.size(); ++m) {
      const auto mode = figures(m);
      const control::Improvements imp = control::paired_improvements(baseline, mode);
      const BatchFlight& first = runs[g];
      axes_md += axis_row(first.environment, first.vehicle, modes[m].name, mode);
      axes_improvement_md +=
          "| " + first.environment + " | " + first.vehicle + " | " + modes[m].name + " |";
      for (const auto& axis : {imp.axis_rms, imp.axis_max})
        for (const control::MeanInterval& i : axis)
          axes_improvement_md.append(" ").append(percent(i)).append(" |");
      axes_improvement_md.append(" ").append(percent(imp.disturbance)).append(" |\n");
      const double eb = mean_of(baseline, &control::FlightFigures::executions_per_s);
      const double em = mean_of(mode, &control::FlightFigures::executions_per_s);
      const double ub = mean_of(baseline, &control::FlightFigures::unchanged_fraction);
      picture_group.executions_per_s.push_back(em);
      picture_group.attitude.push_back(imp.attitude);
      picture_group.cross_track.push_back(imp.cross_track);
      picture_group.flight_time.push_back(imp.flight_time);
      c.groups.push_back(
          {{"environment", first.environment},
           {"vehicle", first.vehicle},
           {"mode", modes[m].name},
           {"baseline", modes.front().name},
           {"attitude", interval(imp.attitude)},
           {"attitude_estimated", interval(imp.attitude_estimated)},
           {"cross_track", interval(imp.cross_track)},
           {"executions", interval(imp.executions)},
           {"flight_time", interval(imp.flight_time)},
           {"executions_per_s", {{"baseline", round_to(eb, 3)}, {"mode", round_to(em, 3)}}},
           {"unchanged_fraction_baseline", round_to(ub, 6)},
           {"axes", axes_json(imp)},
           {"attitude_disturbance", interval(imp.disturbance)}});
      c.md += "| " + first.environment + " | " + first.vehicle + " | " + modes[m].name + " | " +
              percent(imp.attitude) + " | " + percent(imp.attitude_estimated) + " | " +
              percent(imp.cross_track) + " | " + fixed_text(eb, 1) + " → " + fixed_text(em, 1) +
              " | " + fixed_text(100 * ub, 2) + " % | " + percent(imp.flight_time) + " |\n";
    }
    c.picture_groups.push_back(std::move(picture_group));
  }
  c.md += axes_md + axes_improvement_md;
  return c;
}

// The modes: each scheduler file, then time-triggered runs at each --tt-rate.
std::vector<Mode> compare_modes(const std::vector<std::string>& schedulers,
                                const std::vector<double>& tt_rates) {
  std::vector<Mode> modes;
  for (const std::string& s : schedulers) modes.push_back({stem(s), s, {}});
  for (double rate : tt_rates)
    modes.push_back(
        {"tt-" + base::shortest_text(rate),
         schedulers.front(),
         {"scheduler.mode=time_triggered", "scheduler.rate_hz=" + base::shortest_text(rate)}});
  return modes;
}

}  // namespace

int ControlCompareCommand::run() {
  if (seeds_ < 1 || seeds_ > 1000)
    throw InputError("--seeds " + std::to_string(seeds_) + ": expected 1 to 1000");
  if (schedulers_.empty() || environments_.empty() || vehicles_.empty())
    throw InputError("--schedulers, --environments and --vehicles each need at least one name");
  FlightRequest base = request_;
  int seeds = seeds_;
  if (quick_) {
    seeds = std::min(seeds, 2);
    base.max_time_s = std::min(base.max_time_s.value_or(20.0), 20.0);
    base.sets.push_back("scheduler.reactive.boot_s=5");
    base.sets.push_back("scheduler.run.metrics_from_s=5");
  }
  const std::vector<Mode> modes = compare_modes(schedulers_, tt_rates_);
  // Every flight's settings read and checked before anything is flown or written.
  std::vector<BatchFlight> runs;
  for (const std::string& env : environments_)
    for (const std::string& vehicle : vehicles_)
      for (const Mode& mode : modes)
        for (int seed = 1; seed <= seeds; ++seed) {
          FlightRequest r = base;
          if (r.mission == "paper") r.mission = paper_mission(env);
          r.environment = env;
          r.vehicle = vehicle;
          r.scheduler = mode.scheduler;
          r.seed = static_cast<std::uint64_t>(seed);
          r.sets.insert(r.sets.end(), mode.sets.begin(), mode.sets.end());
          runs.push_back(
              {env, stem(vehicle), mode.name, "", r.seed, prepare_flight(r).settings, {}});
        }
  const bool pictures = !no_pictures_ && modes.size() > 1;
  // A file of the user's in the way is refused before the flights, not after them.
  std::vector<std::string> written{"runs.csv", "comparison.json", "comparison.md"};
  if (pictures) written.insert(written.end(), {"improvement.png", "rate.png"});
  base::check_output_names(output_, "control-compare", written);
  base::OutputSet set(output_, "control-compare");
  const unsigned jobs = jobs_ > 0 ? jobs_ : base::machine_threads();
  fly_all(runs, std::min<unsigned>(jobs, static_cast<unsigned>(runs.size())), progress_);
  const Comparison c = compare_pairs(runs, modes, seeds);
  ordered_json j;
  j["mission"] = request_.mission;
  j["seeds"] = seeds;
  j["quick"] = quick_;
  j["modes"] = ordered_json::array();
  for (const Mode& m : modes) j["modes"].push_back(m.name);
  j["comparisons"] = c.groups;
  set.add("runs.csv", runs_csv(runs));
  set.add("comparison.json", base::json_text(j, 1) + "\n");
  set.add("comparison.md", c.md);
  if (pictures) {
    std::vector<std::string> names;
    for (const Mode& m : modes) names.push_back(m.name);
    auto png = [](const ControlPicture& p) {
      return render::encode_png(render::draw(p.scene, p.view));
    };
    set.add("improvement.png", png(improvement_picture(c.picture_groups, names, 1200, 1200)));
    set.add("rate.png", png(rate_picture(c.picture_groups, names, 1200, 600)));
  }
  set.commit();
  std::cout << "swath-control compare: " << runs.size() << " flights (" << environments_.size()
            << " environments x " << vehicles_.size() << " vehicles x " << modes.size()
            << " modes x " << seeds << " seeds); wrote " << output_ << '\n';
  return base::kExitSuccess;
}

}  // namespace swath::apps
