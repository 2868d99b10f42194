#pragma once
// Whether a flown leg lies inside the fence (steps::missions): the fence step grows the fence
// around every leg that does not.

#include <vector>

#include "swath/geometry/polygon.hpp"

namespace swath::planning::steps::detail {

/// Whether the leg a-b (a point when a == b) lies inside one of `rings` (closed): the length of it
/// inside them at least its length less 1e-6 m (geometry::length_inside). A leg whose ends lie
/// strictly inside one ring and which touches none of its edges is answered without measuring.
bool leg_within(geometry::Point2 a, geometry::Point2 b, const std::vector<geometry::Ring>& rings);

}  // namespace swath::planning::steps::detail
