// VisibilityRouter's search (path()): A* over the reflex corners, with the legs' visibility
// tested as the search takes them (visibility.cpp holds the tests, the fans and the tables).
#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "swath/geometry/capped_heap.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/geometry/visibility.hpp"
#include "visibility_tables.hpp"

namespace swath::geometry {

template <class F>
void VisibilityRouter::onward(std::size_t v, Sides in, Point2 lo, Point2 hi, F&& f) const {
  // Cells from the corner's outwards (the cells the cone meets are connected, as the cone's two
  // halves and the box are convex), each cell looked at once (its stamp).
  thread_local std::vector<std::uint64_t> stamps;
  thread_local std::uint64_t stamp = 0;
  thread_local std::vector<long> todo;
  const std::size_t cells = std::size_t(grid_.nx * grid_.ny);
  if (stamps.size() < cells) stamps.resize(cells, 0);
  ++stamp;
  const Point2 c = nodes_[v];
  const Bowtie& cone = bowties_[v];
  const double cell = grid_.cell_m;
  const long cx = std::clamp(long((c.x - grid_.x0) / cell), 0L, grid_.nx - 1);
  const long cy = std::clamp(long((c.y - grid_.y0) / cell), 0L, grid_.ny - 1);
  const long bx0 = std::max(0L, long(std::floor((lo.x - grid_.x0) / cell)) - 1),
             bx1 = std::min(grid_.nx - 1, long(std::floor((hi.x - grid_.x0) / cell)) + 1),
             by0 = std::max(0L, long(std::floor((lo.y - grid_.y0) / cell)) - 1),
             by1 = std::min(grid_.ny - 1, long(std::floor((hi.y - grid_.y0) / cell)) + 1);
  // Rounding of the products below is ~1e-16 of the extent; slack far above it.
  const double slack = 1e-9 * (1 + extent_m_);
  const bool everywhere = !(cone.spread < 1e12);
  // The half along +axis takes the turns to the side the edges lie on of +axis; the other half
  // the others.
  const bool plus = cone.axis_left ? in.left : in.right,
             minus = cone.axis_left ? in.right : in.left;
  const auto meets = [&](long x, long y) {
    if (everywhere || (std::abs(x - cx) <= 1 && std::abs(y - cy) <= 1)) return true;
    // The cone's half along +axis is the points with t along - across >= 0 and t along + across
    // >= 0, the other half with -t along -+ across >= 0: a cell misses a half when all its
    // corners break one of its two conditions.
    double m[4] = {-INFINITY, -INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < 4; ++k) {
      const Point2 q =
          Point2{grid_.x0 + cell * double(x + (k & 1)), grid_.y0 + cell * double(y + (k >> 1))} - c;
      const double along = cone.spread * dot(q, cone.axis), across = dot(q, cone.across);
      m[0] = std::max(m[0], along - across), m[1] = std::max(m[1], along + across);
      m[2] = std::max(m[2], -along - across), m[3] = std::max(m[3], -along + across);
    }
    return (plus && m[0] >= -slack && m[1] >= -slack) ||
           (minus && m[2] >= -slack && m[3] >= -slack);
  };
  todo.assign({cy * grid_.nx + cx});
  stamps[std::size_t(todo.back())] = stamp;
  while (!todo.empty()) {
    const long k = todo.back();
    todo.pop_back();
    const long x = k % grid_.nx, y = k / grid_.nx;
    const bool round_corner = std::abs(x - cx) <= 1 && std::abs(y - cy) <= 1;
    for (std::uint32_t i = grid_.start[std::size_t(k)]; i < grid_.start[std::size_t(k) + 1]; ++i) {
      const std::uint32_t u = grid_.items[i];
      if (!round_corner && !everywhere) {
        const Point2 q = nodes_[u] - c;
        const double along = cone.spread * dot(q, cone.axis),
                     across = std::abs(dot(q, cone.across));
        if (!(plus && across <= along + slack) && !(minus && across <= -along + slack)) continue;
      }
      f(std::size_t(u));
    }
    for (const auto& [dx, dy] : {std::pair{1L, 0L}, {-1L, 0L}, {0L, 1L}, {0L, -1L}}) {
      const long nx = x + dx, ny = y + dy;
      if (nx < bx0 || nx > bx1 || ny < by0 || ny > by1) continue;
      std::uint64_t& seen = stamps[std::size_t(ny * grid_.nx + nx)];
      if (seen == stamp || !meets(nx, ny)) continue;
      seen = stamp;
      todo.push_back(ny * grid_.nx + nx);
    }
  }
}

// A shortest path bends at a corner only round it: near the corner, the corner's obstacle (between
// its two edges, an angle below pi) lies on the inner side of both legs. Were it otherwise, two
// points on the legs near the corner would see each other (the triangle they make with the corner
// holds none of the obstacle) and the path would not be shortest. So the edges, towards the ring
// neighbours before and after the corner, lie left of (or on) both directed legs when the path
// turns left, right when it turns right. A path straight on (or back: never shortest, harmless)
// passes.
VisibilityRouter::Sides VisibilityRouter::corner_sides(Point2 p, Point2 c, std::size_t v) const {
  // An end of a leg computed on an edge lies a rounding error to either side of it, and the leg
  // still counts as inside (visible()): an edge within an angle of ~4 tolerance / (the shorter of
  // the leg and the edge) of the leg's line counts as on it. Too many legs kept only costs time.
  // Without the wedge a simple area has at each corner (rings that cross or touch), or for a leg
  // from within a millionth of the area's size of the corner (its direction is rounding), any.
  if (!prune_ || distance(p, c) <= 1e-6 * (1 + extent_m_)) return {true, true};
  const auto side = [&](Point2 x) {
    const Orientation o = orientation(p, c, x);
    if (o == Orientation::collinear) return o;
    const Point2 leg = p - c, edge = x - c;
    const double slack =
        4 * tolerance_ * std::max(std::hypot(leg.x, leg.y), std::hypot(edge.x, edge.y));
    return std::abs(cross(leg, edge)) <= slack ? Orientation::collinear : o;
  };
  const Orientation o1 = side(before_[v]), o2 = side(after_[v]);
  return {o1 != Orientation::clockwise && o2 != Orientation::clockwise,
          o1 != Orientation::counter_clockwise && o2 != Orientation::counter_clockwise};
}

bool VisibilityRouter::taut(Sides in, Point2 p, std::size_t v, Point2 q) const {
  if (!prune_) return true;
  const Point2 c = nodes_[v];
  const Orientation turn = orientation(p, c, q);
  if (turn == Orientation::collinear) return true;
  const bool left = turn == Orientation::counter_clockwise;
  if (!(left ? in.left : in.right)) return false;
  const Sides out = corner_sides(c, q, v);
  return left ? out.left : out.right;
}

namespace {

// A candidate of path()'s search, ordered as the search takes them (see there).
// Ordered by (f, to_b, g, from_node, from_g, from, node); laid out in 40 bytes (the queue moves
// millions of them a plan) and compared inline, field by field as a defaulted <=> would.
struct SearchItem {
  SearchItem() = default;
  SearchItem(double f_, int to_b_, double g_, int from_node_, double from_g_, std::size_t from_,
             std::size_t node_)
      : f(f_),
        g(g_),
        from_g(from_g_),
        from(std::uint32_t(from_)),
        node(std::uint32_t(node_)),
        to_b(std::uint8_t(to_b_)),
        from_node(std::uint8_t(from_node_)) {}
  double f = 0;
  double g = 0;
  double from_g = 0;
  std::uint32_t from = 0;
  std::uint32_t node = 0;
  std::uint8_t to_b = 0;       ///< 0: a leg to `node`, 1: the way to b through `node`
  std::uint8_t from_node = 0;  ///< 0: straight from a, 1: from `from` (settled at `from_g`)
  friend bool operator<(const SearchItem& x, const SearchItem& y) {
    if (x.f != y.f) return x.f < y.f;
    if (x.to_b != y.to_b) return x.to_b < y.to_b;
    if (x.g != y.g) return x.g < y.g;
    if (x.from_node != y.from_node) return x.from_node < y.from_node;
    if (x.from_g != y.from_g) return x.from_g < y.from_g;
    if (x.from != y.from) return x.from < y.from;
    return x.node < y.node;
  }
  friend bool operator>(const SearchItem& x, const SearchItem& y) { return y < x; }
};

// The queue's lead key: candidates of different f are ordered by f alone (never NaN: a candidate
// is queued only when its f is at most the limit).
struct ByF {
  double operator()(const SearchItem& item) const { return item.f; }
};

// Per node of a search: the least candidate queued whose leg is known to be seen. Taken, it
// settles the node (if none before it has), so a candidate after it is never used: path() does
// not queue it (most of a long search's queue, once the tables know the corners near its path).
struct Settlers {
  std::vector<SearchItem> item;
  std::vector<char> has;
  void reset(std::size_t n) {
    item.resize(n);
    has.assign(n, 0);
  }
  /// Whether `c` comes after its node's settler: the node is settled before `c` is taken.
  bool after(const SearchItem& c) const { return has[c.node] && item[c.node] < c; }
  /// `c`, whose leg is known to be seen, as its node's settler unless it comes after it.
  void offer(const SearchItem& c) {
    if (after(c)) return;
    item[c.node] = c;
    has[c.node] = 1;
  }
};

// The path a, the nodes back from `last` along `previous` (nodes.size(): straight from a), b.
std::vector<Point2> route_back(Point2 a, Point2 b, std::size_t last,
                               const std::vector<std::size_t>& previous,
                               const std::vector<Point2>& nodes) {
  std::vector<Point2> route{b};
  for (std::size_t v = last; v != nodes.size(); v = previous[v]) route.push_back(nodes[v]);
  route.push_back(a);
  std::reverse(route.begin(), route.end());
  return route;
}

}  // namespace

// The answer is a shortest path through the graph of corners (its length is the one a full
// Dijkstra search over the whole graph gives, written out in
// tests/geometry/visibility_search_test.cpp). A shortest path bends only round its corners
// (taut()), so the search goes on from a node only along such legs: at the nearly flat corners
// of a traced outline, a narrow fan of them. Between paths of equal length (up to rounding) it
// may pick another than the full search. A* finds it while settling only the nodes towards b,
// and testing only the legs it takes:
// - Candidates are taken in order of f = g + h, h = (1 - 1e-6) |node b|: a predecessor u of v on
//   a shortest path is then settled strictly before v (h(u) <= (1 - 1e-6) w(u, v) + h(v): f
//   grows by at least 1e-6 w(u, v) along an edge, far above rounding), and every candidate for
//   v of that length is in the queue before v's first is taken.
// - A candidate is a leg to a node not yet settled: straight from a, or from a settled node u
//   (g = distance(u) + |u v|); its leg is tested when it is taken, and the first seen settles
//   the node. Of equal g, the straight leg comes first, then the one from the least (distance,
//   index): the node Dijkstra's search settled first, whose candidate it kept.
// - The way to b through node v is a candidate of f = distance(v) + |v b| (the sum the full
//   search compares), taken after nodes' candidates of equal f: once one b sees is taken, no
//   node still to settle can end lower (its f is a lower bound of its sum, and strictly above)
//   nor equal with a lower index (those come first, by index).
// One run of path()'s search from a to b under `limit` (and under `bound`, an upper bound of the
// answer's f once one is known), on buffers of the thread's, reused from search to search.
struct VisibilityRouter::Search {
  static constexpr double kShrink = 1 - 1e-6;
  // Nodes by kGroup consecutive indices (a ring's corners in order: near each other): the box of
  // a group's near nodes bounds the f of every leg into them from below, so a settled node skips
  // a group whose legs all lie above the cut (most legs above it, on traced outlines) without
  // measuring each.
  static constexpr std::size_t kGroup = 8;
  struct Group {
    Point2 lo, hi;   // the box of the group's near nodes
    double h_least;  // (1 - 1e-6) times the box's distance from b: at most any of their h
  };
  static constexpr std::uint64_t kGroupBits = (std::uint64_t{1} << kGroup) - 1;
  // The open legs from settled node v into one group that its bound left out: `bits` of word
  // `word` of `open`.
  struct Skipped {
    std::uint32_t v, word;
    std::uint64_t bits;
  };
  struct Buffers {
    std::vector<double> h;              // per node of `near`: (1 - 1e-6) |node b|
    std::vector<std::size_t> previous;  // n: straight from a
    std::vector<char> settled;
    std::vector<char> is_near;          // per node: near (a candidate under the limit can reach it)
    CappedHeap<SearchItem, ByF> queue;  // a search takes ~1 candidate in 10 it queues
    Settlers settlers;
    std::vector<std::uint64_t> open;           // per node (a bit): in `near` and not settled
    std::size_t first_word = 0, end_word = 0;  // the words of `open` that hold near nodes
    std::vector<double> g_of;                  // per node settled: its g
    std::vector<std::uint32_t> settled_list;   // the nodes settled, in order
    std::vector<Group> groups;                 // per kGroup nodes holding a near node
    std::vector<Skipped> skipped;              // the legs left out by their group's bound
  };
  static Buffers& buffers() {
    thread_local Buffers b;
    return b;
  }

  const VisibilityRouter& r;
  Point2 a, b;
  std::size_t n;
  Row& from_a;
  Row& to_b;
  Buffers& x = buffers();
  double limit = 0;
  double bound = std::numeric_limits<double>::infinity();
  double beyond = std::numeric_limits<double>::infinity();  // least f left out
  bool left_out = false;
  bool use_groups = true;  // false: every leg measured (tests: search_run())
  Point2 box_lo{}, box_hi{};

  Search(const VisibilityRouter& router, Point2 from, Point2 to, Row& row_a, Row& row_b)
      : r(router), a(from), b(to), n(router.nodes_.size()), from_a(row_a), to_b(row_b) {
    x.h.resize(n);
    x.g_of.resize(n);
  }

  // Without pruning, a node's settler (its least candidate known seen) settles it at or before
  // it (at no greater g), and the node then queues its way to b at no greater f (rounding is
  // monotone): an upper bound of the answer's f where b is known to see the node.
  void bound_by_settler(const SearchItem& settler) {
    if (r.prune_ || to_b.seen[settler.node] != 1) return;
    const double f = settler.g + distance(r.nodes_[settler.node], b);
    if (f <= limit) bound = std::min(bound, f);
  }

  void push(const SearchItem& item) {
    if (!(item.f <= std::min(limit, bound))) {
      beyond = std::min(beyond, item.f);
      return;
    }
    x.queue.push(item);
  }

  // A run's start: the nodes its candidates can reach (`near`), each with its straight leg from a
  // queued where not known hidden. A node u whose |a u| + h(u) is above the limit has every
  // candidate above it (its g is at least |a u|): left out of the search. Such a node lies
  // farther than limit / (2 (1 - 1e-6)) from the middle of a b (|a u| + |u b| is at least twice
  // that distance): only the nodes within that of it in x (by search in the nodes sorted by x)
  // and in y are asked. With a first bound, nodes whose straight f (a lower bound of their
  // candidates', up to rounding) is above it are left out too.
  void start(double run_limit, double first) {
    limit = run_limit;
    bound = first;
    beyond = std::numeric_limits<double>::infinity();
    const double near_cut = bound * (1 + 1e-9) + r.tolerance_;
    x.settled_list.clear();
    x.previous.assign(n, n);
    x.settled.assign(n, 0);
    x.is_near.assign(n, 0);
    x.settlers.reset(n);
    x.queue.clear({-std::numeric_limits<double>::infinity(), 0, 0.0, 0, 0.0, 0, 0});
    // The near nodes as bits of `open` (in the order of their indices, without a sort), and the
    // least and greatest of them.
    x.open.assign((n + 63) / 64, 0);
    std::size_t least_near = n, most_near = 0;
    const Point2 middle = (a + b) * 0.5;
    const double reach = limit / (2 * kShrink) * (1 + 1e-9) + r.tolerance_;
    box_lo = middle - Point2{reach, reach};
    box_hi = middle + Point2{reach, reach};
    const auto by_x = [this](std::uint32_t u, double at) { return r.nodes_[u].x < at; };
    const auto first_x =
        std::lower_bound(r.nodes_by_x_.begin(), r.nodes_by_x_.end(), middle.x - reach, by_x);
    const auto end_x = std::lower_bound(first_x, r.nodes_by_x_.end(), middle.x + reach, by_x);
    left_out = end_x - first_x < std::ptrdiff_t(n);
    for (auto it = first_x; it != end_x; ++it) {
      const std::size_t u = *it;
      if (std::abs(r.nodes_[u].y - middle.y) > reach) {
        left_out = true;
        continue;
      }
      x.h[u] = kShrink * distance(r.nodes_[u], b);
      const double d = distance(a, r.nodes_[u]), f = d + x.h[u];
      if (!(f <= limit)) {
        beyond = std::min(beyond, f);
        continue;
      }
      if (f > near_cut) {  // never taken (the search ends with an answer: `beyond` unused)
        left_out = true;
        continue;
      }
      x.open[u / 64] |= std::uint64_t{1} << (u % 64);
      least_near = std::min(least_near, u);
      most_near = std::max(most_near, u);
      x.is_near[u] = 1;
      const SearchItem straight{f, 0, d, 0, 0.0, n, u};
      if (from_a.seen[u] != 0) x.queue.push(straight);  // not known hidden
      if (from_a.seen[u] == 1) {                        // the only one from a for u
        x.settlers.offer(straight);
        bound_by_settler(straight);
      }
    }
    x.first_word = least_near < n ? least_near / 64 : 0;
    x.end_word = least_near < n ? most_near / 64 + 1 : 0;
    x.skipped.clear();
    if (r.prune_) return;  // go_on_pruned() asks no group
    x.groups.resize((n + kGroup - 1) / kGroup);
    if (!use_groups) {  // boxes of the whole plane: a bound of g, never above the cut
      constexpr double inf = std::numeric_limits<double>::infinity();
      std::fill(x.groups.begin(), x.groups.end(), Group{{-inf, -inf}, {inf, inf}, 0.0});
      return;
    }
    for (std::size_t w = x.first_word; w < x.end_word; ++w)
      for (std::uint64_t open = x.open[w]; open;) {
        const std::size_t q = std::size_t(std::countr_zero(open)) / kGroup;
        std::uint64_t bits = open & (kGroupBits << (q * kGroup));
        open &= ~bits;
        Point2 lo = r.nodes_[w * 64 + std::size_t(std::countr_zero(bits))], hi = lo;
        for (bits &= bits - 1; bits; bits &= bits - 1) {
          const Point2 p = r.nodes_[w * 64 + std::size_t(std::countr_zero(bits))];
          lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
          hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
        }
        x.groups[w * (64 / kGroup) + q] = {lo, hi, kShrink * distance_to_box(b, lo, hi)};
      }
  }

  // The candidates in order up to the first way to b that b sees: its node, or n (none).
  std::size_t run() {
    while (!x.queue.empty()) {
      const SearchItem item = x.queue.pop();
      const std::size_t v = item.node;
      if (item.to_b) {
        if (r.sees(b, to_b, v)) return v;
        continue;
      }
      if (x.settled[v]) continue;
      const std::size_t from = item.from;
      if (item.from_node ? !r.nodes_see(std::min(from, v), std::max(from, v))
                         : !r.sees(a, from_a, v))
        continue;
      settle(item);
    }
    fold_skipped();
    return n;
  }

  // A run without an answer: its `beyond` as though every leg its groups' bounds left out had
  // been measured (path() reads it only then), each f summed as go_on_to_every_open_node() sums
  // it (the least of the same values, in any order: none is NaN or 0).
  void fold_skipped() {
    for (const Skipped& skip : x.skipped) {
      const Point2 c = r.nodes_[skip.v];
      const double g = x.g_of[skip.v];
      for (std::uint64_t bits = skip.bits; bits; bits &= bits - 1) {
        const std::size_t u = skip.word * std::size_t{64} + std::size_t(std::countr_zero(bits));
        const double through = g + distance(c, r.nodes_[u]), f = through + x.h[u];
        beyond = std::min(beyond, f);
      }
    }
  }

  // Node v settled by `item`, and its ways on: to b, and to the open nodes.
  void settle(const SearchItem& item) {
    const std::size_t v = item.node, from = item.from;
    x.settled[v] = 1;
    x.g_of[v] = item.g;
    x.settled_list.push_back(std::uint32_t(v));
    x.open[v / 64] &= ~(std::uint64_t{1} << (v % 64));
    x.previous[v] = item.from_node ? from : n;
    // Paths on from v bend there, round its corner only (taut()): where the corner's edges lie on
    // both sides of the leg in, none goes on.
    const Point2 in_from = item.from_node ? r.nodes_[from] : a;
    const Sides in = r.corner_sides(in_from, r.nodes_[v], v);
    if (!in.left && !in.right) return;
    if (to_b.seen[v] != 0 && r.taut(in, in_from, v, b)) {
      const double f = item.g + distance(r.nodes_[v], b);
      push({f, 1, 0.0, 0, 0.0, 0, v});
      if (to_b.seen[v] == 1 && f <= limit) bound = std::min(bound, f);
    }
    if (r.prune_)
      go_on_pruned(item, in, in_from);
    else
      go_on_to_every_open_node(item);
  }

  // The leg from v (settled at g) on to open node u, not known hidden (`seen`: 1 seen, kUnknown
  // not tested yet), of f under the cut (the bound may have come down since the cut was taken).
  void queue_leg(double g, std::size_t v, std::size_t u, signed char seen, double through,
                 double f) {
    if (f > bound) return;
    const SearchItem next{f, 0, through, 1, g, v, u};
    if (x.settlers.after(next)) return;
    if (seen == 1) {
      x.settlers.offer(next);
      bound_by_settler(next);
    }
    x.queue.push(next);
  }

  void go_on_pruned(const SearchItem& item, Sides in, Point2 in_from) {
    const std::size_t v = item.node;
    r.onward(v, in, box_lo, box_hi, [&](std::size_t u) {
      if (!x.is_near[u] || x.settled[u]) return;
      const signed char seen = r.nodes_known(v, u);
      if (seen == 0 || !r.taut(in, in_from, v, r.nodes_[u])) return;
      const double through = item.g + distance(r.nodes_[std::min(u, v)], r.nodes_[std::max(u, v)]);
      const double f = through + x.h[u];
      if (!(f <= std::min(limit, bound))) {  // as push() does
        beyond = std::min(beyond, f);
        return;
      }
      queue_leg(item.g, v, u, seen, through, f);
    });
  }

  // Every open node (near, not settled) not known hidden from v, whose leg's f is under the cut
  // (taken once: the bound may come down as legs are queued, as queue_leg() checks). The nodes
  // known hidden (about half of the open ones) are skipped by their bits, 64 at a time: their
  // legs would not be queued, so the search takes the same candidates. `beyond` then holds the
  // least f of the other legs above the cut: a hidden leg is never a candidate, at any limit, so
  // the least f left out is still a lower bound of every candidate left out (path() only needs
  // that: a higher next limit, and no candidate left when it is infinite). Each leg's through and
  // f are g + distance() and that + h, as the full search sums them. The legs into a group whose
  // bound is above the cut are left out together (about 8 in 10 legs above the cut on traced
  // outlines, few nodes a group), their f folded into `beyond` only after a run without an answer,
  // the one run path() reads it after (fold_skipped()).
  void go_on_to_every_open_node(const SearchItem& item) {
    const std::size_t v = item.node;
    const Point2 c = r.nodes_[v];
    const double cut = std::min(limit, bound);
    const NodeTables& tables = *r.node_tables_;
    const NodeTables::Chunk* chunk = nullptr;
    const NodeTables::Bits* hidden = nullptr;
    std::size_t chunk_at = std::numeric_limits<std::size_t>::max();
    // The arrays the loop reads, and the least f left out, held here: through members, each would
    // be loaded again after every leg queued (queue_leg() writes the search's state), and `beyond`
    // stored for every leg above the cut (about half the legs). queue_leg() reads none of them.
    const Point2* nodes = r.nodes_.data();
    const double* h = x.h.data();
    const std::uint64_t* open_words = x.open.data();
    const double g = item.g;
    double least_out = beyond;
    for (std::size_t w = x.first_word; w < x.end_word; ++w) {
      const std::size_t at = w / NodeTables::kWords;
      if (at != chunk_at) {
        chunk = tables.chunk_of(v, chunk_at = at);
        hidden = tables.hidden_of(v, at);
      }
      std::uint64_t open = open_words[w];
      if (hidden && open) open &= ~hidden[w % NodeTables::kWords].load(std::memory_order_relaxed);
      while (open) {
        // The open nodes group by group, each in index order: the legs in the same order.
        const std::size_t q = std::size_t(std::countr_zero(open)) / kGroup;
        const std::uint64_t in_group = open & (kGroupBits << (q * kGroup));
        open &= ~in_group;
        if (in_group & (in_group - 1)) {  // two or more: the bound first
          const Group& group = x.groups[w * (64 / kGroup) + q];
          const double least = g + distance_to_box(c, group.lo, group.hi) + group.h_least;
          // Never above a leg's f, bit for bit: distance_to_box() is distance()'s formula on
          // differences no greater (rounding is monotone: subtraction, squares, the sum, sqrt;
          // -ffp-contract=off), h_least the same of b's, and both sums are added in the same
          // order. The margin only guards against a later change to either formula.
          if (use_groups && least * (1 - 1e-12) > cut) {
            x.skipped.push_back({std::uint32_t(v), std::uint32_t(w), in_group});
            continue;
          }
        }
        for (std::uint64_t bits = in_group; bits; bits &= bits - 1) {
          const std::size_t u = w * 64 + std::size_t(std::countr_zero(bits));
          const double through = g + distance(c, nodes[u]), f = through + h[u];
          if (!(f <= cut)) {
            least_out = std::min(least_out, f);
            continue;
          }
          const signed char seen =
              chunk ? chunk[u % NodeTables::kChunk].load(std::memory_order_relaxed) : kUnknown;
          if (seen != 0) queue_leg(g, v, u, seen, through, f);
        }
      }
    }
    beyond = least_out;
  }
};

// A node v that b sees, settled by an earlier search from a at g, settles at the same g here (up
// to rounding) and then queues its way to b at g + |v b| (computed so), unless the search ends
// before. Without pruning only (with it, that way is queued only when it turns round v's corner,
// which depends on how v was reached). Whether b sees them is asked in order of that sum, up to
// the first seen: the search asks the same of each one whose sum is below its answer's (their
// ways to b are taken before the answer), so at most the last question is one it would not have
// asked. A bound a rounding below the answer's f costs a run, not the answer: the bounded run
// then finds no way to b (any it took would have been taken before the answer without the
// bound) and the next, at a higher limit, has none.
double VisibilityRouter::first_bound(const Row& from_a, Row& to_b, Point2 b, double limit) const {
  if (prune_ || from_a.reached.empty()) return std::numeric_limits<double>::infinity();
  thread_local std::vector<std::pair<double, std::uint32_t>> ways;
  ways.clear();
  for (const auto& [v, g] : from_a.reached) {
    const double f = g + distance(nodes_[v], b);
    if (to_b.seen[v] != 0 && f <= limit * (1 - 1e-9)) ways.push_back({f, v});
  }
  std::sort(ways.begin(), ways.end());
  for (const auto& [f, v] : ways)
    if (sees(b, to_b, v)) return f;
  return std::numeric_limits<double>::infinity();
}

void VisibilityRouter::remember_reached(Row& from_a, const std::vector<std::uint32_t>& settled,
                                        const std::vector<double>& g_of) {
  // Each node once: the nodes already kept marked on a scratch of the thread's.
  thread_local std::vector<char> kept;
  for (const auto& [v, g] : from_a.reached) {
    if (kept.size() <= v) kept.resize(std::size_t(v) + 1, 0);
    kept[v] = 1;
  }
  for (const std::uint32_t v : settled) {
    if (kept.size() <= v) kept.resize(std::size_t(v) + 1, 0);
    if (kept[v]) continue;
    kept[v] = 1;
    from_a.reached.push_back({v, g_of[v]});
  }
  for (const auto& [v, g] : from_a.reached) kept[v] = 0;
}

VisibilityRouter::SearchRun VisibilityRouter::search_run(Point2 a, Point2 b, double limit,
                                                         bool groups) const {
  Row& from_a = seen_row(a);
  Row& to_b = seen_row(b);
  Search search(*this, a, b, from_a, to_b);
  search.use_groups = groups;
  search.start(limit, std::numeric_limits<double>::infinity());
  const std::size_t last = search.run();
  return {last != nodes_.size(), last, search.beyond, search.left_out};
}

std::vector<Point2> VisibilityRouter::path(Point2 a, Point2 b) const {
  if (!routing_) return {a, b};
  // Through a's fan where a has one (a run end asked about often, home): the same exact tests
  // on the same edges, without walking the grid along the leg. Only towards b within the area's
  // extent, as the fan's margins assume (see outside_fraction()).
  const auto known_a = sees_.find({a.x, a.y});
  const Fan* fan = known_a != sees_.end() && std::max(std::abs(b.x), std::abs(b.y)) <= extent_m_
                       ? known_a->second.fan.get()
                       : nullptr;
  if (visible_with(a, b, fan)) return {a, b};
  const std::size_t n = nodes_.size();
  Row& from_a = seen_row(a);
  Row& to_b = seen_row(b);
  // An end known to see no node at all (outside the area, home beyond the field): no path.
  if ((from_a.known == n && from_a.visible == 0) || (to_b.known == n && to_b.visible == 0))
    return {a, b};
  // The search takes candidates in order of f up to the answer's; those above a limit are not
  // queued. A search that ends without reaching b under the limit is run again with a higher
  // one: the candidates taken up to the answer, and so the answer, are those of a search without
  // a limit. The first limit: 1.25 times the straight leg (most transits bend round one
  // obstacle); each further one at least twice that. The first run also starts with the first
  // bound (first_bound()), when it lies below the limit by far more than rounding: the nodes on
  // its way from a then have their f, and their straight f from a, under the limit too, so they
  // are in the search. With a bound the search ends with an answer, or (a bound a rounding too
  // low) with none and is run again without it.
  double limit = 1.25 * distance(a, b) + tolerance_;
  const double first = first_bound(from_a, to_b, b, limit);
  Search search(*this, a, b, from_a, to_b);
  std::size_t last = n;
  for (bool found = false, first_run = true; !found; first_run = false) {
    search.start(limit, first_run && first <= limit * (1 - 1e-9)
                            ? first
                            : std::numeric_limits<double>::infinity());
    last = search.run();
    // Done: b reached, or every candidate taken (no inside path).
    const double beyond = search.beyond;
    found = last != n || (!search.left_out && beyond == std::numeric_limits<double>::infinity());
    limit = std::max(2 * limit, beyond == std::numeric_limits<double>::infinity() ? 0 : beyond);
  }
  if (last == n) return {a, b};  // no inside path (separate pieces): straight
  // The last run took its candidates in the order of a search without a limit: its nodes are
  // settled at Dijkstra's distances from a.
  if (!prune_) remember_reached(from_a, search.x.settled_list, search.x.g_of);
  return route_back(a, b, last, search.x.previous, nodes_);
}

}  // namespace swath::geometry
