#pragma once
// Split against hull on one area, measured by the planner's own summary and by the independent
// footprint oracle (coverage_oracle.hpp): the row of the split corpus table (issue 18).

#include <string>

#include "swath/geometry/polygon.hpp"
#include "swath/planning/split.hpp"

namespace swath::test {

struct SplitSettingsForCorpus {
  double altitude_m = 40;     ///< test camera (23.2 x 15.4 mm, 16 mm): footprint 58 m across
  double side_overlap = 0.7;  ///< spacing 17.4 m at 40 m
  planning::SplitCells cells = planning::SplitCells::best;
  bool half_footprint_margin = false;  ///< --outside-margin half the footprint width
  planning::SplitDirections directions = planning::SplitDirections::one;  ///< --directions
};

struct SplitRow {
  bool concave = false;  ///< split planned (false: a convex area, the strip rule)
  double split_m = 0;    ///< split's path, home legs included
  double hull_m = 0;     ///< --concave hull's path
  double coverage = 0;   ///< by the oracle, of the area to cover (no-fly zones out)
  /// By the oracle, of the area lines may fly over: no-fly zones grown by the clearance out (the
  /// band within the clearance of a zone is seen only from lanes beside the zone, never at their
  /// ends: the footprint gets no credit beyond a line's end).
  double flyable_coverage = 0;
  double reported_coverage = 0;  ///< summary's covered_fraction
  double line_outside_m = 0;     ///< split's lines outside the area (holes count as outside)
  double transit_outside_m = 0;  ///< split's turns and transits outside
  /// The same measured here, not by the planner's router: the turns and transits sampled every
  /// 0.25 m, a sample more than 1 cm outside the area (or in a hole) counting 0.25 m.
  double transit_outside_sampled_m = 0;
  std::size_t cells = 0;    ///< split's cells (runs)
  std::size_t lines = 0;    ///< split's lines
  std::size_t regions = 0;  ///< split's regions with their own direction (0: one direction)
  double plan_ms = 0;       ///< split's planning time, wall clock
};

/// Plans `area` (local metres, placed at 47 N 8 E) with --concave split and hull, default
/// settings otherwise (5 m clearance from holes), and measures both.
SplitRow measure_split(const geometry::Polygon& area, const SplitSettingsForCorpus& settings = {});

}  // namespace swath::test
