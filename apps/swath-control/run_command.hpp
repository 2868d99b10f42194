#pragma once
#include <optional>
#include <string>
#include <vector>

#include "command.hpp"

namespace swath::apps {

/// swath-control run MISSION -o DIR: one mission flown by the simulated multirotor and its
/// control task (DESIGN.md §17.5).
class ControlRunCommand : public Command {
 public:
  const char* name() const override { return "run"; }
  const char* description() const override {
    return "Fly a mission (swath's mission.geojson or a QGC .plan/.waypoints, a stage plan, or "
           "random:N@WxH) with a simulated multirotor, its sensors, control task, flight computer "
           "and battery, in wind; writes timeseries.csv, rate.csv, summary.json, trajectory.png, "
           "attitude.png, energy.png";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::string mission_, vehicle_ = "quad-f450", scheduler_ = "tt-400", environment_ = "calm";
  std::string output_, drone_, start_, size_ = "1200x900";
  std::vector<std::string> sets_;
  std::uint64_t seed_ = 1;
  bool loop_ = false, progress_ = false, no_pictures_ = false;
  std::optional<double> speed_m_s_, altitude_m_, max_time_s_;
};

}  // namespace swath::apps
