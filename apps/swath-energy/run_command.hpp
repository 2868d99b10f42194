#pragma once
#include <string>

#include "command.hpp"

namespace swath::apps {

/// swath-energy run PLAN --config CFG -o DIR: the flight simulation with the energy model.
class RunCommand : public Command {
 public:
  const char* name() const override { return "run"; }
  const char* description() const override {
    return "Simulate a plan of flight stages with the energy model and the battery (parameters "
           "fixed at the config's values); writes trajectory.csv, energy.csv, summary.json";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::string plan_, config_, output_;
  bool progress_ = false;
};

}  // namespace swath::apps
