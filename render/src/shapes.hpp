#pragma once
// Internal: the scene's strokes and markers as closed rings in image pixels, for the coverage
// rasteriser. Every ring is counter-clockwise in the y-down frame (positive signed area), so a
// shape made of several rings fills as their union under the nonzero rule.

#include <vector>

#include "swath/geometry/point.hpp"
#include "swath/render/scene.hpp"

namespace swath::render::detail {

using Ring = std::vector<geometry::Point2>;

/// The same ring with a positive signed area (reversed if needed).
Ring positive(Ring ring);

/// A circle as a polygon whose edges stray at most 0.01 px inside it.
Ring disc(geometry::Point2 centre, double radius_px);

/// A line `width_px` wide along `points`: one quad per segment, flat ends, round joins at every
/// interior vertex and where the line closes on itself (the wedge outside the turn, its arc within
/// 0.05 px of the circle).
std::vector<Ring> stroke(const std::vector<geometry::Point2>& points, double width_px);

/// Direction arrowheads (triangles `size_px` long and wide) about every `every_px` (at least 1 px
/// and 1/64 of their size)
/// along the line, the first half a spacing from its start; only those that can touch an image of
/// `image_px` (width, height) are made.
std::vector<Ring> arrowheads(const std::vector<geometry::Point2>& points, double every_px,
                             double size_px, geometry::Point2 image_px);

/// A marker of `size_px` across centred at `at`.
Ring marker(geometry::Point2 at, double size_px, MarkerShape shape);

/// A band `width_px` wide centred on the segment a-b (empty when a == b).
Ring band(geometry::Point2 a, geometry::Point2 b, double width_px);

}  // namespace swath::render::detail
