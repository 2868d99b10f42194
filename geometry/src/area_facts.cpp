#include "swath/geometry/area_facts.hpp"

namespace swath::geometry {

AreaFacts describe_area(const Polygon& polygon) {
  AreaFacts facts;
  facts.classification = classify(polygon);
  for (std::size_t r = 0; r < ring_count(polygon); ++r)
    facts.vertex_count += ring_at(polygon, r).size();
  facts.perimeter_m = perimeter(polygon);
  facts.min_height = min_height_rotation(polygon.outer);
  if (facts.classification.type != AreaType::self_intersecting) {
    facts.area_m2 = area(polygon);
    facts.centroid = centroid(polygon);
    facts.regularity = regularity(polygon.outer);
  }
  return facts;
}

}  // namespace swath::geometry
