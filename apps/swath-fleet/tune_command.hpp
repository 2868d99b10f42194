#pragma once
// swath-fleet tune (docs/swath-fleet.md): the sub-utility weights of `predictive` (sa + GMF +
// relief) chosen by replaying the app in its worlds. Trials draw the free weights log-uniformly in
// [1e-3, 1e3] or 0; successive halving over the tuning seeds keeps the better half after each
// seed; the winner, the default weights and `reactive` are re-scored on held-out seeds.
// `tune ask STATE` / `tune tell STATE RUN..` split the same search into command lines for an
// engine that runs them (GNU parallel, Slurm; docs/swath-fleet.md): ask prints the runs of the next
// rung, tell feeds their run directories back; after the last rung tell writes weights.yaml and
// tune.csv as tune does. `--replay trace` scores the trials by trace replay of the tuning seeds'
// reactive runs instead of re-running the app (valid where the graph does not depend on the
// schedule, docs/swath-fleet.md).

#include <cstdint>
#include <string>
#include <vector>

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
  void add_tune_options(CLI::App& app, bool required);
  int ask();
  int tell();
  void check_last_seed() const;

  FleetRequest request_;
  std::string output_;
  std::string replay_ = "world";  ///< world | trace: how a trial's run replays the app
  CLI::App* ask_ = nullptr;
  CLI::App* tell_ = nullptr;
  std::string state_, runs_dir_, program_;
  std::vector<std::string> told_runs_;
  int trials_ = 64;            ///< weight sets tried, the defaults and reactive's among them
  int tuning_seeds_ = 3;       ///< seeds of the halving (one more per rung)
  int held_out_ = 10;          ///< seeds the winner is scored on, none of them tuned on
  std::size_t histories_ = 5;  ///< reactive runs GMF learns from (their own seeds)
};

}  // namespace swath::apps
