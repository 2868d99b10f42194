#pragma once
// Everything `swath classify` and a plan summary say about an area, computed once.

#include <optional>

#include "swath/geometry/classification.hpp"
#include "swath/geometry/min_height.hpp"
#include "swath/geometry/regularity.hpp"

namespace swath::geometry {

struct AreaFacts {
  Classification classification;
  std::size_t vertex_count = 0;  ///< all rings, after normalisation
  double perimeter_m = 0.0;      ///< all rings
  /// Minimum height over the convex hull of the outer ring (defined for every type).
  SweepDirection min_height;
  /// Not defined for a self-intersecting area (the shoelace sum of a crossing ring means nothing).
  std::optional<double> area_m2;
  std::optional<Point2> centroid;
  std::optional<Regularity> regularity;  ///< of the outer ring
};

AreaFacts describe_area(const Polygon& polygon);

}  // namespace swath::geometry
