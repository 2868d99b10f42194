#pragma once
// Fixed-seed random polygons for property tests and benchmarks.

#include <cstdint>
#include <random>

#include "swath/geometry/polygon.hpp"

namespace swath::test {

using Rng = std::mt19937_64;

/// A simple polygon, star-shaped about the origin: n vertices at sorted random angles with radii in
/// [r_min, r_max] metres, counter-clockwise. Concave unless r_min == r_max.
geometry::Ring random_star_polygon(Rng& rng, std::size_t n, double r_min, double r_max);

/// A field-like simple polygon: n vertices around a smooth boundary of mean radius r metres
/// (a few low harmonics, so it is gently concave) with radial jitter of 20 % of the vertex
/// spacing, as a boundary traced from imagery looks. Simple; counter-clockwise.
geometry::Ring random_field_polygon(Rng& rng, std::size_t n, double r);

/// A convex polygon: n vertices at sorted random angles on an ellipse with semi-axes a, b metres,
/// rotated by a random angle, counter-clockwise.
geometry::Ring random_convex_polygon(Rng& rng, std::size_t n, double a, double b);

/// n points with integer coordinates in [0, grid) in random order (duplicates removed): mostly
/// self-intersecting, full of collinear and touching edges, for exactness tests.
geometry::Ring random_grid_ring(Rng& rng, std::size_t n, int grid);

/// A comb: `teeth` vertical teeth of width w and height h on a base of height b, CCW. Concave.
geometry::Ring comb_polygon(int teeth, double w, double h, double b);

/// A rectangular spiral corridor `2 half_width` wide whose centre line turns left `arms` times,
/// arms `gap` apart (gap > 2 half_width), the first `length` long. Counter-clockwise. Concave.
geometry::Ring spiral_polygon(int arms, double length, double gap, double half_width);

/// `ring` rotated by angle_deg about the origin and moved by (dx, dy).
geometry::Ring transformed(const geometry::Ring& ring, double angle_deg, double dx, double dy);

}  // namespace swath::test
