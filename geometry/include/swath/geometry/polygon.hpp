#pragma once
// Polygon with holes in a local metric frame, and its measures.

#include <cstddef>
#include <vector>

#include "swath/geometry/point.hpp"

namespace swath::geometry {

/// A closed ring of vertices; the closing edge from back() to front() is implicit.
using Ring = std::vector<Point2>;

/// An area: an outer ring and optional holes (no-fly zones). After normalise_polygon() the outer
/// ring is counter-clockwise and every hole clockwise, so the area is always on the left of an
/// edge.
struct Polygon {
  Ring outer;
  std::vector<Ring> holes;
};

/// Identifies a vertex or edge: ring 0 is the outer ring, ring k >= 1 is hole k-1.
/// Edge i of a ring runs from vertex i to vertex (i+1) mod n.
struct RingIndex {
  std::size_t ring = 0;
  std::size_t index = 0;
  friend bool operator==(const RingIndex&, const RingIndex&) = default;
};

/// The ring with number `ring` (0 = outer, k = hole k-1).
const Ring& ring_at(const Polygon& polygon, std::size_t ring);
std::size_t ring_count(const Polygon& polygon);

/// Signed shoelace area in m²: > 0 for a counter-clockwise ring.
double signed_area(const Ring& ring);
/// Area of the polygon in m²: |outer| minus the holes' areas.
double area(const Polygon& polygon);
/// Sum of the edge lengths of every ring, in metres.
double perimeter(const Polygon& polygon);
double perimeter(const Ring& ring);
/// Centre of mass of the area (paper 001 eq. 1-3, holes subtracted), in the polygon's frame.
/// Precondition: area(polygon) > 0.
Point2 centroid(const Polygon& polygon);

/// Result of normalising one ring: the kept vertices and, for each, its position in the input.
struct NormalisedRing {
  Ring ring;
  std::vector<std::size_t> source_index;
};

/// Drops a closing vertex equal to the first, removes consecutive duplicates (also across the
/// wrap-around) and orients the ring counter-clockwise (`counter_clockwise` = true) or clockwise.
/// Orientation is by the sign of the shoelace area; a ring of zero area keeps its order.
NormalisedRing normalise_ring(const Ring& ring, bool counter_clockwise);

}  // namespace swath::geometry
