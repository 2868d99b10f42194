#pragma once
#include <optional>
#include <string>
#include <vector>

#include "command.hpp"
#include "flight_inputs.hpp"

namespace swath::apps {

/// swath-control run MISSION -o DIR: one mission flown by the simulated multirotor and its
/// control task (docs/swath-control.md).
class ControlRunCommand : public Command {
 public:
  const char* name() const override { return "run"; }
  const char* description() const override {
    return "Fly a mission (swath's mission.geojson or a QGC .plan/.waypoints, a stage plan, or "
           "random:N@WxH) with a simulated multirotor, its sensors, control task, flight computer "
           "and battery, in wind; writes timeseries.csv, rate.csv, fits.csv, summary.json, "
           "trajectory.png, attitude.png, energy.png, triggers.png";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  FlightRequest request_;
  std::string output_, size_ = "1200x900";
  bool progress_ = false, no_pictures_ = false, log_executions_ = false;
  std::optional<double> raster_at_s_;
};

}  // namespace swath::apps
