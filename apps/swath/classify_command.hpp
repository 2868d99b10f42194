#pragma once

#include <string>

#include "area_options.hpp"
#include "command.hpp"

namespace swath::apps {

/// `swath classify FIELD [--json] [--local]`: area type, measures and minimum height.
class ClassifyCommand : public Command {
 public:
  const char* name() const override { return "classify"; }
  const char* description() const override {
    return "Check an area: convex/concave/self-intersecting, area, regularity, minimum height "
           "and sweep direction, reflex vertices or the crossing (a crossing is a finding: exit 0)";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::string field_path_;
  bool json_ = false;
  bool local_ = false;
  AreaChoice area_choice_;
};

}  // namespace swath::apps
