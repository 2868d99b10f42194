#include "swath/geometry/decomposition.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <utility>

#include "swath/geometry/predicates.hpp"
#include "swath/geometry/sort_runs.hpp"

namespace swath::geometry {
namespace {

// A turn by angle_deg: its cosine and sine, taken once for all the points it turns (libm's sincos
// per point was a sixth of a 10,000-vertex plan's instructions). The same values as per point.
struct Turn {
  double c, s;
};

Turn turn_by(double angle_deg) {
  const double t = angle_deg * std::numbers::pi / 180.0;
  return {std::cos(t), std::sin(t)};
}

Point2 rotated(Point2 p, Turn t) {
  return {t.c * p.x - t.s * p.y, t.s * p.x + t.c * p.y};
}

// "Below" with ties broken by x: the sweep behaves as if tilted infinitesimally, so edges along
// the sweep direction need no special case.
bool below(Point2 a, Point2 b) {
  return a.y < b.y || (a.y == b.y && a.x < b.x);
}

struct Edge {
  Point2 lower, upper;
};

double x_at(const Edge& e, double y) {
  if (e.upper.y == e.lower.y) return e.lower.x;
  return e.lower.x + (e.upper.x - e.lower.x) * (y - e.lower.y) / (e.upper.y - e.lower.y);
}

// Strictly right of the edge directed lower -> upper.
bool right_of(const Edge& e, Point2 p) {
  return orientation(e.lower, e.upper, p) == Orientation::clockwise;
}

struct OpenCell {
  std::size_t left_edge, right_edge;
  std::vector<Point2> left_chain, right_chain;  // bottom to top
};

struct Chains {
  std::vector<Point2> left, right;  // bottom to top, in the sweep frame
};

// Kuhn's augmenting paths: can `lower` be matched to an upper cell (possibly re-matching others)?
bool augment(std::size_t lower, const std::vector<std::vector<std::size_t>>& above,
             std::vector<long>& upper_of, std::vector<char>& seen) {
  for (const std::size_t u : above[lower]) {
    if (seen[u]) continue;
    seen[u] = 1;
    if (upper_of[u] < 0 || augment(static_cast<std::size_t>(upper_of[u]), above, upper_of, seen)) {
      upper_of[u] = static_cast<long>(lower);
      return true;
    }
  }
  return false;
}

// Joins cells across cuts into the fewest monotone cells: a cell continued through a cut by one
// cell above it is still met by every lane in one interval, so a set of such chains is a
// minimum path cover of the "directly above" graph: cells minus a maximum matching.
std::vector<std::vector<std::size_t>> merge_across_cuts(const std::vector<Chains>& cells) {
  const std::size_t n = cells.size();
  std::map<double, std::vector<std::size_t>> by_bottom;  // cells starting on a cut at that ordinate
  for (std::size_t b = 0; b < n; ++b)
    if (cells[b].left.front().y == cells[b].right.front().y)
      by_bottom[cells[b].left.front().y].push_back(b);
  std::vector<std::vector<std::size_t>> above(n);
  std::vector<std::pair<double, std::size_t>> candidates;
  for (std::size_t a = 0; a < n; ++a) {
    const Point2 tl = cells[a].left.back(), tr = cells[a].right.back();
    const auto starting = by_bottom.find(tl.y);
    if (starting == by_bottom.end() || tr.y != tl.y) continue;
    candidates.clear();
    for (const std::size_t b : starting->second) {
      const Point2 bl = cells[b].left.front(), br = cells[b].right.front();
      if (b == a) continue;
      const double overlap = std::min(tr.x, br.x) - std::max(tl.x, bl.x);
      if (overlap > 0) candidates.push_back({-overlap, b});  // widest shared cut first
    }
    std::sort(candidates.begin(), candidates.end());
    for (const auto& c : candidates) above[a].push_back(c.second);
  }
  std::vector<long> lower_of(n, -1);  // upper cell -> the cell below it in its chain
  std::vector<char> seen(n);
  for (std::size_t a = 0; a < n; ++a) {
    std::fill(seen.begin(), seen.end(), 0);
    augment(a, above, lower_of, seen);
  }
  std::vector<long> upper_of(n, -1);
  for (std::size_t b = 0; b < n; ++b)
    if (lower_of[b] >= 0) upper_of[static_cast<std::size_t>(lower_of[b])] = static_cast<long>(b);
  std::vector<std::vector<std::size_t>> merged;
  for (std::size_t start = 0; start < n; ++start) {
    if (lower_of[start] >= 0) continue;  // not the bottom of a chain
    std::vector<std::size_t> chain;
    for (long c = static_cast<long>(start); c >= 0; c = upper_of[static_cast<std::size_t>(c)])
      chain.push_back(static_cast<std::size_t>(c));
    merged.push_back(std::move(chain));
  }
  return merged;
}

// A ring from chains (right chain up, left chain down), cleaned and rotated back; empty if no area.
Ring chains_ring(const std::vector<Point2>& left, const std::vector<Point2>& right,
                 double angle_deg) {
  // Up the right chain, down the left, repeats dropped (taken in place: a 10,000-vertex outline
  // makes ~10^5 chain points a direction).
  Ring clean;
  clean.reserve(right.size() + left.size());
  const auto add = [&clean](const Point2& p) {
    if (clean.empty() || !(clean.back() == p)) clean.push_back(p);
  };
  for (const Point2& p : right) add(p);
  for (auto p = left.rbegin(); p != left.rend(); ++p) add(*p);
  while (clean.size() > 1 && clean.back() == clean.front()) clean.pop_back();
  if (clean.size() < 3 || signed_area(clean) <= 0) return {};
  const Turn back = turn_by(angle_deg);
  for (Point2& p : clean) p = rotated(p, back);
  return clean;
}

}  // namespace

std::vector<Ring> rings_of(const Polygon& polygon) {
  std::vector<Ring> rings{polygon.outer};
  rings.insert(rings.end(), polygon.holes.begin(), polygon.holes.end());
  return rings;
}

std::vector<Ring> boustrophedon_cells(const std::vector<Ring>& rings, double angle_deg) {
  return boustrophedon_decomposition(rings, angle_deg).cell_rings;
}

Decomposition boustrophedon_decomposition(const std::vector<Ring>& rings_in, double angle_deg) {
  // Work in a frame where the cut lines are horizontal.
  std::vector<Ring> rings;
  std::vector<Edge> edges;
  std::vector<std::size_t> first_edge;
  struct Vertex {
    Point2 p;
    std::size_t ring, index;
  };
  std::vector<Vertex> vertices;
  double extent = 0;
  std::size_t total = 0;
  for (const Ring& ring : rings_in) {
    total += ring.size();
    for (const Point2& p : ring) extent = std::max({extent, std::abs(p.x), std::abs(p.y)});
  }
  // Sized once: grown by doubling, a 10,000-vertex area's buffers were most of the fresh pages
  // (page faults) of a direction search that decomposes it ~100 times.
  rings.reserve(rings_in.size());
  edges.reserve(total);
  vertices.reserve(total);
  // Rotation rounds: an edge along the lanes comes out tilted by ~1e-16 of the coordinates, which
  // would make cuts that meet at one ordinate miss each other. Such edges are made exactly
  // parallel (moves of < 1e-9 of the area's size).
  const double snap = 1e-9 * extent;
  const Turn to_sweep = turn_by(-angle_deg);
  for (std::size_t r = 0; r < rings_in.size(); ++r) {
    Ring ring;
    ring.reserve(rings_in[r].size());
    for (const Point2& p : rings_in[r]) ring.push_back(rotated(p, to_sweep));
    for (std::size_t i = 0; i + 1 < ring.size(); ++i)
      if (std::abs(ring[i + 1].y - ring[i].y) <= snap) ring[i + 1].y = ring[i].y;
    if (ring.size() > 2 && std::abs(ring.back().y - ring.front().y) <= snap)
      ring.back().y = ring.front().y;
    first_edge.push_back(edges.size());
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point2 a = ring[i], b = ring[(i + 1) % ring.size()];
      edges.push_back(below(a, b) ? Edge{a, b} : Edge{b, a});
      vertices.push_back({a, r, i});
    }
    rings.push_back(std::move(ring));
  }
  // In ring order the vertices rise and fall in long stretches: merged, not sorted anew for
  // every direction (the same order, ties between equal points included).
  sort_by_runs(
      vertices, [](const Vertex& a, const Vertex& b) { return below(a.p, b.p); }, false);

  std::vector<OpenCell> open;
  std::vector<Chains> pieces;
  auto close = [&](OpenCell& c) {
    // Pieces between two events at one ordinate (an edge along the lanes) have no area.
    Ring ring = c.right_chain;
    ring.insert(ring.end(), c.left_chain.rbegin(), c.left_chain.rend());
    // Moved, not copied: every closed cell is overwritten or erased next.
    if (signed_area(ring) > 0)
      pieces.push_back({std::move(c.left_chain), std::move(c.right_chain)});
  };
  auto find = [&](auto pred) {
    const auto it = std::find_if(open.begin(), open.end(), pred);
    if (it == open.end())
      throw std::logic_error("boustrophedon_cells: inconsistent sweep (crossing rings?)");
    return it;
  };

  for (const Vertex& v : vertices) {
    const Ring& ring = rings[v.ring];
    const std::size_t n = ring.size();
    const Point2 p = ring[(v.index + n - 1) % n], q = ring[(v.index + 1) % n];
    const std::size_t e_in = first_edge[v.ring] + (v.index + n - 1) % n;  // p -> v
    const std::size_t e_out = first_edge[v.ring] + v.index;               // v -> q
    const bool p_below = below(p, v.p), q_below = below(q, v.p);
    const bool convex = orientation(p, v.p, q) == Orientation::counter_clockwise;
    const double y = v.p.y;

    if (!p_below && !q_below) {
      if (convex) {  // start: p -> v runs down (a left side), v -> q up (a right side)
        auto pos = open.begin();
        while (pos != open.end() && right_of(edges[pos->right_edge], v.p)) ++pos;
        open.insert(pos, OpenCell{e_in, e_out, {v.p}, {v.p}});
      } else {  // split: v inside a cell; the notch above v separates two new cells
        auto c = find([&](const OpenCell& o) {
          return right_of(edges[o.left_edge], v.p) && !right_of(edges[o.right_edge], v.p);
        });
        const Point2 l{x_at(edges[c->left_edge], y), y}, r{x_at(edges[c->right_edge], y), y};
        c->left_chain.push_back(l);
        c->right_chain.push_back(r);
        const std::size_t left_edge = c->left_edge, right_edge = c->right_edge;
        close(*c);
        *c = OpenCell{left_edge, e_out, {l}, {v.p}};
        open.insert(c + 1, OpenCell{e_in, right_edge, {v.p}, {r}});
      }
    } else if (p_below && q_below) {
      if (convex) {  // end: the cell whose right side is p -> v closes at v
        auto c = find([&](const OpenCell& o) { return o.right_edge == e_in; });
        c->left_chain.push_back(v.p);
        c->right_chain.push_back(v.p);
        close(*c);
        open.erase(c);
      } else {  // merge: the cells left and right of v close; one cell continues above
        auto a = find([&](const OpenCell& o) { return o.right_edge == e_in; });
        auto b = a + 1;
        if (b == open.end() || b->left_edge != e_out)
          throw std::logic_error("boustrophedon_cells: bad merge");
        const Point2 l{x_at(edges[a->left_edge], y), y}, r{x_at(edges[b->right_edge], y), y};
        a->left_chain.push_back(l);
        a->right_chain.push_back(v.p);
        b->left_chain.push_back(v.p);
        b->right_chain.push_back(r);
        const std::size_t left_edge = a->left_edge, right_edge = b->right_edge;
        close(*a);
        close(*b);
        *a = OpenCell{left_edge, right_edge, {l}, {r}};
        open.erase(b);
      }
    } else if (p_below) {  // regular on a right side: p -> v -> q both run up
      auto c = find([&](const OpenCell& o) { return o.right_edge == e_in; });
      c->right_chain.push_back(v.p);
      c->right_edge = e_out;
    } else {  // regular on a left side: p -> v -> q both run down
      auto c = find([&](const OpenCell& o) { return o.left_edge == e_out; });
      c->left_chain.push_back(v.p);
      c->left_edge = e_in;
    }
  }

  Decomposition d;
  for (const Chains& piece : pieces)
    d.pieces.push_back(chains_ring(piece.left, piece.right, angle_deg));
  for (const std::vector<std::size_t>& chain : merge_across_cuts(pieces)) {
    Chains joined;
    for (const std::size_t k : chain) {
      joined.left.insert(joined.left.end(), pieces[k].left.begin(), pieces[k].left.end());
      joined.right.insert(joined.right.end(), pieces[k].right.begin(), pieces[k].right.end());
    }
    Ring ring = chains_ring(joined.left, joined.right, angle_deg);
    if (ring.empty()) continue;
    d.cells.push_back(chain);
    d.cell_rings.push_back(std::move(ring));
  }
  return d;
}

}  // namespace swath::geometry
