#pragma once
// Growing and shrinking areas by a distance, and distances between paths and areas: the
// clearance around no-fly zones and the fences of docs/swath-plan.md (Boost.Geometry's buffer and
// boolean operations, in one .cpp).

#include <vector>

#include "swath/geometry/polygon.hpp"

namespace swath::geometry {

/// `rings` grown outward by `distance_m` (> 0), overlapping results united. Corners are mitred up
/// to twice the distance (Boost's join_miter(2)); where the area's corner is sharper than 60
/// degrees, and such a mitre would cut into the circle about the corner, a 16-gon about that
/// circle is added. The result contains every point within `distance_m` of the input (the full
/// round buffer) and reaches at most 2 `distance_m` beyond it at a corner.
/// Each result is a counter-clockwise outer ring (holes that appear inside a union are dropped:
/// for fences, whose parts must each be whole). `distance_m` = 0 returns the rings
/// counter-clockwise.
std::vector<Ring> grow(const std::vector<Ring>& rings, double distance_m);

/// grow() of each ring on its own, the results then united: the same shape, reached another way.
/// Boost's buffer of the union of many overlapping pieces (an area with dozens of 1 m strips
/// reaching out of it, the fence of a fast crosshatch) can return a wrong shape (pieces missing,
/// several polygons); a single simple ring's buffer and the union of buffers do not.
std::vector<Ring> grow_each(const std::vector<Ring>& rings, double distance_m);

/// grow(), with the holes a union encloses kept: each part's outer ring counter-clockwise followed
/// by its holes clockwise (subtract()'s obstacles take them so). For no-fly zones: zones that
/// ring a field leave it, and a home inside, free; filled, they covered the whole area.
std::vector<Ring> grow_keeping_holes(const std::vector<Ring>& rings, double distance_m);

/// grow() of the rings first simplified (Douglas-Peucker) within `tolerance_m` (>= 0, metres), by
/// `distance_m` (>= 0, metres) + `tolerance_m`: every input point lies within the tolerance of the
/// simplified rings, so the result holds every point within `distance_m` of the input, and
/// reaches at most 2 (`distance_m` + `tolerance_m`) + `tolerance_m` beyond it. For long outlines:
/// buffering a 10,000-vertex field took seconds and gave a fence of ~1,900 vertices (an outline's
/// small wiggles, each grown). Where simplifying drops no vertex, grow(rings, distance_m) itself; a
/// ring whose simplification is not a valid polygon is kept whole (the others still simplified).
std::vector<Ring> grow_simplified(const std::vector<Ring>& rings, double distance_m,
                                  double tolerance_m);

/// The area `outer` shrunk by `inset_m` (>= 0) minus `obstacles` (counter-clockwise rings, each
/// followed by its holes clockwise, as grow_keeping_holes() gives them), as
/// rings ready for sweeping and routing: each part's outer ring counter-clockwise followed by its
/// holes clockwise, parts one after another (several when obstacles cut the area in pieces;
/// none when nothing is left).
std::vector<Ring> subtract(const Ring& outer, double inset_m, const std::vector<Ring>& obstacles);

/// Least distance between the polyline `path` (its segments) and the closed areas `rings`
/// (counter-clockwise or clockwise, each a separate area), metres; 0 when the path touches or
/// enters one. +infinity when `rings` is empty. Exact up to rounding (segment-segment distances).
double least_distance(const std::vector<Point2>& path, const std::vector<Ring>& rings);

/// Length of the polyline `path` inside the closed areas `rings`, metres.
double length_inside(const std::vector<Point2>& path, const std::vector<Ring>& rings);

}  // namespace swath::geometry
