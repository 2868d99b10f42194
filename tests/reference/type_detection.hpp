#pragma once
// The paper's TypeDetection (paper 001 §V-A), O(n²): a reference to check classify() against
// and to benchmark it with. Not used by the tools.

#include "swath/geometry/classification.hpp"

namespace swath::reference {

struct TypeDetection {
  geometry::AreaType type = geometry::AreaType::convex;
  std::vector<geometry::RingIndex> reflex_vertices;  ///< ring then index order
};

/// Self-intersection by testing every pair of edges (exact predicates); reflex vertices by the
/// paper's drop-one-vertex test: a vertex is reflex when it lies inside the ring redrawn without
/// it (for a hole, when it lies outside, since the area is on the hole's other side).
TypeDetection type_detection_quadratic(const geometry::Polygon& polygon);

}  // namespace swath::reference
