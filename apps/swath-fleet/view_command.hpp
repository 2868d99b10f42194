#pragma once
// swath-fleet view RUN_DIR [-o PAGE]: the live page of `run --live`, replaying a finished run.

#include <string>

#include "command.hpp"

namespace swath::apps {

class FleetViewCommand : public Command {
 public:
  const char* name() const override { return "view"; }
  const char* description() const override {
    return "Write a self-contained HTML page that replays a finished run from its events.jsonl "
           "(the page of run --live, with a time slider and a play button)";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::string run_, output_;
};

}  // namespace swath::apps
