#pragma once
#include <string>

#include "command.hpp"
#include "flight_inputs.hpp"
#include "swath/control/response.hpp"

namespace swath::apps {

/// swath-control response: a step or a chirp into one axis of the hovering multirotor; the time
/// series, the step figures or the Bode plot with its margins.
class ControlResponseCommand : public Command {
 public:
  const char* name() const override { return "response"; }
  const char* description() const override {
    return "Inject a step (attitude setpoint) or a chirp (torque at the rate loop's output) into "
           "one axis of the hovering multirotor; write the time series, the step's rise time, "
           "overshoot and settling time, or the loop's Bode plot and its gain and phase margins "
           "beside the closed form";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  FlightRequest request_;
  std::string output_, axis_ = "roll", input_ = "step", loop_ = "attitude", size_ = "1200x900";
  control::ResponseSettings test_;
  std::optional<double> duration_s_;
};

}  // namespace swath::apps
