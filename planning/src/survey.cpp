#include "swath/planning/survey.hpp"

#include <cmath>

#include "swath/planning/survey_steps.hpp"

namespace swath::planning {

const char* to_string(Handling handling) {
  switch (handling) {
    case Handling::convex:
      return "convex";
    case Handling::hull:
      return "hull";
    case Handling::split:
      return "split";
  }
  return "";
}

std::string duration_text(double seconds) {
  const long total = std::lround(std::max(0.0, seconds));
  const auto two = [](long v) {
    std::string text = std::to_string(v);
    if (v < 10) text.insert(text.begin(), '0');
    return text;
  };
  if (total >= 3600)
    return std::to_string(total / 3600) + ":" + two(total / 60 % 60) + ":" + two(total % 60);
  return std::to_string(total / 60) + " min " + two(total % 60) + " s";
}

geometry::Polygon measured_area(const SurveyPlan& plan) {
  geometry::Polygon measured = plan.area;
  measured.holes.insert(measured.holes.end(), plan.extra_pieces.begin(), plan.extra_pieces.end());
  measured.holes.insert(measured.holes.end(), plan.extra_piece_holes.begin(),
                        plan.extra_piece_holes.end());
  return measured;
}

std::string no_fly_name(const SurveyPlan& plan, std::size_t k) {
  const std::size_t holes = plan.request.field.polygon.holes.size();
  if (k < holes) return "hole " + std::to_string(k);
  const std::size_t zone = k - holes;
  const std::vector<std::string>& names = plan.request.exclusion_names;
  return "no-fly zone " + (zone < names.size() ? names[zone] : std::to_string(zone + 1));
}

SurveyPlan plan_survey(const SurveyRequest& request) {
  SurveyPlan plan;
  plan.request = request;
  steps::area(plan);
  steps::imaging(plan);
  steps::direction(plan);
  steps::lanes(plan);
  steps::drones(plan);
  steps::missions(plan);
  steps::sorties(plan);
  steps::deconflict(plan);
  steps::terrain(plan);
  steps::fences(plan);
  steps::measures(plan);
  steps::checks(plan);
  plan.routes.reset();  // their tables are large, and no caller routes again
  // The observer is the caller's, for this call only (it may refer to what the call outlives).
  plan.request.progress = nullptr;
  return plan;
}

}  // namespace swath::planning
