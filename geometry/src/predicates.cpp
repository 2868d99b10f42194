// The only translation unit of swath::geometry that includes CGAL: its filtered predicates are
// exact on doubles and cost a few ns when the floating-point filter succeeds.
#include "swath/geometry/predicates.hpp"

#include <algorithm>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <variant>

namespace swath::geometry {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using KPoint = Kernel::Point_2;
using KSegment = Kernel::Segment_2;

KPoint to_kernel(Point2 p) {
  return {p.x, p.y};
}

}  // namespace

Orientation orientation_exact(Point2 a, Point2 b, Point2 c) {
  switch (CGAL::orientation(to_kernel(a), to_kernel(b), to_kernel(c))) {
    case CGAL::LEFT_TURN:
      return Orientation::counter_clockwise;
    case CGAL::RIGHT_TURN:
      return Orientation::clockwise;
    default:
      return Orientation::collinear;
  }
}

bool segments_intersect(Point2 a, Point2 b, Point2 c, Point2 d) {
  // By the inline exact orientation (visibility asks this ~10^6 times a plan): ends of one segment
  // strictly on one side of the other's line share nothing with it; otherwise, unless all four
  // points are on one line, the segments meet when each separates (or touches) the other's ends.
  const Orientation o1 = orientation(a, b, c), o2 = orientation(a, b, d);
  if (o1 != Orientation::collinear && o1 == o2) return false;
  const Orientation o3 = orientation(c, d, a), o4 = orientation(c, d, b);
  if (o3 != Orientation::collinear && o3 == o4) return false;
  if (o1 != o2 && o3 != o4) return true;
  if (!(a == b) && !(c == d)) {
    // All four on one line (o1 = o2 = 0 or o3 = o4 = 0 with neither a point): ordered along it by
    // x unless it is vertical, so the segments meet when those intervals do.
    if (a.x != b.x)
      return std::max(std::min(a.x, b.x), std::min(c.x, d.x)) <=
             std::min(std::max(a.x, b.x), std::max(c.x, d.x));
    return std::max(std::min(a.y, b.y), std::min(c.y, d.y)) <=
           std::min(std::max(a.y, b.y), std::max(c.y, d.y));
  }
  return CGAL::do_intersect(KSegment(to_kernel(a), to_kernel(b)),
                            KSegment(to_kernel(c), to_kernel(d)));
}

Point2 segments_common_point(Point2 a, Point2 b, Point2 c, Point2 d) {
  // Degenerate (zero-length) segments are points; CGAL's intersection wants real segments.
  if (a == b) return a;
  if (c == d) return c;
  const auto result = CGAL::intersection(KSegment(to_kernel(a), to_kernel(b)),
                                         KSegment(to_kernel(c), to_kernel(d)));
  if (!result) return a;  // precondition violated; any point keeps the caller's report readable
  if (const KPoint* p = boost::get<KPoint>(&*result)) return {p->x(), p->y()};
  const KSegment* s = boost::get<KSegment>(&*result);
  return {s->source().x(), s->source().y()};
}

Containment locate_point(Point2 p, const std::vector<Point2>& ring) {
  // Even-odd crossing count with half-open edges; every decision is an exact predicate.
  bool inside = false;
  const std::size_t n = ring.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const EdgeAndRay e = edge_and_ray(p, ring[j], ring[i]);
    if (e == EdgeAndRay::p_on_edge) return Containment::on_boundary;
    if (e == EdgeAndRay::crosses) inside = !inside;
  }
  return inside ? Containment::inside : Containment::outside;
}

bool segments_cross_clearly(Point2 p, Point2 q, Point2 a, Point2 b, double tolerance_m) {
  return segments_cross_clearly(p, q, distance(p, q), a, b, distance(a, b), tolerance_m);
}

bool segments_cross_clearly(Point2 p, Point2 q, double pq_m, Point2 a, Point2 b, double ab_m,
                            double tolerance_m) {
  auto side = [tolerance_m](Point2 o, Point2 d, double od_m, Point2 x) {
    const double c = cross(d - o, x - o) / std::max(od_m, 1e-300);
    return c > tolerance_m ? 1 : c < -tolerance_m ? -1 : 0;
  };
  return side(p, q, pq_m, a) * side(p, q, pq_m, b) < 0 &&
         side(a, b, ab_m, p) * side(a, b, ab_m, q) < 0;
}

double distance_to_segment(Point2 p, Point2 a, Point2 b) {
  const Point2 d = b - a;
  const double len2 = dot(d, d);
  const double t = len2 > 0 ? std::clamp(dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
  return distance(p, a + d * t);
}

}  // namespace swath::geometry
