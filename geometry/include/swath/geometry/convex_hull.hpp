#pragma once

#include "swath/geometry/polygon.hpp"

namespace swath::geometry {

/// Convex hull of a point set as a counter-clockwise ring without collinear vertices, starting at
/// the lexicographically smallest point (x, then y). Exact (Andrew's monotone chain with exact
/// orientation), O(n log n). Fewer than 3 non-collinear points give the 1 or 2 extreme points.
Ring convex_hull(const std::vector<Point2>& points);

}  // namespace swath::geometry
