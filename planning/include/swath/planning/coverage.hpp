#pragma once
// How much of an area the camera footprints of a set of flight lines cover, and how much of the
// flown swath lies outside the area.

#include <vector>

#include "swath/geometry/polygon.hpp"
#include "swath/planning/sweep.hpp"

namespace swath::planning {

struct CoverageMeasure {
  double area_m2 = 0.0;           ///< of the area measured
  double covered_area_m2 = 0.0;   ///< area under at least one footprint
  double swath_area_m2 = 0.0;     ///< union of the footprints
  double covered_fraction = 0.0;  ///< covered / area, in [0, 1]
  double outside_fraction = 0.0;  ///< (swath - covered) / swath, in [0, 1]
  double line_length_m = 0.0;     ///< total length of the flight lines
  double line_length_outside_m =
      0.0;  ///< of it, over ground outside the area (holes count as outside)
};

/// Footprint of a line: the rectangle along the whole segment, `footprint_width_m` across, centred
/// on it (no credit for the photo extending beyond the segment's ends). All lines must share one
/// direction `angle_deg` (degrees CCW from x). Measured by scanlines along the lines: exact along
/// each scanline; across, the midpoint rule between consecutive vertex and footprint-edge
/// ordinates, which is exact where lengths vary linearly, so areas and swath are exact up to
/// rounding and only the covered part carries an error, where an edge crosses a footprint's end
/// (bounded by ~ that edge's share of one of `rows` slices). O((n + lines) log(n + lines) +
/// samples x active); each line's length outside the area is exact (its own ordinate is a
/// scanline).
CoverageMeasure measure_coverage(const geometry::Polygon& area, const std::vector<SweepLine>& lines,
                                 double angle_deg, double footprint_width_m, int rows = 4096);

/// The same for lines at any directions (a split plan with a direction per region): each line's
/// footprint is the rectangle along it, `footprint_width_m` across, and scanlines run along the
/// local x axis (exact along each; across, the midpoint rule between consecutive vertex and
/// rectangle-corner ordinates, exact where lengths vary linearly; `rows` slices over the height).
/// Each line's length outside the area is exact (the line clipped by the rings). Lines sharing one
/// direction are better measured by measure_coverage() (fewer events); it is kept for them.
CoverageMeasure measure_coverage_any_direction(const geometry::Polygon& area,
                                               const std::vector<SweepLine>& lines,
                                               double footprint_width_m, int rows = 4096);

}  // namespace swath::planning
