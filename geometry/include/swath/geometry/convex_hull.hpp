#pragma once

#include "swath/geometry/polygon.hpp"

namespace swath::geometry {

/// Convex hull of a point set as a counter-clockwise ring without collinear vertices, starting at
/// the lexicographically smallest point (x, then y). Exact (Andrew's monotone chain with exact
/// orientation), O(n log n). Fewer than 3 non-collinear points give the 1 or 2 extreme points.
Ring convex_hull(const std::vector<Point2>& points);

/// The same hull of a simple polygon's ring (either orientation, no self-intersection), without
/// sorting: Melkman's algorithm (1987) walks the ring once with a deque, O(n), exact orientation.
/// Counter-clockwise without collinear vertices; the start vertex may differ from convex_hull()'s.
/// Precondition: `ring` is simple (on a crossing ring the result is not the hull).
Ring convex_hull_of_simple_ring(const Ring& ring);

}  // namespace swath::geometry
