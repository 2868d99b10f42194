#pragma once
// Polygon type detection (paper 001 §V-A, done exactly in O(n log n)).

#include <optional>
#include <string_view>
#include <vector>

#include "swath/geometry/polygon.hpp"

namespace swath::geometry {

enum class AreaType { convex, concave, self_intersecting };

std::string_view to_string(AreaType type);

/// Two edges that touch, cross or overlap although they are not neighbours in one ring (or two
/// neighbours that fold back onto each other), and a point they share.
struct Crossing {
  RingIndex edge_a;
  RingIndex edge_b;
  Point2 point;
};

struct Classification {
  AreaType type = AreaType::convex;
  /// Concave: the vertices where the boundary turns away from the area (interior angle > 180°),
  /// holes' vertices included, in ring then index order. Empty otherwise.
  std::vector<RingIndex> reflex_vertices;
  /// Self-intersecting: the first offending edge pair the sweep meets (leftmost sweep event).
  std::optional<Crossing> crossing;
};

/// Classifies a normalised polygon (outer ring counter-clockwise, holes clockwise, no consecutive
/// duplicate vertices) with exact predicates: a sweep over the vertices (Shamos-Hoey) finds any
/// touching, crossing or overlapping pair of edges in O(n log n); a simple polygon without holes
/// and without a clockwise turn is convex (collinear vertices allowed), any other simple polygon
/// concave. A polygon with holes is never convex.
Classification classify(const Polygon& polygon);

/// Only the self-intersection part of classify(): the first crossing, if any.
std::optional<Crossing> find_crossing(const Polygon& polygon);

}  // namespace swath::geometry
