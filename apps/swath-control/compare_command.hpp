#pragma once
#include <string>
#include <vector>

#include "command.hpp"
#include "flight_inputs.hpp"

namespace swath::apps {

/// swath-control compare MISSION|paper -o DIR: paper 002's experiment (§7) on our own missions —
/// every environment × vehicle × mode × seed, paired by seed (docs/swath-control.md).
class ControlCompareCommand : public Command {
 public:
  const char* name() const override { return "compare"; }
  const char* description() const override {
    return "Fly a mission in every environment x vehicle x scheduling mode x seed, paired by seed, "
           "and compare each mode with the first (time-triggered) one: runs.csv, "
           "comparison.json (paired improvements with 95 % Student-t intervals), comparison.md, "
           "improvement.png, rate.png";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  FlightRequest request_;
  std::string output_;
  std::vector<std::string> vehicles_{"quad-f450"}, schedulers_{"tt-400", "reactive"};
  std::vector<std::string> environments_{"lab", "rugby", "arch"};
  std::vector<double> tt_rates_;
  int seeds_ = 5;
  unsigned jobs_ = 0;
  bool quick_ = false, progress_ = false, no_pictures_ = false;
};

}  // namespace swath::apps
