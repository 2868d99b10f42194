#include "fit_command.hpp"

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "swath/base/file_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/json_document.hpp"
#include "swath/base/number_text.hpp"
#include "swath/control/logistic.hpp"

namespace swath::apps {

void ControlFitCommand::setup(CLI::App& app) {
  app.add_option("DATA", data_,
                 "CSV with a header naming the columns x (the sensor's change, >= 0) and changed "
                 "(0 or 1: whether the control output changed)")
      ->required();
  app.add_option("--method", method_,
                 "logit_ols (the paper's OLS on grouped empirical logits), logit_wls (weighted) "
                 "or mle (maximum likelihood, IRLS)")
      ->check(CLI::IsMember({"logit_ols", "logit_wls", "mle"}))
      ->capture_default_str();
  app.add_option("--p-run", p_run_, "P_run: the probability above which the sensor triggers")
      ->check(CLI::Range(1e-9, 1 - 1e-9))
      ->capture_default_str();
  app.add_flag("--json", json_, "Print JSON instead of text");
}

int ControlFitCommand::run() {
  const std::vector<control::TriggerPoint> data =
      control::parse_trigger_data(base::read_text_file(data_, "trigger data file"), data_);
  // A header alone fits nothing: refused rather than printing a model of no points.
  if (data.empty())
    throw base::InputError(data_ + ": no data rows after the header (x,changed): nothing to fit");
  const control::FitMethod method = method_ == "mle"         ? control::FitMethod::mle
                                    : method_ == "logit_wls" ? control::FitMethod::logit_wls
                                                             : control::FitMethod::logit_ols;
  const control::LogisticModel m = control::fit_logistic(data, method);
  const double threshold = control::trigger_threshold(m, p_run_);
  std::size_t changed = 0;
  for (const auto& p : data) changed += p.changed ? 1 : 0;
  if (json_) {
    nlohmann::ordered_json j;
    j["points"] = data.size();
    j["changed"] = changed;
    j["method"] = method_;
    j["beta1"] = m.beta1;
    j["beta2"] = m.beta2;
    j["degenerate"] = m.degenerate;
    j["p_run"] = p_run_;
    j["threshold"] = std::isfinite(threshold) ? nlohmann::ordered_json(threshold)
                                              : nlohmann::ordered_json("never");
    std::cout << base::json_text(j, 1) << '\n';
    return base::kExitSuccess;
  }
  std::cout << "points     " << data.size() << " (" << changed << " changed)\n"
            << "method     " << method_ << (m.degenerate ? " (degenerate: pooled logit)" : "")
            << "\nbeta1      " << base::shortest_text(m.beta1) << "\nbeta2      "
            << base::shortest_text(m.beta2) << "\nthreshold  "
            << (std::isfinite(threshold) ? base::shortest_text(threshold) : "never") << " (L(x) > "
            << base::shortest_text(p_run_) << ")\n";
  return base::kExitSuccess;
}

}  // namespace swath::apps
