#include "run_command.hpp"

#include <filesystem>
#include <iostream>

#include "control_images.hpp"
#include "data_dir.hpp"
#include "flight_inputs.hpp"
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

void warn(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) std::cerr << "swath-control run: warning: " << w << '\n';
}

// Rows into the streams as they come; a bounded copy for the pictures.
class Recorder : public control::SimulationObserver {
 public:
  Recorder(base::OutputSet::Stream& rows, base::OutputSet::Stream& seconds,
           base::OutputSet::Stream& fits, control::FitMethod method, double raster_from_s,
           ProgressBar& bar)
      : rows_(rows), seconds_(seconds), fits_(fits), method_(method), bar_(bar) {
    raster_.from_s = raster_from_s;
    raster_.to_s = raster_from_s + 2;
  }
  void on_execution(const control::ExecutionRow& row) override {
    raster_.add_execution(row.start_s, row.cause, row.changed);
    if (executions_) *executions_ << control::executions_csv_row(row, trigger_sensors_);
  }
  /// --log-executions: every execution into `stream`.
  void log_executions(base::OutputSet::Stream& stream, std::size_t trigger_sensors) {
    executions_ = &stream;
    trigger_sensors_ = trigger_sensors;
  }
  void on_trigger(double t_s, std::size_t sensor) override { raster_.add_trigger(t_s, sensor); }
  void on_fit(const control::FitRow& row) override { fits_ << control::fits_csv_row(row, method_); }
  const Raster& raster() const { return raster_; }
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
  base::OutputSet::Stream& fits_;
  control::FitMethod method_;
  ProgressBar& bar_;
  Raster raster_;
  base::OutputSet::Stream* executions_ = nullptr;
  std::size_t trigger_sensors_ = 0;
  FlightSeries kept_;
  std::vector<control::RateRow> rates_;
};

}  // namespace

void ControlRunCommand::setup(CLI::App& app) {
  app.add_option("MISSION", request_.mission,
                 "swath's mission.geojson, a QGC .plan or .waypoints (one drone: --drone), a stage "
                 "plan (.stages or .yaml), or random:N@WxH (N waypoints in a W by H metre box; the "
                 "paper's missions are random:8@20x20, random:8@100x70, random:8@170x170)")
      ->required();
  app.add_option("-o,--output", output_,
                 "Directory for timeseries.csv, rate.csv, fits.csv, summary.json and the pictures")
      ->required();
  app.add_option("--vehicle", request_.vehicle,
                 "Vehicle file, or a bundled one: quad-f450, hexa-f550, y6, quad-f450-cc3d")
      ->capture_default_str();
  app.add_option("--scheduler", request_.scheduler,
                 "Scheduler file, or a bundled one: tt-400, reactive")
      ->capture_default_str();
  app.add_option("--environment", request_.environment,
                 "Wind: calm, lab, rugby, arch (paper 002's places) or an environment file")
      ->capture_default_str();
  add_flight_options(app, request_);
  app.add_flag("--log-executions", log_executions_,
               "Also write executions.csv: every execution's request, start and end, cause, "
               "trigger sensors, output change, false positive/negative and each sensor's change "
               "(~100 bytes per execution: 140 MB per hour at 400 Hz)");
  app.add_option("--raster-at", raster_at_s_,
                 "Where triggers.png's two-second raster starts, s (default: the scheduler's "
                 "run.metrics_from_s, 30)")
      ->check(CLI::Range(0.0, 86'400.0));
  app.add_option("--size", size_, "Size of the pictures, WxH pixels")->capture_default_str();
  app.add_flag("--no-pictures", no_pictures_,
               "Write the CSV files and summary.json only (drawing costs ~0.4 s and ~25 MB of "
               "memory, whatever the flight's length)");
  app.add_flag("--progress", progress_, "Show a progress bar (only on a terminal)");
}

int ControlRunCommand::run() {
  // 1. Inputs, each checked before anything is written.
  const auto [width_px, height_px] = parse_size(size_);
  PreparedFlight prepared = prepare_flight(request_);
  warn(prepared.warnings);
  const control::SimulationSettings& settings = prepared.settings;

  // 2. The flight, its rows streamed into the output set's temporaries.
  base::OutputSet set(output_, "control-run");
  // The files added after the flight refused before it too: no flight for nothing.
  std::vector<std::string> later{"summary.json"};
  if (!no_pictures_)
    for (const std::string& name : control_image_names()) later.push_back(name);
  base::check_output_names(output_, "control-run", later);
  base::OutputSet::Stream& rows = set.stream("timeseries.csv");
  base::OutputSet::Stream& seconds = set.stream("rate.csv");
  const std::vector<std::string> triggers = control::trigger_sensor_names(settings.physics);
  rows << control::timeseries_csv_header(settings.physics.airframe.rotors.size());
  seconds << control::rate_csv_header(triggers);
  base::OutputSet::Stream& fits = set.stream("fits.csv");
  fits << control::fits_csv_header();
  control::SimulationSummary summary;
  FlightSeries kept;
  std::vector<control::RateRow> rates;
  Raster raster;
  {
    ProgressBar bar(progress_, "flying");
    Recorder recorder(rows, seconds, fits, settings.scheduler.reactive.fit_method,
                      raster_at_s_.value_or(settings.scheduler.run.metrics_from_s), bar);
    if (log_executions_) {
      base::OutputSet::Stream& executions = set.stream("executions.csv");
      executions << control::executions_csv_header(triggers);
      recorder.log_executions(executions, triggers.size());
    }
    summary = control::simulate(settings, &recorder);
    kept = recorder.kept();
    rates = recorder.rates();
    raster = recorder.raster();
  }

  // 3. The summary and the pictures; everything appears at once.
  set.add("summary.json", control::summary_json(summary, prepared.inputs, settings));
  if (!no_pictures_)
    add_control_images(set, settings, summary, kept, rates, raster, width_px, height_px);
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
