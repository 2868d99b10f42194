#pragma once
// Repairing a ring that crosses itself.

#include <vector>

#include "swath/geometry/polygon.hpp"

namespace swath::geometry {

/// The areas a closed ring encloses, crossing itself or not: the union of the bounded faces of
/// the arrangement of its edges (computed exactly), as simple counter-clockwise rings, largest
/// first. Pieces that touch only at a point are separate rings (a bowtie gives two triangles);
/// edges that enclose nothing (spikes) disappear. Empty if the ring encloses no area.
std::vector<Ring> enclosed_areas(const Ring& ring);

}  // namespace swath::geometry
