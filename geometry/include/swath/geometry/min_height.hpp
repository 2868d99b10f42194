#pragma once
// Minimum height (paper 001 §V-B): the sweep direction that minimises the area's extent
// perpendicular to the sweep lines.

#include <vector>

#include "swath/geometry/point.hpp"

namespace swath::geometry {

/// A sweep direction and the extent of the area perpendicular to it.
struct SweepDirection {
  /// Direction of the sweep lines, degrees counter-clockwise from the local x axis (east),
  /// in [0, 180).
  double angle_deg = 0.0;
  /// Extent of the points perpendicular to the sweep lines, metres.
  double height_m = 0.0;
};

/// Extent of the points perpendicular to sweep lines at `angle_deg` (CCW from x): the height the
/// paper measures after rotating the area by -angle_deg. O(n).
double height_at(const std::vector<Point2>& points, double angle_deg);

/// Exact minimum height by rotating calipers on the convex hull: the minimum is attained with a
/// hull edge flush against a supporting line, so only hull edge directions are candidates.
/// O(n log n) for the hull, O(h) after it. Ties go to the smallest angle.
SweepDirection min_height_rotation(const std::vector<Point2>& points);

/// The same for the ring of a simple polygon, with its hull by Melkman's walk (no sort): O(n).
/// Precondition: `ring` does not cross itself (after classification or repair).
SweepDirection min_height_of_simple_ring(const std::vector<Point2>& ring);

/// The paper's scan: heights at 0, step, 2 step, ... < 180 degrees; the smallest wins (ties: the
/// first). Never below min_height_rotation(); above it by at most diameter * sin(step / 2).
/// Precondition: 0 < step_deg <= 180.
SweepDirection min_height_scan(const std::vector<Point2>& points, double step_deg);

/// Converts a sweep line direction (degrees CCW from east) to a compass bearing of the line
/// (degrees clockwise from north), in [0, 180) since a line has two ends.
double line_bearing_deg(double angle_deg);

}  // namespace swath::geometry
