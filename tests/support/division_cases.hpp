#pragma once
// The balance cases of issue 18 (docs/swath-plan.md): the bundled meadow, vineyard and orchard,
// each with three equal drones and with the drones of share/fleets/three-quads.yaml, Sony QX1 at 60
// m as the README's division examples plan them. Shared by the division tests and the division
// bench's --balance-table.

#include <cstdint>
#include <string>
#include <vector>

#include "swath/planning/survey.hpp"

namespace swath::test {

struct DivisionCase {
  std::string field;  ///< file name under share/fields
  std::string fleet;  ///< "3 equal" or "three-quads"
  planning::SurveyRequest request;
};

/// Six requests (fields x fleets) with `division` and `balance`, in a fixed order. Three equal
/// drones start at the plan's default home (as `--drones 3` without `--home`); three-quads keeps
/// its drones and the offsets of their homes from the fleet's, with the fleet's home moved next
/// to fields it was not drawn for (the meadow keeps the file's; the vineyard takes the README's
/// home south-west of it; the orchard one south-west of its corner).
std::vector<DivisionCase> division_cases(const std::string& source_dir,
                                         planning::DivisionMode division,
                                         planning::Balance balance);

/// Region or path division of split-corpus shapes (field_shapes.hpp, `per_family` of each family
/// from `seed`, the concave ones planned by split), Sony QX1 at 60 m, each with three equal drones
/// and with three-quads' drones (speeds 5, 5 and 8 m/s, bravo's battery at 0.6): the fleet's home
/// 40 m beyond the area's south-west corner of its bounding box, charlie's 40 m beyond its
/// east side. `field` names the family and index.
std::vector<DivisionCase> corpus_division_cases(const std::string& source_dir, std::uint64_t seed,
                                                int per_family, planning::DivisionMode division,
                                                planning::Balance balance);

/// The same request without a fleet, from the fleet's home: the undivided plan.
planning::SurveyRequest undivided(const planning::SurveyRequest& request);

/// Longest over shortest flight_time_s of the drones that fly lines (as summary.json reports
/// it), or 0 when fewer than one drone flies.
double max_over_min_flight(const planning::SurveyPlan& plan);

}  // namespace swath::test
