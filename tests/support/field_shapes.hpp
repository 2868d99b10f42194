#pragma once
// The split corpus (issue 18, docs/swath-plan.md): families of areas a pilot meets, generated from
// a seed so the corpus is a program, not a set of hand-picked files. Every shape is a simple outer
// ring (counter-clockwise) with disjoint holes inside it (clockwise), in metres, centred near the
// origin and turned by a random angle, so no family favours the axes.

#include <string>
#include <vector>

#include "random_polygons.hpp"
#include "swath/geometry/polygon.hpp"

namespace swath::test {

/// A strip 60-300 m wide and 250-1,400 m long whose long sides are ragged: a vertex every
/// 20-60 m along each, moved in and out by up to 15 m (hedges, tracks, ditches).
geometry::Polygon ragged_strip(Rng& rng);

/// A rectangle of 300-600 x 200-400 m with 1-4 notches (rectangular or slanted, 40-150 m) cut into
/// its sides and 0-2 slivers: 10-25 m wide strips 60-160 m long jutting out of a side.
geometry::Polygon notched_rectangle(Rng& rng);

/// A comb of 2-6 teeth 30-80 m wide and 150-400 m long on a 30-80 m base.
geometry::Polygon random_comb(Rng& rng);

/// An L (two arms) or a T (a bar and a stem), arms 80-250 m wide and 250-700 m long.
geometry::Polygon l_or_t_shape(Rng& rng);

/// A gently concave field (random_field_polygon, 200-400 m across, 12-60 vertices) with 1-5 holes:
/// round ponds (8-24 vertices, 15-45 m radius) and rectangular buildings (15-60 m), at least 20 m
/// from each other and from the boundary.
geometry::Polygon field_with_holes(Rng& rng);

/// A real-like outline: n vertices (5-150) on a closed smoothed random walk of the log radius
/// about a centre (star-shaped, so simple), 200-500 m across, squashed by up to 2:1.
geometry::Polygon random_walk_outline(Rng& rng, std::size_t n);

/// A traced outline (issue 52's farm-scale corpus), as a boundary walked with a GPS or traced from
/// imagery looks: 0.3-3 km across (log-uniform), a concave smoothed random walk of the radius with
/// 0-2 narrow arms (20-70 m wide) jutting out, its edges resampled into 150-900 vertices (2-12 m
/// apart, so more on the largest) with a slowly drifting error of 0.2-1.2 m (at most 0.15 of the
/// spacing), so most vertices are nearly collinear and a few metres apart; about 40 % have 1-4
/// holes (traced ponds and buildings). Simple (checked exactly).
geometry::Polygon traced_outline(Rng& rng);

struct CorpusShape {
  std::string family;  ///< "ragged-strip", "notched", "comb", "l-t", "holes", "walk"
  int index = 0;       ///< within its family
  geometry::Polygon area;
};

/// `per_family` shapes of each family, all from `seed` (each family its own stream, so adding
/// shapes to one family leaves the others unchanged). Walk outlines take 5-150 vertices, spread
/// evenly over the family.
std::vector<CorpusShape> split_corpus(std::uint64_t seed, int per_family);

}  // namespace swath::test
