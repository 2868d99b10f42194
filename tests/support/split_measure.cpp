#include "split_measure.hpp"

#include <chrono>

#include "coverage_oracle.hpp"
#include "local_field.hpp"
#include "swath/geometry/visibility.hpp"
#include "swath/planning/survey.hpp"

namespace swath::test {

namespace {

planning::SurveyPlan plan(const geometry::Polygon& area, planning::ConcaveMode mode,
                          const SplitSettingsForCorpus& s) {
  planning::SurveyRequest r;
  r.field = local_field(area);
  r.camera = {"test", 23.2, 15.4, 16, 5456, 3632, std::nullopt};
  // Landscape: the sensor's width across the lines, so the footprint is altitude x 23.2 / 16.
  const double footprint_m = s.altitude_m * r.camera.sensor_width_mm / r.camera.focal_length_mm;
  planning::PhotogrammetryMode m;
  m.altitude_m = s.altitude_m;
  m.side_overlap = s.side_overlap;
  r.mode = m;
  r.concave = mode;
  r.split_cells = s.cells;
  r.split_directions = s.directions;
  if (s.half_footprint_margin) r.outside_margin_m = footprint_m / 2;
  return planning::plan_survey(r);
}

}  // namespace

SplitRow measure_split(const geometry::Polygon& area, const SplitSettingsForCorpus& s) {
  SplitRow row;
  const auto t0 = std::chrono::steady_clock::now();
  const planning::SurveyPlan split = plan(area, planning::ConcaveMode::split, s);
  row.plan_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  const planning::SurveyPlan hull = plan(area, planning::ConcaveMode::hull, s);
  row.concave = split.handling == planning::Handling::split;
  row.split_m = split.drones[0].mission.path_length_m;
  row.hull_m = hull.drones[0].mission.path_length_m;
  const auto& lines = split.drones[0].mission.lines;
  row.coverage =
      sample_coverage(split.area, lines, split.imaging.footprint_across_m, 300).fraction();
  geometry::Polygon flyable;  // the corpus's areas are one piece: one outer ring, then holes
  for (const geometry::Ring& ring : split.planning_rings) {
    if (flyable.outer.empty())
      flyable.outer = ring;
    else
      flyable.holes.push_back(ring);
  }
  row.flyable_coverage =
      sample_coverage(flyable, lines, split.imaging.footprint_across_m, 300).fraction();
  row.reported_coverage = split.coverage.covered_fraction;
  row.line_outside_m = split.coverage.line_length_outside_m;
  row.transit_outside_m = split.transit_outside_m;
  row.cells = split.cells.size();
  row.lines = lines.size();
  row.regions = split.region_angles_deg.size();
  return row;
}

}  // namespace swath::test
