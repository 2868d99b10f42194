#pragma once
// Independent coverage truth for tests: sample a fine grid in the original frame and test each
// sample against every footprint rectangle directly (no rotation into the sweep frame, no
// scanlines), so it shares nothing with measure_coverage().

#include "swath/planning/sweep.hpp"

namespace swath::test {

struct SampledCoverage {
  long inside = 0;   ///< samples inside the area
  long covered = 0;  ///< of those, under some footprint
  double fraction() const { return inside == 0 ? 0.0 : double(covered) / double(inside); }
};

/// `per_side` x `per_side` samples over the area's bounding box.
SampledCoverage sample_coverage(const geometry::Polygon& area,
                                const std::vector<planning::SweepLine>& lines,
                                double footprint_width_m, int per_side);

}  // namespace swath::test
