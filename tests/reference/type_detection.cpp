#include "type_detection.hpp"

#include "swath/geometry/predicates.hpp"

namespace swath::reference {

using namespace swath::geometry;

namespace {

bool any_crossing(const Polygon& polygon) {
  struct Edge {
    std::size_t ring, index, ring_size;
    Point2 a, b;
  };
  std::vector<Edge> edges;
  for (std::size_t r = 0; r < ring_count(polygon); ++r) {
    const Ring& ring = ring_at(polygon, r);
    for (std::size_t i = 0; i < ring.size(); ++i)
      edges.push_back({r, i, ring.size(), ring[i], ring[(i + 1) % ring.size()]});
  }
  for (std::size_t i = 0; i < edges.size(); ++i) {
    for (std::size_t j = i + 1; j < edges.size(); ++j) {
      const Edge& e = edges[i];
      const Edge& f = edges[j];
      const bool consecutive = e.ring == f.ring && ((e.index + 1) % e.ring_size == f.index ||
                                                    (f.index + 1) % f.ring_size == e.index);
      if (!consecutive) {
        if (segments_intersect(e.a, e.b, f.a, f.b)) return true;
        continue;
      }
      // Neighbours share a vertex; they conflict only when they fold back along one line.
      const Point2 shared = e.b == f.a ? e.b : e.a;
      const Point2 p = e.b == f.a ? e.a : e.b;
      const Point2 q = e.b == f.a ? f.b : f.a;
      if (orientation(p, shared, q) == Orientation::collinear && dot(p - shared, q - shared) > 0)
        return true;
    }
  }
  return false;
}

}  // namespace

TypeDetection type_detection_quadratic(const Polygon& polygon) {
  TypeDetection result;
  if (any_crossing(polygon)) {
    result.type = AreaType::self_intersecting;
    return result;
  }
  for (std::size_t r = 0; r < ring_count(polygon); ++r) {
    const Ring& ring = ring_at(polygon, r);
    for (std::size_t i = 0; i < ring.size(); ++i) {
      Ring without = ring;
      without.erase(without.begin() + static_cast<std::ptrdiff_t>(i));
      const Containment c = locate_point(ring[i], without);
      if ((r == 0 && c == Containment::inside) || (r > 0 && c == Containment::outside))
        result.reflex_vertices.push_back({r, i});
    }
  }
  result.type = result.reflex_vertices.empty() && polygon.holes.empty() ? AreaType::convex
                                                                        : AreaType::concave;
  return result;
}

}  // namespace swath::reference
