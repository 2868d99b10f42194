#pragma once
#include <string>

#include "command.hpp"

namespace swath::apps {

/// swath-control fit DATA.csv: a trigger model (paper 002 eq. 1) fitted to (x, changed) data.
class ControlFitCommand : public Command {
 public:
  const char* name() const override { return "fit"; }
  const char* description() const override {
    return "Fit a sensor's trigger model L(x) = 1/(1+exp(-(b1+b2 x))) to a CSV of x,changed "
           "(paper 002 eq. 1) and print b1, b2 and the threshold x* where L = P_run";
  }
  void setup(CLI::App& app) override;
  int run() override;

 private:
  std::string data_, method_ = "logit_ols";
  double p_run_ = 0.6;
  bool json_ = false;
};

}  // namespace swath::apps
