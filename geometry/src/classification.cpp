#include "swath/geometry/classification.hpp"

#include <algorithm>
#include <numeric>
#include <set>
#include <stdexcept>

#include "swath/geometry/predicates.hpp"

namespace swath::geometry {

std::string_view to_string(AreaType type) {
  switch (type) {
    case AreaType::convex:
      return "convex";
    case AreaType::concave:
      return "concave";
    case AreaType::self_intersecting:
      return "self-intersecting";
  }
  return "unknown";
}

namespace {

bool lex_less(Point2 a, Point2 b) {
  return a.x < b.x || (a.x == b.x && a.y < b.y);
}

// All edges of all rings, numbered consecutively ring by ring.
struct EdgeTable {
  std::vector<RingIndex> id;
  std::vector<Point2> left, right;  // lexicographically smaller / larger end
  std::vector<std::size_t> ring_start;

  explicit EdgeTable(const Polygon& polygon) {
    for (std::size_t r = 0; r < ring_count(polygon); ++r) {
      const Ring& ring = ring_at(polygon, r);
      if (ring.size() < 3)
        throw std::invalid_argument("classify: a ring has fewer than 3 vertices");
      ring_start.push_back(id.size());
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const Point2 p = ring[i];
        const Point2 q = ring[(i + 1) % ring.size()];
        id.push_back({r, i});
        left.push_back(lex_less(p, q) ? p : q);
        right.push_back(lex_less(p, q) ? q : p);
      }
    }
    ring_start.push_back(id.size());
  }
  std::size_t ring_size(std::size_t r) const { return ring_start[r + 1] - ring_start[r]; }
  std::size_t edge(std::size_t r, std::size_t i) const { return ring_start[r] + i; }
  bool neighbours(std::size_t a, std::size_t b) const {
    if (id[a].ring != id[b].ring) return false;
    const std::size_t n = ring_size(id[a].ring);
    return (id[a].index + 1) % n == id[b].index || (id[b].index + 1) % n == id[a].index;
  }
};

// Orders the edges crossing the sweep line from bottom to top. Valid while no two edges in the
// set intersect; a degenerate comparison (a start vertex on another edge, or two edges leaving
// one vertex along the same line) is an intersection and is recorded in `hit`.
struct BelowAtSweep {
  const EdgeTable* edges;
  std::optional<std::pair<std::size_t, std::size_t>>* hit;

  bool operator()(std::size_t a, std::size_t b) const {
    if (a == b) return false;
    const EdgeTable& e = *edges;
    Orientation o;
    bool b_above_means_less;
    if (e.left[a] == e.left[b]) {
      o = orientation(e.left[a], e.right[a], e.right[b]);
      b_above_means_less = true;
    } else if (lex_less(e.left[b], e.left[a])) {
      o = orientation(e.left[b], e.right[b], e.left[a]);  // where a starts relative to b
      b_above_means_less = false;
    } else {
      o = orientation(e.left[a], e.right[a], e.left[b]);  // where b starts relative to a
      b_above_means_less = true;
    }
    if (o == Orientation::collinear) {
      if (!*hit) *hit = std::make_pair(a, b);
      return a < b;
    }
    const bool upper = o == Orientation::counter_clockwise;  // the later-starting point is above
    return b_above_means_less ? upper : !upper;
  }
};

Crossing make_crossing(const EdgeTable& e, std::size_t a, std::size_t b) {
  if (e.id[b].ring < e.id[a].ring ||
      (e.id[b].ring == e.id[a].ring && e.id[b].index < e.id[a].index))
    std::swap(a, b);
  return {e.id[a], e.id[b], segments_common_point(e.left[a], e.right[a], e.left[b], e.right[b])};
}

}  // namespace

std::optional<Crossing> find_crossing(const Polygon& polygon) {
  const EdgeTable edges(polygon);

  struct Vertex {
    Point2 p;
    std::size_t ring, index;
  };
  std::vector<Vertex> vertices;
  vertices.reserve(edges.id.size());
  for (std::size_t r = 0; r < ring_count(polygon); ++r) {
    const Ring& ring = ring_at(polygon, r);
    for (std::size_t i = 0; i < ring.size(); ++i) vertices.push_back({ring[i], r, i});
  }
  std::sort(vertices.begin(), vertices.end(), [](const Vertex& u, const Vertex& v) {
    if (u.p != v.p) return lex_less(u.p, v.p);
    return u.ring < v.ring || (u.ring == v.ring && u.index < v.index);
  });

  std::optional<std::pair<std::size_t, std::size_t>> hit;
  std::set<std::size_t, BelowAtSweep> status(BelowAtSweep{&edges, &hit});
  std::vector<std::set<std::size_t, BelowAtSweep>::iterator> where(edges.id.size(), status.end());

  auto check = [&](std::size_t a, std::size_t b) {
    if (!hit && !edges.neighbours(a, b) &&
        segments_intersect(edges.left[a], edges.right[a], edges.left[b], edges.right[b]))
      hit = std::make_pair(a, b);
  };

  for (std::size_t k = 0; k < vertices.size() && !hit; ++k) {
    const Vertex& v = vertices[k];
    const Ring& ring = ring_at(polygon, v.ring);
    const std::size_t n = ring.size();
    const std::size_t e_prev = edges.edge(v.ring, (v.index + n - 1) % n);
    const std::size_t e_next = edges.edge(v.ring, v.index);

    // Two vertices at one point: the boundary touches itself there.
    if (k > 0 && vertices[k - 1].p == v.p) {
      const Vertex& u = vertices[k - 1];
      hit = std::make_pair(edges.edge(u.ring, u.index), e_next);
      break;
    }
    // Spike: the boundary runs out and back along one line, so the two edges overlap.
    const Point2 p = ring[(v.index + n - 1) % n];
    const Point2 q = ring[(v.index + 1) % n];
    if (orientation(p, v.p, q) == Orientation::collinear && dot(p - v.p, q - v.p) > 0) {
      hit = std::make_pair(e_prev, e_next);
      break;
    }

    for (const std::size_t e : {e_prev, e_next}) {
      if (edges.right[e] != v.p) continue;
      auto it = where[e];
      if (it == status.end()) continue;
      auto above = std::next(it);
      if (it != status.begin() && above != status.end()) check(*std::prev(it), *above);
      status.erase(it);
      where[e] = status.end();
    }
    for (const std::size_t e : {e_prev, e_next}) {
      if (edges.left[e] != v.p) continue;
      auto [it, inserted] = status.insert(e);
      if (hit) break;
      where[e] = it;
      if (it != status.begin()) check(*std::prev(it), e);
      if (std::next(it) != status.end()) check(e, *std::next(it));
    }
  }
  if (!hit) return std::nullopt;
  return make_crossing(edges, hit->first, hit->second);
}

Classification classify(const Polygon& polygon) {
  Classification result;
  if (auto crossing = find_crossing(polygon)) {
    result.type = AreaType::self_intersecting;
    result.crossing = crossing;
    return result;
  }
  for (std::size_t r = 0; r < ring_count(polygon); ++r) {
    const Ring& ring = ring_at(polygon, r);
    const std::size_t n = ring.size();
    for (std::size_t i = 0; i < n; ++i) {
      if (orientation(ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]) == Orientation::clockwise)
        result.reflex_vertices.push_back({r, i});
    }
  }
  result.type = result.reflex_vertices.empty() && polygon.holes.empty() ? AreaType::convex
                                                                        : AreaType::concave;
  return result;
}

}  // namespace swath::geometry
