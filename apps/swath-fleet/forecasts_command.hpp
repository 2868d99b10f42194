#pragma once
#include <string>

#include "command.hpp"
#include "fleet_inputs.hpp"
#include "swath/fleet/forecaster.hpp"

namespace swath::apps {

/// swath-fleet forecasts APP --world W --seeds N -o DIR: how well each forecaster predicts the
/// app's next requests and cancellations on held-out runs (docs/swath-fleet.md): N runs, each
/// scored with the other N − 1 as history (leave one out).
class FleetForecastsCommand : public Command {
 public:
  const char* name() const override { return "forecasts"; }
  const char* description() const override {
    return "Score forecasters on held-out runs (leave one out over seeds): distance from each "
           "task spawned next to the nearest confident forecast, recall within 2 m, Brier score "
           "of cancellations; writes forecasts.csv and summary.json";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  FleetRequest request_;
  std::string output_, forecasters_ = "gmf,constant-velocity";
  int seeds_ = 20;
  double p_min_ = 0.5, within_m_ = 2.0;
  fleet::GmfSettings gmf_;
};

}  // namespace swath::apps
