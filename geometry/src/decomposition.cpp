#include "swath/geometry/decomposition.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <stdexcept>
#include <utility>

#include "swath/geometry/predicates.hpp"
#include "swath/geometry/sort_runs.hpp"
#include "swath/geometry/turn.hpp"

namespace swath::geometry {
namespace {

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

// Chains' buffers kept by the thread between decompositions, their capacity with them: a chain
// grown point by point from nothing was most of a direction's allocations and copies (a split
// plan decomposes its area at ~100 directions). What a buffer held before is cleared first, so the
// chains are the same.
class ChainPool {
 public:
  std::vector<Point2> take(Point2 first) {
    std::vector<Point2> chain;
    if (!spare_.empty()) {
      chain = std::move(spare_.back());
      spare_.pop_back();
      chain.clear();
    }
    chain.push_back(first);
    return chain;
  }
  void give(std::vector<Point2>& chain) {
    if (chain.capacity() > 0) spare_.push_back(std::move(chain));
    chain = {};
  }

 private:
  std::vector<std::vector<Point2>> spare_;
};

ChainPool& chain_pool() {
  thread_local ChainPool pool;
  return pool;
}

struct OpenCell {
  std::size_t left_edge, right_edge;
  std::vector<Point2> left_chain, right_chain;  // bottom to top
};

struct Chains {
  std::vector<Point2> left, right;  // bottom to top, in the sweep frame
};

// Kuhn's augmenting paths: can `lower` be matched to an upper cell (possibly re-matching others)?
// `seen[u] == stamp`: u was looked at in this search (a stamp per search, not a cleared array:
// that was quadratic in the pieces).
bool augment(std::size_t lower, const std::vector<std::vector<std::size_t>>& above,
             std::vector<long>& upper_of, std::vector<std::size_t>& seen, std::size_t stamp) {
  for (const std::size_t u : above[lower]) {
    if (seen[u] == stamp) continue;
    seen[u] = stamp;
    if (upper_of[u] < 0 ||
        augment(static_cast<std::size_t>(upper_of[u]), above, upper_of, seen, stamp)) {
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
  // The cells starting on a cut, by its ordinate and then by index: a sorted list rather than a
  // map of lists (a node and a list per cut at every direction), each cut's cells in the order
  // the map's list held them.
  std::vector<std::pair<double, std::size_t>> by_bottom;
  for (std::size_t b = 0; b < n; ++b)
    if (cells[b].left.front().y == cells[b].right.front().y)
      by_bottom.push_back({cells[b].left.front().y, b});
  std::sort(by_bottom.begin(), by_bottom.end());
  std::vector<std::vector<std::size_t>> above(n);
  std::vector<std::pair<double, std::size_t>> candidates;
  for (std::size_t a = 0; a < n; ++a) {
    const Point2 tl = cells[a].left.back(), tr = cells[a].right.back();
    if (tr.y != tl.y) continue;
    auto starting = std::lower_bound(by_bottom.begin(), by_bottom.end(), tl.y,
                                     [](const auto& c, double y) { return c.first < y; });
    candidates.clear();
    for (; starting != by_bottom.end() && !(tl.y < starting->first); ++starting) {
      const std::size_t b = starting->second;
      const Point2 bl = cells[b].left.front(), br = cells[b].right.front();
      if (b == a) continue;
      const double overlap = std::min(tr.x, br.x) - std::max(tl.x, bl.x);
      if (overlap > 0) candidates.push_back({-overlap, b});  // widest shared cut first
    }
    std::sort(candidates.begin(), candidates.end());
    for (const auto& c : candidates) above[a].push_back(c.second);
  }
  std::vector<long> lower_of(n, -1);  // upper cell -> the cell below it in its chain
  std::vector<std::size_t> seen(n, 0);
  for (std::size_t a = 0; a < n; ++a) {
    augment(a, above, lower_of, seen, a + 1);
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

std::logic_error inconsistent_sweep() {
  return std::logic_error("boustrophedon_cells: inconsistent sweep (crossing rings?)");
}

// signed_area() of the ring up the right chain and down the left, without building it: the same
// terms in the same order, so the same value (a ring copied per closed cell was ~40,000
// allocations a plan on traced outlines).
double chains_area(const std::vector<Point2>& left, const std::vector<Point2>& right) {
  const std::size_t n_right = right.size(), n = n_right + left.size();
  if (n < 3) return 0.0;
  const auto at = [&](std::size_t i) { return i < n_right ? right[i] : left[n - 1 - i]; };
  const Point2 o = at(0);
  double twice = 0.0;
  // Term i is cross(at(i) - o, at(i + 1) - o): over the rest of the right chain, then down the
  // left one (a chain test per point was most of this function's work).
  Point2 before = at(1);
  for (std::size_t i = 2; i < n_right; ++i) {
    twice += cross(before - o, right[i] - o);
    before = right[i];
  }
  for (std::size_t i = std::max<std::size_t>(2, n_right); i < n; ++i) {
    const Point2 p = left[n - 1 - i];
    twice += cross(before - o, p - o);
    before = p;
  }
  return twice / 2.0;
}

// Pieces between two events at one ordinate (an edge along the lanes) have no area. The chains
// are moved, not copied: every closed cell is reopened or shut next.
void close_piece(OpenCell& c, std::vector<Chains>& pieces) {
  if (chains_area(c.left_chain, c.right_chain) > 0)
    pieces.push_back({std::move(c.left_chain), std::move(c.right_chain)});
}

// The cells the sweep line crosses, left to right. A cell stays in one slot while open and each
// edge knows the cell it bounds, so that a regular vertex (most of a traced outline's) finds its
// cell at once; a scan of the open cells for each was a third of the decomposition's instructions.
struct CellSweep {
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  // Empty, for a sweep of `edges` edges; the chains its slots still hold go back to the pool.
  void reset(std::size_t edges) {
    for (std::size_t c = 0; c < cell.size(); ++c) recycle(c);
    cell.clear();
    order.clear();
    free.clear();
    right_of_edge.assign(edges, kNone);
    left_of_edge.assign(edges, kNone);
  }

  std::vector<OpenCell> cell;                            // slots, reused once shut
  std::vector<std::size_t> order;                        // the open cells' slots, left to right
  std::vector<std::size_t> right_of_edge, left_of_edge;  // the open cell an edge bounds
  std::vector<std::size_t> free;

  std::size_t right_cell(std::size_t edge) const { return found(right_of_edge[edge]); }
  std::size_t left_cell(std::size_t edge) const { return found(left_of_edge[edge]); }
  std::size_t position(std::size_t c) const {
    return static_cast<std::size_t>(std::find(order.begin(), order.end(), c) - order.begin());
  }
  void open(std::size_t pos, std::size_t left_edge, std::size_t right_edge,
            std::vector<Point2> left, std::vector<Point2> right) {
    std::size_t c = cell.size();
    if (free.empty()) {
      cell.push_back({});
    } else {
      c = free.back();
      free.pop_back();
    }
    recycle(c);
    cell[c] = OpenCell{left_edge, right_edge, std::move(left), std::move(right)};
    left_of_edge[left_edge] = right_of_edge[right_edge] = c;
    order.insert(order.begin() + static_cast<std::ptrdiff_t>(pos), c);
  }
  void reopen(std::size_t c, std::size_t left_edge, std::size_t right_edge, Point2 left,
              Point2 right) {
    unlink(c);
    recycle(c);
    cell[c] = OpenCell{left_edge, right_edge, chain_pool().take(left), chain_pool().take(right)};
    left_of_edge[left_edge] = right_of_edge[right_edge] = c;
  }
  // The chains a slot still holds (a piece without area is not moved out) back to the pool.
  void recycle(std::size_t c) {
    chain_pool().give(cell[c].left_chain);
    chain_pool().give(cell[c].right_chain);
  }
  void shut(std::size_t c) {
    unlink(c);
    order.erase(order.begin() + static_cast<std::ptrdiff_t>(position(c)));
    free.push_back(c);
  }
  void set_right(std::size_t c, std::size_t edge) {
    right_of_edge[cell[c].right_edge] = kNone;
    right_of_edge[cell[c].right_edge = edge] = c;
  }
  void set_left(std::size_t c, std::size_t edge) {
    left_of_edge[cell[c].left_edge] = kNone;
    left_of_edge[cell[c].left_edge = edge] = c;
  }

 private:
  static std::size_t found(std::size_t c) {
    if (c == kNone) throw inconsistent_sweep();
    return c;
  }
  void unlink(std::size_t c) {
    if (left_of_edge[cell[c].left_edge] == c) left_of_edge[cell[c].left_edge] = kNone;
    if (right_of_edge[cell[c].right_edge] == c) right_of_edge[cell[c].right_edge] = kNone;
  }
};

// A ring from a chain of pieces (up their right chains, bottom piece first, down their left
// chains), cleaned and rotated back by `back`; empty if no area. Read in place: a 10,000-vertex
// outline makes ~10^5 chain points a direction, and a cell's chains joined first were a copy more.
Ring chains_ring(const std::vector<Chains>& pieces, std::span<const std::size_t> chain, Turn back) {
  std::size_t points = 0;
  for (const std::size_t k : chain) points += pieces[k].right.size() + pieces[k].left.size();
  Ring clean;
  clean.reserve(points);
  const auto add = [&clean](const Point2& p) {
    if (clean.empty() || !(clean.back() == p)) clean.push_back(p);
  };
  for (const std::size_t k : chain)
    for (const Point2& p : pieces[k].right) add(p);
  for (auto k = chain.rbegin(); k != chain.rend(); ++k)
    for (auto p = pieces[*k].left.rbegin(); p != pieces[*k].left.rend(); ++p) add(*p);
  while (clean.size() > 1 && clean.back() == clean.front()) clean.pop_back();
  if (clean.size() < 3 || signed_area(clean) <= 0) return {};
  for (Point2& p : clean) p = back(p);
  return clean;
}

// sort_by_runs(v, less, true) with the merges' buffer kept by the thread (`spare`, swapped with
// v level by level): inplace_merge took a buffer of its own for every merge. Merged stably, so
// the order sort_by_runs() gives (a sort's whole, where there are too many runs).
template <typename T, typename Less>
void merge_by_runs(std::vector<T>& v, std::vector<T>& spare, Less less) {
  thread_local std::vector<SortedRun> runs;
  thread_local std::vector<std::size_t> bounds, merged;
  if (!sorted_runs(v, less, runs)) {  // too many: sorted whole
    std::sort(v.begin(), v.end(), less);
    return;
  }
  bounds.assign(1, 0);
  for (const SortedRun& r : runs) {
    if (r.decreasing)
      std::reverse(v.begin() + std::ptrdiff_t(r.begin), v.begin() + std::ptrdiff_t(r.end));
    bounds.push_back(r.end);
  }
  const auto at = [](std::vector<T>& w, std::size_t k) { return w.begin() + std::ptrdiff_t(k); };
  while (bounds.size() > 2) {
    spare.resize(v.size());
    merged.assign(1, 0);
    for (std::size_t k = 0; k + 1 < bounds.size(); k += 2)
      if (k + 2 < bounds.size()) {
        std::merge(at(v, bounds[k]), at(v, bounds[k + 1]), at(v, bounds[k + 1]),
                   at(v, bounds[k + 2]), at(spare, bounds[k]), less);
        merged.push_back(bounds[k + 2]);
      } else {
        std::copy(at(v, bounds[k]), at(v, bounds[k + 1]), at(spare, bounds[k]));
        merged.push_back(bounds[k + 1]);
      }
    v.swap(spare);
    bounds.swap(merged);
  }
}

struct Vertex {
  Point2 p;
  std::size_t ring, index;
};

// The rings turned to the sweep's frame (`rings`), their edges lower end first (ring r's from
// first_edge[r] on) and their vertices in the sweep's order, into the caller's buffers.
void to_sweep_frame(const std::vector<Ring>& rings_in, double angle_deg, std::vector<Ring>& rings,
                    std::vector<Edge>& edges, std::vector<std::size_t>& first_edge,
                    std::vector<Vertex>& vertices) {
  rings.resize(rings_in.size());
  first_edge.clear();
  // Turned as the extent is taken, one pass over the input. The buffers are written in place,
  // sized once (grown by doubling, a 10,000-vertex area's buffers were most of the fresh pages of a
  // direction search that decomposes it ~100 times; pushed point by point, a tenth of its work).
  double extent = 0;
  std::size_t total = 0;
  const Turn to_sweep(-angle_deg);
  for (std::size_t r = 0; r < rings_in.size(); ++r) {
    const Ring& in = rings_in[r];
    Ring& ring = rings[r];
    ring.resize(in.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
      const Point2 p = in[i];
      extent = std::max({extent, std::abs(p.x), std::abs(p.y)});
      ring[i] = to_sweep(p);
    }
    total += in.size();
  }
  edges.resize(total);
  vertices.resize(total);
  // Rotation rounds: an edge along the lanes comes out tilted by ~1e-16 of the coordinates, which
  // would make cuts that meet at one ordinate miss each other. Such edges are made exactly
  // parallel (moves of < 1e-9 of the area's size).
  const double snap = 1e-9 * extent;
  std::size_t at = 0;  // the next edge's and vertex's slot
  for (std::size_t r = 0; r < rings.size(); ++r) {
    Ring& ring = rings[r];
    for (std::size_t i = 0; i + 1 < ring.size(); ++i)
      if (std::abs(ring[i + 1].y - ring[i].y) <= snap) ring[i + 1].y = ring[i].y;
    if (ring.size() > 2 && std::abs(ring.back().y - ring.front().y) <= snap)
      ring.back().y = ring.front().y;
    first_edge.push_back(at);
    const std::size_t n = ring.size();
    for (std::size_t i = 0; i < n; ++i, ++at) {
      const Point2 a = ring[i], b = ring[i + 1 < n ? i + 1 : 0];
      edges[at] = below(a, b) ? Edge{a, b} : Edge{b, a};
      vertices[at] = {a, r, i};
    }
  }
  // In ring order the vertices rise and fall in long stretches: merged, not sorted anew for
  // every direction (the same order, ties between equal points included). Where two are equal
  // points std::sort's own order between them is kept: sorted whole from ring order, as
  // sort_by_runs(..., false) does, the ring order remade from the rings rather than copied first
  // at every direction (equal points are rare; the copy was 2 M instructions on traced-067).
  const auto by_ordinate = [](const Vertex& a, const Vertex& b) { return below(a.p, b.p); };
  thread_local std::vector<Vertex> spare;
  merge_by_runs(vertices, spare, by_ordinate);
  for (std::size_t i = 0; i + 1 < vertices.size(); ++i)
    if (!by_ordinate(vertices[i], vertices[i + 1])) {  // sorted, so equal points
      vertices.clear();
      for (std::size_t r = 0; r < rings.size(); ++r)
        for (std::size_t k = 0; k < rings[r].size(); ++k) vertices.push_back({rings[r][k], r, k});
      std::sort(vertices.begin(), vertices.end(), by_ordinate);
      break;
    }
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
  // Work in a frame where the cut lines are horizontal. The buffers are the thread's, their
  // capacity kept: a split plan decomposes its area at every candidate direction.
  thread_local std::vector<Ring> rings;
  thread_local std::vector<Edge> edges;
  thread_local std::vector<std::size_t> first_edge;
  thread_local std::vector<Vertex> vertices;
  to_sweep_frame(rings_in, angle_deg, rings, edges, first_edge, vertices);

  thread_local std::vector<Chains> pieces;
  pieces.clear();
  thread_local CellSweep sweep;
  sweep.reset(edges.size());
  for (const Vertex& v : vertices) {
    const Ring& ring = rings[v.ring];
    const std::size_t n = ring.size();
    const std::size_t before = v.index == 0 ? n - 1 : v.index - 1;
    const Point2 p = ring[before], q = ring[v.index + 1 == n ? 0 : v.index + 1];
    const std::size_t e_in = first_edge[v.ring] + before;    // p -> v
    const std::size_t e_out = first_edge[v.ring] + v.index;  // v -> q
    const bool p_below = below(p, v.p), q_below = below(q, v.p);
    // Asked only where both neighbours lie on one side: a regular vertex (most of a traced
    // outline's) needs no turn (the exact predicate at every vertex was 2.2 M instructions of
    // traced-067's 29 M of decompositions).
    const auto convex = [&] { return orientation(p, v.p, q) == Orientation::counter_clockwise; };
    const double y = v.p.y;

    if (!p_below && !q_below) {
      if (convex()) {  // start: p -> v runs down (a left side), v -> q up (a right side)
        std::size_t pos = 0;
        while (pos < sweep.order.size() &&
               right_of(edges[sweep.cell[sweep.order[pos]].right_edge], v.p))
          ++pos;
        sweep.open(pos, e_in, e_out, chain_pool().take(v.p), chain_pool().take(v.p));
      } else {  // split: v inside a cell; the notch above v separates two new cells
        std::size_t pos = 0;
        while (pos < sweep.order.size() &&
               !(right_of(edges[sweep.cell[sweep.order[pos]].left_edge], v.p) &&
                 !right_of(edges[sweep.cell[sweep.order[pos]].right_edge], v.p)))
          ++pos;
        if (pos == sweep.order.size()) throw inconsistent_sweep();
        const std::size_t c = sweep.order[pos];
        const std::size_t left_edge = sweep.cell[c].left_edge,
                          right_edge = sweep.cell[c].right_edge;
        const Point2 l{x_at(edges[left_edge], y), y}, r{x_at(edges[right_edge], y), y};
        sweep.cell[c].left_chain.push_back(l);
        sweep.cell[c].right_chain.push_back(r);
        close_piece(sweep.cell[c], pieces);
        sweep.reopen(c, left_edge, e_out, l, v.p);
        sweep.open(pos + 1, e_in, right_edge, chain_pool().take(v.p), chain_pool().take(r));
      }
    } else if (p_below && q_below) {
      const std::size_t a = sweep.right_cell(e_in);
      if (convex()) {  // end: the cell whose right side is p -> v closes at v
        sweep.cell[a].left_chain.push_back(v.p);
        sweep.cell[a].right_chain.push_back(v.p);
        close_piece(sweep.cell[a], pieces);
        sweep.shut(a);
      } else {  // merge: the cells left and right of v close; one cell continues above
        const std::size_t pos = sweep.position(a);
        if (pos + 1 == sweep.order.size() || sweep.cell[sweep.order[pos + 1]].left_edge != e_out)
          throw std::logic_error("boustrophedon_cells: bad merge");
        const std::size_t b = sweep.order[pos + 1];
        const std::size_t left_edge = sweep.cell[a].left_edge,
                          right_edge = sweep.cell[b].right_edge;
        const Point2 l{x_at(edges[left_edge], y), y}, r{x_at(edges[right_edge], y), y};
        sweep.cell[a].left_chain.push_back(l);
        sweep.cell[a].right_chain.push_back(v.p);
        sweep.cell[b].left_chain.push_back(v.p);
        sweep.cell[b].right_chain.push_back(r);
        close_piece(sweep.cell[a], pieces);
        close_piece(sweep.cell[b], pieces);
        sweep.shut(b);
        sweep.reopen(a, left_edge, right_edge, l, r);
      }
    } else if (p_below) {  // regular on a right side: p -> v -> q both run up
      const std::size_t c = sweep.right_cell(e_in);
      sweep.cell[c].right_chain.push_back(v.p);
      sweep.set_right(c, e_out);
    } else {  // regular on a left side: p -> v -> q both run down
      const std::size_t c = sweep.left_cell(e_out);
      sweep.cell[c].left_chain.push_back(v.p);
      sweep.set_left(c, e_in);
    }
  }

  Decomposition d;
  const Turn back(angle_deg);
  d.pieces.reserve(pieces.size());
  for (std::size_t k = 0; k < pieces.size(); ++k)
    d.pieces.push_back(chains_ring(pieces, std::span<const std::size_t>(&k, 1), back));
  for (const std::vector<std::size_t>& chain : merge_across_cuts(pieces)) {
    // A cell of one piece is that piece's ring: chains_ring() of the same chains (a copy).
    Ring ring = chain.size() == 1 ? d.pieces[chain.front()] : chains_ring(pieces, chain, back);
    if (ring.empty()) continue;
    d.cells.push_back(chain);
    d.cell_rings.push_back(std::move(ring));
  }
  for (Chains& piece : pieces) {
    chain_pool().give(piece.left);
    chain_pool().give(piece.right);
  }
  return d;
}

}  // namespace swath::geometry
