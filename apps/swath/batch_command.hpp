#pragma once

#include <string>
#include <vector>

#include "area_options.hpp"
#include "command.hpp"

namespace swath::apps {

/// `swath batch AREAS -o DIR [--jobs N] [--emit-jobs] [PLAN OPTIONS...]`: every area of a
/// multi-area GIS file (or every area file of a directory) planned as `swath plan` would, one
/// sub-directory each, with batch.csv and batch.geojson (docs/swath-plan.md).
class BatchCommand : public Command {
 public:
  const char* name() const override { return "batch"; }
  const char* description() const override {
    return "Plan every area of a multi-area file or a directory (the plan options after the "
           "batch's own): one sub-directory per area, batch.csv and batch.geojson; an area that "
           "cannot be planned is reported in its row (exit 3)";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::string areas_, output_, layer_;
  std::string name_field_;
  int jobs_ = 1;
  double timeout_s_ = 0;  ///< --timeout-s: wall-clock seconds an area may plan; 0 none
  bool emit_jobs_ = false, progress_ = false;
  std::vector<std::string> plan_args_;
};

}  // namespace swath::apps
