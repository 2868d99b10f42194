#pragma once
#include <memory>
#include <string>

#include "command.hpp"
#include "fleet_inputs.hpp"

namespace swath::fleet {
struct RuntimeSettings;
}

namespace swath::apps {

class LiveServer;
class RunControl;

/// swath-fleet run APP --world W -o DIR: one application on a simulated fleet
/// (docs/swath-fleet.md).
class FleetRunCommand : public Command {
 public:
  const char* name() const override { return "run"; }
  const char* description() const override {
    return "Run an application on a simulated fleet (or on vehicles over MAVLink with --backend "
           "mavlink); writes events.jsonl, summary.json, "
           "dtg.json, tracks.geojson and timing.json (with --render also tracks.png and "
           "gantt.png)";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::unique_ptr<LiveServer> start_live(fleet::RuntimeSettings& settings) const;
  void linger(const LiveServer& server, const RunControl& control) const;

  FleetRequest request_;
  std::string output_, size_ = "1200x900";
  bool render_ = false;
  std::string backend_ = "sim", vehicles_;  ///< --backend sim|mavlink, --vehicles URL,..
  std::uint64_t world_seed_ = 0;
  CLI::Option* world_seed_option_ = nullptr;  ///< given: the world's random parts re-drawn
  // --on-abort rtl|land, --ctl-socket PATH, --pace FACTOR (simulated fleet),
  // --allow-no-gcs-failsafe.
  std::string on_abort_ = "rtl", ctl_socket_;
  double pace_ = 0;
  bool allow_no_gcs_failsafe_ = false;
  std::string signing_key_;  ///< --signing-key FILE
  // --live [PORT] (a page of the run as it happens, live_server.hpp), --live-linger S.
  CLI::Option* live_option_ = nullptr;
  std::string live_;
  double live_linger_s_ = -1;  ///< < 0: until Ctrl-C
};

/// swath-fleet apps: the built-in applications.
class FleetAppsCommand : public Command {
 public:
  const char* name() const override { return "apps"; }
  const char* description() const override { return "List the built-in applications"; }
  void setup(CLI::App&) override {}
  int run() override;
};

/// swath-fleet check RUN_DIR: the independent judge of a run's events.jsonl (docs/swath-fleet.md).
class FleetCheckCommand : public Command {
 public:
  const char* name() const override { return "check"; }
  const char* description() const override {
    return "Check a run's events.jsonl against the runtime's rules (every task ends "
           "once, no result twice, charge in [0, 1], termination, no lost drone dispatched); "
           "exit 4 when a rule is broken";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::string run_;
};

/// swath-fleet render RUN [--world W] [--size WxH] [-o DIR]: tracks.png and gantt.png of a run,
/// from its files alone (events.jsonl, summary.json and the world file it names).
class FleetRenderCommand : public Command {
 public:
  const char* name() const override { return "render"; }
  const char* description() const override {
    return "Draw tracks.png and gantt.png of a finished run from its events.jsonl and "
           "summary.json (the same pictures run --render draws)";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::string run_, world_, output_, size_ = "1200x900";
};

/// swath-fleet worlds gen KIND [--seed N]: a world file with its random parts written out.
class FleetWorldsCommand : public Command {
 public:
  const char* name() const override { return "worlds"; }
  const char* description() const override {
    return "worlds gen KIND [--seed N]: print a world of KIND (hotspot, road, rf_field, sites, "
           "tracking) drawn from the seed, its random parts (source, road, access points, sites) "
           "written out";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::string action_, kind_;
  std::uint64_t seed_ = 1;
};

/// swath-fleet compare APP --world W -o DIR: schedulers over seeds, with intervals.
class FleetCompareCommand : public Command {
 public:
  const char* name() const override { return "compare"; }
  const char* description() const override {
    return "Run an application with several schedulers over many seeds (each seed also a "
           "scenario of the world): predictive (sa + GMF learning from the reactive runs of "
           "the other seeds), reactive, sa, greedy, round-robin, hungarian; writes compare.csv "
           "and summary.json with 95 % intervals over the completed runs, runs that did not "
           "complete "
           "counted as censored (Kaplan–Meier median) and every seed paired against the first";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  FleetRequest request_;
  std::string output_, schedulers_ = "reactive,predictive";
  int seeds_ = 20;
  std::size_t histories_ = 5;
};

}  // namespace swath::apps
