#include "swath/geometry/polygon.hpp"

#include <algorithm>

namespace swath::geometry {

const Ring& ring_at(const Polygon& polygon, std::size_t ring) {
  return ring == 0 ? polygon.outer : polygon.holes.at(ring - 1);
}

std::size_t ring_count(const Polygon& polygon) {
  return 1 + polygon.holes.size();
}

double signed_area(const Ring& ring) {
  // Shoelace about the first vertex: same value, less cancellation far from the origin.
  if (ring.size() < 3) return 0.0;
  const Point2 o = ring.front();
  double twice = 0.0;
  for (std::size_t i = 1; i + 1 < ring.size(); ++i) twice += cross(ring[i] - o, ring[i + 1] - o);
  return twice / 2.0;
}

double area(const Polygon& polygon) {
  double a = std::abs(signed_area(polygon.outer));
  for (const Ring& hole : polygon.holes) a -= std::abs(signed_area(hole));
  return a;
}

double perimeter(const Ring& ring) {
  double length = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i)
    length += distance(ring[i], ring[(i + 1) % ring.size()]);
  return length;
}

double perimeter(const Polygon& polygon) {
  double length = perimeter(polygon.outer);
  for (const Ring& hole : polygon.holes) length += perimeter(hole);
  return length;
}

namespace {

// Paper 001 eq. 1-3 for one ring, relative to `o`; returns (signed area, area-weighted centre).
void accumulate_centroid(const Ring& ring, Point2 o, double sign, double& area_sum,
                         Point2& moment) {
  double a = 0.0;
  Point2 m{};
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point2 p = ring[i] - o;
    const Point2 q = ring[(i + 1) % ring.size()] - o;
    const double c = cross(p, q);
    a += c;
    m = m + (p + q) * c;
  }
  // a is twice the signed area; m / (3 a) is the centre. Orient every ring by `sign` so holes
  // subtract whatever their stored orientation.
  const double s = (a >= 0 ? 1.0 : -1.0) * sign;
  area_sum += s * a / 2.0;
  moment = moment + m * (s / 6.0);
}

}  // namespace

Point2 centroid(const Polygon& polygon) {
  const Point2 o = polygon.outer.empty() ? Point2{} : polygon.outer.front();
  double a = 0.0;
  Point2 moment{};
  accumulate_centroid(polygon.outer, o, 1.0, a, moment);
  for (const Ring& hole : polygon.holes) accumulate_centroid(hole, o, -1.0, a, moment);
  return o + moment * (1.0 / a);
}

NormalisedRing normalise_ring(const Ring& ring, bool counter_clockwise) {
  NormalisedRing out;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    if (!out.ring.empty() && out.ring.back() == ring[i]) continue;
    out.ring.push_back(ring[i]);
    out.source_index.push_back(i);
  }
  // Closing vertex(es) equal to the first one.
  while (out.ring.size() > 1 && out.ring.back() == out.ring.front()) {
    out.ring.pop_back();
    out.source_index.pop_back();
  }
  const double a = signed_area(out.ring);
  if ((counter_clockwise && a < 0) || (!counter_clockwise && a > 0)) {
    // Reverse but keep the first vertex first, so vertex 0 stays the file's vertex 0.
    std::reverse(out.ring.begin() + 1, out.ring.end());
    std::reverse(out.source_index.begin() + 1, out.source_index.end());
  }
  return out;
}

}  // namespace swath::geometry
