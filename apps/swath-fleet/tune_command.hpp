#pragma once
// swath-fleet tune (DESIGN.md §18.8): the sub-utility weights of `predictive` (sa + GMF + relief)
// chosen by replaying the app in its worlds. Trials draw the free weights log-uniformly in
// [1e-3, 1e3] or 0; successive halving over the tuning seeds keeps the better half after each
// seed; the winner, the default weights and `reactive` are re-scored on held-out seeds.

#include <cstdint>
#include <string>

#include "command.hpp"
#include "fleet_inputs.hpp"

namespace swath::apps {

class FleetTuneCommand : public Command {
 public:
  const char* name() const override { return "tune"; }
  const char* description() const override {
    return "Tune predictive's weights by world replay: log-uniform trials, successive halving "
           "over tuning seeds, the winner re-scored on held-out seeds; writes weights.yaml, "
           "tune.csv, held_out.csv and summary.json";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  FleetRequest request_;
  std::string output_;
  int trials_ = 64;            ///< weight sets tried, the defaults and reactive's among them
  int tuning_seeds_ = 3;       ///< seeds of the halving (one more per rung)
  int held_out_ = 10;          ///< seeds the winner is scored on, none of them tuned on
  std::size_t histories_ = 5;  ///< reactive runs GMF learns from (their own seeds)
};

}  // namespace swath::apps
