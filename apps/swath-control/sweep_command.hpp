#pragma once
#include <string>
#include <vector>

#include "command.hpp"
#include "flight_inputs.hpp"

namespace swath::apps {

/// swath-control sweep MISSION --param FILE.KEY=V1,V2,..|LO:HI:STEP -o DIR: one key of the
/// vehicle, scheduler or environment file over values, each flown with seeds 1..N
/// (docs/swath-control.md; paper 002's Fig. 14: P_run and T_failsafe swept, each value's pitch
/// error improvement over a time-triggered --baseline, one curve per environment and vehicle).
class ControlSweepCommand : public Command {
 public:
  const char* name() const override { return "sweep"; }
  const char* description() const override {
    return "Fly a mission for each value of one key (any --set key) and seeds 1..N: runs.csv and "
           "sweep.md with each value's means and 95 % intervals";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  FlightRequest request_;
  std::string output_, param_, baseline_;
  std::vector<std::string> vehicles_, environments_;
  int seeds_ = 3;
  unsigned jobs_ = 0;
  bool progress_ = false, no_pictures_ = false;
};

}  // namespace swath::apps
