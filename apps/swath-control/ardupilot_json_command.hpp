#pragma once
#include <cstdint>
#include <string>

#include "command.hpp"

namespace swath::apps {

/// swath-control ardupilot-json: swath's multirotor as the physics of ArduPilot's JSON SITL
/// interface (arducopter --model JSON), served over UDP until Ctrl-C.
class ControlArduPilotJsonCommand : public Command {
 public:
  const char* name() const override { return "ardupilot-json"; }
  const char* description() const override {
    return "Serve swath's simulated multirotor to ArduPilot SITL (arducopter --model "
           "JSON:127.0.0.1) over its JSON physics interface until Ctrl-C, then print what was "
           "served";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::string vehicle_ = "quad-f450", environment_ = "calm", address_ = "127.0.0.1", output_;
  int port_ = 9002;
  std::uint64_t seed_ = 1;
  double idle_exit_s_ = 0;
};

}  // namespace swath::apps
