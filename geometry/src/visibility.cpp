#include "swath/geometry/visibility.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>

#include "swath/geometry/predicates.hpp"

namespace swath::geometry {
namespace {

// Whether p and q lie strictly on one side of the line through a along d = b - a, certainly: the
// double cross products decide where they exceed their rounding bound (each of the four
// differences, two products and the subtraction round by at most 2^-53 relative: 1e-15 of the
// products' sum is well above it), else no answer (false). A filter before segments_intersect,
// which such an edge cannot meet; inline, as visibility asks it ~10^6 times a plan.
bool strictly_one_side(Point2 a, Point2 d, Point2 p, Point2 q) {
  const double p1 = d.x * (p.y - a.y), p2 = d.y * (p.x - a.x);
  const double q1 = d.x * (q.y - a.y), q2 = d.y * (q.x - a.x);
  const double sp = p1 - p2, sq = q1 - q2;
  const double bp = 1e-15 * (std::abs(p1) + std::abs(p2)),
               bq = 1e-15 * (std::abs(q1) + std::abs(q2));
  return (sp > bp && sq > bq) || (sp < -bp && sq < -bq);
}

}  // namespace

double polyline_length(const std::vector<Point2>& points) {
  double length = 0;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) length += distance(points[i], points[i + 1]);
  return length;
}

bool VisibilityRouter::inside_closed(Point2 p) const {
  // locate_point() over every ring, on the edges the ray right of p may meet only (the others
  // neither hold p nor cross the ray): on an edge is inside, else an odd number of crossings.
  bool on_edge = false, odd = false;
  edges_.near_ray_right(p, [&](std::uint32_t e) {
    const Segment& s = edges_.segments()[e];
    const EdgeAndRay where = edge_and_ray(p, s.a, s.b);
    on_edge |= where == EdgeAndRay::p_on_edge;
    odd ^= where == EdgeAndRay::crosses;
  });
  if (on_edge || odd) return true;
  // Within rounding of the boundary counts as on it: legs between two boundary points run along
  // an edge, a hair to either side of it. The box asked for is twice the tolerance: an edge whose
  // computed distance is within it has a point in the box despite rounding.
  const Point2 reach{2 * tolerance_, 2 * tolerance_};
  bool near = false;
  edges_.near_box(p - reach, p + reach, [&](std::uint32_t e) {
    const Box& b = edge_boxes_[e];
    if (near || p.x < b.x0 - tolerance_ || p.x > b.x1 + tolerance_ || p.y < b.y0 - tolerance_ ||
        p.y > b.y1 + tolerance_)
      return;
    const Point2 a = edges_.segments()[e].a, d = edges_.segments()[e].b - a;
    const double t = std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0);
    near = distance(p, a + d * t) <= tolerance_;
  });
  return near;
}

// The direction of (dx, dy) != 0 as a "diamond angle" in [0, 4): 0 along +x, 1 along +y, 2
// along -x, 3 along -y, increasing counter-clockwise, and the opposite direction 2 further round.
// A monotone stand-in for atan2 at a few instructions (fans take two per edge): arcs below pi
// are arcs below 2. Its rounding is of the order of atan2's.
static double diamond(double dx, double dy) {
  if (dy >= 0) return dx >= 0 ? dy / (dx + dy) : 1 - dx / (dy - dx);
  return dx < 0 ? 2 - dy / (-dx - dy) : 3 + dx / (dx - dy);
}

long VisibilityRouter::fan_bin(double diamond_angle) const {
  // Monotone in the angle (rounding included), so an angle within a range lands in a bin
  // between the bins of the range's ends.
  return long(std::floor(diamond_angle * bins_per_unit_));
}

VisibilityRouter::Fan VisibilityRouter::fan_of(Point2 a) const {
  // An edge that does not hold a is seen from it within an arc of directions below pi (below 2
  // in diamond angle): the directions of its ends and the shorter way between them. Legs from a
  // through any of its points run in a direction of that arc. The computed directions are off by
  // less than ~1e-9 for points at least near_m from a (differences of coordinates round by ~1e-16
  // of the larger of the area's and a's extent, near_m is 1e-6 of it); each arc is widened by
  // 1e-7. An edge nearer than near_m is asked for every leg.
  constexpr double kMargin = 1e-7;
  const std::vector<Segment>& segments = edges_.segments();
  Fan fan;
  fan.near_m = 1e-6 * (1 + std::max({extent_m_, std::abs(a.x), std::abs(a.y)}));
  const long bins = long(fan_bins_);
  std::vector<std::pair<long, long>> range(segments.size(), {1, 0});
  std::vector<std::uint32_t> count(fan_bins_ + 1, 0);
  for (std::uint32_t e = 0; e < segments.size(); ++e) {
    const Point2 p = segments[e].a, q = segments[e].b;
    if (distance_to_segment(a, p, q) <= fan.near_m) {
      fan.near.push_back(e);
      continue;
    }
    const double tp = diamond(p.x - a.x, p.y - a.y), tq = diamond(q.x - a.x, q.y - a.y);
    double turn = tq - tp;
    if (turn > 2)
      turn -= 4;
    else if (turn < -2)
      turn += 4;
    const long lo = fan_bin(std::min(tp, tp + turn) - kMargin);
    const long hi = fan_bin(std::max(tp, tp + turn) + kMargin);
    range[e] = {lo, std::min(hi, lo + bins - 1)};
    for (long k = lo; k <= range[e].second; ++k)
      ++count[std::size_t(((k % bins) + bins) % bins) + 1];
  }
  for (std::size_t k = 0; k < fan_bins_; ++k) count[k + 1] += count[k];
  fan.start = count;
  fan.items.resize(count.back());
  for (std::uint32_t e = 0; e < segments.size(); ++e)
    for (long k = range[e].first; k <= range[e].second; ++k)
      fan.items[count[std::size_t(((k % bins) + bins) % bins)]++] = e;
  return fan;
}

double VisibilityRouter::outside_fraction(Point2 a, Point2 b, double stop_m, const Fan* fan) const {
  // Cut [a, b] where it meets the boundary; each piece is wholly inside or outside.
  const Point2 d = b - a;
  const double len2 = dot(d, d);
  if (len2 == 0) return 0.0;
  thread_local std::vector<double> cuts;
  cuts.assign({0.0, 1.0});
  const Box seg{std::min(a.x, b.x), std::min(a.y, b.y), std::max(a.x, b.x), std::max(a.y, b.y)};
  auto apart = [&](const Box& e) {
    return e.x0 > seg.x1 || e.x1 < seg.x0 || e.y0 > seg.y1 || e.y1 < seg.y0;
  };
  // Only the edges the index (or a's fan) finds near [a, b] can meet it, and only those that meet
  // it cut; the cuts are sorted, so the order the edges come in does not matter. An edge found
  // twice cuts twice at the same place: the piece between is empty and skipped, so the sum below
  // does not change.
  // An edge's end within rounding of [a, b]'s line cuts there too, whichever side of the line
  // rounding put it: a leg along a row of collinear edges (a comb's tooth tips) otherwise found
  // either no cut at a gap's corners or one from an intersection of two nearly parallel lines
  // (any parameter at all), and a leg across the gap's mouth was inside for some of its end
  // points and not for the next ones.
  const double off_line_limit = tolerance_ * std::sqrt(len2);
  const auto cut_by = [&](std::uint32_t e) {
    const Box& box = edge_boxes_[e];
    if (box.x0 > seg.x1 + tolerance_ || box.x1 < seg.x0 - tolerance_ ||
        box.y0 > seg.y1 + tolerance_ || box.y1 < seg.y0 - tolerance_)
      return;
    const Point2 p = edges_.segments()[e].a, q = edges_.segments()[e].b;
    const bool p_on = std::abs(cross(d, p - a)) <= off_line_limit,
               q_on = std::abs(cross(d, q - a)) <= off_line_limit;
    if (p_on) cuts.push_back(std::clamp(dot(p - a, d) / len2, 0.0, 1.0));
    if (q_on) cuts.push_back(std::clamp(dot(q - a, d) / len2, 0.0, 1.0));
    if (p_on && q_on) return;  // along the line: its ends are its cuts
    if (apart(box)) return;
    if (strictly_one_side(a, d, p, q) || !segments_intersect(a, b, p, q)) return;
    const double denom = cross(d, q - p);
    if (denom != 0) {
      cuts.push_back(std::clamp(cross(p - a, q - p) / denom, 0.0, 1.0));
    } else {  // collinear overlap: its ends are cuts
      cuts.push_back(std::clamp(dot(p - a, d) / len2, 0.0, 1.0));
      cuts.push_back(std::clamp(dot(q - a, d) / len2, 0.0, 1.0));
    }
  };
  // A fan is trusted for legs longer than twice its near_m, to points b within the area's extent
  // (the nodes): b's direction is then as accurate as the edges' (a shorter leg meets only edges
  // within its length of a, all in fan->near).
  if (fan && len2 > 4 * fan->near_m * fan->near_m) {
    const long bins = long(fan_bins_);
    const auto k = std::size_t(((fan_bin(diamond(d.x, d.y)) % bins) + bins) % bins);
    for (std::uint32_t i = fan->start[k]; i < fan->start[k + 1]; ++i) cut_by(fan->items[i]);
    for (const std::uint32_t e : fan->near) cut_by(e);
  } else {
    edges_.near_segment(a, b, cut_by);
  }
  std::sort(cuts.begin(), cuts.end());
  double outside = 0;
  const double length = std::sqrt(len2);
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    if (cuts[k + 1] <= cuts[k]) continue;
    if (!inside_closed(a + d * ((cuts[k] + cuts[k + 1]) / 2))) {
      outside += (cuts[k + 1] - cuts[k]);
      // The sum of non-negative terms only grows (rounding too): past stop_m it stays past.
      if (outside * length > stop_m) return outside;
    }
  }
  return outside;
}

double VisibilityRouter::length_outside(Point2 a, Point2 b) const {
  return outside_fraction(a, b, std::numeric_limits<double>::infinity()) *
         std::sqrt(dot(b - a, b - a));
}

Point2 VisibilityRouter::moved_out(Point2 before, Point2 corner, Point2 after,
                                   double allowance_m) const {
  if (!(allowance_m > 0)) return corner;
  const Point2 u = before - corner, v = after - corner;
  const double nu = std::hypot(u.x, u.y), nv = std::hypot(v.x, v.y);
  if (nu == 0 || nv == 0) return corner;
  // Away from the obstacle: against the sum of the two edge directions (the corner is reflex for
  // the area, so both edges bend towards the obstacle).
  Point2 out = (u * (1 / nu) + v * (1 / nv)) * -1.0;
  const double len = std::hypot(out.x, out.y);
  if (len < 1e-12) return corner;
  const Point2 moved = corner + out * (allowance_m / len);
  if (inside_closed(moved) && visible(moved, corner + u * 0.5) && visible(moved, corner + v * 0.5))
    return moved;
  return corner;
}

bool VisibilityRouter::visible(Point2 a, Point2 b) const {
  return visible_with(a, b, nullptr);
}

bool VisibilityRouter::visible_with(Point2 a, Point2 b, const Fan* fan) const {
  // Decided by the length outside, with a tolerance: end points computed on the boundary (line
  // ends, cut points) sit a rounding error off it, and must still see inwards. Counting stops
  // as soon as the tolerance is exceeded (most legs between far corners are blocked).
  const double limit_m = 1e-9 * (1 + distance(a, b));
  return outside_fraction(a, b, limit_m, fan) * std::sqrt(dot(b - a, b - a)) <= limit_m;
}

VisibilityRouter::VisibilityRouter(std::vector<Ring> rings, std::size_t max_nodes,
                                   double corner_allowance_m)
    : rings_(std::move(rings)) {
  double extent = 0;
  for (const Ring& ring : rings_)
    for (const Point2& p : ring) extent = std::max({extent, std::abs(p.x), std::abs(p.y)});
  tolerance_ = 1e-9 * (1 + extent);
  std::vector<Segment> edges;
  for (const Ring& ring : rings_)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point2 p = ring[i], q = ring[(i + 1) % ring.size()];
      edges.push_back({p, q});
      edge_boxes_.push_back(
          {std::min(p.x, q.x), std::min(p.y, q.y), std::max(p.x, q.x), std::max(p.y, q.y)});
    }
  edges_ = SegmentIndex(std::move(edges));
  for (const Ring& ring : rings_) {
    const std::size_t n = ring.size();
    for (std::size_t i = 0; i < n; ++i)
      if (orientation(ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]) == Orientation::clockwise)
        nodes_.push_back(
            moved_out(ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n], corner_allowance_m));
  }
  if (nodes_.size() > max_nodes) {
    routing_ = false;
    nodes_.clear();
    return;
  }
  nodes_by_x_.resize(nodes_.size());
  for (std::size_t u = 0; u < nodes_.size(); ++u) nodes_by_x_[u] = std::uint32_t(u);
  std::stable_sort(nodes_by_x_.begin(), nodes_by_x_.end(),
                   [this](std::uint32_t u, std::uint32_t v) { return nodes_[u].x < nodes_[v].x; });
  node_asked_.assign(nodes_.size(), 0);
  fan_bins_ = std::clamp<std::size_t>(edges_.segments().size(), 64, 1024);
  bins_per_unit_ = double(fan_bins_) / 4;
  extent_m_ = extent;
  node_tables_ = std::make_shared<NodeTables>(nodes_.size());
}

VisibilityRouter::~VisibilityRouter() = default;

std::unique_ptr<VisibilityRouter> VisibilityRouter::fresh_copy() const {
  std::unique_ptr<VisibilityRouter> copy(new VisibilityRouter);
  copy->rings_ = rings_;
  copy->edges_ = edges_;
  copy->edge_boxes_ = edge_boxes_;
  copy->nodes_ = nodes_;
  copy->nodes_by_x_ = nodes_by_x_;
  copy->routing_ = routing_;
  copy->tolerance_ = tolerance_;
  copy->fan_bins_ = fan_bins_;
  copy->bins_per_unit_ = bins_per_unit_;
  copy->extent_m_ = extent_m_;
  copy->node_asked_.assign(nodes_.size(), 0);
  copy->node_tables_ = node_tables_;
  return copy;
}

VisibilityRouter::Row& VisibilityRouter::seen_row(Point2 p) const {
  auto [it, added] = sees_.try_emplace({p.x, p.y});
  if (added) it->second.seen.assign(nodes_.size(), kUnknown);
  return it->second;
}

bool VisibilityRouter::sees(Point2 p, Row& row, std::size_t node) const {
  signed char& known = row.seen[node];
  if (known == kUnknown) {
    if (!row.fan && ++row.asked > kFanAfter) row.fan = std::make_unique<Fan>(fan_of(p));
    known = visible_with(p, nodes_[node], row.fan.get());
    ++row.known;
    row.visible += known != 0;
  }
  return known != 0;
}

// Threads that share the tables may test a pair at once: both find the same answer (the same exact
// tests, with or without a fan), so either store stands. A fan is published whole (release) and
// only the first one made is kept.
struct VisibilityRouter::NodeTables {
  explicit NodeTables(std::size_t n)
      : sees(new std::atomic<signed char>[n * n]), fans(new std::atomic<Fan*>[n]), nodes(n) {
    for (std::size_t k = 0; k < n * n; ++k) sees[k].store(kUnknown, std::memory_order_relaxed);
    for (std::size_t k = 0; k < n; ++k) fans[k].store(nullptr, std::memory_order_relaxed);
  }
  ~NodeTables() {
    for (std::size_t k = 0; k < nodes; ++k) delete fans[k].load(std::memory_order_acquire);
  }
  NodeTables(const NodeTables&) = delete;
  NodeTables& operator=(const NodeTables&) = delete;
  std::unique_ptr<std::atomic<signed char>[]> sees;  ///< nodes², kUnknown until asked
  std::unique_ptr<std::atomic<Fan*>[]> fans;         ///< per node, null until made
  std::size_t nodes;
};

bool VisibilityRouter::nodes_hidden(std::size_t i, std::size_t j) const {
  return node_tables_->sees[i * nodes_.size() + j].load(std::memory_order_relaxed) == 0;
}

bool VisibilityRouter::nodes_see(std::size_t i, std::size_t j) const {
  std::atomic<signed char>& known = node_tables_->sees[i * nodes_.size() + j];
  signed char answer = known.load(std::memory_order_relaxed);
  if (answer == kUnknown) {
    std::atomic<Fan*>& shared_fan = node_tables_->fans[i];
    Fan* fan = shared_fan.load(std::memory_order_acquire);
    if (!fan && ++node_asked_[i] > kFanAfter) {
      auto made = std::make_unique<Fan>(fan_of(nodes_[i]));
      if (shared_fan.compare_exchange_strong(fan, made.get(), std::memory_order_acq_rel,
                                             std::memory_order_acquire))
        fan = made.release();  // kept; otherwise `fan` is the one another thread published
    }
    answer = visible_with(nodes_[i], nodes_[j], fan) ? 1 : 0;
    known.store(answer, std::memory_order_relaxed);
  }
  return answer != 0;
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

  // The answer is the one Dijkstra's search from a over the whole graph gives (the router before
  // A*, written out in tests/geometry/visibility_search_test.cpp): a node's distance and
  // predecessor are what that search settles it with, and the path ends through the node v that
  // b sees with the least distance(v) + |v b|, the lowest index of equal ones. A* finds it while
  // settling only the nodes towards b, and testing only the legs it takes:
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
  constexpr double kShrink = 1 - 1e-6;
  struct Item {
    double f;
    int to_b;  ///< 0: a leg to `node`, 1: the way to b through `node`
    double g;
    int from_node;  ///< 0: straight from a, 1: from `from` (settled with distance `from_g`)
    double from_g;
    std::size_t from;
    std::size_t node;
    auto operator<=>(const Item&) const = default;
  };
  thread_local std::vector<double> h;              // per node of `near`: (1 - 1e-6) |node b|
  thread_local std::vector<std::size_t> previous;  // n: straight from a
  thread_local std::vector<char> settled;
  thread_local std::vector<std::size_t> near;  // the nodes a candidate under the limit can reach
  thread_local std::vector<Item> queue;        // a min-heap (std::push_heap with greater)
  h.resize(n);
  // The search takes candidates in order of f up to the answer's; those above a limit are not
  // queued. A search that ends without reaching b under the limit is run again with a higher
  // one: the candidates taken up to the answer, and so the answer, are those of a search without
  // a limit. The first limit: 1.25 times the straight leg (most transits bend round one
  // obstacle); each further one at least twice that. A node u whose |a u| + h(u) is above the
  // limit has every candidate above it (its g is at least |a u|): left out of the search. Such
  // a node lies farther than limit / (2 (1 - 1e-6)) from the middle of a b (|a u| + |u b| is at
  // least twice that distance): only the nodes within that of it in x (by search in the nodes
  // sorted by x) and in y are asked.
  double limit = 1.25 * distance(a, b) + tolerance_;
  std::size_t last = n;
  for (bool found = false; !found;) {
    double beyond = std::numeric_limits<double>::infinity();  // least f left out
    previous.assign(n, n);
    settled.assign(n, 0);
    queue.clear();
    near.clear();
    const Point2 middle = (a + b) * 0.5;
    const double reach = limit / (2 * kShrink) * (1 + 1e-9) + tolerance_;
    const auto by_x = [this](std::uint32_t u, double x) { return nodes_[u].x < x; };
    const auto first =
        std::lower_bound(nodes_by_x_.begin(), nodes_by_x_.end(), middle.x - reach, by_x);
    const auto end = std::lower_bound(first, nodes_by_x_.end(), middle.x + reach, by_x);
    bool left_out = end - first < std::ptrdiff_t(n);
    for (auto it = first; it != end; ++it) {
      const std::size_t u = *it;
      if (std::abs(nodes_[u].y - middle.y) > reach) {
        left_out = true;
        continue;
      }
      h[u] = kShrink * distance(nodes_[u], b);
      const double d = distance(a, nodes_[u]), f = d + h[u];
      if (!(f <= limit)) {
        beyond = std::min(beyond, f);
        continue;
      }
      near.push_back(u);
      if (from_a.seen[u] != 0) queue.push_back({f, 0, d, 0, 0.0, n, u});  // not known hidden
    }
    // In the order of the nodes' indices, as every node was asked before (the heap's ties).
    std::sort(near.begin(), near.end());
    std::make_heap(queue.begin(), queue.end(), std::greater<>());
    const auto push = [&](const Item& item) {
      if (!(item.f <= limit)) {
        beyond = std::min(beyond, item.f);
        return;
      }
      queue.push_back(item);
      std::push_heap(queue.begin(), queue.end(), std::greater<>());
    };
    while (!queue.empty()) {
      std::pop_heap(queue.begin(), queue.end(), std::greater<>());
      const Item item = queue.back();
      queue.pop_back();
      const std::size_t v = item.node;
      if (item.to_b) {
        if (sees(b, to_b, v)) {
          last = v;
          break;
        }
        continue;
      }
      if (settled[v]) continue;
      if (item.from_node ? !nodes_see(std::min(item.from, v), std::max(item.from, v))
                         : !sees(a, from_a, v))
        continue;
      settled[v] = 1;
      previous[v] = item.from_node ? item.from : n;
      if (to_b.seen[v] != 0) push({item.g + distance(nodes_[v], b), 1, 0.0, 0, 0.0, 0, v});
      for (const std::size_t u : near) {
        if (settled[u] || nodes_hidden(std::min(u, v), std::max(u, v))) continue;
        const double through = item.g + distance(nodes_[std::min(u, v)], nodes_[std::max(u, v)]);
        push({through + h[u], 0, through, 1, item.g, v, u});
      }
    }
    // Done: b reached, or every candidate taken (no inside path).
    found = last != n || (!left_out && beyond == std::numeric_limits<double>::infinity());
    limit = std::max(2 * limit, beyond == std::numeric_limits<double>::infinity() ? 0 : beyond);
  }
  if (last == n) return {a, b};  // no inside path (separate pieces): straight
  std::vector<Point2> route{b};
  for (std::size_t v = last; v != n; v = previous[v]) route.push_back(nodes_[v]);
  route.push_back(a);
  std::reverse(route.begin(), route.end());
  return route;
}

}  // namespace swath::geometry
