#pragma once
// Internal to lane_runs.cpp (and its tests): which intervals of a horizontal line lie inside an
// area turned so that lanes run along x.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <span>
#include <utility>
#include <vector>

#include "swath/geometry/polygon.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/geometry/sort_few.hpp"
#include "swath/planning/lane_runs.hpp"

namespace swath::planning::detail {

using geometry::Point2;
using geometry::Ring;

// std::lower_bound for items whose keys key(items[k]) ascend, free of NaN: the first item whose key
// is not below `value`, walked to from `hint` (the answer for a nearby value) instead of searched:
// a ring's edges come in order, each starting where the last ended, so the walk is a step or two
// (at most the rows the edges span, which their callers walk anyway).
template <typename T, typename Key>
std::size_t walk_lower_bound_by(const T* items, std::size_t n, double value, std::size_t hint,
                                Key key) {
  std::size_t k = std::min(hint, n);
  while (k > 0 && !(key(items[k - 1]) < value)) --k;
  while (k < n && key(items[k]) < value) ++k;
  return k;
}

// walk_lower_bound_by() on the keys themselves: std::lower_bound(keys, keys + n, value).
inline std::size_t walk_lower_bound(const double* keys, std::size_t n, double value,
                                    std::size_t hint) {
  return walk_lower_bound_by(keys, n, value, hint, [](double key) { return key; });
}

struct Span {
  double x0, x1;
};

// Spans per row in one array (row k's from start[k] to start[k + 1]): rows are asked by the
// hundred per direction, and a vector each was a tenth of a split plan's allocations.
class SpanRows {
 public:
  std::size_t size() const { return start_.size() - 1; }
  std::span<const Span> operator[](std::size_t k) const {
    return {spans_.data() + start_[k], spans_.data() + start_[k + 1]};
  }
  /// Appends a span to the last row (add_row() first).
  void add(Span s) {
    spans_.push_back(s);
    ++start_.back();
  }
  void add_row() { start_.push_back(start_.back()); }
  void reserve(std::size_t rows, std::size_t spans) {
    start_.reserve(rows + 1);
    spans_.reserve(spans);
  }

 private:
  std::vector<std::size_t> start_{0};
  std::vector<Span> spans_;
};

// The area in the frame turned by -angle: lanes run along x. Which intervals of a horizontal
// line lie inside, by crossings (a vertex on the line counts for the edge above it only).
class LaneScan {
 public:
  LaneScan(const std::vector<Ring>& rings, double angle_deg) {
    // rotate()'s arithmetic with its sine and cosine taken once: 10,000-vertex outlines are
    // turned for every candidate direction.
    const double t = -angle_deg * std::numbers::pi / 180.0;
    const double c = std::cos(t), sn = std::sin(t);
    // Sized once (grown by doubling, a 10,000-vertex area's edges were fresh pages every time).
    std::size_t total = 0;
    for (const Ring& ring : rings) total += ring.size();
    edges_.reserve(total);
    const auto turn = [c, sn](Point2 p) { return Point2{c * p.x - sn * p.y, sn * p.x + c * p.y}; };
    for (const Ring& ring : rings) {
      if (ring.empty()) continue;
      const Point2 first = turn(ring.front());
      Point2 a = first;
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const Point2 b = i + 1 < ring.size() ? turn(ring[i + 1]) : first;
        edges_.push_back({a, b});
        y_min = std::min(y_min, a.y);
        y_max = std::max(y_max, a.y);
        a = b;
      }
    }
  }

  std::vector<Span> at(double y) const {
    std::vector<Span> out;
    at(y, out);
    return out;
  }
  /// at(y) into `out` (cleared; its capacity kept: coverage lanes ask ~100 ordinates a direction,
  /// and two fresh vectors each were a tenth of the time at(y) took).
  void at(double y, std::vector<Span>& out) const {
    // Only the edges of y's bucket can span y (coverage lanes ask this for every corner the grid
    // misses: O(n) each made 10,000-vertex outlines slow). The crossings are sorted, so the
    // spans do not depend on the order the edges come in.
    if (buckets_ == 0) fill_buckets();
    thread_local std::vector<double> xs;
    xs.clear();
    const std::size_t k = bucket(y);
    for (std::uint32_t e = start_[k]; e < start_[k + 1]; ++e) {
      const auto& [a, b] = edges_[items_[e]];
      if ((a.y <= y) != (b.y <= y)) xs.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
    }
    out.clear();
    pair_up(xs.data(), xs.data() + xs.size(), [&](Span span) { out.push_back(span); });
  }

  /// at() for many increasing ordinates: each edge finds its first by search. The crossings of a
  /// row come in edge order as at(y)'s do, so the spans are the same.
  SpanRows at(const std::vector<double>& ys) const {
    // The crossings (row, x) in edge order, then by row (a counting sort keeps edge order within
    // a row): each edge searched once.
    thread_local std::vector<std::pair<std::uint32_t, double>> hits;
    hits.clear();
    std::size_t near = 0;  // the last edge's first row
    for (const auto& [a, b] : edges_) {
      const double lo = std::min(a.y, b.y), hi = std::max(a.y, b.y);
      near = walk_lower_bound(ys.data(), ys.size(), lo, near);
      for (auto k = ys.begin() + std::ptrdiff_t(near); k != ys.end() && *k < hi; ++k)
        hits.push_back(
            {std::uint32_t(k - ys.begin()), a.x + (*k - a.y) * (b.x - a.x) / (b.y - a.y)});
    }
    // The thread's buffers (three fresh vectors a call; three calls a direction).
    thread_local std::vector<std::uint32_t> first, next;
    thread_local std::vector<double> xs;
    first.assign(ys.size() + 1, 0);  // row k's crossings from first[k]
    for (const auto& hit : hits) ++first[hit.first + 1];
    for (std::size_t k = 0; k < ys.size(); ++k) first[k + 1] += first[k];
    xs.resize(hits.size());
    next.assign(first.begin(), first.end() - 1);
    for (const auto& [k, x] : hits) xs[next[k]++] = x;
    SpanRows out;
    out.reserve(ys.size(), xs.size() / 2);
    for (std::size_t k = 0; k < ys.size(); ++k) {
      out.add_row();
      pair_up(xs.data() + first[k], xs.data() + first[k + 1], [&](Span span) { out.add(span); });
    }
    return out;
  }
  const std::vector<std::pair<Point2, Point2>>& edges() const { return edges_; }
  double y_min = std::numeric_limits<double>::infinity();
  double y_max = -std::numeric_limits<double>::infinity();

 private:
  // The crossings [first, last) of one line sorted, and each inside interval longer than a
  // micrometre to add().
  template <typename Add>
  static void pair_up(double* first, double* last, Add add) {
    geometry::sort_few(first, last);  // a line's few crossings, as std::sort orders them
    for (; last - first >= 2; first += 2)
      if (first[1] - first[0] > 1e-6) add(Span{first[0], first[1]});
  }
  // Buckets of equal height over [y_min, y_max], each listing the edges whose ordinate range
  // meets it. bucket() is monotone (rounding included), so an edge spanning y (min <= y < max)
  // is listed in y's bucket: it is in every bucket from bucket(min) to bucket(max).
  std::size_t bucket(double y) const {
    const double f = (y - y_min) * inv_height_;
    if (!(f > 0)) return 0;
    if (f >= last_bucket_) return buckets_ - 1;
    // 0 < f < 4095: truncated through 32 bits, the same as to 64 (one instruction, not a dozen:
    // two of these an edge were most of fill_buckets()).
    return std::uint32_t(f);
  }
  void fill_buckets() const {
    // An edge is listed in every bucket it spans, so a line crossing c edges costs c entries a
    // bucket: an edge a bucket listed ~10 c entries (a traced field's fill cost more than all its
    // queries); one bucket per 8 edges keeps a query to ~8 + c edges.
    buckets_ = std::clamp<std::size_t>(edges_.size() / 8, 1, 4096);
    inv_height_ = y_max > y_min ? double(buckets_) / (y_max - y_min) : 0.0;
    last_bucket_ = double(buckets_ - 1);
    std::vector<std::uint32_t> counts(buckets_ + 1, 0);
    // Each edge's buckets [first, last] found once, counted, then kept for placing the edge (two
    // bucket() calls an edge, not four: they were most of this).
    thread_local std::vector<std::pair<std::uint32_t, std::uint32_t>> spans;
    spans.resize(edges_.size());
    for (std::size_t e = 0; e < edges_.size(); ++e) {
      const auto& [a, b] = edges_[e];
      const std::size_t first = bucket(std::min(a.y, b.y)), last = bucket(std::max(a.y, b.y));
      for (std::size_t k = first; k <= last; ++k) ++counts[k + 1];
      spans[e] = {std::uint32_t(first), std::uint32_t(last)};
    }
    for (std::size_t k = 0; k < buckets_; ++k) counts[k + 1] += counts[k];
    start_ = counts;
    items_.resize(counts.back());
    for (std::size_t e = 0; e < edges_.size(); ++e)
      for (std::uint32_t k = spans[e].first; k <= spans[e].second; ++k)
        items_[counts[k]++] = std::uint32_t(e);
  }

  std::vector<std::pair<Point2, Point2>> edges_;
  mutable std::size_t buckets_ = 0;  ///< 0 until at(y) is first asked
  mutable double inv_height_ = 0;
  mutable double last_bucket_ = 0;  ///< buckets_ - 1
  mutable std::vector<std::uint32_t> start_, items_;
};

// Half the width across a lane within which it sees a sample (lane_runs' coverage check); along
// it, its ends widened by kSeenAlongM. One expression for the check and for what it may skip.
inline double seen_half_width_m(double footprint_width_m) {
  return footprint_width_m / 2 + 1e-9;
}
inline constexpr double kSeenAlongM = 1e-6;

// A box holding every point a + (b - a) * t, t = i / n as rounded (coverage_samples()' samples
// of an edge): the edge's own box widened by 8 units of rounding u of its largest coordinate M per
// axis (the least normal double for underflow). Counted fully (b - a, t = i / n, their product,
// the sum, each rounded) a sample is within about 7uM of the exact point, so the widening covers
// even t = 1 with little to spare; the samples made (i < n) need none, for they lie at least
// |b - a| / n inside both ends, far more than their rounding (~3u |b - a|), and rounding is
// monotone: the widening is a guard, not a need.
inline std::pair<Point2, Point2> edge_samples_box(Point2 a, Point2 b) {
  constexpr double eight_u = 4 * std::numeric_limits<double>::epsilon();
  const double tiny = std::numeric_limits<double>::min();
  const double wx = eight_u * std::max(std::abs(a.x), std::abs(b.x)) + tiny;
  const double wy = eight_u * std::max(std::abs(a.y), std::abs(b.y)) + tiny;
  return {{std::min(a.x, b.x) - wx, std::min(a.y, b.y) - wy},
          {std::max(a.x, b.x) + wx, std::max(a.y, b.y) + wy}};
}

// Where the long lanes see: the points that a lane longer than the slivers' length sees, by the
// coverage check's own test (lane.y - half <= p.y <= lane.y + half, lane.x0 - kSeenAlongM <= p.x
// <= lane.x1 + kSeenAlongM, in those roundings). Per ordinate, the union of the long lanes'
// abscissa ranges (closed intervals, merged: no arithmetic, so exactly the union) over the rows
// within reach, kept while an ordinate asked next has the same rows within reach.
class LongLaneReach {
 public:
  /// Rows `ys` ascending; `lanes[k]` the lanes on ys[k]; a lane counts when x1 - x0 > min_length_m.
  LongLaneReach(const std::vector<double>& ys, const SpanRows& lanes, double half_m,
                double min_length_m)
      : ys_(ys), lanes_(lanes), half_(half_m), min_length_(min_length_m) {}

  /// The merged ranges [x0, x1] that the long lanes within reach of ordinate y see, ascending;
  /// valid until the next call.
  std::span<const Span> at(double y) {
    // The rows within reach stay [lo, hi) for y in (below_lo_, up_to_lo_] and [from_hi_,
    // below_hi_): a boundary's samples, one ordinate each, mostly ask the same rows again.
    if (!(y > below_lo_ && y <= up_to_lo_ && y >= from_hi_ && y < below_hi_)) refill(y);
    return {ranges_.data() + current_.first, ranges_.data() + current_.second};
  }
  /// Whether a long lane sees p.
  bool sees(Point2 p) {
    const std::span<const Span> in = at(p.y);
    // The last range starting at or before p.x (ranges are disjoint and ascending).
    const auto after = std::upper_bound(in.begin(), in.end(), p.x,
                                        [](double x, const Span& s) { return x < s.x0; });
    return after != in.begin() && p.x <= std::prev(after)->x1;
  }
  /// Whether the long lanes see every point of the box [lo, hi] (each point some long lane) (lo.x
  /// <= hi.x, lo.y <= hi.y), told by the rows within reach of ordinate y (at(y)'s: a caller asks
  /// them next anyway, so no rows are merged or found that sees() would not have): true where those
  /// rows are within reach of every ordinate of the box and one of their ranges holds its
  /// abscissae, so sees() is true at each of its points; else false.
  bool sees_all(Point2 lo, Point2 hi, double y) {
    const std::span<const Span> in = at(y);
    if (in.empty()) return false;  // no long lane within reach (most of some fields' boundary)
    // The rows within reach of y' are [first, last): first the first row with y' <= ys[k] + half,
    // last the first with y' < ys[k] - half; both rise with y'. So they include y's rows from
    // y' = ys[last - 1] - half (from_hi_) up to y' = ys[first] + half (up_to_lo_): there, each of
    // y's ranges lies within one of y''s.
    if (!(lo.y >= from_hi_ && hi.y <= up_to_lo_)) return false;
    const auto after = std::upper_bound(in.begin(), in.end(), lo.x,
                                        [](double x, const Span& s) { return x < s.x0; });
    return after != in.begin() && hi.x <= std::prev(after)->x1;
  }

 private:
  void refill(double y) {
    // Rows within reach: ys[k] - half <= y <= ys[k] + half. Both ends ascend with k (rounding
    // is monotone), so they are [lo, hi): lo the first row with y <= ys[lo] + half, hi the first
    // with y < ys[hi] - half.
    const auto lo = std::size_t(
        std::partition_point(ys_.begin(), ys_.end(), [&](double k) { return k + half_ < y; }) -
        ys_.begin());
    const auto hi = std::size_t(
        std::partition_point(ys_.begin(), ys_.end(), [&](double k) { return k - half_ <= y; }) -
        ys_.begin());
    const double inf = std::numeric_limits<double>::infinity();
    const std::size_t n = ys_.size();
    below_lo_ = lo > 0 ? ys_[lo - 1] + half_ : -inf;
    up_to_lo_ = lo < n ? ys_[lo] + half_ : inf;
    from_hi_ = hi > 0 ? ys_[hi - 1] - half_ : -inf;
    below_hi_ = hi < n ? ys_[hi] - half_ : inf;
    // Each [lo, hi) merged once: as y rises, lo and hi only rise, each step one of them, so the
    // rows within reach are told apart by lo + hi (the boundary's samples, in edge order, ask
    // the same rows again and again).
    if (memo_.empty()) memo_.assign(2 * n + 1, {1, 0});
    std::pair<std::uint32_t, std::uint32_t>& kept = memo_[lo + hi];
    if (kept.first > kept.second) kept = merge(lo, hi);
    current_ = kept;
  }
  // The long lanes' ranges of rows [lo, hi), merged, appended to ranges_: where they are.
  std::pair<std::uint32_t, std::uint32_t> merge(std::size_t lo, std::size_t hi) {
    const auto first = std::uint32_t(ranges_.size());
    for (std::size_t k = lo; k < hi; ++k)
      for (const Span& s : lanes_[k])
        if (s.x1 - s.x0 > min_length_) ranges_.push_back({s.x0 - kSeenAlongM, s.x1 + kSeenAlongM});
    const auto begin = ranges_.begin() + first;
    std::sort(begin, ranges_.end(), [](const Span& a, const Span& b) { return a.x0 < b.x0; });
    auto out = begin;
    for (auto i = begin; i != ranges_.end(); ++i) {
      if (out != begin && i->x0 <= std::prev(out)->x1)
        std::prev(out)->x1 = std::max(std::prev(out)->x1, i->x1);
      else
        *out++ = *i;
    }
    ranges_.erase(out, ranges_.end());
    return {first, std::uint32_t(ranges_.size())};
  }

  const std::vector<double>& ys_;
  const SpanRows& lanes_;
  double half_, min_length_;
  // The ordinates for which current_ holds: none until it is first filled (NaN compares false).
  double below_lo_ = std::numeric_limits<double>::quiet_NaN(), up_to_lo_ = below_lo_,
         from_hi_ = below_lo_, below_hi_ = below_lo_;
  std::vector<Span> ranges_;  ///< every merged union made, one after another
  std::vector<std::pair<std::uint32_t, std::uint32_t>>
      memo_;  ///< per lo + hi: in ranges_, or {1, 0}
  std::pair<std::uint32_t, std::uint32_t> current_{0, 0};
};

// Points the lanes must see, sorted by ordinate (then abscissa): the boundary every eighth of a
// spacing (vertices included) and the inside on rows a quarter of a spacing apart, a quarter along
// them. At most ~200,000: steps grow on very large areas. Into `samples` (its capacity kept: a
// direction search samples the area ~100 times, and fresh pages for each were a large part of a
// 10,000-vertex area's time). With `skip`, those a long lane sees are left out (the others in the
// same order): lane_runs' decisions never turn on them (see lane_runs). Defined in lane_runs.cpp.
void coverage_samples(const LaneScan& scan, double spacing_m, std::vector<Point2>& samples,
                      LongLaneReach* skip = nullptr);

// lane_runs() with its coverage check on every sample, those a long lane sees too, `see` scanned
// even where it is `fly` bit for bit, and the coverage lanes' unseen samples pruned whole after
// each lane: the reference that lane_runs' tests compare it with. Defined in lane_runs.cpp.
LaneRuns lane_runs_on_every_sample(const LaneRunArea& area, const LaneRunSettings& settings);

// Whether a turn between lane ends on neighbouring grid rows stays inside: no boundary edge
// crosses it and its middle is inside or on the boundary. Only the edges that reach into the band
// between the two rows can tell, so they are bucketed by band: O(edges in the band) a turn, not
// O(n) as a general visibility test (10,000-vertex outlines ask this ~10^5 times).
class Turns {
 public:
  Turns(const LaneScan& scan, const std::vector<double>& ys) {
    if (ys.empty()) return;
    // The bands' edges in one array (band b's from start_[b] to start_[b + 1], in edge order):
    // counted, then placed (a vector per band was most of this step's allocations). Each edge's
    // bands [first, end) are found once, kept for the placing.
    const auto& edges = scan.edges();
    thread_local std::vector<std::pair<std::size_t, std::size_t>> reach;
    reach.resize(edges.size());
    start_.assign(ys.size() + 1, 0);
    std::size_t near = 0;  // the last edge's first band
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const double lo = std::min(edges[e].first.y, edges[e].second.y);
      const double hi = std::max(edges[e].first.y, edges[e].second.y);
      // Band r spans [ys[r], ys[r + 1]]: the first band whose top reaches lo, up to the last whose
      // bottom is below hi (the tops ys[1...] by walk_lower_bound: a search per edge was most of
      // this).
      near = walk_lower_bound(ys.data() + 1, ys.size() - 1, lo, near);
      std::size_t end = near;
      for (; end + 1 < ys.size() && ys[end] <= hi; ++end) ++start_[end + 1];
      reach[e] = {near, end};
    }
    for (std::size_t b = 0; b < ys.size(); ++b) start_[b + 1] += start_[b];
    edges_.resize(start_.back());
    std::vector<std::size_t> next(start_.begin(), start_.end() - 1);
    for (std::size_t e = 0; e < edges.size(); ++e)
      for (std::size_t b = reach[e].first; b < reach[e].second; ++b) edges_[next[b]++] = edges[e];
    double scale = 0;
    for (const auto& [p, q] : edges)
      scale = std::max({scale, std::abs(p.x), std::abs(p.y), std::abs(q.x), std::abs(q.y)});
    skip_far_ = 64 * std::numeric_limits<double>::epsilon() * scale < 1e-9;
  }

  /// a on row `row`, b on the next, both in the rotated frame.
  bool inside(Point2 a, Point2 b, std::size_t row) const {
    const std::span<const std::pair<Point2, Point2>> edges(edges_.data() + start_[row],
                                                           edges_.data() + start_[row + 1]);
    const double tolerance = 1e-9 * (1 + geometry::distance(a, b));
    // Edges away from the turn are passed over without the tests below: they cannot pass them
    // (skip_far_: the coordinates are small enough, below ~7e4 m, for the proofs' rounding bound).
    // The rounding of a side value (segments_cross_clearly: cross(d - o, x - o) / |d - o|) and of
    // a computed distance (distance_to_segment) is at most ~30 eps S, S the edges' largest
    // coordinate (a turn joins lane ends, inside the area's box): below 64 eps S < 1e-9 <=
    // tolerance. A crossing "clearly" needs |side| > tolerance, so each computed sign is the exact
    // one: the exact segments then cross, and their abscissa ranges meet; an edge whose range
    // misses the turn's is never one. An edge whose box lies farther than 2 tolerance from the
    // middle is farther than that from it exactly, so its computed distance is above the
    // tolerance: only the crossing count is asked of it.
    const bool skip = skip_far_;
    const double x_lo = std::min(a.x, b.x), x_hi = std::max(a.x, b.x);
    for (const auto& [p, q] : edges) {
      if (skip && (std::max(p.x, q.x) < x_lo || std::min(p.x, q.x) > x_hi)) continue;
      if (geometry::segments_cross_clearly(a, b, p, q, tolerance)) return false;
    }
    // The middle: on an edge counts as inside (closed area), else by crossings to the right.
    const Point2 m = (a + b) * 0.5;
    const double far = 2 * tolerance;
    bool in = false;
    for (const auto& [p, q] : edges) {
      const bool away = skip && (std::max(p.x, q.x) < m.x - far || std::min(p.x, q.x) > m.x + far ||
                                 std::max(p.y, q.y) < m.y - far || std::min(p.y, q.y) > m.y + far);
      if (!away && geometry::distance_to_segment(m, p, q) <= tolerance) return true;
      if ((p.y <= m.y) != (q.y <= m.y) && p.x + (m.y - p.y) * (q.x - p.x) / (q.y - p.y) > m.x)
        in = !in;
    }
    return in;
  }

 private:
  std::vector<std::size_t> start_;
  std::vector<std::pair<Point2, Point2>> edges_;
  bool skip_far_ = false;  ///< whether inside() may pass over the edges away from a turn
};

// Points sorted by ordinate, then abscissa (lane_runs' coverage samples). A box walks the points
// in its ordinate range, but a long row of equal ordinate (the inside's rows hold most of the
// samples) is asked for the box's abscissae by search instead of walked whole: a row crossed by
// several holes holds several lanes, and each lane walked every sample of every row within its
// reach. The boundary's samples (rows of one) are walked as before.
class SampleRows {
 public:
  /// `sorted` is kept by reference and must stay as it is. block_m > 0: the points outside long
  /// rows are also kept by bands of that height, by abscissa within one, for any_order_in().
  explicit SampleRows(const std::vector<Point2>& sorted, double block_m = 0) : points_(sorted) {
    const std::size_t n = points_.size();
    for (std::size_t i = 0; i < n;) {
      const double y = points_[i].y;
      std::size_t j = i + 1;
      if (i + kLongRow <= n && points_[i + kLongRow - 1].y == y) {
        // A long row (sorted: every point between is on it too): its end by search, not by
        // walking its ~50 points (every sample was walked here, once a direction).
        j = std::size_t(std::upper_bound(points_.begin() + std::ptrdiff_t(i + kLongRow),
                                         points_.end(), y,
                                         [](double v, Point2 p) { return v < p.y; }) -
                        points_.begin());
        long_rows_.push_back({i, j});
      } else {
        while (j < n && points_[j].y == y) ++j;
      }
      i = j;
    }
    if (block_m > 0 && !points_.empty()) fill_blocks(block_m);
  }

  /// f(i) for every point i with y_lo <= y <= y_hi and x_lo <= x <= x_hi, in increasing i.
  template <typename F>
  void each_in(double y_lo, double y_hi, double x_lo, double x_hi, F f) const {
    runs_in(
        y_lo, y_hi, x_lo, x_hi,
        [&](std::size_t first, std::size_t last) {
          for (std::size_t i = first; i < last; ++i) f(i);
        },
        f);
  }

  /// each_in()'s points, those of a long row as one run: on_run(first, last) for the points
  /// [first, last) of a long row inside the box (never empty), on_point(i) for each other point
  /// inside; every point once, in increasing i. A caller counting points per box adds a run in
  /// O(1) (lane_runs' grid lanes each see ~10 rows of ~50 samples).
  template <typename Run, typename Point>
  void runs_in(double y_lo, double y_hi, double x_lo, double x_hi, Run on_run,
               Point on_point) const {
    auto i = std::size_t(std::lower_bound(points_.begin(), points_.end(), y_lo,
                                          [](Point2 p, double y) { return p.y < y; }) -
                         points_.begin());
    // The first point at or above y_lo starts its row: the next long row starts there or later.
    auto row = std::lower_bound(long_rows_.begin(), long_rows_.end(), i,
                                [](const Row& r, std::size_t k) { return r.begin < k; });
    const std::size_t n = points_.size();
    const std::size_t next_long = row == long_rows_.end() ? n : row->begin;
    for (std::size_t stop = next_long; i < n && points_[i].y <= y_hi;) {
      if (i == stop) {  // a long row: its points from x_lo on, up to x_hi
        row_run_in(*row, x_lo, x_hi, on_run);
        i = row->end;
        ++row;
        stop = row == long_rows_.end() ? n : row->begin;
        continue;
      }
      if (points_[i].x >= x_lo && points_[i].x <= x_hi) on_point(i);
      ++i;
    }
  }

  /// runs_in()'s runs and points in no particular order: the long rows by search, the other
  /// points by band and abscissa (a field's boundary samples, one per row, were walked whole
  /// across the box's ordinates: a traced outline's thousand of them, for every lane). runs_in()
  /// where no bands were made.
  template <typename Run, typename Point>
  void any_order_in(double y_lo, double y_hi, double x_lo, double x_hi, Run on_run,
                    Point on_point) const {
    if (block_start_.empty()) return runs_in(y_lo, y_hi, x_lo, x_hi, on_run, on_point);
    if (!(y_lo <= y_hi)) return;
    for (auto row = std::lower_bound(long_rows_.begin(), long_rows_.end(), y_lo,
                                     [&](const Row&r, double y) { return points_[r.begin].y < y; });
         row != long_rows_.end() && points_[row->begin].y <= y_hi; ++row)
      row_run_in(*row, x_lo, x_hi, on_run);
    const std::size_t blocks = block_start_.size() - 1;
    const std::size_t b_lo = block(y_lo), b_hi = block(y_hi);
    for (std::size_t b = b_lo; b <= b_hi && b < blocks; ++b) {
      const auto first = loose_.begin() + std::ptrdiff_t(block_start_[b]);
      const auto last = loose_.begin() + std::ptrdiff_t(block_start_[b + 1]);
      for (auto it =
               std::lower_bound(first, last, x_lo, [](const Loose&p, double x) { return p.x < x; });
           it != last && it->x <= x_hi; ++it)
        if (it->y >= y_lo && it->y <= y_hi) on_point(std::size_t(it->index));
    }
  }

 private:
  static constexpr std::size_t kLongRow = 16;
  struct Row {
    std::size_t begin, end;
  };
  /// The run of a long row's points from x_lo on, up to x_hi (the row sorted by x), if any.
  template <typename Run>
  void row_run_in(const Row& row, double x_lo, double x_hi, Run& on_run) const {
    const auto first = points_.begin() + std::ptrdiff_t(row.begin);
    const auto last = points_.begin() + std::ptrdiff_t(row.end);
    const auto from =
        std::lower_bound(first, last, x_lo, [](Point2 p, double x) { return p.x < x; });
    const auto to = std::upper_bound(from, last, x_hi, [](double x, Point2 p) { return x < p.x; });
    if (from < to) on_run(std::size_t(from - points_.begin()), std::size_t(to - points_.begin()));
  }
  struct Loose {
    double x, y;
    std::size_t index;
  };
  // Band of an ordinate: monotone (a point's band is found again for any y_lo <= y <= y_hi: the
  // bands from block(y_lo) to block(y_hi) hold it), clamped to the bands made.
  std::size_t block(double y) const {
    const double f = (y - block_y0_) * inv_block_;
    if (!(f > 0)) return 0;
    if (f >= double(block_start_.size() - 2)) return block_start_.size() - 2;
    return std::size_t(f);
  }
  void fill_blocks(double block_m) {
    const double height = points_.back().y - points_.front().y;
    // At most ~4 bands a point: a huge area's bands grow rather than outnumber its points.
    const double count = std::min(std::floor(height / block_m) + 1, 4.0 * double(points_.size()));
    block_y0_ = points_.front().y;
    inv_block_ = height > 0 ? (count - 1) / height : 0.0;
    block_start_.assign(std::size_t(count) + 1, 0);
    // Sized once (grown by doubling, the copies were a fifth of this).
    std::size_t on_rows = 0;
    for (const Row& r : long_rows_) on_rows += r.end - r.begin;
    loose_.reserve(points_.size() - on_rows);
    auto row = long_rows_.begin();
    for (std::size_t i = 0; i < points_.size(); ++i) {
      if (row != long_rows_.end() && i == row->begin) {
        i = row->end - 1;
        ++row;
        continue;
      }
      loose_.push_back({points_[i].x, points_[i].y, i});
    }
    // Points ascend by ordinate, so bands ascend along loose_: each band's stretch sorted by x.
    for (const Loose& p : loose_) ++block_start_[block(p.y) + 1];
    for (std::size_t b = 0; b + 1 < block_start_.size(); ++b)
      block_start_[b + 1] += block_start_[b];
    for (std::size_t b = 0; b + 1 < block_start_.size(); ++b)
      std::sort(loose_.begin() + std::ptrdiff_t(block_start_[b]),
                loose_.begin() + std::ptrdiff_t(block_start_[b + 1]),
                [](const Loose& p, const Loose& q) { return p.x < q.x; });
  }
  const std::vector<Point2>& points_;
  std::vector<Row> long_rows_;  ///< rows of at least kLongRow points of one ordinate, ascending
  std::vector<Loose> loose_;    ///< the other points, by band, then abscissa
  std::vector<std::size_t> block_start_;  ///< band b's in loose_ from [b] to [b + 1]; or none
  double block_y0_ = 0, inv_block_ = 0;
};

}  // namespace swath::planning::detail
