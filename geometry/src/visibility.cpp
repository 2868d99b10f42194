#include "swath/geometry/visibility.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>

#include "swath/geometry/capped_heap.hpp"
#include "swath/geometry/classification.hpp"
#include "swath/geometry/open_nodes.hpp"
#include "swath/geometry/predicates.hpp"

namespace swath::geometry {
namespace {

// The side of p from the line through a along d, where the double cross product decides it
// beyond its rounding bound (each of the differences, two products and the subtraction round by
// at most 2^-53 relative: 1e-15 of the products' sum is well above it): +1 left, -1 right, else
// 0 (no answer). Two points certainly on one side: a filter before segments_intersect, which such
// an edge cannot meet; certainly on either side of each other's lines: the segments cross. Inline,
// as visibility asks it ~10^6 times a plan.
int certain_side(Point2 a, Point2 d, Point2 p) {
  const double p1 = d.x * (p.y - a.y), p2 = d.y * (p.x - a.x);
  const double s = p1 - p2, bound = 1e-15 * (std::abs(p1) + std::abs(p2));
  return s > bound ? 1 : s < -bound ? -1 : 0;
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
  // Or on the ray to the left, where the index has fewer edges that way: each ring crosses the
  // whole line through p an even number of times (edge_and_ray's half-open rule), so the two rays
  // cross it equally often, up to 2 (exact predicates; x -> -x is exact, the ray to the left is
  // the mirror image's ray to the right). An edge that holds p is found either way.
  bool on_edge = false, odd = false;
  const auto count = [&](EdgeAndRay where) {
    on_edge |= where == EdgeAndRay::p_on_edge;
    odd ^= where == EdgeAndRay::crosses;
  };
  const auto [right, left] = edges_.ray_items(p);
  if (left < right) {
    const auto mirrored = [](Point2 x) { return Point2{-x.x, x.y}; };
    edges_.near_ray_left(p, [&](std::uint32_t e) {
      const Segment& s = edges_.segments()[e];
      count(edge_and_ray(mirrored(p), mirrored(s.a), mirrored(s.b)));
    });
  } else {
    edges_.near_ray_right(p, [&](std::uint32_t e) {
      const Segment& s = edges_.segments()[e];
      count(edge_and_ray(p, s.a, s.b));
    });
  }
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
  // between the bins of the range's ends. std::floor without its library call (the build's
  // baseline x86-64 has no rounding instruction): truncation, one less for a negative fraction.
  const double v = diamond_angle * bins_per_unit_;
  const long k = long(v);
  return k - long(double(k) > v);
}

VisibilityRouter::Fan VisibilityRouter::fan_of(Point2 a) const {
  // An edge that does not hold a is seen from it within an arc of directions below pi (below 2
  // in diamond angle): the directions of its ends and the shorter way between them. Legs from a
  // through any of its points run in a direction of that arc. The computed directions are off by
  // less than ~1e-9 for points at least near_m from a (differences of coordinates round by ~1e-16
  // of the larger of the area's and a's extent, near_m is 1e-6 of it); each arc is widened by
  // 1e-7. An edge nearer than near_m is asked for every leg.
  constexpr double kMargin = 1e-7;
  Fan fan;
  fan.near_m = 1e-6 * (1 + std::max({extent_m_, std::abs(a.x), std::abs(a.y)}));
  const long bins = long(fan_bins_);
  // Per edge, its first bin (wrapped) and how many bins it spans (0: near, in no bin).
  struct Span {
    std::uint32_t first, bins;
  };
  thread_local std::vector<Span> spans;
  thread_local std::vector<double> angles;       // per vertex of a ring, its diamond angle from a
  thread_local std::vector<std::int32_t> steps;  // per bin, edges whose span starts - ends there
  spans.resize(edges_.segments().size());
  steps.assign(fan_bins_ + 1, 0);
  // A bin index taken round the turn: lo is at least -bins / 2 - 1 and at most bins, so a step
  // either way wraps it (the general form kept for safety).
  const auto wrapped = [bins](long k) {
    if (k < 0) k += bins;
    if (k >= bins) k -= bins;
    if (k < 0 || k >= bins) k = ((k % bins) + bins) % bins;
    return std::uint32_t(k);
  };
  std::uint32_t e = 0;  // edges_ holds every ring's edges, ring after ring, in ring order
  for (const Ring& ring : rings_) {
    const std::size_t n = ring.size();
    // One diamond angle per vertex, not two per edge: an edge's end is the next edge's start.
    // (a's own vertex gets NaN, unused: the edges at it are near.)
    angles.resize(n);
    for (std::size_t i = 0; i < n; ++i) angles[i] = diamond(ring[i].x - a.x, ring[i].y - a.y);
    for (std::size_t i = 0; i < n; ++i, ++e) {
      // An edge whose box lies more than twice near_m from a is farther than near_m from it, its
      // computed distance too (rounding is ~1e-16 of the extent, near_m 1e-6 of it): no distance.
      const Box& box = edge_boxes_[e];
      const bool far = a.x < box.x0 - 2 * fan.near_m || a.x > box.x1 + 2 * fan.near_m ||
                       a.y < box.y0 - 2 * fan.near_m || a.y > box.y1 + 2 * fan.near_m;
      if (!far && distance_to_segment(a, ring[i], ring[i + 1 == n ? 0 : i + 1]) <= fan.near_m) {
        fan.near.push_back(e);
        spans[e] = {0, 0};
        continue;
      }
      const double tp = angles[i], tq = angles[i + 1 == n ? 0 : i + 1];
      double turn = tq - tp;
      if (turn > 2)
        turn -= 4;
      else if (turn < -2)
        turn += 4;
      const long lo = fan_bin(std::min(tp, tp + turn) - kMargin);
      const long hi = std::min(fan_bin(std::max(tp, tp + turn) + kMargin), lo + bins - 1);
      spans[e] = {wrapped(lo), std::uint32_t(hi - lo + 1)};
      // Counted per span, not per bin (a fan holds several times as many items as edges): +1
      // where it starts, -1 past its end, in two pieces where it wraps past the last bin.
      const std::size_t first = spans[e].first, end = first + spans[e].bins;
      ++steps[first];
      if (end <= fan_bins_) {
        --steps[end];
      } else {
        --steps[fan_bins_];
        ++steps[0];
        --steps[end - fan_bins_];
      }
    }
  }
  std::vector<std::uint32_t> count(fan_bins_ + 1, 0);  // per bin, its first item; + the end
  std::int32_t covering = 0;
  for (std::size_t k = 0; k < fan_bins_; ++k) {
    covering += steps[k];
    count[k + 1] = count[k] + std::uint32_t(covering);
  }
  fan.start = count;
  fan.items.resize(count.back());
  for (std::uint32_t edge = 0; edge < e; ++edge)
    for (std::uint32_t k = spans[edge].first, left = spans[edge].bins; left > 0;
         --left, k = k + 1 == fan_bins_ ? 0 : k + 1)
      fan.items[count[k]++] = edge;
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
  // The same box widened by the tolerance, its sums taken once rather than per edge asked.
  const Box wide{seg.x0 - tolerance_, seg.y0 - tolerance_, seg.x1 + tolerance_,
                 seg.y1 + tolerance_};
  const Segment* const segments = edges_.segments().data();
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
  // Inlined where the edges are walked (~20 edges a leg, most turned away by their box): a call
  // per edge reloaded the leg from memory each time.
  const auto cut_by = [&](std::uint32_t e) __attribute__((always_inline)) {
    const Box& box = edge_boxes_[e];
    if (box.x0 > wide.x1 || box.x1 < wide.x0 || box.y0 > wide.y1 || box.y1 < wide.y0) return;
    const Point2 p = segments[e].a, q = segments[e].b;
    // cross(d, p - a) and cross(d, q - a), as their products, which certain_side() takes too.
    const double p1 = d.x * (p.y - a.y), p2 = d.y * (p.x - a.x);
    const double q1 = d.x * (q.y - a.y), q2 = d.y * (q.x - a.x);
    const double sp = p1 - p2, sq = q1 - q2;
    const bool p_on = std::abs(sp) <= off_line_limit, q_on = std::abs(sq) <= off_line_limit;
    if (p_on) cuts.push_back(std::clamp(dot(p - a, d) / len2, 0.0, 1.0));
    if (q_on) cuts.push_back(std::clamp(dot(q - a, d) / len2, 0.0, 1.0));
    if (p_on && q_on) return;  // along the line: its ends are its cuts
    if (apart(box)) return;
    const double bp = 1e-15 * (std::abs(p1) + std::abs(p2)),
                 bq = 1e-15 * (std::abs(q1) + std::abs(q2));
    if ((sp > bp && sq > bq) || (sp < -bp && sq < -bq))
      return;  // both on one side (certain_side())
    // a and b strictly on one side of the edge's line: segments_intersect() would say no.
    const int a_side = certain_side(p, q - p, a), b_side = certain_side(p, q - p, b);
    if (a_side != 0 && a_side == b_side) return;
    // Each segment's ends certainly on either side of the other's line: they cross, as
    // segments_intersect() would say (most cuts of a blocked leg), without its exact predicates.
    const bool crossing = a_side * b_side < 0 && ((sp > bp && sq < -bq) || (sp < -bp && sq > bq));
    if (!crossing && !segments_intersect(a, b, p, q)) return;
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
    long bin = fan_bin(diamond(d.x, d.y));  // in [0, bins] (4 is the end of the turn)
    if (bin >= bins || bin < 0) bin = ((bin % bins) + bins) % bins;
    const auto k = std::size_t(bin);
    for (std::uint32_t i = fan->start[k]; i < fan->start[k + 1]; ++i) cut_by(fan->items[i]);
    for (const std::uint32_t e : fan->near) cut_by(e);
  } else {
    edges_.near_segment(a, b, cut_by);
  }
  std::sort(cuts.begin(), cuts.end());
  const double length = std::sqrt(len2);
  const auto inside_piece = [&](std::size_t k) {
    return inside_closed(a + d * ((cuts[k] + cuts[k + 1]) / 2));
  };
  // A visibility test (a finite stop_m) asks the longest piece first: on a blocked leg it is
  // mostly outside and alone past stop_m, and then so is the sum below (it adds non-negative
  // terms, rounding included, so it is at least that piece): the answer without asking the
  // others. Otherwise its answer is kept for the sum, which is taken in order as before.
  std::size_t longest = cuts.size();  // the piece asked first; cuts.size(): none
  bool longest_inside = false;
  if (stop_m < std::numeric_limits<double>::infinity() && cuts.size() > 2) {
    longest = 0;
    for (std::size_t k = 1; k + 1 < cuts.size(); ++k)
      if (cuts[k + 1] - cuts[k] > cuts[longest + 1] - cuts[longest]) longest = k;
    const double piece = cuts[longest + 1] - cuts[longest];
    longest_inside = inside_piece(longest);
    if (!longest_inside && piece * length > stop_m) return piece;
  }
  double outside = 0;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    if (cuts[k + 1] <= cuts[k]) continue;
    if (!(k == longest ? longest_inside : inside_piece(k))) {
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

VisibilityRouter::VisibilityRouter(std::vector<Ring> rings, Routing routing,
                                   double corner_allowance_m)
    : rings_(std::move(rings)) {
  double extent = 0;
  for (const Ring& ring : rings_)
    for (const Point2& p : ring) extent = std::max({extent, std::abs(p.x), std::abs(p.y)});
  tolerance_ = 1e-9 * (1 + extent);
  extent_m_ = extent;
  std::vector<Segment> edges;
  for (const Ring& ring : rings_)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point2 p = ring[i], q = ring[(i + 1) % ring.size()];
      edges.push_back({p, q});
      edge_boxes_.push_back(
          {std::min(p.x, q.x), std::min(p.y, q.y), std::max(p.x, q.x), std::max(p.y, q.y)});
    }
  // 8 cells an edge, not the index's default 4: shorter rows for inside_closed()'s rays, for a
  // few more cells along a leg (traced outlines: 0.4 % fewer instructions a plan; 16: more).
  edges_ = SegmentIndex(std::move(edges), 8);
  if (routing == Routing::measure_only) {
    routing_ = false;
    return;
  }
  // The search's pruning (taut()) holds where each corner has the area's outside between its two
  // edges alone: rings that neither cross nor touch.
  // A bend moved off its corner (the allowance) is no corner: a shortest path through the moved
  // bends may turn at one the other way, so with an allowance the search is not pruned.
  prune_ = !(corner_allowance_m > 0);
  if (prune_ && !rings_.empty()) {
    try {
      prune_ = !find_crossing(Polygon{rings_.front(), {rings_.begin() + 1, rings_.end()}});
    } catch (const std::exception&) {
      prune_ = false;
    }
  }
  for (const Ring& ring : rings_) {
    const std::size_t n = ring.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Point2 before = ring[(i + n - 1) % n], after = ring[(i + 1) % n];
      if (orientation(before, ring[i], after) != Orientation::clockwise) continue;
      nodes_.push_back(moved_out(before, ring[i], after, corner_allowance_m));
      before_.push_back(before);
      after_.push_back(after);
    }
  }
  nodes_by_x_.resize(nodes_.size());
  for (std::size_t u = 0; u < nodes_.size(); ++u) nodes_by_x_[u] = std::uint32_t(u);
  std::stable_sort(nodes_by_x_.begin(), nodes_by_x_.end(),
                   [this](std::uint32_t u, std::uint32_t v) { return nodes_[u].x < nodes_[v].x; });
  build_node_grid();
  node_asked_.assign(nodes_.size(), 0);
  fan_bins_ = std::clamp<std::size_t>(edges_.segments().size(), 64, 1024);
  bins_per_unit_ = double(fan_bins_) / 4;
  node_tables_ = std::make_shared<NodeTables>(nodes_.size());
}

void VisibilityRouter::build_node_grid() {
  const std::size_t n = nodes_.size();
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (const Point2& p : nodes_)
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  if (n == 0) x0 = y0 = x1 = y1 = 0;
  // About eight nodes a cell; cells no smaller than 1e-4 of the area's extent, so that a node
  // outside the 3 x 3 cells round a corner is far enough from it for its direction to be
  // computed well (onward()).
  const double w = x1 - x0, h = y1 - y0, cells = double(n) / 8 + 1;
  grid_.cell_m = std::max(
      {std::sqrt(w * h / cells), std::max(w, h) / (double(n) + 1), 1e-4 * (1 + extent_m_)});
  grid_.x0 = x0, grid_.y0 = y0;
  grid_.nx = long(w / grid_.cell_m) + 1, grid_.ny = long(h / grid_.cell_m) + 1;
  const auto cell_of = [this](Point2 p) {
    const long cx = std::clamp(long((p.x - grid_.x0) / grid_.cell_m), 0L, grid_.nx - 1);
    const long cy = std::clamp(long((p.y - grid_.y0) / grid_.cell_m), 0L, grid_.ny - 1);
    return std::size_t(cy * grid_.nx + cx);
  };
  grid_.start.assign(std::size_t(grid_.nx * grid_.ny) + 1, 0);
  for (const Point2& p : nodes_) ++grid_.start[cell_of(p) + 1];
  for (std::size_t k = 1; k < grid_.start.size(); ++k) grid_.start[k] += grid_.start[k - 1];
  grid_.items.resize(n);
  std::vector<std::uint32_t> fill(grid_.start.begin(), grid_.start.end() - 1);
  for (std::size_t u = 0; u < n; ++u) grid_.items[fill[cell_of(nodes_[u])]++] = std::uint32_t(u);
  // The cone (taut()): the line of a leg on from the corner must not pass through the obstacle's
  // angle w between the unit edge vectors e1, e2, so it makes an angle of at most (pi - w) / 2
  // with e2 - e1 (at right angles to the bisector e1 + e2), whose tan is |e1 + e2| / |e2 - e1|.
  // Widened by 1e-9 radians for rounding of the unit vectors (~1e-16).
  bowties_.clear();
  for (std::size_t v = 0; v < n; ++v) {
    const Point2 c = nodes_[v];
    const Point2 e1 = (before_[v] - c) * (1 / distance(before_[v], c));
    const Point2 e2 = (after_[v] - c) * (1 / distance(after_[v], c));
    const Point2 sum = e1 + e2, difference = e2 - e1;
    const double along = std::hypot(difference.x, difference.y);
    if (!prune_ || !(along > 1e-6)) {  // a spike: (nearly) any direction
      bowties_.push_back({{1, 0}, {0, 1}, INFINITY, true});
      continue;
    }
    const Point2 axis = difference * (1 / along);
    // Widened by the angle corner_sides() lets a leg's line pass within an edge: 4 tolerance over
    // the shorter of the edge and the leg (legs to nodes outside the 3 x 3 cells round the corner
    // are at least a cell long).
    const double shortest =
        std::min({distance(before_[v], c), distance(after_[v], c), grid_.cell_m});
    const double half =
        std::atan(std::hypot(sum.x, sum.y) / along) + 8 * tolerance_ / shortest + 1e-9;
    if (!(half < 1.5707)) {
      bowties_.push_back({{1, 0}, {0, 1}, INFINITY, true});
      continue;
    }
    const double spread = std::tan(half);
    // Both edges lie on one side of +axis (cross(e2 - e1, e1) = cross(e2 - e1, e2)): left of it,
    // the half along +axis is where left turns go on.
    bowties_.push_back({axis, {-axis.y, axis.x}, spread, cross(axis, sum) > 0});
  }
}

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

VisibilityRouter::~VisibilityRouter() = default;

std::unique_ptr<VisibilityRouter> VisibilityRouter::fresh_copy() const {
  std::unique_ptr<VisibilityRouter> copy(new VisibilityRouter);
  copy->rings_ = rings_;
  copy->edges_ = edges_;
  copy->edge_boxes_ = edge_boxes_;
  copy->nodes_ = nodes_;
  copy->before_ = before_;
  copy->after_ = after_;
  copy->bowties_ = bowties_;
  copy->prune_ = prune_;
  copy->grid_ = grid_;
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
    if (!row.fan && row.asked <= kFanAfter && ++row.asked > kFanAfter) {
      // Kept within a budget: from inside a field of long needles (a star of 200 spikes) each edge
      // spans a sixth of the turn, 96 kB a fan, and 15,000 run ends asked often enough to get one
      // held 1.5 GB. Past the budget a point asks along the grid (more tests, the same answers:
      // a fan only chooses which edges the exact tests look at).
      Fan fan = fan_of(p);
      const std::size_t items = fan.items.size() + fan.start.size() + fan.near.size();
      if (row_fan_items_ + items <= kRowFanItemBudget) {
        row_fan_items_ += items;
        row.fan = std::make_unique<Fan>(std::move(fan));
      }
    }
    known = visible_with(p, nodes_[node], row.fan.get());
    ++row.known;
    row.visible += known != 0;
  }
  return known != 0;
}

// Threads that share the tables may test a pair at once: both find the same answer (the same exact
// tests, with or without a fan), so either store stands. A fan and a chunk of the table are
// published whole (release) and only the first one made is kept. The table comes in chunks made
// when first written: a search asks about the pairs near its path only, and a full table of 10^4
// nodes would be 10^8 bytes.
struct VisibilityRouter::NodeTables {
  static constexpr std::size_t kChunk = 4096;  ///< pairs per chunk of one row (the last: the rest)
  using Chunk = std::atomic<signed char>;
  explicit NodeTables(std::size_t n)
      : nodes(n),
        per_row((n + kChunk - 1) / kChunk),
        chunks(new std::atomic<Chunk*>[n * per_row]),
        fans(new std::atomic<Fan*>[n]) {
    for (std::size_t k = 0; k < n * per_row; ++k)
      chunks[k].store(nullptr, std::memory_order_relaxed);
    for (std::size_t k = 0; k < n; ++k) fans[k].store(nullptr, std::memory_order_relaxed);
  }
  ~NodeTables() {
    for (std::size_t k = 0; k < nodes * per_row; ++k)
      delete[] chunks[k].load(std::memory_order_acquire);
    for (std::size_t k = 0; k < nodes; ++k) delete fans[k].load(std::memory_order_acquire);
  }
  NodeTables(const NodeTables&) = delete;
  NodeTables& operator=(const NodeTables&) = delete;
  /// Whether i sees j: kUnknown until asked; null where nothing of its chunk has been asked.
  const Chunk* find(std::size_t i, std::size_t j) const {
    const Chunk* chunk = chunks[i * per_row + j / kChunk].load(std::memory_order_acquire);
    return chunk ? chunk + j % kChunk : nullptr;
  }
  /// Chunk c of row i (its pairs c kChunk, ...), null while nothing of it has been asked.
  const Chunk* chunk_of(std::size_t i, std::size_t c) const {
    return chunks[i * per_row + c].load(std::memory_order_acquire);
  }
  Chunk& at(std::size_t i, std::size_t j) {
    std::atomic<Chunk*>& slot = chunks[i * per_row + j / kChunk];
    Chunk* chunk = slot.load(std::memory_order_acquire);
    if (!chunk) {
      // Only as long as the row (below kChunk nodes): rows of 4096 bytes each, of which a search
      // reads the first few hundred, all fell on the same few sets of the caches.
      const std::size_t size = std::min(kChunk, nodes - j / kChunk * kChunk);
      auto made = std::make_unique<Chunk[]>(size);
      for (std::size_t k = 0; k < size; ++k) made[k].store(kUnknown, std::memory_order_relaxed);
      if (slot.compare_exchange_strong(chunk, made.get(), std::memory_order_acq_rel,
                                       std::memory_order_acquire))
        chunk = made.release();  // kept; otherwise `chunk` is the one another thread published
    }
    return chunk[j % kChunk];
  }
  std::size_t nodes, per_row;
  std::unique_ptr<std::atomic<Chunk*>[]> chunks;  ///< per row, per chunk of it
  std::unique_ptr<std::atomic<Fan*>[]> fans;      ///< per node, null until made
};

signed char VisibilityRouter::nodes_known(std::size_t i, std::size_t j) const {
  const NodeTables::Chunk* known = node_tables_->find(i, j);
  return known ? known->load(std::memory_order_relaxed) : kUnknown;
}

bool VisibilityRouter::nodes_see(std::size_t i, std::size_t j) const {
  std::atomic<signed char>& known = node_tables_->at(i, j);
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
    // Also in j's row: a search reads the row of the node it settles (nodes_known(v, u)), one
    // chunk in the cache, not one row per node it looks at.
    node_tables_->at(j, i).store(answer, std::memory_order_relaxed);
  }
  return answer != 0;
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
  struct Buffers {
    std::vector<double> h;              // per node of `near`: (1 - 1e-6) |node b|
    std::vector<std::size_t> previous;  // n: straight from a
    std::vector<char> settled;
    std::vector<std::size_t> near;  // the nodes a candidate under the limit can reach
    std::vector<char> is_near;      // per node: in `near`
    CappedHeap<SearchItem> queue;   // a search takes ~1 candidate in 10 it queues
    Settlers settlers;
    OpenNodes open;
    std::vector<double> g_of;                 // per node settled: its g
    std::vector<std::uint32_t> settled_list;  // the nodes settled, in order
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
    x.near.clear();
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
      x.near.push_back(u);
      x.is_near[u] = 1;
      const SearchItem straight{f, 0, d, 0, 0.0, n, u};
      if (from_a.seen[u] != 0) x.queue.push(straight);  // not known hidden
      if (from_a.seen[u] == 1) {                        // the only one from a for u
        x.settlers.offer(straight);
        bound_by_settler(straight);
      }
    }
    // In the order of the nodes' indices, as every node was asked before (the heap's ties).
    std::sort(x.near.begin(), x.near.end());
    x.open.reset(x.near, n, r.nodes_, x.h);
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
    return n;
  }

  // Node v settled by `item`, and its ways on: to b, and to the open nodes.
  void settle(const SearchItem& item) {
    const std::size_t v = item.node, from = item.from;
    x.settled[v] = 1;
    x.g_of[v] = item.g;
    x.settled_list.push_back(std::uint32_t(v));
    x.open.remove(v);
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

  // Every open node (near, not settled) whose leg's f is under the cut; those known hidden
  // (nearly half) skipped. Row v's chunk is looked up once per chunk, not once per node (one
  // chunk below 4096 nodes).
  void go_on_to_every_open_node(const SearchItem& item) {
    const std::size_t v = item.node;
    beyond = std::min(beyond, x.open.legs(r.nodes_[v], item.g, std::min(limit, bound)));
    const NodeTables& tables = *r.node_tables_;
    const NodeTables::Chunk* chunk = nullptr;
    std::size_t chunk_at = std::numeric_limits<std::size_t>::max();
    for (const std::uint32_t k : x.open.under()) {
      const std::uint32_t u = x.open.node(k);
      const std::size_t c = u / NodeTables::kChunk;
      if (c != chunk_at) chunk = tables.chunk_of(v, chunk_at = c);
      const signed char seen =
          chunk ? chunk[u % NodeTables::kChunk].load(std::memory_order_relaxed) : kUnknown;
      if (seen != 0) queue_leg(item.g, v, u, seen, x.open.through(k), x.open.f(k));
    }
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
