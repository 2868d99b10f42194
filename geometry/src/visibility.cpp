#include "swath/geometry/visibility.hpp"

#include <algorithm>
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
  adjacent_.resize(nodes_.size());
  node_fans_.resize(nodes_.size());
  fan_bins_ = std::clamp<std::size_t>(edges_.segments().size(), 64, 1024);
  bins_per_unit_ = double(fan_bins_) / 4;
  extent_m_ = extent;
  expanded_.assign(nodes_.size(), 0);
  node_sees_.assign(nodes_.size() * nodes_.size(), kUnknown);
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
  }
  return known != 0;
}

const std::vector<std::pair<std::size_t, double>>& VisibilityRouter::adjacent(std::size_t u) const {
  if (expanded_[u]) return adjacent_[u];
  // Ascending, as the eager graph listed them; each pair tested once (visible(i, j) with i < j,
  // as the eager build asked it: the test is not symmetric in rounding).
  const std::size_t n = nodes_.size();
  // The pairs (u, v > u) are tested from u: through u's fan when there are enough of them.
  if (!node_fans_[u] && n - u > std::size_t(kFanAfter))
    node_fans_[u] = std::make_unique<Fan>(fan_of(nodes_[u]));
  for (std::size_t v = 0; v < n; ++v) {
    if (v == u) continue;
    const std::size_t i = std::min(u, v), j = std::max(u, v);
    signed char& known = node_sees_[i * n + j];
    if (known == kUnknown) known = visible_with(nodes_[i], nodes_[j], node_fans_[i].get());
    if (known) adjacent_[u].push_back({v, distance(nodes_[i], nodes_[j])});
  }
  expanded_[u] = 1;
  return adjacent_[u];
}

VisibilityRouter::Search& VisibilityRouter::search_from(Point2 a) const {
  auto [it, added] = trees_.try_emplace({a.x, a.y});
  Search& s = it->second;
  if (!added) return s;
  const std::size_t n = nodes_.size();
  s.distance.assign(n, std::numeric_limits<double>::infinity());
  s.previous.assign(n, n);
  s.settled.assign(n, 0);
  s.from_row = &seen_row(a);
  // Every node starts as a candidate straight from a; whether a sees it is tested when it would
  // be settled so, and only then: nodes beyond the paths asked so far are never tested.
  for (std::size_t i = 0; i < n; ++i) s.queue.push_back({distance(a, nodes_[i]), i, 0});
  std::make_heap(s.queue.begin(), s.queue.end(), std::greater<>());
  return s;
}

std::size_t VisibilityRouter::settle_next(Point2 a, Search& s) const {
  // Dijkstra as over the eager graph, whose queue held (distance, node) pairs: straight from a
  // for the nodes a sees, then through settled nodes when strictly shorter. Here the straight
  // candidates all wait in the queue untested. Popped in the same (distance, node) order, with
  // the straight candidate first of equal ones, a node is settled with the distance and
  // predecessor the eager search gave it: a tested straight candidate that is visible and no
  // longer than the best through a node replaces that (the eager search never took a path
  // through a node that was not strictly shorter than the straight one); one that is not visible
  // is dropped, as the eager search never had it.
  const std::size_t n = nodes_.size();
  while (!s.queue.empty()) {
    std::pop_heap(s.queue.begin(), s.queue.end(), std::greater<>());
    const Search::Item item = s.queue.back();
    s.queue.pop_back();
    const std::size_t u = item.node;
    const double d = item.distance_m;
    if (s.settled[u] || d > s.distance[u]) continue;
    if (item.from_point == 0) {
      if (!sees(a, *s.from_row, u)) continue;
      s.distance[u] = d;
      s.previous[u] = n;
    }
    s.settled[u] = 1;
    s.settled_nodes.push_back(u);
    for (const auto& [v, w] : adjacent(u))
      if (!s.settled[v] && d + w < s.distance[v]) {
        s.distance[v] = d + w;
        s.previous[v] = u;
        s.queue.push_back({d + w, v, 1});
        std::push_heap(s.queue.begin(), s.queue.end(), std::greater<>());
      }
    return u;
  }
  return n;
}

std::vector<Point2> VisibilityRouter::path(Point2 a, Point2 b) const {
  if (!routing_) return {a, b};
  // Through a's fan where a has one (a run end asked about often, home): the same exact tests
  // on the same edges, without walking the grid along the leg. Only towards b within the area's
  // extent, as the fan's margins assume (see outside_fraction()).
  const auto row = sees_.find({a.x, a.y});
  const Fan* fan = row != sees_.end() && std::max(std::abs(b.x), std::abs(b.y)) <= extent_m_
                       ? row->second.fan.get()
                       : nullptr;
  if (visible_with(a, b, fan)) return {a, b};
  // The eager answer: of the nodes b sees, the one with the least distance from a plus the
  // straight leg to b, the lowest index of equal ones. A node's sum is at least its distance,
  // and nodes are settled in order of distance, so they are taken in that order: those b is
  // known to see into `best`, those not yet tested into a heap of sums, tested from its least
  // while that could still win. `best` is final once no node still to take (or to settle) has a
  // distance below its sum.
  Search& s = search_from(a);
  Row& to_b = seen_row(b);
  const std::size_t n = nodes_.size();
  thread_local std::vector<std::pair<double, std::size_t>> untested;  // (sum, node), a heap
  untested.clear();
  std::pair<double, std::size_t> best{std::numeric_limits<double>::infinity(), n};
  std::size_t taken = 0;  // s.settled_nodes before this are taken
  while (true) {
    double bound = std::numeric_limits<double>::infinity();
    if (taken < s.settled_nodes.size())
      bound = s.distance[s.settled_nodes[taken]];
    else if (!s.queue.empty())
      bound = s.queue.front().distance_m;
    const bool untested_first = !untested.empty() && untested.front() < best;
    if (untested_first && untested.front().first < bound) {
      std::pop_heap(untested.begin(), untested.end(), std::greater<>());
      const auto candidate = untested.back();
      untested.pop_back();
      if (sees(b, to_b, candidate.second)) best = candidate;
      continue;
    }
    if (!untested_first && best.first < bound) break;  // nothing left can do better
    if (taken < s.settled_nodes.size()) {
      const std::size_t i = s.settled_nodes[taken++];
      if (to_b.seen[i] == 0) continue;
      const std::pair<double, std::size_t> candidate{s.distance[i] + distance(nodes_[i], b), i};
      if (to_b.seen[i] == kUnknown) {
        untested.push_back(candidate);
        std::push_heap(untested.begin(), untested.end(), std::greater<>());
      } else {
        best = std::min(best, candidate);
      }
      continue;
    }
    if (settle_next(a, s) == n && !untested_first) break;  // all settled
  }
  const std::size_t last = best.second;
  if (last == n) return {a, b};  // no inside path (separate pieces): straight
  std::vector<Point2> route{b};
  for (std::size_t v = last; v != n; v = s.previous[v]) route.push_back(nodes_[v]);
  route.push_back(a);
  std::reverse(route.begin(), route.end());
  return route;
}

}  // namespace swath::geometry
