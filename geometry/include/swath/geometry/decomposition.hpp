#pragma once
// Boustrophedon cell decomposition: cells that lanes in one direction sweep without leaving them.

#include <vector>

#include "swath/geometry/polygon.hpp"

namespace swath::geometry {

/// Splits an area (one or more outer rings counter-clockwise, holes clockwise, no crossings) into
/// cells that every line at `angle_deg` (degrees CCW from x) meets in at most one interval, so a
/// zigzag of such lines sweeps a cell without leaving it. Cells are cut only along lines at that
/// angle through the critical vertices, where the area splits (a reflex vertex with both
/// neighbours ahead of it: a notch or a hole's near side) or merges (both behind): the fewest
/// cuts of that kind; trapezoids between critical vertices are never cut. Counter-clockwise rings
/// in the input's frame; zero-area cells are dropped. Their areas sum to the input's area.
/// O(n log n + n c) for n vertices and c cells open at once.
std::vector<Ring> boustrophedon_cells(const std::vector<Ring>& rings, double angle_deg);

/// The same decomposition with its parts: the pieces between critical ordinates (trapezoid-like,
/// never cut further) and, per cell, its pieces from bottom to top. Useful where a cell's lanes are
/// placed per piece (a thin piece still gets one).
struct Decomposition {
  std::vector<Ring> pieces;                     ///< counter-clockwise, input frame
  std::vector<std::vector<std::size_t>> cells;  ///< piece indices of each cell, bottom to top
  std::vector<Ring> cell_rings;                 ///< each cell as one ring (as boustrophedon_cells)
};
Decomposition boustrophedon_decomposition(const std::vector<Ring>& rings, double angle_deg);

/// The rings of a polygon, outer first (the input form of boustrophedon_cells()).
std::vector<Ring> rings_of(const Polygon& polygon);

}  // namespace swath::geometry
