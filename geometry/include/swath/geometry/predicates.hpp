#pragma once
// Exact geometric predicates on double coordinates (CGAL's filtered exact kernel underneath):
// the answers are exact for the given doubles, never wrong by rounding.

#include <algorithm>
#include <vector>

#include "swath/geometry/point.hpp"

namespace swath::geometry {

enum class Orientation { clockwise = -1, collinear = 0, counter_clockwise = 1 };

/// Exact orientation of (a, b, c), decided by CGAL's exact kernel. Use orientation().
Orientation orientation_exact(Point2 a, Point2 b, Point2 c);

/// Exact orientation of the triangle (a, b, c). The double determinant decides whenever it
/// exceeds Shewchuk's error bound (orient2d stage A); only near-degenerate cases go to
/// orientation_exact(). Inline because the sweeps call it millions of times.
inline Orientation orientation(Point2 a, Point2 b, Point2 c) {
  const double left = (a.x - c.x) * (b.y - c.y);
  const double right = (a.y - c.y) * (b.x - c.x);
  const double det = left - right;
  double sum;
  if (left > 0) {
    if (right <= 0) return det > 0 ? Orientation::counter_clockwise : Orientation::clockwise;
    sum = left + right;
  } else if (left < 0) {
    if (right >= 0) return det < 0 ? Orientation::clockwise : Orientation::counter_clockwise;
    sum = -left - right;
  } else {
    // left is 0. A difference of doubles is 0 only for equal doubles, so when a factor is, the
    // exact left is 0 and the sign is right's, whose factors' signs are exact: axis-aligned
    // edges and equal coordinates (rectangular zones, corners on one row) need no exact kernel.
    if (a.x == c.x || b.y == c.y) {
      const double u = a.y - c.y, v = b.x - c.x;
      if (u == 0 || v == 0) return Orientation::collinear;
      return (u > 0) == (v > 0) ? Orientation::clockwise : Orientation::counter_clockwise;
    }
    return orientation_exact(a, b, c);
  }
  constexpr double kErrorBound = 3.3306690738754716e-16;  // (3 + 16 eps) eps, eps = 2^-53
  const double bound = kErrorBound * sum;
  if (det >= bound && det > 0) return Orientation::counter_clockwise;
  if (-det >= bound && det < 0) return Orientation::clockwise;
  return orientation_exact(a, b, c);
}

/// Exact test whether the closed segments [a, b] and [c, d] share at least one point.
bool segments_intersect(Point2 a, Point2 b, Point2 c, Point2 d);

/// A point shared by the closed segments [a, b] and [c, d] (the crossing, or for overlapping
/// segments an end point of the overlap). Precondition: segments_intersect(a, b, c, d).
/// Accuracy: a few ulps of the coordinates (computed in doubles after an exact decision).
Point2 segments_common_point(Point2 a, Point2 b, Point2 c, Point2 d);

/// Whether the segments [p, q] and [a, b] cross at a point inside both, with every end of either
/// farther than `tolerance_m` from the other's line. Not exact, on purpose: ends computed on a
/// boundary sit a rounding error off it, and a turn or transit between such ends must not count
/// as crossing the edges it starts and ends on.
bool segments_cross_clearly(Point2 p, Point2 q, Point2 a, Point2 b, double tolerance_m);
/// The same with the segments' lengths |pq| and |ab| (metres) given: for callers that test one
/// segment against many and keep the lengths (the answers are those of the form above).
bool segments_cross_clearly(Point2 p, Point2 q, double pq_m, Point2 a, Point2 b, double ab_m,
                            double tolerance_m);

/// Distance from p to the closed segment [a, b], metres (a point for a = b).
double distance_to_segment(Point2 p, Point2 a, Point2 b);

/// Where p lies relative to a ring (even-odd rule, exact).
enum class Containment { outside, on_boundary, inside };
Containment locate_point(Point2 p, const std::vector<Point2>& ring);

/// One edge [a, b] of a ring in locate_point(): p on it, or whether it crosses the horizontal ray
/// from p towards +x (half-open in y, so a vertex on the ray counts once). The parity of the
/// crossings over all edges is the even-odd rule, whatever order the edges are asked in.
enum class EdgeAndRay { apart, crosses, p_on_edge };
inline EdgeAndRay edge_and_ray(Point2 p, Point2 a, Point2 b) {
  // Wholly above, below or left of p: neither holds p nor crosses the ray (no predicate needed).
  if ((a.y > p.y && b.y > p.y) || (a.y < p.y && b.y < p.y) || (a.x < p.x && b.x < p.x))
    return EdgeAndRay::apart;
  const Orientation o = orientation(a, b, p);
  if (o == Orientation::collinear && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
      std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y))
    return EdgeAndRay::p_on_edge;
  // An edge across the horizontal through p crosses right of p when p is on its left going up.
  if ((a.y > p.y) != (b.y > p.y) && (o == Orientation::counter_clockwise) == (b.y > a.y))
    return EdgeAndRay::crosses;
  return EdgeAndRay::apart;
}

}  // namespace swath::geometry
