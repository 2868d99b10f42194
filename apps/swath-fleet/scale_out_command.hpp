#pragma once
// swath-fleet's scale-out (docs/swath-fleet.md): a run is one process with deterministic files, so
// many runs are spread by an existing engine. `sweep SPEC` prints one command line per run (GNU
// parallel locally or over SSH, a Slurm job array); `collect RUN... -o DIR` merges the runs'
// summaries into one table and refuses runs of another swath version or another configuration.

#include <string>
#include <vector>

#include "command.hpp"

namespace swath::apps {

class FleetSweepCommand : public Command {
 public:
  const char* name() const override { return "sweep"; }
  const char* description() const override {
    return "Print one swath-fleet run command line per (scheduler, seed) of a sweep file, for "
           "GNU parallel or a Slurm job array";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::string spec_, runs_dir_ = "runs", program_, part_ = "all";
};

class FleetCollectCommand : public Command {
 public:
  const char* name() const override { return "collect"; }
  const char* description() const override {
    return "Merge the summaries of runs (one swath version, one configuration) into collect.csv";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::vector<std::string> runs_;
  std::string output_;
};

}  // namespace swath::apps
