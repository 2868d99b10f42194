#include "energy_plan_files.hpp"

#include <cmath>
#include <filesystem>

#include "input_text.hpp"
#include "swath/base/input_error.hpp"
#include "swath/base/number_text.hpp"
#include "swath/energy/survey_stages.hpp"
#include "swath/planning/mission.hpp"
#include "swath/planning/spacing_scale.hpp"

namespace swath::apps {

using base::fixed_text;
using base::InputError;
using base::shortest_text;

energy::Interval parse_interval(const std::string& text, const std::string& option) {
  const auto pair = parse_number_pair(text, ',');
  if (!pair || pair->first > pair->second)
    throw InputError(option + " '" + text + "': expected LO,HI with LO <= HI, e.g. 2,10");
  return {pair->first, pair->second};
}

std::vector<std::pair<std::string, std::string>> energy_plan_files(
    const planning::SurveyPlan& plan, const EnergyPlanRequest& request,
    std::vector<std::string>& warnings) {
  const std::filesystem::path name(request.file_name);
  if (name.empty() || name.has_parent_path() || name == "." || name == "..")
    throw InputError("--energy-plan '" + request.file_name +
                     "': give a file name; it is written into the -o directory");
  if (!(request.min_covered_fraction > 0 && request.min_covered_fraction <= 1))
    throw InputError("--energy-min-coverage " + shortest_text(request.min_covered_fraction) +
                     ": must be a fraction in (0, 1]");

  const planning::SpacingScaleBounds bounds =
      planning::spacing_scale_bounds(plan, request.min_covered_fraction);
  // c1 <= 1: the plan as written is the best one can fly; replanning may only close the lines in
  // (shorter turns) while the coverage stays above the minimum. Inwards to 4 decimals: short
  // numbers in the file, and still within the coverage bound.
  energy::Interval scale{std::ceil(bounds.lo * 1e4 - 1e-9) / 1e4,
                         std::floor(bounds.hi * 1e4 + 1e-9) / 1e4};
  if (scale.lo > 1 || scale.hi < 1) scale = {1, 1};
  if (bounds.nominal_covered_fraction < request.min_covered_fraction)
    warnings.push_back("the survey covers " + fixed_text(bounds.nominal_covered_fraction * 100, 2) +
                       " % of the area, below --energy-min-coverage; the energy plan keeps the "
                       "line spacing fixed (c1 in [1, 1])");

  energy::SurveyStageSettings settings;
  settings.angle_deg = plan.sweep.angle_deg;
  settings.line_spacing_m = plan.imaging.line_spacing_m;
  settings.middle_m = bounds.middle_m;
  settings.spacing_scale = scale;
  settings.computations = request.computations;

  std::string computations;
  for (const energy::Interval& c : request.computations) {
    if (!computations.empty()) computations += ", ";
    computations += '[';
    computations += shortest_text(c.lo);
    computations += ", ";
    computations += shortest_text(c.hi);
    computations += ']';
  }
  const bool several = plan.drones.size() > 1;
  std::vector<std::pair<std::string, std::string>> files;
  for (const planning::DronePlan& drone : plan.drones) {
    const planning::DroneMission* m = &drone.mission;
    std::string file = request.file_name;
    if (several)
      file = name.stem().string() + "-" + std::to_string(m->drone) + name.extension().string();
    if (m->lines.empty()) {
      warnings.push_back("drone " + std::to_string(m->drone) + " has no lines; no " + file);
      continue;
    }
    energy::SurveyLines survey{m->drone, m->home, {}};
    for (const planning::SweepLine& l : m->lines) survey.lines.push_back({l.start, l.end});
    const energy::Plan stages = energy::survey_stage_plan(survey, settings);
    const geometry::GeoPoint origin = plan.request.field.frame->origin();
    std::string text = "# Energy plan of " + request.field;
    if (several) text += ", drone " + std::to_string(m->drone);
    text += " (swath plan --energy-plan): " + std::to_string(stages.stages.size()) +
            " stages for swath-energy run.\n";
    text += "# Local frame: x east, y north, metres from " + fixed_text(origin.lat_deg, 7) + ", " +
            fixed_text(origin.lon_deg, 7) + " (lat, lon).\n";
    text += "# Home, the simulation's start_m: [" + fixed_text(m->home.x, 2) + ", " +
            fixed_text(m->home.y, 2) + "].\n# Lines at " + fixed_text(settings.angle_deg, 3) +
            " deg counter-clockwise from east, " + fixed_text(settings.line_spacing_m, 3) +
            " m apart.\n";
    text += "# c1 scales the line spacing about the lanes' middle (1 = as planned);\n# within [" +
            shortest_text(scale.lo) + ", " + shortest_text(scale.hi) +
            "] the lines cover >= " + fixed_text(request.min_covered_fraction * 100, 2) +
            " % of the area (" + fixed_text(bounds.nominal_covered_fraction * 100, 2) +
            " % at 1).\n";
    text += "# Computations " + (computations.empty() ? std::string("none") : computations) +
            " on lines and turns, off on the legs from and to home.\n\n";
    text += energy::format_plan(stages);
    energy::parse_plan(text, file);  // swath-energy must accept what swath writes
    files.emplace_back(file, std::move(text));
  }
  return files;
}

}  // namespace swath::apps
