#pragma once
// The paper's region division search (paper 001 Algorithm 4, eq. 7-8) as published: a reference
// to benchmark swath's exact bisection against. Not used by the tools.

#include <cstddef>
#include <vector>

#include "swath/geometry/polygon.hpp"

namespace swath::reference {

/// Cut ordinates (frame rotated by -angle_deg) giving bands with area fractions `fractions`
/// (summing to 1): the height divided evenly first, then each cut moved in steps of 1/1000 of the
/// height, recursively drone by drone, until its band's area lies within target ± tuning x area
/// (eq. 7-8). `evaluations` counts the area computations.
std::vector<double> paper_region_cuts(const std::vector<geometry::Ring>& rings, double angle_deg,
                                      const std::vector<double>& fractions, double tuning,
                                      std::size_t& evaluations);

}  // namespace swath::reference
