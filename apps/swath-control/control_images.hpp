#pragma once
// swath-control's pictures (docs/swath-control.md): the flight over the mission coloured by
// cross-track error with the area and no-fly zones (trajectory.png); attitude and its setpoint, and
// the tracking error, over time (attitude.png); power by consumer, state of charge and executions
// per second (energy.png).

#include <vector>

#include "swath/base/output_set.hpp"
#include "swath/control/experiment.hpp"
#include "swath/control/simulation.hpp"
#include "swath/render/chart.hpp"
#include "swath/render/image.hpp"

namespace swath::apps {

/// The rows kept for the pictures: every row until kMaxKept, then every 2nd, 4th, … (the memory
/// of a flight of any length stays bounded; the CSV has every row).
class FlightSeries {
 public:
  static constexpr std::size_t kMaxKept = 4096;
  void add(const control::TimeseriesRow& row);
  const std::vector<control::TimeseriesRow>& rows() const { return rows_; }

 private:
  std::vector<control::TimeseriesRow> rows_;
  std::size_t stride_ = 1, seen_ = 0;
};

/// Two seconds of events for the raster of triggers.png.
struct Raster {
  double from_s = 0, to_s = 2;
  std::vector<std::pair<double, control::ReleaseCause>> executions;  ///< start, cause
  std::vector<double> unchanged;                                     ///< starts of those
  std::vector<std::vector<double>> triggers;                         ///< per trigger sensor
  void add_execution(double t, control::ReleaseCause cause, bool changed) {
    if (t < from_s || t >= to_s) return;
    executions.push_back({t, cause});
    if (!changed) unchanged.push_back(t);
  }
  void add_trigger(double t, std::size_t sensor) {
    if (t < from_s || t >= to_s) return;
    if (triggers.size() <= sensor) triggers.resize(sensor + 1);
    triggers[sensor].push_back(t);
  }
};

struct ControlPicture {
  render::Scene scene;
  render::View view;
  std::vector<render::ChartLayout> charts;  ///< stacked charts (y offsets in offsets_px)
  std::vector<double> offsets_px;
};

/// The mission (grey), area and no-fly zones, the flight coloured by cross-track error (green 0,
/// red at or above max(1 m, the flight's largest)), start and end, a scale bar and north.
ControlPicture trajectory_picture(const control::SimulationSettings& settings,
                                  const control::SimulationSummary& summary,
                                  const FlightSeries& flight, int width_px, int height_px);
/// Roll and pitch with their setpoints; cross-track error.
ControlPicture attitude_picture(const FlightSeries& flight, int width_px, int height_px);
/// Motor, CPU and avionics power; state of charge with the reserve; executions per second.
ControlPicture energy_picture(const control::SimulationSettings& settings,
                              const FlightSeries& flight, int width_px, int height_px);

/// Executions per second by cause (paper 002 Fig. 11) over the flight, and a raster of two
/// seconds: a tick per execution in its cause's row, per unchanged output, per sensor trigger.
ControlPicture triggers_picture(const std::vector<control::RateRow>& rates, const Raster& raster,
                                const std::vector<std::string>& trigger_sensors, int width_px,
                                int height_px);

/// One group of a comparison (an environment and vehicle) and each mode's figures in it.
struct ComparedGroup {
  std::string label;                     ///< "lab quad-f450"
  std::vector<double> executions_per_s;  ///< per mode, the baseline first
  std::vector<control::MeanInterval> attitude, cross_track,
      flight_time;  ///< per mode but the baseline
};

/// improvement.png: attitude, cross-track and flight-time improvement of each mode over the
/// baseline, per group, with 95 % intervals as bars (x: the group's number, listed in the title).
ControlPicture improvement_picture(const std::vector<ComparedGroup>& groups,
                                   const std::vector<std::string>& modes, int width_px,
                                   int height_px);
/// rate.png: executions per second of every mode, per group.
ControlPicture rate_picture(const std::vector<ComparedGroup>& groups,
                            const std::vector<std::string>& modes, int width_px, int height_px);

/// One curve of a sweep (an environment and vehicle): each value's mean and 95 % interval.
struct SweptCurve {
  std::string label;                     ///< "arch hexa-f550"
  std::vector<double> x;                 ///< the values (or their index when not numbers)
  std::vector<control::MeanInterval> y;  ///< per value, in the chart's unit
};

/// sweep.png: one chart of every curve against the swept value, intervals as bars (paper 002's
/// Fig. 14 when y is the pitch error improvement over time-triggered control).
ControlPicture sweep_picture(const std::vector<SweptCurve>& curves, const std::string& title,
                             const std::string& x_label, const std::string& y_label, int width_px,
                             int height_px);

/// The names of the four pictures add_control_images() writes.
std::vector<std::string> control_image_names();

/// The four pictures into the output set as PNG.
void add_control_images(base::OutputSet& set, const control::SimulationSettings& settings,
                        const control::SimulationSummary& summary, const FlightSeries& flight,
                        const std::vector<control::RateRow>& rates, const Raster& raster,
                        int width_px, int height_px);

}  // namespace swath::apps
