#pragma once
// swath-fleet replay RUN.. -o DIR (docs/swath-fleet.md): trace replay of recorded runs — each
// run's dtg.json played back as an application (fleet/trace_replay.hpp) in the run's own world,
// with its fleet, scheduler, weights and seed unless the options say otherwise.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "command.hpp"
#include "fleet_inputs.hpp"

namespace swath::apps {

/// What a replay may change against the recorded run; empty or unset: the run's own.
struct ReplayOverrides {
  std::string scheduler, weights, fleet, forecast;
  std::vector<std::string> history;
  int drones = 0;
  bool seed_given = false, relief = false, force = false;
  std::uint64_t seed = 1;
};

/// The run a trace replay of run directory `run` makes (its app: the trace of run/dtg.json).
/// Throws base::InputError for a directory that is not a run, a graph without scripts, or a
/// schedule-dependent app without `force` (naming why).
PreparedRun prepare_replay(const std::string& run, const ReplayOverrides& o);

class FleetReplayCommand : public Command {
 public:
  const char* name() const override { return "replay"; }
  const char* description() const override {
    return "Trace replay: play recorded runs' dtg.json back as applications (tasks appear when "
           "their recorded predecessors are done here, plus the recorded delay; cancels fire "
           "with their trigger) in the run's world; writes run's files per run";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::filesystem::path output_directory(std::size_t i) const;

  std::vector<std::string> runs_;
  std::string output_;
  ReplayOverrides o_;
  CLI::Option* seed_option_ = nullptr;
};

}  // namespace swath::apps
