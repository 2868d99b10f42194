#pragma once
#include <string>

#include "command.hpp"

namespace swath::apps {

/// swath-energy budget MISSION --drone CFG: time, energy and state of charge of a mission.
class BudgetCommand : public Command {
 public:
  const char* name() const override { return "budget"; }
  const char* description() const override {
    return "Energy, flight time and state of charge of each drone's waypoint mission "
           "(swath's mission.geojson or a QGC .plan); exit 4 when a drone would land below its "
           "reserve";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::string mission_, drone_, output_;
  bool json_ = false;
};

}  // namespace swath::apps
