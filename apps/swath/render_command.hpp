#pragma once

#include <filesystem>
#include <string>

#include "command.hpp"

namespace swath::apps {

/// `swath render DIR [--coverage PNG] [--paths PNG] [--size WxH] [--basemap FILE] [--html
/// [--basemap-url T]]`: redraws a plan's pictures, or its map page.
class RenderCommand : public Command {
 public:
  const char* name() const override { return "render"; }
  const char* description() const override {
    return "Draw a plan's coverage picture (or its map page) from its files";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::string html_page(const std::filesystem::path& dir) const;

  std::string dir_;
  std::string coverage_;
  std::string paths_;
  std::string size_ = "1600x1200";
  bool html_ = false;
  std::string basemap_url_;
  std::string basemap_;
};

}  // namespace swath::apps
