#pragma once

#include "swath/geometry/polygon.hpp"

namespace swath::geometry {

/// Paper 001 Algorithm 1 on one ring (orientation either way, interior angles in degrees):
///   angle regularity  1 - (sum_i |mean_angle - angle_i| / 360) / n
///   edge regularity   1 - (sum_i |mean_edge - edge_i| / mean_edge) / n
///   regularity        their mean.
/// 1 for a regular polygon; smaller the more angles and edges differ. Range (-inf, 1] in theory,
/// [0, 1] for any sensible field.
struct Regularity {
  double angle = 1.0;
  double edge = 1.0;
  double overall = 1.0;
};

/// Interior angle at each vertex of a simple ring, degrees in (0, 360).
std::vector<double> interior_angles_deg(const Ring& ring);

Regularity regularity(const Ring& ring);

}  // namespace swath::geometry
