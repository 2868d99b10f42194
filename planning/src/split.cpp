// The split plan (plan_split): candidate directions, their cells or lane runs swept and estimated,
// the best refined with routed transits; a direction per region in split_regions.cpp.
#include "swath/planning/split.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <numeric>
#include <span>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include "swath/base/parallel.hpp"
#include "swath/geometry/convex_hull.hpp"
#include "swath/geometry/decomposition.hpp"
#include "swath/geometry/offset.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/planning/cell_order.hpp"
#include "swath/planning/coverage.hpp"
#include "swath/planning/lane_runs.hpp"

#include "lane_scan.hpp"
#include "split_bounds.hpp"
#include "split_candidate.hpp"
#include "split_runs.hpp"
#include "swath/geometry/turn.hpp"

namespace swath::planning {

using geometry::Point2;

namespace split_detail {

double line_angle(Point2 a, Point2 b) {
  double deg = std::atan2(b.y - a.y, b.x - a.x) * 180 / std::numbers::pi;
  deg = std::fmod(deg + 360.0, 180.0);
  return deg >= 180.0 ? deg - 180.0 : deg;
}

// Directions worth trying: along the longest edges (hull edges included: lanes along an edge
// waste least), and a scan; directions closer than 0.25 degrees count once.
std::vector<double> candidate_angles(const std::vector<geometry::Ring>& rings, double scan_step) {
  std::vector<std::pair<double, double>> edges;  // (length, angle)
  std::vector<Point2> all;
  auto add = [&](Point2 a, Point2 b) {
    edges.push_back({geometry::distance(a, b), line_angle(a, b)});
  };
  for (const auto& ring : rings)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      all.push_back(ring[i]);
      add(ring[i], ring[(i + 1) % ring.size()]);
    }
  const geometry::Ring hull = geometry::convex_hull(all);
  for (std::size_t i = 0; i < hull.size(); ++i) add(hull[i], hull[(i + 1) % hull.size()]);
  std::sort(edges.begin(), edges.end(), std::greater<>());
  std::vector<double> angles;
  for (std::size_t i = 0; i < edges.size() && i < 48; ++i) angles.push_back(edges[i].second);
  for (double a = 0; a < 180 - 1e-9; a += scan_step) angles.push_back(a);
  std::sort(angles.begin(), angles.end());
  std::vector<double> unique;
  for (double a : angles)
    if (unique.empty() || a - unique.back() > 0.25) unique.push_back(a);
  return unique;
}

// Sweeps every cell and builds the ordering problem under `metric`.
CellOrderProblem problem_for(Candidate& c, Point2 home, const Metric& metric) {
  CellOrderProblem p;
  p.home = home;
  p.distance = metric;
  c.variant_flags.clear();
  p.cells.reserve(c.sweeps.size());
  c.variant_flags.reserve(c.sweeps.size());
  for (const Sweep& sweep : c.sweeps) {
    std::vector<CellVariant> variants;
    std::vector<std::pair<bool, bool>> flags;
    variants.reserve(4);
    flags.reserve(4);
    for (bool top_first : {false, true})
      for (bool reverse_first : {false, true}) {
        if (sweep.lines.size() == 1 && top_first) continue;  // the same as bottom first
        // zigzag()'s lanes one by one, not built (four variants of every cell of every direction).
        const std::size_t n = sweep.lines.size();
        const auto lane = [&](std::size_t i) {
          SweepLine line = sweep.lines[top_first ? n - 1 - i : i];
          if ((i % 2 == 1) != reverse_first) std::swap(line.start, line.end);
          return line;
        };
        double internal = 0;
        SweepLine here = lane(0);
        const Point2 entry = here.start;
        for (std::size_t i = 0; i < n; ++i) {
          internal += geometry::distance(here.start, here.end);
          if (i + 1 == n) break;
          const SweepLine next = lane(i + 1);
          internal += metric(here.end, next.start);
          here = next;
        }
        variants.push_back({entry, here.end, internal});
        flags.push_back({top_first, reverse_first});
      }
    p.cells.push_back(std::move(variants));
    c.variant_flags.push_back(std::move(flags));
  }
  return p;
}

// Lanes for the pieces of a decomposition, grouped by its cells. `d` is taken (its cells' rings
// moved into the candidate, its pieces lent to the sweeps), not copied.
Candidate sweep_decomposition(const std::vector<geometry::Ring>& rings, geometry::Decomposition d,
                              double angle, const SplitSettings& s) {
  Candidate c;
  c.angle_deg = angle;
  // One lane grid for the whole area: lanes of neighbouring cells stay one spacing apart. Corners'
  // ordinates by turned.y (rotate()'s, the same values), here and for the pieces below.
  const geometry::Turn turned(-angle);
  double y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
  for (const auto& ring : rings)
    for (const Point2& p : ring) {
      const double y = turned.y(p);
      y_min = std::min(y_min, y);
      y_max = std::max(y_max, y);
    }
  SweepSettings sweep_settings;
  sweep_settings.angle_deg = angle;
  sweep_settings.line_spacing_m = s.line_spacing_m;
  sweep_settings.footprint_width_m = s.footprint_width_m;
  sweep_settings.placement = s.placement;
  sweep_settings.turnaround_m = s.turnaround_m;
  sweep_settings.segments = SegmentRule::inside;
  sweep_settings.fill_protrusions = true;
  sweep_settings.ordinates =
      line_offsets(y_min, y_max, s.line_spacing_m, s.footprint_width_m, s.placement);
  // Lanes are placed per piece, so a piece thinner than the grid still gets one; cells (chains of
  // pieces) only group them for ordering.
  std::vector<std::vector<SweepLine>> piece_lines(d.pieces.size());
  geometry::Polygon piece;  // each piece's ring lent to it (swapped in and back), not copied
  for (std::size_t k = 0; k < d.pieces.size(); ++k)
    if (!d.pieces[k].empty()) {
      piece.outer.swap(d.pieces[k]);
      piece_lines[k] = plan_sweep(piece, sweep_settings).lines;
      piece.outer.swap(d.pieces[k]);
    }
  // A lane on a cut between two pieces belongs to both: keep the longer one. Lanes sorted by
  // ordinate, so only neighbours in that order can coincide.
  struct Lane {
    double y, x0, x1;
    SweepLine* line;
    std::size_t piece;
  };
  std::vector<Lane> lanes;
  // Piece k's lines' ordinates (their starts', turned) from line_first[k] on, in its lines' order:
  // the cells' lines are sorted by them below (a removal below keeps a line's start).
  std::vector<double> line_y;
  std::vector<std::size_t> line_first{0};
  for (std::size_t k = 0; k < piece_lines.size(); ++k) {
    for (SweepLine& l : piece_lines[k]) {
      const Point2 p = turned(l.start), q = turned(l.end);
      lanes.push_back({p.y, std::min(p.x, q.x), std::max(p.x, q.x), &l, k});
      line_y.push_back(p.y);
    }
    line_first.push_back(line_y.size());
  }
  std::sort(lanes.begin(), lanes.end(), [](const Lane& u, const Lane& v) { return u.y < v.y; });
  for (std::size_t i = 0; i < lanes.size(); ++i)
    for (std::size_t j = i + 1;
         j < lanes.size() && lanes[j].y - lanes[i].y <= 1e-9 * (1 + std::abs(lanes[i].y)); ++j) {
      Lane& u = lanes[i];
      Lane& v = lanes[j];
      if (u.line->start == u.line->end || v.line->start == v.line->end) continue;
      if (std::min(u.x1, v.x1) <= std::max(u.x0, v.x0)) continue;  // side by side, not overlapping
      SweepLine& shorter = *(u.x1 - u.x0 < v.x1 - v.x0 ? u.line : v.line);
      shorter.end = shorter.start;  // marked for removal
    }
  // A piece no grid ordinate crosses (its lanes are the mid-height one and protrusion fills) that
  // the footprint of one grid lane of another piece sees whole gets no lane (docs/swath-plan.md,
  // slivers by coverage): e.g. the 4 cm wedge that an edge 0.004 degrees off the lanes leaves
  // beside a reflex vertex got two lanes 305 and 458 m long beside the grid lane that sees it.
  const double half = s.footprint_width_m / 2 + 1e-9;
  // A piece's least and greatest ordinate (a rotate() call per corner of every piece was most of
  // this function's own instructions); the whole corners only for the thin pieces asked below.
  std::vector<char> thin(d.pieces.size(), 0), covered(d.pieces.size(), 0);
  std::vector<std::pair<double, double>> span_y(d.pieces.size());  // a piece's least, greatest y
  for (std::size_t k = 0; k < d.pieces.size(); ++k) {
    if (d.pieces[k].empty()) continue;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Point2& p : d.pieces[k]) {
      const double y = turned.y(p);
      lo = std::min(lo, y);
      hi = std::max(hi, y);
    }
    span_y[k] = {lo, hi};
    const auto grid =
        std::lower_bound(sweep_settings.ordinates.begin(), sweep_settings.ordinates.end(), lo);
    thin[k] = grid == sweep_settings.ordinates.end() || *grid > hi;
  }
  std::vector<Point2> corners;  // a thin piece's, turned
  for (std::size_t k = 0; k < d.pieces.size(); ++k) {
    if (!thin[k] || piece_lines[k].empty()) continue;
    corners.clear();
    for (const Point2& p : d.pieces[k]) corners.push_back(turned(p));
    // Only a lane within half a footprint of the piece's lowest and highest corners can see it
    // whole: the lanes (sorted by ordinate) in that window, widened well past rounding, are asked
    // (all lanes were, hundreds of thin pieces by thousands of lanes on 10,000-vertex areas).
    const auto [y_lo, y_hi] = span_y[k];
    const double slack = 1e-6 * (1 + std::abs(y_lo) + std::abs(y_hi) + half);
    const auto first = std::lower_bound(lanes.begin(), lanes.end(), y_hi - half - slack,
                                        [](const Lane& l, double y) { return l.y < y; });
    for (auto it = first; it != lanes.end() && it->y <= y_lo + half + slack; ++it) {
      const Lane& lane = *it;
      if (thin[lane.piece] || lane.line->start == lane.line->end) continue;
      const double x0 = lane.x0 + s.turnaround_m - 1e-6, x1 = lane.x1 - s.turnaround_m + 1e-6;
      if (std::all_of(corners.begin(), corners.end(), [&](Point2 q) {
            return std::abs(q.y - lane.y) <= half && q.x >= x0 && q.x <= x1;
          })) {
        covered[k] = 1;
        break;
      }
    }
  }
  for (std::size_t k = 0; k < d.pieces.size(); ++k)
    if (covered[k]) piece_lines[k].clear();
  // A cell's lines by ordinate: sorted with their ordinates beside them (not turned again for
  // every comparison), the same comparisons in the same order, so the same order of equal ones.
  std::vector<std::pair<double, SweepLine>> by_y;
  for (std::size_t cell = 0; cell < d.cells.size(); ++cell) {
    by_y.clear();
    for (const std::size_t k : d.cells[cell])
      for (std::size_t i = 0; i < piece_lines[k].size(); ++i) {
        const SweepLine& l = piece_lines[k][i];
        if (!(l.start == l.end)) by_y.push_back({line_y[line_first[k] + i], l});
      }
    std::sort(by_y.begin(), by_y.end(),
              [](const auto& u, const auto& v) { return u.first < v.first; });
    if (by_y.empty()) continue;
    Sweep sweep;
    sweep.angle_deg = angle;
    sweep.lines.reserve(by_y.size());
    for (const auto& [y, l] : by_y) sweep.lines.push_back(l);
    keep_turnarounds_out(sweep.lines, s.turnaround_m, s.keep_out_rings);
    c.cells.push_back(std::move(d.cell_rings[cell]));
    c.sweeps.push_back(std::move(sweep));
  }
  return c;
}

Candidate sweep_cells(const std::vector<geometry::Ring>& rings, double angle,
                      const SplitSettings& s) {
  return sweep_decomposition(rings, geometry::boustrophedon_decomposition(rings, angle), angle, s);
}

Candidate sweep_runs(const std::vector<geometry::Ring>& rings, double angle, const SplitSettings& s,
                     bool bridged, std::vector<Point2>& samples, bool drop_slivers,
                     std::optional<double> grid_ordinate_m, LaneGridExtent* grid) {
  LaneRunSettings settings;
  if (!drop_slivers) settings.sliver_length_footprints = 0;
  settings.grid_ordinate_m = grid_ordinate_m;
  settings.angle_deg = angle;
  settings.line_spacing_m = s.line_spacing_m;
  settings.footprint_width_m = s.footprint_width_m;
  settings.placement = s.placement;
  LaneRuns runs =
      lane_runs({rings, s.seen_rings, bridged ? s.bridge_rings : std::vector<geometry::Ring>{}},
                settings, samples);
  if (grid != nullptr) *grid = runs.grid;
  Candidate c;
  c.angle_deg = angle;
  c.method = SplitCells::runs;
  c.cells = std::move(runs.outlines);
  c.sweeps = std::move(runs.runs);
  if (s.turnaround_m > 0)
    for (Sweep& sweep : c.sweeps)
      for (SweepLine& l : sweep.lines) {
        const Point2 d = (l.end - l.start) * (s.turnaround_m / geometry::distance(l.start, l.end));
        l.start = l.start - d;
        l.end = l.end + d;
      }
  for (Sweep& sweep : c.sweeps) keep_turnarounds_out(sweep.lines, s.turnaround_m, s.keep_out_rings);
  return c;
}

double straight_m(Point2 a, Point2 b) {
  return geometry::distance(a, b);
}

// The candidate's ordering problem with straight transits, its estimate's and bounds'.
CellOrderProblem straight_problem(Candidate& c, Point2 home) {
  CellOrderProblem problem = problem_for(c, home, straight_m);
  problem.distance_at_least_straight = true;
  return problem;
}

// The candidate's straight-transit estimate (nearest neighbour from home) into c.order.
void estimate(Candidate& c, Point2 home) {
  c.order = nearest_neighbour_order(straight_problem(c, home));
}

// The cells at one direction as a candidate, with its estimate; no cells: none.
std::optional<Candidate> estimated_cells(const std::vector<geometry::Ring>& rings, double angle,
                                         const SplitSettings& s, Point2 home) {
  Candidate c = sweep_cells(rings, angle, s);
  if (c.cells.empty()) return std::nullopt;
  estimate(c, home);
  return c;
}

}  // namespace split_detail

namespace split_detail {

double cells_estimate_bound(const std::vector<geometry::Ring>& rings, double angle_deg,
                            const SplitSettings& s, Point2 home) {
  const detail::LaneScan scan(rings, angle_deg);
  const std::vector<double> ys =
      line_offsets(scan.y_min, scan.y_max, s.line_spacing_m, s.footprint_width_m, s.placement);
  const detail::SpanRows spans = scan.at(ys);
  LaneGridExtent grid;
  for (std::size_t k = 0; k < ys.size(); ++k) {
    for (const detail::Span& span : spans[k]) grid.lanes_m += span.x1 - span.x0;
    if (!spans[k].empty()) {
      grid.y_lo_m = std::min(grid.y_lo_m, ys[k]);
      grid.y_hi_m = std::max(grid.y_hi_m, ys[k]);
    }
  }
  return cells_estimate_bound(grid, angle_deg, home);
}

double cells_estimate_bound(const LaneGridExtent& grid, double angle_deg, Point2 home) {
  const double y = rotate(home, -angle_deg).y;
  const double lo = std::min(y, grid.y_lo_m), hi = std::max(y, grid.y_hi_m);
  return (grid.lanes_m + 2 * (hi - lo)) * (1 - 1e-6);
}

double cells_estimate(const std::vector<geometry::Ring>& rings, double angle_deg,
                      const SplitSettings& s, Point2 home) {
  const std::optional<Candidate> c = estimated_cells(rings, angle_deg, s, home);
  return c ? c->order.length_m : 0.0;
}

}  // namespace split_detail

namespace split_detail {

// The cells (bits, the first 63) whose lanes a routed transit crosses.
class LaneCrossings {
 public:
  explicit LaneCrossings(const Candidate& c) : c_(c) {
    for (const Sweep& sweep : c.sweeps) {
      Box box;
      std::vector<Box> lanes;
      std::vector<double> lengths;
      for (const SweepLine& l : sweep.lines) {
        Box lane;
        for (const Point2& p : {l.start, l.end}) lane.add(p);
        box.add(lane);
        lanes.push_back(lane);
        lengths.push_back(geometry::distance(l.start, l.end));
      }
      boxes_.push_back(box);
      lane_boxes_.push_back(std::move(lanes));
      lane_lengths_.push_back(std::move(lengths));
    }
  }
  std::uint64_t operator()(const std::vector<Point2>& path) const {
    // Two segments that cross clearly share a point, so their bounding boxes meet: only the
    // lanes whose box meets a leg's are tested, with the lengths of the legs and lanes worked out
    // once (segments_cross_clearly()'s form with lengths given: the same answers).
    thread_local std::vector<Box> legs;
    thread_local std::vector<double> leg_lengths;
    legs.clear();
    leg_lengths.clear();
    Box span;
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
      Box leg;
      leg.add(path[i]);
      leg.add(path[i + 1]);
      span.add(leg);
      legs.push_back(leg);
      leg_lengths.push_back(geometry::distance(path[i], path[i + 1]));
    }
    std::uint64_t cells = 0;
    for (std::size_t k = 0; k < c_.sweeps.size() && k < 63; ++k) {
      if (!span.meets(boxes_[k])) continue;
      const std::vector<SweepLine>& lines = c_.sweeps[k].lines;
      for (std::size_t j = 0; j < lines.size() && !(cells >> k & 1); ++j) {
        const SweepLine& l = lines[j];
        const Box& lane = lane_boxes_[k][j];
        if (!span.meets(lane)) continue;
        for (std::size_t i = 0; i + 1 < path.size() && !(cells >> k & 1); ++i)
          if (legs[i].meets(lane) &&
              geometry::segments_cross_clearly(path[i], path[i + 1], leg_lengths[i], l.start, l.end,
                                               lane_lengths_[k][j],
                                               1e-9 * (leg_lengths[i] + lane_lengths_[k][j])))
            cells |= std::uint64_t{1} << k;
      }
    }
    return cells;
  }

 private:
  struct Box {
    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    void add(Point2 p) {
      x0 = std::min(x0, p.x);
      y0 = std::min(y0, p.y);
      x1 = std::max(x1, p.x);
      y1 = std::max(y1, p.y);
    }
    void add(const Box& o) {
      x0 = std::min(x0, o.x0);
      y0 = std::min(y0, o.y0);
      x1 = std::max(x1, o.x1);
      y1 = std::max(y1, o.y1);
    }
    bool meets(const Box& o) const { return x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1; }
  };
  const Candidate& c_;
  std::vector<Box> boxes_;                         ///< per cell, of its lanes
  std::vector<std::vector<Box>> lane_boxes_;       ///< per cell, per lane
  std::vector<std::vector<double>> lane_lengths_;  ///< per cell, per lane
};

// The candidate's cells in their best order (exact where small), transits routed and kept off
// lanes still to be flown where that costs less than flying them again, as a plan.
SplitPlan ordered_plan(Candidate& c, Point2 home, RoutedMetric& routed) {
  CellOrderProblem problem =
      problem_for(c, home, [&routed](Point2 a, Point2 b) { return routed(a, b); });
  problem.distance_at_least_straight = true;  // a path inside the area, or the straight leg
  // RoutedMetric keeps one path per pair of ends (from the lexicographically smaller), so its
  // length and the lanes it crosses are the same either way and whenever asked.
  problem.symmetric = true;
  const LaneCrossings crossings(c);
  problem.crossed = [&](Point2 a, Point2 b) { return crossings(routed.path(a, b)); };
  const CellOrder order = order_cells(problem);
  SplitPlan plan;
  plan.angle_deg = c.angle_deg;
  plan.method = c.method;
  plan.path_length_m = order.length_m;
  plan.objective_m = order.objective_m;
  plan.cells = c.cells;
  for (const CellVisit& v : order.visits) {
    const auto [top_first, reverse_first] = c.variant_flags[v.cell][v.variant];
    for (const SweepLine& line : zigzag(c.sweeps[v.cell], top_first, reverse_first)) {
      plan.lines.push_back(line);
      plan.line_cell.push_back(v.cell);
    }
  }
  return plan;
}

}  // namespace split_detail

SplitPlan plan_pieces(const std::vector<geometry::Ring>& pieces, double angle_deg, Point2 home,
                      const SplitSettings& s, const geometry::VisibilityRouter& router) {
  using namespace split_detail;
  geometry::Decomposition d;
  for (const geometry::Ring& piece : pieces) {
    if (piece.size() < 3) continue;
    d.cells.push_back({d.pieces.size()});
    d.pieces.push_back(piece);
    d.cell_rings.push_back(piece);
  }
  Candidate c = sweep_decomposition(d.pieces, d, angle_deg, s);
  if (c.cells.empty()) return {};
  RoutedMetric routed(router);
  SplitPlan plan = ordered_plan(c, home, routed);
  plan.candidates = 1;
  return plan;
}

struct RunOrder::Memo {
  explicit Memo(const geometry::VisibilityRouter& router) : routed(router) {}
  split_detail::RoutedMetric routed;
};

RunOrder::RunOrder(const geometry::VisibilityRouter& router)
    : memo_(std::make_unique<Memo>(router)) {}

RunOrder::~RunOrder() = default;

SplitPlan RunOrder::operator()(std::vector<geometry::Ring> outlines, std::vector<Sweep> runs,
                               double angle_deg, Point2 home) {
  using namespace split_detail;
  Candidate c;
  c.angle_deg = angle_deg;
  c.method = SplitCells::runs;
  c.cells = std::move(outlines);
  c.sweeps = std::move(runs);
  if (c.sweeps.empty()) return {};
  SplitPlan plan = ordered_plan(c, home, memo_->routed);
  plan.candidates = 1;
  return plan;
}

namespace split_detail {

// SplitSettings::progress, told one call at a time: each part of the search adds its share of 1
// as its pieces finish (on any thread).
class SearchProgress {
 public:
  /// `scale`: the part of the whole the three shares below make (the rest: a search after them).
  SearchProgress(const std::function<void(double)>& tell, double scale)
      : tell_(tell), scale_(scale) {}
  /// `share` of `count` pieces of that share: one piece done, or all of them at once when there
  /// are none.
  void piece(double share, std::size_t count) {
    add(scale_ * (count == 0 ? share : share / static_cast<double>(count)));
  }
  void finish() { add(1.0); }

 private:
  void add(double share) {
    if (!tell_) return;
    const std::lock_guard<std::mutex> guard(lock_);
    done_ = std::min(1.0, done_ + share);
    tell_(done_);
  }
  const std::function<void(double)>& tell_;
  double scale_;
  std::mutex lock_;
  double done_ = 0;
};

// The shares of the whole search: the lanes at every direction, the cells where they could rank,
// the candidates refined (the dearest part on concave areas: routed transits).
constexpr double kRunsShare = 1.0 / 3, kCellsShare = 1.0 / 6, kRefineShare = 1.0 / 2;

// Which kinds of candidate (0 bridged runs, 1 runs, 2 cells) each direction may lay within
// s.max_lines, counted before any lane is laid (grid_lane_count): on a concave area a lane
// position holds a lane per arm it crosses, and laying and ordering them at every direction ran a
// 2,000-vertex star (20,663 lanes) out of memory after 145 s, before the limit was asked.
struct LaneLimits {
  std::vector<std::array<bool, 3>> fits;  ///< per direction and kind
  /// The fewest grid lanes of a kind tried, and its direction (0 where none were counted: all
  /// fit).
  std::size_t least = 0;
  double least_angle_deg = 0;
};

LaneLimits lane_limits(const std::vector<geometry::Ring>& rings, const std::vector<double>& angles,
                       const SplitSettings& s) {
  LaneLimits out;
  out.fits.assign(angles.size(), {true, true, true});
  if (s.max_lines == 0) return out;
  // An edge crosses at most |dy| / spacing + 2 lane positions, whatever the direction (+ 2: the
  // paper placement's last is half a spacing above the one before), and a lane takes two
  // crossings: where the whole boundary cannot reach the limit (any field but pathological ones),
  // nothing needs counting.
  double crossings = 0;
  for (const geometry::Ring& ring : rings)
    for (std::size_t i = 0; i < ring.size(); ++i)
      crossings += geometry::distance(ring[i], ring[(i + 1) % ring.size()]) / s.line_spacing_m + 2;
  if (crossings / 2 <= double(s.max_lines)) return out;
  out.least = std::numeric_limits<std::size_t>::max();
  const bool runs = s.cells != SplitCells::boustrophedon;
  const bool bridged = runs && !s.bridge_rings.empty();
  const bool cells = s.cells != SplitCells::runs;
  // Grid lanes at a direction: inside (runs and cells: one grid), and bridged.
  const auto counts = [&](double angle_deg) {
    LaneRunSettings ls;
    ls.angle_deg = angle_deg;
    ls.line_spacing_m = s.line_spacing_m;
    ls.footprint_width_m = s.footprint_width_m;
    ls.placement = s.placement;
    const std::size_t inside = grid_lane_count({rings, {}, {}}, ls);
    return std::pair{inside, bridged ? grid_lane_count({rings, {}, s.bridge_rings}, ls) : inside};
  };
  std::vector<std::array<std::size_t, 3>> needed(angles.size());
  base::parallel_for(angles.size(), s.threads, [&](std::size_t a) {
    const auto [inside, joined] = counts(angles[a]);
    std::size_t cross = 0;  // the pass at 90 degrees (in [0, 180) as plan_split flies it)
    if (s.limit_cross_pass) {
      const auto [cross_inside, cross_joined] =
          counts(std::fmod(std::fmod(angles[a] + 90, 180.0) + 180.0, 180.0));
      cross = std::min(cross_inside, cross_joined);
    }
    needed[a] = {std::max(joined, cross), std::max(inside, cross), std::max(inside, cross)};
  });
  for (std::size_t a = 0; a < angles.size(); ++a)
    for (const int kind : {0, 1, 2}) {
      if (!(kind == 0 ? bridged : kind == 1 ? runs : cells)) continue;
      const std::size_t n = needed[a][std::size_t(kind)];
      out.fits[a][std::size_t(kind)] = n <= s.max_lines;
      if (n < out.least) {
        out.least = n;
        out.least_angle_deg = angles[a];
      }
    }
  return out;
}

// The runs at every direction within the lane limit (kinds 0 bridged runs, 1 runs; per direction
// in that order) with their straight-transit estimates where they may rank among the refined ones
// (elsewhere: order.length_m +inf, no order), and the cells' lower bound
// (split_detail::cells_estimate_bound()) at each direction whose cells fit the limit.
struct RunEstimates {
  std::vector<std::vector<std::pair<int, Candidate>>> per_angle;
  std::vector<double> cells_bound;            ///< per direction (0 where cells are not planned)
  std::vector<std::size_t> cells_directions;  ///< where they are, ascending
};

// Whether an estimate whose lower bound is `bound_m` could rank among the `per_kind` least of its
// kind, given `least`, the least estimates of that kind found so far (ascending, at most per_kind).
// Not when per_kind are found and the bound is above the last of them by more than rounding: the
// estimate is at least the bound, so above that last one, and the ones found only fall as more are.
// (The runs' bound and estimate are sums of the same straight distances and internal lengths in
// other orders: their rounding differs by ~1e-13 relative, far below the 1e-9 margin.)
bool may_rank(double bound_m, const std::vector<double>& least, std::size_t per_kind) {
  return per_kind == 0 || least.size() < per_kind || !(bound_m > least.back() * (1 + 1e-9));
}

std::vector<double> estimates_by_bound(const std::vector<int>& kinds,
                                       const std::vector<double>& bounds_m, std::size_t per_kind,
                                       unsigned threads,
                                       const std::function<double(std::size_t)>& tighter_bound,
                                       const std::function<double(std::size_t)>& estimate) {
  // Why best_of_each_kind() chooses the same: one left out has a bound above per_kind estimates
  // of its kind found (may_rank()), and its estimate, at least its bound, is above them too; so
  // it ranks after them with every estimate known, and with +inf as well. Which are left out
  // depends on the threads' timing, not that. In order of the bounds, most are left out at once.
  const std::size_t n = kinds.size();
  std::vector<std::size_t> by_bound(n);
  std::iota(by_bound.begin(), by_bound.end(), std::size_t{0});
  std::stable_sort(by_bound.begin(), by_bound.end(),
                   [&](std::size_t x, std::size_t y) { return bounds_m[x] < bounds_m[y]; });
  std::vector<double> out(n, std::numeric_limits<double>::infinity());
  std::mutex lock;                                     // guards least
  std::unordered_map<int, std::vector<double>> least;  // per kind, as may_rank() has it
  const auto ranks = [&](std::size_t i, double bound) {
    const std::lock_guard<std::mutex> guard(lock);
    return may_rank(bound, least[kinds[i]], per_kind);
  };
  base::parallel_for(n, threads, [&](std::size_t j) {
    const std::size_t i = by_bound[j];
    if (!ranks(i, bounds_m[i]) || (tighter_bound && !ranks(i, tighter_bound(i)))) return;
    const double e = estimate(i);
    const std::lock_guard<std::mutex> guard(lock);
    out[i] = e;
    std::vector<double>& of_kind = least[kinds[i]];
    of_kind.insert(std::upper_bound(of_kind.begin(), of_kind.end(), e), e);
    if (of_kind.size() > per_kind) of_kind.pop_back();
  });
  return out;
}

// A lower bound on every order's length of `p` cheaper than order_lower_bound(): every cell is
// flown by one of its variants, transits add to that; less 1e-9 of it for rounding (the sums of
// the same lengths in other orders).
double internal_lower_bound(const CellOrderProblem& p) {
  double sum = 0;
  for (const std::vector<CellVariant>& variants : p.cells) {
    double least = std::numeric_limits<double>::infinity();
    for (const CellVariant& v : variants) least = std::min(least, v.internal_m);
    sum += least;
  }
  return sum * (1 - 1e-9);
}

RunEstimates estimate_runs(const std::vector<geometry::Ring>& rings,
                           const std::vector<double>& angles, Point2 home, const SplitSettings& s,
                           const LaneLimits& limits, SearchProgress& progress) {
  // The directions are independent: spread over threads, each into its own slot. First the runs
  // and a bound of their estimate (internal_lower_bound()) at every direction, then the estimates
  // (nearest neighbour, straight transits) in order of those bounds, each left out (+inf) where
  // that bound, or order_lower_bound(), shows it cannot rank among the refined_candidates least of
  // its kind (estimates_by_bound(): best_of_each_kind() chooses the same). Most directions' bounds
  // are above the refined_candidates-th least estimate of their kind.
  const std::size_t n = angles.size();
  RunEstimates out;
  out.per_angle.resize(n);
  const bool cells = s.cells != SplitCells::runs;
  if (cells) out.cells_bound.assign(n, 0.0);
  std::vector<std::vector<CellOrderProblem>> problems(n);  // per direction, as out.per_angle
  std::vector<std::vector<double>> bounds(n);
  base::parallel_for(n, s.threads, [&](std::size_t a) {
    // Bridged runs where there is a margin, runs inside: each takes the coverage samples its own
    // lanes leave to check (into a buffer of the thread's).
    thread_local std::vector<Point2> samples;
    std::optional<LaneGridExtent> grid;  // the runs inside's: the cells' bound is made of it
    for (const int kind : {0, 1}) {
      if (s.cells == SplitCells::boustrophedon || (kind == 0 && s.bridge_rings.empty()) ||
          !limits.fits[a][std::size_t(kind)])
        continue;
      Candidate c = sweep_runs(rings, angles[a], s, kind == 0, samples, true, std::nullopt,
                               kind == 1 ? &grid.emplace() : nullptr);
      if (c.cells.empty()) continue;
      problems[a].push_back(straight_problem(c, home));
      bounds[a].push_back(internal_lower_bound(problems[a].back()));
      out.per_angle[a].push_back({kind, std::move(c)});
    }
    if (cells && limits.fits[a][2])
      out.cells_bound[a] = grid ? split_detail::cells_estimate_bound(*grid, angles[a], home)
                                : split_detail::cells_estimate_bound(rings, angles[a], s, home);
    progress.piece(kRunsShare, n);
  });
  std::vector<std::pair<std::size_t, std::size_t>> at;  // (direction, its k-th candidate)
  std::vector<int> kinds;
  std::vector<double> bounds_m;
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t k = 0; k < out.per_angle[a].size(); ++k) {
      at.push_back({a, k});
      kinds.push_back(out.per_angle[a][k].first);
      bounds_m.push_back(bounds[a][k]);
    }
  const std::vector<double> estimates = estimates_by_bound(
      kinds, bounds_m, s.refined_candidates, s.threads,
      [&](std::size_t i) { return order_lower_bound(problems[at[i].first][at[i].second]); },
      [&](std::size_t i) {
        // estimate()'s order, on the problem built for the bounds.
        const auto [a, k] = at[i];
        Candidate& c = out.per_angle[a][k].second;
        c.order = nearest_neighbour_order(problems[a][k]);
        return c.order.length_m;
      });
  for (std::size_t i = 0; i < at.size(); ++i)  // the ones left out: +inf (the others' own)
    out.per_angle[at[i].first][at[i].second].second.order.length_m = estimates[i];
  if (cells)
    for (std::size_t a = 0; a < n; ++a)
      if (limits.fits[a][2]) out.cells_directions.push_back(a);
  return out;
}

std::vector<std::size_t> best_of_each_kind(
    std::vector<std::tuple<int, double, std::size_t>> estimates, std::size_t per_kind) {
  std::sort(estimates.begin(), estimates.end());
  std::vector<std::size_t> chosen;
  for (std::size_t e = 0, of_kind = 0; e < estimates.size(); ++e) {
    of_kind = e > 0 && std::get<0>(estimates[e]) == std::get<0>(estimates[e - 1]) ? of_kind + 1 : 0;
    if (of_kind < per_kind) chosen.push_back(std::get<2>(estimates[e]));
  }
  return chosen;
}

// One candidate ordered with transits routed inside the area.
struct Refined {
  std::optional<SplitPlan> plan;  ///< none: skipped, it could not beat a plan already found
  double seen_fraction = -1;      ///< < 0: not measured, its plan is longer than one already found
};

// `c` ordered on `routed` and its coverage of `to_see` measured, unless a plan seeing >= 99.9 %
// with objective `beaten_m` is already found and this one cannot be shorter: then not ordered when
// `bound_m`, a lower bound on every order's length (straight transits), is at or above it
// (ordering with routed transits is most of a plan's time; the margin keeps rounding of the two
// sums from deciding a tie), its coverage not measured when its objective is above it.
Refined refine(Candidate& c, double bound_m, Point2 home, const SplitSettings& s,
               const geometry::Polygon& to_see, RoutedMetric& routed, double beaten_m) {
  Refined r;
  if (beaten_m < std::numeric_limits<double>::infinity() && bound_m >= beaten_m * (1 + 1e-9))
    return r;
  r.plan = ordered_plan(c, home, routed);
  if (r.plan->objective_m > beaten_m) return r;
  r.seen_fraction =
      measure_coverage(to_see, r.plan->lines, r.plan->angle_deg, s.footprint_width_m, 1024)
          .covered_fraction;
  return r;
}

// The best plan so far and its key: (0, objective) for a plan that sees >= 99.9 % of the area,
// else (1, minus the fraction seen); less is better. A plan that sees less than 99.9 % (cells'
// lanes can miss a corner a large footprint was trusted with) only wins where none sees more.
struct Best {
  SplitPlan plan;
  std::pair<double, double> key{std::numeric_limits<double>::infinity(), 0};
  /// The objective a candidate must get below to win: +inf until a plan sees >= 99.9 %.
  double beaten_m() const {
    return key.first == 0 ? key.second : std::numeric_limits<double>::infinity();
  }
};

// `r` compared with the best so far; candidates folded in the order of their estimates, the
// first of equal ones kept. One not ordered or not measured lost to a plan before it or beside it
// (refine()): that plan, seeing >= 99.9 % and shorter, is folded too and beats it.
void fold(Refined& r, Best& best) {
  if (!r.plan || r.seen_fraction < 0 || r.plan->objective_m >= best.beaten_m()) return;
  const std::pair<double, double> key = r.seen_fraction >= 0.999
                                            ? std::pair{0.0, r.plan->objective_m}
                                            : std::pair{1.0, -r.seen_fraction};
  if (key < best.key) {
    best.key = key;
    best.plan = *std::move(r.plan);
  }
}

// Routers for the threads of a pool: thread 0 the caller's, the others fresh copies (a router's
// tables serve one thread), made when a thread first asks.
class RouterPerThread {
 public:
  RouterPerThread(const geometry::VisibilityRouter& router, RoutedMetric& routed, unsigned threads)
      : router_(router), routed_(routed), copies_(threads), metrics_(threads) {}
  RoutedMetric& operator()(unsigned worker) {
    if (worker == 0) return routed_;
    if (!metrics_[worker]) {
      copies_[worker] = router_.fresh_copy();
      metrics_[worker] = std::make_unique<RoutedMetric>(*copies_[worker]);
    }
    return *metrics_[worker];
  }

 private:
  const geometry::VisibilityRouter& router_;
  RoutedMetric& routed_;
  std::vector<std::unique_ptr<geometry::VisibilityRouter>> copies_;
  std::vector<std::unique_ptr<RoutedMetric>> metrics_;
};

// The cells with their estimates at the directions where they could rank among the refined ones
// (per direction; none: no cells there, or left out), in one pool of threads, in order of their
// bound (a decomposition per direction), each left out when its bound shows it cannot rank among
// the refined_candidates least estimates (estimates_by_bound(): the cells that rank are the ones
// that would with every direction decomposed). A direction without cells counts as +inf, which
// rules nothing out: the least found are the same finite estimates as without it.
std::vector<std::optional<Candidate>> estimate_cells(const std::vector<geometry::Ring>& rings,
                                                     const std::vector<double>& angles,
                                                     const RunEstimates& found, Point2 home,
                                                     const SplitSettings& s,
                                                     SearchProgress& progress) {
  const std::vector<std::size_t>& at = found.cells_directions;
  std::vector<double> bounds_m;
  for (const std::size_t a : at) bounds_m.push_back(found.cells_bound[a]);
  std::vector<std::optional<Candidate>> cells(angles.size());
  std::vector<char> asked(at.size(), 0);
  if (at.empty()) progress.piece(kCellsShare, 0);
  estimates_by_bound(std::vector<int>(at.size(), 2), bounds_m, s.refined_candidates, s.threads, {},
                     [&](std::size_t i) {
                       std::optional<Candidate>& c = cells[at[i]] =
                           estimated_cells(rings, angles[at[i]], s, home);
                       asked[i] = 1;
                       progress.piece(kCellsShare, at.size());
                       return c ? c->order.length_m : std::numeric_limits<double>::infinity();
                     });
  for (std::size_t i = 0; i < at.size(); ++i)  // the ones left out, told at once
    if (!asked[i]) progress.piece(kCellsShare, at.size());
  return cells;
}

// The candidates of `to_refine` refined (in that order), the most promising first: in order of
// their lower bounds (straight transits), by a pool of threads, each skipped or not measured
// against the best plan found before it or beside it. Which are skipped depends on the threads'
// timing, but not what fold() makes of them: one skipped or not measured is longer than a plan
// seeing >= 99.9 % that is refined and measured (refine()), and so loses to it wherever it is
// folded. On a field where cells win, their plan (often found first) rules out the runs at once:
// ordering a direction's runs, one cell per run with every turn routed, is the dearest kind.
std::vector<Refined> refine_best_first(std::vector<Candidate>& candidates,
                                       const std::vector<std::size_t>& to_refine, Point2 home,
                                       const SplitSettings& s, const geometry::Polygon& to_see,
                                       RouterPerThread& routers, SearchProgress& progress) {
  const std::size_t n = to_refine.size();
  std::vector<double> bound_m(n);
  base::parallel_for(n, s.threads, [&](std::size_t k) {
    bound_m[k] = order_lower_bound(problem_for(candidates[to_refine[k]], home, straight_m));
  });
  std::vector<std::size_t> by_bound(n);
  std::iota(by_bound.begin(), by_bound.end(), std::size_t{0});
  std::stable_sort(by_bound.begin(), by_bound.end(),
                   [&](std::size_t x, std::size_t y) { return bound_m[x] < bound_m[y]; });
  std::vector<Refined> refined(n);
  std::mutex lock;                                            // guards beaten_m
  double beaten_m = std::numeric_limits<double>::infinity();  // least objective seeing >= 99.9 %
  base::parallel_for(n, s.threads, [&](std::size_t j, unsigned worker) {
    const std::size_t k = by_bound[j];
    double beaten = 0;
    {
      const std::lock_guard<std::mutex> guard(lock);
      beaten = beaten_m;
    }
    Refined& r = refined[k] =
        refine(candidates[to_refine[k]], bound_m[k], home, s, to_see, routers(worker), beaten);
    if (r.seen_fraction >= 0.999) {
      const std::lock_guard<std::mutex> guard(lock);
      beaten_m = std::min(beaten_m, r.plan->objective_m);
    }
    progress.piece(kRefineShare, n);
  });
  return refined;
}

}  // namespace split_detail

SplitPlan plan_split(const std::vector<geometry::Ring>& rings, Point2 home, const SplitSettings& s,
                     const geometry::VisibilityRouter& router) {
  if (!(s.line_spacing_m > 0) || !(s.footprint_width_m >= s.line_spacing_m) ||
      !(s.scan_step_deg > 0))
    throw std::invalid_argument(
        "plan_split: need 0 < spacing <= footprint width and a scan step > 0");
  using namespace split_detail;
  RoutedMetric routed(router);
  RouterPerThread routers(router, routed, s.threads ? s.threads : base::machine_threads());
  const std::vector<geometry::Ring>& seen = s.seen_rings.empty() ? rings : s.seen_rings;
  const geometry::Polygon to_see{seen.front(), {seen.begin() + 1, seen.end()}};

  const std::vector<double> angles =
      s.fixed_angle_deg
          ? std::vector<double>{std::fmod(std::fmod(*s.fixed_angle_deg, 180.0) + 180.0, 180.0)}
          : candidate_angles(rings, s.scan_step_deg);
  const LaneLimits limits = lane_limits(rings, angles, s);
  if (s.max_lines > 0 && limits.least > s.max_lines)
    throw LaneLimitExceeded(limits.least, limits.least_angle_deg);
  // Rank the directions by a cheap estimate (straight transits, heuristic order; asked only where
  // a lower bound shows it may rank), and refine the best few of each kind with transits routed
  // inside the area, ordered exactly where small: a straight-line estimate ranks runs and cells
  // differently (runs' transits hop around what cells' turns go along). The runs are estimated,
  // then the cells; the candidates to refine are refined in order of their lower bounds, so that
  // the first good plan rules out the rest early. A search for a direction per region may follow:
  // the shares below make 85 % of the whole.
  const bool may_mix =
      s.directions == SplitDirections::per_region && !s.fixed_angle_deg && s.bridge_rings.empty();
  SearchProgress progress(s.progress, may_mix ? 0.85 : 1.0);
  RunEstimates found = estimate_runs(rings, angles, home, s, limits, progress);
  if (angles.empty()) progress.piece(kRunsShare, 0);
  std::vector<Candidate> candidates;
  std::vector<std::tuple<int, double, std::size_t>> estimates;  // kind, estimate, candidate
  const auto add = [&](int kind, Candidate c) {
    estimates.push_back({kind, c.order.length_m, candidates.size()});
    candidates.push_back(std::move(c));
  };
  for (std::vector<std::pair<int, Candidate>>& of_angle : found.per_angle)
    for (auto& [kind, c] : of_angle) add(kind, std::move(c));
  std::vector<std::size_t> to_refine = best_of_each_kind(estimates, s.refined_candidates);
  const std::size_t run_candidates = candidates.size();
  estimates.clear();
  for (std::optional<Candidate>& c : estimate_cells(rings, angles, found, home, s, progress))
    if (c) add(2, *std::move(c));
  if (candidates.empty()) throw std::invalid_argument("plan_split: the area holds no line");
  // The runs' best of each kind, then the cells': the order they are folded in (the first of
  // equal plans wins), whatever order they are refined in.
  for (const std::size_t c : best_of_each_kind(estimates, s.refined_candidates))
    to_refine.push_back(c);
  Best best;
  if (to_refine.empty()) progress.piece(kRefineShare, 0);
  for (Refined& r : refine_best_first(candidates, to_refine, home, s, to_see, routers, progress))
    fold(r, best);
  // Every direction whose cells fit the lane limit a cells candidate, decomposed or ruled out by
  // its bound.
  best.plan.candidates = run_candidates + found.cells_directions.size();
  if (may_mix && best.key.first == 0)
    if (std::optional<SplitPlan> mixed =
            per_region_plan(rings, home, s, to_see, best.plan, routed)) {
      progress.finish();
      return *std::move(mixed);
    }
  progress.finish();
  return std::move(best.plan);
}

}  // namespace swath::planning
