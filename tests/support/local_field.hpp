#pragma once
// Fields drawn in local metres, for the tests and corpus tools that build their own.

#include "swath/geometry/field.hpp"
#include "swath/geometry/polygon.hpp"

namespace swath::test {

/// A field from a polygon in local metres (rings normalised, placed at 47° N, 8° E).
inline geometry::Field local_field(geometry::Polygon polygon) {
  geometry::Field f;
  f.source = "test";
  polygon.outer = geometry::normalise_ring(polygon.outer, true).ring;
  for (geometry::Ring& h : polygon.holes) h = geometry::normalise_ring(h, false).ring;
  f.polygon = polygon;
  for (std::size_t r = 0; r < geometry::ring_count(polygon); ++r) {
    f.source_index.push_back({});
    for (std::size_t i = 0; i < geometry::ring_at(polygon, r).size(); ++i)
      f.source_index.back().push_back(i);
  }
  geometry::place_local_field(f, {47.0, 8.0, 0.0});
  return f;
}

}  // namespace swath::test
