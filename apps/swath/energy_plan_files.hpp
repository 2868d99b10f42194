#pragma once
// `swath plan --energy-plan FILE`: each drone's zigzag as a stage plan for swath-energy.

#include <string>
#include <utility>
#include <vector>

#include "swath/energy/plan.hpp"
#include "swath/planning/survey.hpp"

namespace swath::apps {

struct EnergyPlanRequest {
  std::string file_name;  ///< a plain name; with a fleet, -<drone> before the extension
  double min_covered_fraction = 0.99;  ///< c1's bounds keep at least this coverage, in (0, 1]
  std::vector<energy::Interval> computations;  ///< on lines and turns
  std::string field;                           ///< for the header comment
};

/// The plan files (name, text) in the stage format with a comment header giving the frame, the
/// home (the simulation's start_m) and what c1 means; one per drone with lines. Each is parsed
/// back before it is returned, so a file that swath-energy would refuse is never written. Warns
/// (into `warnings`) when the plan as written already covers less than the minimum (c1 fixed at 1)
/// or when a drone has no lines.
std::vector<std::pair<std::string, std::string>> energy_plan_files(
    const planning::SurveyPlan& plan, const EnergyPlanRequest& request,
    std::vector<std::string>& warnings);

/// "LO,HI" as an interval, lo <= hi; throws base::InputError naming `option`.
energy::Interval parse_interval(const std::string& text, const std::string& option);

}  // namespace swath::apps
