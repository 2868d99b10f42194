#include "swath/geometry/visibility.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>

#include "swath/geometry/classification.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/geometry/sort_few.hpp"
#include "visibility_tables.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

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
  const RayCount cast = ray_count(p);
  if (cast.on_edge || cast.odd) return true;
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

VisibilityRouter::RayCount VisibilityRouter::ray_count(Point2 p) const {
  // locate_point() over every ring, on the edges the ray right of p may meet only (the others
  // neither hold p nor cross the ray): on an edge is inside, else an odd number of crossings.
  // Or on the ray to the left, where fewer of the row's edges reach (near_ray()): each ring crosses
  // the whole line through p an even number of times (edge_and_ray's half-open rule), so the two
  // rays cross it equally often, up to 2 (exact predicates; x -> -x is exact, the ray to the left
  // is the mirror image's ray to the right). An edge that holds p is found either way.
  bool on_edge = false, odd = false;
  const auto count = [&](EdgeAndRay where) {
    on_edge |= where == EdgeAndRay::p_on_edge;
    odd ^= where == EdgeAndRay::crosses;
  };
  // Most edges of the ray's row are apart: wholly above or below p. edge_and_ray() says so by its
  // first test, written out here before the call, so that those edges cost no call; none asked
  // lies wholly behind p (near_ray() stops at the first that does).
  const Segment* const segments = edges_.segments().data();
  const auto mirrored = [](Point2 x) { return Point2{-x.x, x.y}; };
  edges_.near_ray(
      p,
      [&](std::uint32_t e) {
        const Segment& s = segments[e];
        if ((s.a.y > p.y && s.b.y > p.y) || (s.a.y < p.y && s.b.y < p.y)) return;
        count(edge_and_ray(p, s.a, s.b));
      },
      [&](std::uint32_t e) {
        const Segment& s = segments[e];
        if ((s.a.y > p.y && s.b.y > p.y) || (s.a.y < p.y && s.b.y < p.y)) return;
        count(edge_and_ray(mirrored(p), mirrored(s.a), mirrored(s.b)));
      });
  return {on_edge, odd};
}

// The direction of (dx, dy) != 0 as a "diamond angle" in [0, 4): 0 along +x, 1 along +y, 2
// along -x, 3 along -y, increasing counter-clockwise, and the opposite direction 2 further round.
// A monotone stand-in for atan2 at a few instructions (fans take two per edge): arcs below pi
// are arcs below 2. Its rounding is of the order of atan2's.
static double diamond(double dx, double dy) {
  if (dy >= 0) return dx >= 0 ? dy / (dx + dy) : 1 - dx / (dy - dx);
  return dx < 0 ? 2 - dy / (-dx - dy) : 3 + dx / (dx - dy);
}

namespace {

// A fan's edge: its first bin (wrapped) and how many bins it spans (0: near, in no bin).
struct FanSpan {
  std::uint32_t first, bins;
};

// The spans of a fan's edges, counted into its bins (+1 where a span starts, -1 past its end).
struct FanBins {
  double per_unit;     // bins per unit of diamond angle
  std::size_t count;   // bins
  FanSpan* span_of;    // per edge
  std::int32_t* step;  // per bin, + the end
  // floor(x * per_unit) of both, as fan_bin() takes it: truncation, one less for a negative
  // fraction. With SSE2 both in the two lanes of a register: the same IEEE operations lane by
  // lane, the truncation to 32 bits exact for the bins of angles in [-2 - kMargin, 6 + kMargin]
  // (at most 1,024 bins a turn: a few thousand, far inside 32 bits).
  std::pair<long, long> floors(double lo, double hi) const {
#if defined(__SSE2__)
    const __m128d v = _mm_mul_pd(_mm_set_pd(hi, lo), _mm_set1_pd(per_unit));
    const __m128i k = _mm_cvttpd_epi32(v);
    const __m128i up = _mm_castpd_si128(_mm_cmpgt_pd(_mm_cvtepi32_pd(k), v));
    const __m128i floor = _mm_add_epi32(k, _mm_shuffle_epi32(up, _MM_SHUFFLE(3, 3, 2, 0)));
    return {_mm_cvtsi128_si32(floor), _mm_cvtsi128_si32(_mm_srli_si128(floor, 4))};
#else
    const auto bin_of = [this](double x) {
      const double v = x * per_unit;
      const long k = long(v);
      return k - long(double(k) > v);
    };
    return {bin_of(lo), bin_of(hi)};
#endif
  }
  // The edges first, ..., first + edges - 1, from the angles of their ends (angle[0] to
  // angle[edges]): arcs widened by kMargin, in bins as fan_bin() takes them.
  void add(const double* angle, std::uint32_t first, std::size_t edges) const {
    constexpr double kMargin = 1e-7;
    const long bins = long(count);
    for (std::size_t i = 0; i < edges; ++i) {
      const double tp = angle[i], tq = angle[i + 1];
      double turn = tq - tp;
      if (turn > 2)
        turn -= 4;
      else if (turn < -2)
        turn += 4;
      const double end = tp + turn;
      const auto [lo, hi_bin] = floors(std::min(tp, end) - kMargin, std::max(tp, end) + kMargin);
      const long hi = std::min(hi_bin, lo + bins - 1);
      // diamond() lies in [0, 4] and the turn in [-2, 2], so lo, the bin of (the lesser end -
      // kMargin), lies in [-bins / 2 - 1, bins - 1] (4 - kMargin is a bin below the end of the
      // turn): only a negative one wraps, by one turn.
      const std::uint32_t wrapped = std::uint32_t(lo < 0 ? lo + bins : lo);
      const std::uint32_t spanned = std::uint32_t(hi - lo + 1);
      span_of[first + i] = {wrapped, spanned};
      // Counted per span, not per bin (a fan holds several times as many items as edges), in two
      // pieces where it wraps past the last bin.
      const std::size_t past = std::size_t(wrapped) + spanned;
      ++step[wrapped];
      if (past <= count) {
        --step[past];
      } else {
        --step[count];
        ++step[0];
        --step[past - count];
      }
    }
  }
};

}  // namespace

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
  Fan fan;
  fan.near_m = 1e-6 * (1 + std::max({extent_m_, std::abs(a.x), std::abs(a.y)}));
  const std::size_t edge_count = edges_.segments().size();
  thread_local std::vector<FanSpan> spans;       // per edge, its first bin and how many (0: near)
  thread_local std::vector<double> angles;       // per vertex of a ring, its diamond angle from a
  thread_local std::vector<std::int32_t> steps;  // per bin, edges whose span starts - ends there
  spans.resize(edge_count);
  steps.assign(fan_bins_ + 1, 0);
  // The near edges first, from the index round a (not a box test per edge of the area): an edge
  // within near_m of a has a point within near_m of it, in the cells of the box 4 near_m round a
  // (rounding is ~1e-16 of the extent). Each is asked as every edge was (its box more than twice
  // near_m from a: far, no distance), and kept in index order. They are few (the edges through a
  // point's neighbourhood of 1e-6 of the extent): one found again (in another cell) is looked
  // for among them.
  const double two_near = 2 * fan.near_m;
  const Point2 reach{4 * fan.near_m, 4 * fan.near_m};
  edges_.near_box(a - reach, a + reach, [&](std::uint32_t e) {
    if (std::find(fan.near.begin(), fan.near.end(), e) != fan.near.end()) return;
    // An edge whose box lies more than twice near_m from a is farther than near_m from it, its
    // computed distance too (rounding is ~1e-16 of the extent, near_m 1e-6 of it): no distance.
    const Box& box = edge_boxes_[e];
    const bool far = a.x < box.x0 - two_near || a.x > box.x1 + two_near ||
                     a.y < box.y0 - two_near || a.y > box.y1 + two_near;
    const Segment& s = edges_.segments()[e];
    if (!far && distance_to_segment(a, s.a, s.b) <= fan.near_m) fan.near.push_back(e);
  });
  std::sort(fan.near.begin(), fan.near.end());
  const RayCount cast = ray_count(a);
  fan.inside = cast.odd && !cast.on_edge;
  const FanBins bins{bins_per_unit_, fan_bins_, spans.data(), steps.data()};
  std::uint32_t e = 0;  // edges_ holds every ring's edges, ring after ring, in ring order
  const std::uint32_t* near = fan.near.data();
  const std::uint32_t* const near_end = near + fan.near.size();
  for (const Ring& ring : rings_) {
    const std::size_t n = ring.size();
    // One diamond angle per vertex, not two per edge: an edge's end is the next edge's start
    // (the first vertex's again after the last). a's own vertex gets NaN, unused: the edges at
    // it are near.
    angles.resize(n + 1);
    double* const angle = angles.data();
    for (std::size_t i = 0; i < n; ++i) angle[i] = diamond(ring[i].x - a.x, ring[i].y - a.y);
    angle[n] = angle[0];
    // The ring's edges in stretches between its near edges (no test per edge).
    for (std::size_t i = 0; i < n;) {
      const std::size_t stop = near != near_end && *near < e + n ? *near - e : n;
      bins.add(angle + i, e + std::uint32_t(i), stop - i);
      if (stop == n) break;
      spans[e + stop] = {0, 0};
      ++near;
      i = stop + 1;
    }
    e += std::uint32_t(n);
  }
  const std::size_t bin_count = fan_bins_;
  fan.start.assign(bin_count + 1, 0);  // per bin, its first item; + the end
  std::uint32_t* const start = fan.start.data();
  std::int32_t covering = 0;
  for (std::size_t k = 0; k < bin_count; ++k) {
    covering += steps[k];
    start[k + 1] = start[k] + std::uint32_t(covering);
  }
  fan.items = std::make_unique_for_overwrite<std::uint32_t[]>(start[bin_count]);
  thread_local std::vector<std::uint32_t> cursor;  // per bin, its next free item
  cursor.assign(fan.start.begin(), fan.start.end() - 1);
  std::uint32_t* const next = cursor.data();
  std::uint32_t* const items = fan.items.get();
  const FanSpan* const span_of = spans.data();
  for (std::uint32_t edge = 0; edge < e; ++edge) {
    // A span past the last bin goes on at the first.
    const std::uint32_t first = span_of[edge].first, end = first + span_of[edge].bins;
    const std::uint32_t split = std::min<std::uint32_t>(end, std::uint32_t(bin_count));
    for (std::uint32_t k = first; k < split; ++k) items[next[k]++] = edge;
    for (std::uint32_t k = 0; k + bin_count < end; ++k) items[next[k]++] = edge;
  }
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
  // No edge met [a, b] (every edge that may was asked: the fan's or the index's), so its points
  // all have a's count of crossings, odd for a fan's point inside: the leg is inside, as the
  // count at its midpoint says. The computed midpoint may lie a rounding off the leg, with an
  // edge between; then that edge lies within the rounding of it (~1e-16 of the extent, the fan's
  // point being inside and legs through a fan ending within the extent), and inside_closed()
  // takes it as on the boundary (1e-9 of the extent): inside all the same.
  if (fan && fan->inside && cuts.size() == 2) return 0.0;
  sort_few(cuts.data(), cuts.data() + cuts.size());
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
  copy->node_tables_ = node_tables_;
  return copy;
}

VisibilityRouter::Row& VisibilityRouter::seen_row(Point2 p) const {
  auto [it, added] = sees_.try_emplace({p.x, p.y});
  if (!added) return it->second;
  Row& row = it->second;
  // A point clearly outside (a line end past the area by its turnaround, a home beyond the field)
  // sees no node: known so at once, each search to it ends before it starts. Testing lazily, a
  // search from inside to it settled every node before finding it unreachable: with turnarounds
  // on a 3,000-vertex outline, 45 s.
  // Clearly: farther from every edge than any visibility test's tolerance. A leg from p to a
  // node is outside for at least p's distance from the edges, and visible only when at most
  // 1e-9 (1 + its length) is; its length is at most |p| + sqrt(2) extent. Ten times that, so
  // that no rounding of either measure matters.
  const bool clearly_outside = [&] {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
    const double margin_m = 1e-8 * (1 + std::abs(p.x) + std::abs(p.y) + 2 * extent_m_);
    const Point2 reach{margin_m, margin_m};
    bool near = false;
    edges_.near_box(p - reach, p + reach, [&](std::uint32_t e) {
      if (near) return;
      const Point2 a = edges_.segments()[e].a, d = edges_.segments()[e].b - a;
      const double t = std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0);
      near = distance(p, a + d * t) <= margin_m;
    });
    return !near && !inside_closed(p);
  }();
  if (clearly_outside) {
    row.seen.assign(nodes_.size(), 0);
    row.known = nodes_.size();
  } else {
    row.seen.assign(nodes_.size(), kUnknown);
  }
  return row;
}

bool VisibilityRouter::sees(Point2 p, Row& row, std::size_t node) const {
  signed char& known = row.seen[node];
  if (known == kUnknown) {
    // A point that is not finite gets no fan: it has no direction to bin edges by (fan_of()
    // would take a bin of NaN); its legs are measured along the grid.
    if (!row.fan && row.asked <= kFanAfter && ++row.asked > kFanAfter && std::isfinite(p.x) &&
        std::isfinite(p.y)) {
      // Kept within a budget: from inside a field of long needles (a star of 200 spikes) each edge
      // spans a sixth of the turn, 96 kB a fan, and 15,000 run ends asked often enough to get one
      // held 1.5 GB. Past the budget a point asks along the grid (more tests, the same answers:
      // a fan only chooses which edges the exact tests look at).
      Fan fan = fan_of(p);
      const std::size_t items = fan.start.back() + fan.start.size() + fan.near.size();
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

signed char VisibilityRouter::nodes_known(std::size_t i, std::size_t j) const {
  const NodeTables::Chunk* known = node_tables_->find(i, j);
  return known ? known->load(std::memory_order_relaxed) : kUnknown;
}

bool VisibilityRouter::hidden_bit(std::size_t i, std::size_t j) const {
  const NodeTables::Bits* bits = node_tables_->hidden_of(i, j / NodeTables::kChunk);
  return bits &&
         (bits[j % NodeTables::kChunk / 64].load(std::memory_order_relaxed) >> (j % 64) & 1);
}

bool VisibilityRouter::nodes_see(std::size_t i, std::size_t j) const {
  std::atomic<signed char>& known = node_tables_->at(i, j);
  signed char answer = known.load(std::memory_order_relaxed);
  if (answer == kUnknown) {
    // Measured from the lower-numbered corner whichever asks: visible_with() works from its first
    // point, and its answer near the tolerance may differ the other way round; the pair then has
    // one answer whichever thread or search asks it first (and the hidden bits below agree with
    // the table).
    const std::size_t from = std::min(i, j), to = std::max(i, j);
    std::atomic<Fan*>& shared_fan = node_tables_->fans[from];
    Fan* fan = shared_fan.load(std::memory_order_acquire);
    if (!fan) {
      auto made = std::make_unique<Fan>(fan_of(nodes_[from]));
      if (shared_fan.compare_exchange_strong(fan, made.get(), std::memory_order_acq_rel,
                                             std::memory_order_acquire))
        fan = made.release();  // kept; otherwise `fan` is the one another thread published
    }
    answer = visible_with(nodes_[from], nodes_[to], fan) ? 1 : 0;
    known.store(answer, std::memory_order_relaxed);
    // Also in j's row: a search reads the row of the node it settles (nodes_known(v, u)), one
    // chunk in the cache, not one row per node it looks at.
    node_tables_->at(j, i).store(answer, std::memory_order_relaxed);
    if (answer == 0) {  // after the table's entries: a bit set is an answer stored
      node_tables_->mark_hidden(i, j);
      node_tables_->mark_hidden(j, i);
    }
  }
  return answer != 0;
}

}  // namespace swath::geometry
