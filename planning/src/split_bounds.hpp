#pragma once
// Internal to split.cpp (and its tests): what the direction search knows of boustrophedon cells
// at a direction before it builds them.
#include <vector>

#include "swath/geometry/polygon.hpp"
#include "swath/planning/lane_runs.hpp"
#include "swath/planning/split.hpp"

namespace swath::planning::split_detail {

/// A lower bound, metres, on the straight-transit estimate of the cells at `angle_deg` (degrees
/// CCW from x) from `home`: their lines cover the grid lanes' spans inside the rings (the same
/// ordinates, lane by lane the pieces tile the area), and a closed tour from home over lines at
/// those ordinates climbs and comes down their whole range, home's included: the sum of the spans
/// plus twice that range, less 1e-6 of it for rounding. O(n log n + lanes) for n vertices.
double cells_estimate_bound(const std::vector<geometry::Ring>& rings, double angle_deg,
                            const SplitSettings& s, geometry::Point2 home);
/// The same from the grid's extent at `angle_deg` (the runs' without bridges and on the default
/// grid: LaneRuns::grid), bit for bit: no second scan of the rings.
double cells_estimate_bound(const LaneGridExtent& grid, double angle_deg, geometry::Point2 home);

/// The estimate itself (nearest neighbour over the cells' lines, straight transits), metres; 0
/// when the cells hold no line.
double cells_estimate(const std::vector<geometry::Ring>& rings, double angle_deg,
                      const SplitSettings& s, geometry::Point2 home);

}  // namespace swath::planning::split_detail
