#pragma once

#include <string>

#include "command.hpp"

namespace swath::apps {

/// `swath render DIR [--coverage PNG] [--paths PNG] [--size WxH]`: redraws a plan's pictures.
class RenderCommand : public Command {
 public:
  const char* name() const override { return "render"; }
  const char* description() const override {
    return "Draw a plan's coverage picture from its mission.geojson and summary.json";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::string dir_;
  std::string coverage_;
  std::string paths_;
  std::string size_ = "1600x1200";
};

}  // namespace swath::apps
