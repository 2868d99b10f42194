#include "split_measure.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

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

// Whether p lies in the closed area (outer ring less holes) or within 1 cm of its boundary: ray
// casting and point-segment distances of this file's own.
bool in_area(const geometry::Polygon& area, geometry::Point2 p) {
  constexpr double kNear_m = 0.01;
  bool inside = false;
  double nearest = INFINITY;
  const auto scan = [&](const geometry::Ring& ring, bool& in) {
    for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
      const geometry::Point2 a = ring[i], b = ring[j];
      if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x)
        in = !in;
      const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
      const double t =
          len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0, 1.0) : 0.0;
      nearest = std::min(nearest, std::hypot(p.x - a.x - t * dx, p.y - a.y - t * dy));
    }
  };
  scan(area.outer, inside);
  for (const geometry::Ring& hole : area.holes) {
    bool in_hole = false;
    scan(hole, in_hole);
    inside = inside && !in_hole;
  }
  return inside || nearest <= kNear_m;
}

double sampled_outside_m(const geometry::Polygon& area, const planning::SurveyPath& path) {
  constexpr double kStep_m = 0.25;
  double outside = 0;
  for (std::size_t i = 0; i + 1 < path.points.size(); ++i) {
    if (path.on_line[i]) continue;
    const geometry::Point2 a = path.points[i], b = path.points[i + 1];
    const double length = std::hypot(b.x - a.x, b.y - a.y);
    const int n = std::max(1, int(std::ceil(length / kStep_m)));
    for (int k = 0; k <= n; ++k)
      if (!in_area(area, a + (b - a) * (double(k) / n))) outside += length / (n + 1);
  }
  return outside;
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
  for (const planning::DronePlan& d : split.drones)
    row.transit_outside_sampled_m += sampled_outside_m(split.area, d.work.path);
  row.cells = split.cells.size();
  row.lines = lines.size();
  row.regions = split.region_angles_deg.size();
  return row;
}

}  // namespace swath::test
