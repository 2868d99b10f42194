#pragma once
#include <string>

#include "command.hpp"

namespace swath::apps {

/// swath-energy run PLAN --config CFG -o DIR: the flight simulation with the energy model.
class RunCommand : public Command {
 public:
  const char* name() const override { return "run"; }
  const char* description() const override {
    return "Simulate a plan of flight stages with the energy model and the battery, replanning "
           "its parameters to finish above the reserve; writes trajectory.csv, energy.csv, "
           "control.csv, summary.json, trajectory.png, energy.png";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::string plan_, config_, output_;
  bool progress_ = false;
  bool no_replan_ = false;
  std::string size_ = "1200x900";
};

}  // namespace swath::apps
