#pragma once
// swath-fleet ctl VERB [--socket PATH]: an order to a running `swath-fleet run --ctl-socket PATH`
// (docs/swath-fleet.md, "Abort and control").

#include <string>

#include "command.hpp"

namespace swath::apps {

class FleetCtlCommand : public Command {
 public:
  const char* name() const override { return "ctl"; }
  const char* description() const override {
    return "Tell a running `swath-fleet run --ctl-socket PATH` to pause, resume, rtl-all or "
           "land-all";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::string verb_, socket_;
};

}  // namespace swath::apps
