#pragma once

#include "command.hpp"

namespace swath::apps {

/// `swath cameras [--json]`: the camera database.
class CamerasCommand : public Command {
 public:
  const char* name() const override { return "cameras"; }
  const char* description() const override {
    return "List the camera database (share/cameras/); --camera takes an id, a name or a YAML file";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  bool json_ = false;
};

}  // namespace swath::apps
