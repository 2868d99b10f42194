#include "swath/planning/sweep.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "lane_scan.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/geometry/turn.hpp"

namespace swath::planning {

using geometry::Point2;

Point2 rotate(Point2 p, double angle_deg) {
  // The turns by the last two angles asked (by their bits: -0 and 0 differ in the sine's sign)
  // are kept: callers turn thousands of points by one angle and back. The same values as taken
  // anew (geometry::Turn).
  struct Known {
    std::uint64_t angle_bits = 0;
    geometry::Turn turn{0.0};
  };
  thread_local Known turns[2];
  thread_local int known = 0, newest = 0;
  const auto bits = std::bit_cast<std::uint64_t>(angle_deg);
  for (int k = 0; k < known; ++k)
    if (turns[k].angle_bits == bits) return turns[k].turn(p);
  newest = known < 2 ? known++ : 1 - newest;
  turns[newest] = {bits, geometry::Turn(angle_deg)};
  return turns[newest].turn(p);
}

std::vector<double> line_offsets(double y_min, double y_max, double spacing, double footprint,
                                 LinePlacement placement) {
  const double height = y_max - y_min;
  std::vector<double> ys;
  if (placement == LinePlacement::centered) {
    // Fewest n with (n - 1) spacing + footprint >= height; the relative slack absorbs rounding
    // so that an exact fit does not cost a line.
    const double needed = (height - footprint) / spacing;
    const auto n = static_cast<std::size_t>(needed <= 0 ? 1 : std::ceil(needed - 1e-9) + 1);
    const double first = y_min + height / 2 - static_cast<double>(n - 1) * spacing / 2;
    for (std::size_t i = 0; i < n; ++i) ys.push_back(first + static_cast<double>(i) * spacing);
    return ys;
  }
  // Paper: y = min_y + step/2; while y <= max_y { line; y += step, or for the last line
  // y = min(y + step/2, max_y) }. Read literally the loop never ends once y reaches max_y; the
  // meaning is one last line and stop.
  double y = std::min(y_min + spacing / 2, y_max);
  while (true) {
    ys.push_back(y);
    if (y + spacing >= y_max) {
      if (y < y_max) ys.push_back(std::min(y + spacing / 2, y_max));
      return ys;
    }
    y += spacing;
  }
}

namespace {

// Strip k spans [lo, hi]: between the midpoints to its neighbours (strip rule) or the line's own
// ordinate (inside rule), with the x extent of the area within it and where it is reached.
struct Strip {
  double lo, hi;
  double x_lo = std::numeric_limits<double>::infinity();
  double x_hi = -std::numeric_limits<double>::infinity();
  double y_at_x_lo = 0.0, y_at_x_hi = 0.0;  // where the extremes are reached
};

// An edge clipped to [y0, y1] of a strip widens its x extent.
void widen(Strip& strip, Point2 a, Point2 b, double y0, double y1) {
  auto x_at = [&](double y) {
    return b.y == a.y ? a.x : a.x + (b.x - a.x) * (y - a.y) / (b.y - a.y);
  };
  for (const auto& [x, y] :
       {std::pair{b.y == a.y ? a.x : x_at(y0), y0}, std::pair{b.y == a.y ? b.x : x_at(y1), y1}}) {
    if (x < strip.x_lo) {
      strip.x_lo = x;
      strip.y_at_x_lo = y;
    }
    if (x > strip.x_hi) {
      strip.x_hi = x;
      strip.y_at_x_hi = y;
    }
  }
}

// Edge i of `ring`, lower end first.
std::pair<Point2, Point2> lower_first(const geometry::Ring& ring, std::size_t i) {
  Point2 a = ring[i], b = ring[i + 1 < ring.size() ? i + 1 : 0];
  if (a.y > b.y) std::swap(a, b);
  return {a, b};
}

// The edge a -> b (a below b), clipped to each strip it meets, widens that strip's x extent (and,
// with `points`, the point strip of the same index clipped to its own ordinate): from `first`, the
// first strip whose top reaches the edge, up to the first above it (the strips' bottoms ascend).
void widen_met(Point2 a, Point2 b, std::vector<Strip>& strips, std::size_t first,
               std::vector<Strip>* points) {
  const auto clipped = [&](Strip& strip) {
    const double y0 = std::max(a.y, strip.lo);
    const double y1 = std::min(b.y, strip.hi);
    if (!(y0 > y1)) widen(strip, a, b, y0, y1);
  };
  for (std::size_t k = first; k < strips.size() && strips[k].lo <= b.y; ++k) {
    if (points) clipped((*points)[k]);
    clipped(strips[k]);
  }
}

// Whether widen_met(a, b, strips, first, points), with `first` the first strip whose top reaches
// a.y (tops ascending), widens strip k alone, clipped to the edge itself (no point strip): the
// edge lies within strip k, the strip before it tops out below the edge and the one after it
// starts above. Strip k's bounds are kept while it is asked again (the last edge's strip is most
// edges'), infinities where there is no strip before or after it or no point strip: they refuse
// only infinite ordinates, which the walk then takes. A NaN ordinate fails every test.
class WithinOne {
 public:
  WithinOne(const std::vector<Strip>& strips, const std::vector<Strip>* points)
      : strips_(strips), points_(points) {}
  bool operator()(Point2 a, Point2 b, std::size_t k) {
    if (k != k_) take(k);
    return lo_ <= a.y && b.y <= hi_ && below_ < a.y && above_ > b.y &&
           (point_hi_ < a.y || point_lo_ > b.y);
  }

 private:
  void take(std::size_t k) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    k_ = k;
    if (k >= strips_.size()) {
      lo_ = std::numeric_limits<double>::quiet_NaN();  // no strip: refuses every edge
      return;
    }
    lo_ = strips_[k].lo;
    hi_ = strips_[k].hi;
    below_ = k > 0 ? strips_[k - 1].hi : -inf;
    above_ = k + 1 < strips_.size() ? strips_[k + 1].lo : inf;
    point_lo_ = points_ ? (*points_)[k].lo : inf;
    point_hi_ = points_ ? (*points_)[k].hi : -inf;
  }

  const std::vector<Strip>& strips_;
  const std::vector<Strip>* points_;
  std::size_t k_ = static_cast<std::size_t>(-1);
  double lo_ = 0, hi_ = 0, below_ = 0, above_ = 0, point_lo_ = 0, point_hi_ = 0;
};

// The walk of the turned rings' edges that finds the strips' extents.
class StripWalk {
 public:
  StripWalk(const std::vector<geometry::Ring>& rings, std::size_t ring_count, double y_min,
            double y_max)
      : rings_(rings), ring_count_(ring_count), y_min_(y_min), y_max_(y_max) {}

  // Into `strips` (its capacity kept), for offsets[0, count); with `points` (whole strips only,
  // each holding its own offset), the point strips at the offsets into it in the same walk: an
  // edge that meets an offset meets the whole strip around it, and each strip's edges come in ring
  // order either way, so the same extents as walked on their own.
  void operator()(const double* offsets, std::size_t count, bool whole_strip,
                  std::vector<Strip>& strips, std::vector<Strip>* points = nullptr) const {
    strips.clear();
    if (points) {
      points->clear();
      for (std::size_t k = 0; k < count; ++k) points->push_back({offsets[k], offsets[k]});
    }
    for (std::size_t k = 0; k < count; ++k) {
      if (!whole_strip) {
        strips.push_back({offsets[k], offsets[k]});
      } else {
        strips.push_back({k == 0 ? y_min_ : (offsets[k - 1] + offsets[k]) / 2,
                          k + 1 == count ? y_max_ : (offsets[k] + offsets[k + 1]) / 2});
      }
    }
    // The first strip whose top reaches y: std::lower_bound's, walked to from the last edge's
    // (neighbouring edges share a vertex: a few steps, not a search per edge) where the tops
    // ascend, as they do for the grid's ordinates (NaN-free: `<=` fails on NaN).
    bool tops_ascend = true;
    for (std::size_t k = 0; k + 1 < strips.size(); ++k)
      tops_ascend = tops_ascend && strips[k].hi <= strips[k + 1].hi;
    std::size_t near = 0;
    const auto first_reaching = [&](double y) {
      if (!tops_ascend)
        return std::size_t(std::lower_bound(strips.begin(), strips.end(), y,
                                            [](const Strip& st, double v) { return st.hi < v; }) -
                           strips.begin());
      near = detail::walk_lower_bound_by(strips.data(), strips.size(), y, near,
                                         [](const Strip& st) { return st.hi; });
      return near;
    };
    if (!whole_strip && !points && tops_ascend) {
      walk_points(strips, first_reaching);
      return;
    }
    // Each edge, clipped to every strip it meets, widens that strip's x extent. Most edges (metres
    // long; the strips a lane spacing high) lie within the last edge's strip and meet no point
    // strip: that one is widened without the walk to it and the loop over the strips (WithinOne:
    // the same strip, clipped the same; a third of the edges of the split's pieces still cross a
    // strip's bound or its lane).
    WithinOne within_one(strips, points);
    for (std::size_t r = 0; r < ring_count_; ++r) {
      const geometry::Ring& ring = rings_[r];
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const auto [a, b] = lower_first(ring, i);
        if (tops_ascend && within_one(a, b, near))
          widen(strips[near], a, b, a.y, b.y);
        else
          widen_met(a, b, strips, first_reaching(a.y), points);
      }
    }
  }

  // The walk above on point strips (lo = hi) in ascending order (the inside rule's lanes, a
  // reach's sides): most edges meet none of them, so the edges go in blocks of eight, and a block
  // whose ordinates' range holds no strip's ordinate is passed over (none of its edges meets a
  // strip; the rest are walked in the same order, so the same extents; an edge with a NaN ordinate
  // meets none either way). Edge by edge, the reaches' sides were a quarter of a split plan's
  // walks.
  template <typename FirstReaching>
  void walk_points(std::vector<Strip>& strips, FirstReaching& first_reaching) const {
    constexpr std::size_t kBlock = 8;
    for (std::size_t r = 0; r < ring_count_; ++r) {
      const geometry::Ring& ring = rings_[r];
      const std::size_t n = ring.size();
      for (std::size_t i0 = 0; i0 < n; i0 += kBlock) {
        const std::size_t i1 = std::min(i0 + kBlock, n);
        double lo = ring[i0].y, hi = lo;
        for (std::size_t i = i0 + 1; i <= i1; ++i) {
          const double y = ring[i < n ? i : 0].y;
          lo = std::min(lo, y);
          hi = std::max(hi, y);
        }
        const std::size_t k = first_reaching(lo);
        if (k == strips.size() || strips[k].lo > hi) continue;
        for (std::size_t i = i0; i < i1; ++i) {
          const auto [a, b] = lower_first(ring, i);
          widen_met(a, b, strips, first_reaching(a.y), nullptr);
        }
      }
    }
  }

  double y_min() const { return y_min_; }
  double y_max() const { return y_max_; }

 private:
  const std::vector<geometry::Ring>& rings_;
  std::size_t ring_count_;
  double y_min_, y_max_;
};

// A protrusion's extreme (its ordinate) and the side of the lanes it reaches out to.
struct Reach {
  double y;
  bool high;
};

// The protrusions that no lane's footprint reaches already: where a whole strip reaches further
// out than its lane by more than `slack`, and no lane within half a footprint sees that extreme.
void unseen_reaches(const std::vector<double>& ys, const std::vector<Strip>& strips,
                    const std::vector<Strip>& whole, bool ascending, double slack, double half,
                    std::vector<Reach>& reaches) {
  // On ascending ordinates y - ys[j] does not increase with j (rounding is monotone), so the
  // lanes within half a footprint are one run of them, found by search: the same lanes asked as
  // by a scan of all (one per protrusion was a sixth of a split plan's sweeps).
  auto seen = [&](double x, double y) {
    const auto sees = [&](std::size_t j) {
      return x >= strips[j].x_lo - slack && x <= strips[j].x_hi + slack;
    };
    if (!ascending) {
      for (std::size_t j = 0; j < ys.size(); ++j)
        if (std::abs(y - ys[j]) <= half && sees(j)) return true;
      return false;
    }
    const auto first =
        std::partition_point(ys.begin(), ys.end(), [&](double yj) { return y - yj > half; });
    for (auto j = first; j != ys.end() && y - *j >= -half; ++j)
      if (sees(std::size_t(j - ys.begin()))) return true;
    return false;
  };
  reaches.clear();
  for (std::size_t k = 0; k < ys.size(); ++k) {
    if (whole[k].x_hi > strips[k].x_hi + slack && !seen(whole[k].x_hi, whole[k].y_at_x_hi))
      reaches.push_back({whole[k].y_at_x_hi, true});
    if (whole[k].x_lo < strips[k].x_lo - slack && !seen(whole[k].x_lo, whole[k].y_at_x_lo))
      reaches.push_back({whole[k].y_at_x_lo, false});
  }
}

// Where a reach's lane goes: just below or just above its extreme (`sides`, below first), on the
// side that reaches further out; `below` and `above` are the point strips of the two. 1: above.
std::size_t side_of(const Reach& r, const Strip& below, const Strip& above) {
  const bool up = r.high ? above.x_hi >= below.x_hi : above.x_lo <= below.x_lo;
  return up ? 1 : 0;
}

// The two ordinates a reach's lane may take: `inset` below and above its extreme, inside the area.
std::array<double, 2> sides_of(double y, double inset, const StripWalk& walk) {
  return {std::max(y - inset, walk.y_min() + inset), std::min(y + inset, walk.y_max() - inset)};
}

// The reaches' lanes added to the grid's (`ys`, `strips`), a walk per reach, then all walked
// again: for ordinates the shared walk below does not take (unsorted, zero, non-finite).
void add_reach_lanes_walked(const StripWalk& walk, const std::vector<Reach>& reaches, double inset,
                            std::vector<double>& ys, std::vector<Strip>& strips) {
  thread_local std::vector<Strip> at;
  thread_local std::vector<double> extra;
  extra.clear();
  for (const Reach& r : reaches) {
    const std::array<double, 2> sides = sides_of(r.y, inset, walk);
    walk(sides.data(), 2, false, at);
    extra.push_back(sides[side_of(r, at[0], at[1])]);
  }
  std::vector<double> more = ys;
  more.insert(more.end(), extra.begin(), extra.end());
  std::sort(more.begin(), more.end());
  more.erase(std::unique(more.begin(), more.end()), more.end());
  ys = std::move(more);
  walk(ys.data(), ys.size(), false, strips);
}

// The same, every reach's two sides asked in one walk. A point strip's extent is the fold, in
// ring order, of the edges that meet its ordinate: the walk skips only strips an edge cannot
// meet, so each strip's extent is the same whatever strips are asked beside it, provided the walk
// finds them all (ordinates ascending; NaN-free). So the sides of all reaches are asked in one
// walk, sorted, and the lanes at the grid's ordinates keep the extents found for them.
void add_reach_lanes_shared(const StripWalk& walk, const std::vector<Reach>& reaches, double inset,
                            std::vector<double>& ys, std::vector<Strip>& strips) {
  thread_local std::vector<std::pair<double, std::size_t>> asked;  // ordinate, 2 reach + up
  thread_local std::vector<double> asked_y;
  thread_local std::vector<std::size_t> rank;  // asked side -> its strip in `at`
  thread_local std::vector<Strip> at;
  asked.clear();
  for (std::size_t i = 0; i < reaches.size(); ++i) {
    const std::array<double, 2> sides = sides_of(reaches[i].y, inset, walk);
    asked.push_back({sides[0], 2 * i});
    asked.push_back({sides[1], 2 * i + 1});
  }
  std::sort(asked.begin(), asked.end());
  asked_y.clear();
  rank.resize(asked.size());
  for (std::size_t j = 0; j < asked.size(); ++j) {
    asked_y.push_back(asked[j].first);
    rank[asked[j].second] = j;
  }
  walk(asked_y.data(), asked_y.size(), false, at);
  // The grid's lanes and the chosen sides', by ordinate, equal ones once (equal ordinates have
  // equal bits here, so equal extents: which one is kept does not matter).
  thread_local std::vector<std::pair<double, Strip>> lanes;
  lanes.clear();
  for (std::size_t k = 0; k < ys.size(); ++k) lanes.push_back({ys[k], strips[k]});
  bool zero = false;
  for (std::size_t i = 0; i < reaches.size(); ++i) {
    const std::size_t up = side_of(reaches[i], at[rank[2 * i]], at[rank[2 * i + 1]]);
    const std::size_t j = rank[2 * i + up];
    lanes.push_back({asked_y[j], at[j]});
    zero = zero || asked_y[j] == 0;
  }
  std::sort(lanes.begin(), lanes.end(),
            [](const auto& u, const auto& v) { return u.first < v.first; });
  lanes.erase(std::unique(lanes.begin(), lanes.end(),
                          [](const auto& u, const auto& v) { return u.first == v.first; }),
              lanes.end());
  ys.clear();
  strips.clear();
  for (const auto& [y, strip] : lanes) {
    ys.push_back(y);
    strips.push_back(strip);
  }
  // 0 and -0 are one ordinate to the sort and unique: such lanes are walked, as the walk above
  // would not find them in order.
  if (zero) walk(ys.data(), ys.size(), false, strips);
}

// Lanes for the protrusions no lane's footprint reaches (SweepSettings::fill_protrusions), added
// to `ys` and `strips`; `whole` holds the whole strips around the lanes.
void fill_protrusions(const StripWalk& walk, const SweepSettings& s, bool ascending,
                      std::vector<double>& ys, std::vector<Strip>& strips,
                      const std::vector<Strip>& whole) {
  const double slack = 0.02 * s.line_spacing_m;
  // The extreme may lie on an edge along the lanes, where the extent jumps: the lane goes just
  // off it, on the side that reaches out (never on the edge: it would run along the boundary).
  const double inset = std::min(1e-3 * s.line_spacing_m, (walk.y_max() - walk.y_min()) / 4);
  thread_local std::vector<Reach> reaches;
  unseen_reaches(ys, strips, whole, ascending, slack, s.footprint_width_m / 2, reaches);
  if (reaches.empty()) return;
  // Zeros are left to the walks: 0 and -0 are one ordinate to the sort and unique below.
  const auto plain = [](double y) { return std::isfinite(y) && y != 0; };
  bool shared = ascending;
  for (const double y : ys) shared = shared && plain(y);
  for (const Reach& r : reaches) shared = shared && std::isfinite(r.y);
  if (shared)
    add_reach_lanes_shared(walk, reaches, inset, ys, strips);
  else
    add_reach_lanes_walked(walk, reaches, inset, ys, strips);
}

// The lanes' ordinates: the area's own grid, or the given ordinates within [y_min, y_max] (the
// middle one where none is).
std::vector<double> lane_ordinates(const SweepSettings& s, double y_min, double y_max) {
  if (s.ordinates.empty())
    return line_offsets(y_min, y_max, s.line_spacing_m, s.footprint_width_m, s.placement);
  std::vector<double> ys;
  const auto inside = [&](double y) { return y >= y_min && y <= y_max; };
  ys.reserve(std::size_t(std::count_if(s.ordinates.begin(), s.ordinates.end(), inside)));
  for (double y : s.ordinates)
    if (inside(y)) ys.push_back(y);
  if (ys.empty()) ys.push_back((y_min + y_max) / 2);
  return ys;
}

// Whether the lanes' strips and the whole strips can be found in one walk: it finds every strip an
// edge meets (ascending tops) and each whole strip holds its lane's ordinate (so on the area's own
// or given ascending ordinates inside it).
bool one_walk_finds_both(const std::vector<double>& ys, double y_min, double y_max) {
  for (std::size_t k = 0; k < ys.size(); ++k) {
    const double lo = k == 0 ? y_min : (ys[k - 1] + ys[k]) / 2;
    const double hi = k + 1 == ys.size() ? y_max : (ys[k] + ys[k + 1]) / 2;
    const double next_hi = k + 2 < ys.size() ? (ys[k + 1] + ys[k + 2]) / 2 : y_max;
    if (!(lo <= ys[k] && ys[k] <= hi && (k + 1 == ys.size() || hi <= next_hi))) return false;
  }
  return true;
}

}  // namespace

namespace {

// Whether p lies in the keep-out rings (even-odd over outer rings and their holes) or on one.
bool in_or_on(Point2 p, const std::vector<geometry::Ring>& keep_out) {
  bool inside = false;
  for (const geometry::Ring& ring : keep_out) {
    const geometry::Containment c = geometry::locate_point(p, ring);
    if (c == geometry::Containment::on_boundary) return true;
    if (c == geometry::Containment::inside) inside = !inside;
  }
  return inside;
}

// The end of the turnaround from `from` (the line's own end) towards `to`: `to` where the segment
// meets no keep-out ring, else the first point it meets one (`from` itself when it lies in one).
Point2 turnaround_end(Point2 from, Point2 to, const std::vector<geometry::Ring>& keep_out) {
  if (in_or_on(from, keep_out)) return from;
  const double x_lo = std::min(from.x, to.x), x_hi = std::max(from.x, to.x);
  const double y_lo = std::min(from.y, to.y), y_hi = std::max(from.y, to.y);
  Point2 end = to;
  double end_m = std::numeric_limits<double>::infinity();
  for (const geometry::Ring& ring : keep_out)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point2 a = ring[i], b = ring[(i + 1) % ring.size()];
      // An edge whose box misses the segment's cannot meet it (no predicate needed).
      if (std::max(a.x, b.x) < x_lo || std::min(a.x, b.x) > x_hi || std::max(a.y, b.y) < y_lo ||
          std::min(a.y, b.y) > y_hi || !geometry::segments_intersect(from, to, a, b))
        continue;
      const Point2 q = geometry::segments_common_point(from, to, a, b);
      const double q_m = geometry::distance(from, q);
      if (q_m < end_m) end_m = q_m, end = q;
    }
  return end;
}

}  // namespace

void keep_turnarounds_out(std::vector<SweepLine>& lines, double turnaround_m,
                          const std::vector<geometry::Ring>& keep_out) {
  if (keep_out.empty() || !(turnaround_m > 0)) return;
  for (SweepLine& l : lines) {
    const double length_m = geometry::distance(l.start, l.end);
    if (!(length_m > 0)) continue;
    // A line of no length of its own (a point lane) is its two turnarounds from its middle.
    const Point2 d = (l.end - l.start) * (std::min(turnaround_m, length_m / 2) / length_m);
    const Point2 first = l.start + d, last = l.end - d;  // the line's own ends
    const Point2 start = turnaround_end(first, l.start, keep_out);
    const Point2 end = turnaround_end(last, l.end, keep_out);
    l.start = start;
    l.end = end;
  }
}

Sweep plan_sweep(const geometry::Polygon& area, const SweepSettings& s) {
  if (!(s.line_spacing_m > 0) || !(s.footprint_width_m >= s.line_spacing_m) ||
      !(s.turnaround_m >= 0))
    throw std::invalid_argument(
        "plan_sweep: need 0 < spacing <= footprint width and turnaround >= 0");
  Sweep sweep;
  sweep.angle_deg = std::fmod(std::fmod(s.angle_deg, 180.0) + 180.0, 180.0);

  // Work in a frame where the lines are horizontal. The buffers are the thread's, their capacity
  // kept: split plans sweep every piece of a decomposition at every direction (~18,000 sweeps of a
  // few vertices each at 100 vertices and 50 holes), and their allocations were a third of it.
  thread_local std::vector<geometry::Ring> rings;
  const geometry::Turn to_lanes(-sweep.angle_deg);
  const std::size_t ring_count = geometry::ring_count(area);
  if (rings.size() < ring_count) rings.resize(ring_count);
  double y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
  for (std::size_t r = 0; r < ring_count; ++r) {
    geometry::Ring& ring = rings[r];
    ring.clear();
    for (const Point2& p : geometry::ring_at(area, r)) {
      ring.push_back(to_lanes(p));
      y_min = std::min(y_min, ring.back().y);
      y_max = std::max(y_max, ring.back().y);
    }
  }
  sweep.height_m = y_max - y_min;
  std::vector<double> ys = lane_ordinates(s, y_min, y_max);
  const StripWalk walk(rings, ring_count, y_min, y_max);

  thread_local std::vector<Strip> strips, whole;
  bool ascending = true;
  for (std::size_t k = 0; k + 1 < ys.size(); ++k) ascending = ascending && ys[k] <= ys[k + 1];
  const bool fill = s.segments == SegmentRule::inside && s.fill_protrusions && !ys.empty();
  if (fill && ascending && one_walk_finds_both(ys, y_min, y_max)) {
    walk(ys.data(), ys.size(), true, whole, &strips);
  } else {
    walk(ys.data(), ys.size(), s.segments == SegmentRule::strip, strips);
    if (fill) walk(ys.data(), ys.size(), true, whole);
  }
  if (fill) fill_protrusions(walk, s, ascending, ys, strips, whole);
  sweep.lines.reserve(strips.size());
  for (std::size_t k = 0; k < strips.size(); ++k) {
    if (strips[k].x_lo > strips[k].x_hi) continue;
    sweep.lines.push_back({rotate({strips[k].x_lo - s.turnaround_m, ys[k]}, sweep.angle_deg),
                           rotate({strips[k].x_hi + s.turnaround_m, ys[k]}, sweep.angle_deg)});
  }
  return sweep;
}

std::vector<SweepLine> zigzag(const Sweep& sweep, bool top_first, bool reverse_first) {
  std::vector<SweepLine> out;
  const std::size_t n = sweep.lines.size();
  for (std::size_t i = 0; i < n; ++i) {
    SweepLine line = sweep.lines[top_first ? n - 1 - i : i];
    if ((i % 2 == 1) != reverse_first) std::swap(line.start, line.end);
    out.push_back(line);
  }
  return out;
}

std::vector<SweepLine> order_lines(const Sweep& sweep, StartCorner start,
                                   std::optional<Point2> home) {
  if (sweep.lines.empty()) return {};
  if (start == StartCorner::nearest_home && !home)
    throw std::invalid_argument("order_lines: nearest_home needs a home point");
  auto score = [&](const std::vector<SweepLine>& v) {
    const Point2 p = v.front().start;
    switch (start) {
      case StartCorner::sw:
        return p.x + p.y;
      case StartCorner::se:
        return -p.x + p.y;
      case StartCorner::nw:
        return p.x - p.y;
      case StartCorner::ne:
        return -p.x - p.y;
      case StartCorner::nearest_home:
        break;
    }
    return geometry::distance(*home, p) + geometry::distance(v.back().end, *home);
  };
  std::vector<SweepLine> best;
  double best_score = std::numeric_limits<double>::infinity();
  for (bool top_first : {false, true})
    for (bool reverse_first : {false, true}) {
      std::vector<SweepLine> v = zigzag(sweep, top_first, reverse_first);
      const double sc = score(v);
      if (sc < best_score - 1e-9) {
        best_score = sc;
        best = std::move(v);
      }
    }
  return best;
}

std::vector<Point2> line_waypoints(const SweepLine& line, std::optional<double> spacing_m) {
  std::vector<Point2> points{line.start};
  const double length = geometry::distance(line.start, line.end);
  if (spacing_m && *spacing_m > 0 && length > *spacing_m) {
    const auto parts = static_cast<std::size_t>(std::ceil(length / *spacing_m - 1e-9));
    for (std::size_t i = 1; i < parts; ++i)
      points.push_back(line.start + (line.end - line.start) *
                                        (static_cast<double>(i) / static_cast<double>(parts)));
  }
  points.push_back(line.end);
  return points;
}

}  // namespace swath::planning
