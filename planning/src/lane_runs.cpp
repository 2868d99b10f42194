#include "swath/planning/lane_runs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <stdexcept>
#include <tuple>

#include "lane_scan.hpp"
#include "swath/geometry/predicates.hpp"
#include "swath/geometry/sort_runs.hpp"
#include "swath/geometry/turn.hpp"

namespace swath::planning {
namespace {

using geometry::Point2;
using geometry::Ring;

using detail::LaneScan;
using detail::Span;

// Per ordinate, the pieces inside joined across the gaps that one interval of the bridge area
// spans: from the first piece's start to the last piece's end within it.
detail::SpanRows bridged(const detail::SpanRows& inside, const detail::SpanRows& bridge) {
  detail::SpanRows out;
  std::vector<Span> row;
  for (std::size_t k = 0; k < inside.size(); ++k) {
    row.clear();
    for (const Span& piece : inside[k]) {
      const double mid = (piece.x0 + piece.x1) / 2;
      const auto within = std::find_if(bridge[k].begin(), bridge[k].end(),
                                       [&](const Span& b) { return mid >= b.x0 && mid <= b.x1; });
      const bool joins = !row.empty() && within != bridge[k].end() && row.back().x1 >= within->x0 &&
                         row.back().x1 <= within->x1;
      if (joins)
        row.back().x1 = piece.x1;
      else
        row.push_back(piece);
    }
    out.add_row();
    for (const Span& s : row) out.add(s);
  }
  return out;
}

// Whether two areas' rings hold the same points bit for bit (their scans are then the same).
bool same_bits(const std::vector<Ring>& a, const std::vector<Ring>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t r = 0; r < a.size(); ++r)
    if (a[r].size() != b[r].size() ||
        (!a[r].empty() && std::memcmp(a[r].data(), b[r].data(), a[r].size() * sizeof(Point2)) != 0))
      return false;
  return true;
}

struct RunLane {
  double y, x0, x1;
  int row;  ///< the grid ordinate's index; -1 for a lane off the grid
};

}  // namespace

namespace detail {

void coverage_samples(const LaneScan& scan, double spacing_m, std::vector<Point2>& samples,
                      LongLaneReach* skip) {
  double perimeter = 0;
  for (const auto& [a, b] : scan.edges()) perimeter += geometry::distance(a, b);
  double step = spacing_m;
  const double height = scan.y_max - scan.y_min;
  while (perimeter / (step / 8) + height / (step / 4) * (perimeter / 2) / (step / 4) > 2e5 &&
         step < 1e6 * spacing_m)
    step *= 1.5;
  // An edge's (a span's) samples are written into the room made for them at once: pushed one by
  // one, their capacity checks were most of this function.
  thread_local std::vector<Point2> boundary;
  boundary.clear();
  for (const auto& [a, b] : scan.edges()) {
    if (skip) {
      // An edge whose samples' box the long lanes see whole (each point some long lane) has none
      // left (most edges: the long lanes reach the boundary), passed over without making them. Its
      // first sample is a.
      const auto [lo, hi] = edge_samples_box(a, b);
      if (skip->sees_all(lo, hi, a.y)) continue;
    }
    const int n = std::max(1, int(std::ceil(geometry::distance(a, b) / (step / 8))));
    if (skip) {
      // Those a long lane sees left out as they are made, before the sort (an edge's samples
      // mostly ask the rows within reach the one before asked: LongLaneReach keeps them).
      for (int i = 0; i < n; ++i) {
        const Point2 p = a + (b - a) * (double(i) / n);
        if (!skip->sees(p)) boundary.push_back(p);
      }
      continue;
    }
    const std::size_t at = boundary.size();
    boundary.resize(at + std::size_t(n));
    Point2* out = boundary.data() + at;
    for (int i = 0; i < n; ++i) out[i] = a + (b - a) * (double(i) / n);
  }
  const auto by_ordinate = [](Point2 p, Point2 q) {
    return p.y < q.y || (p.y == q.y && p.x < q.x);
  };
  // The inside samples come in order already (rows upwards, spans and their samples left to
  // right): only the boundary's are sorted, then merged in as the inside's are made, a boundary
  // sample before an equal inside one (as a stable merge of the two; equal samples are equal
  // points, so the result is the one sorting all gave). The boundary's come in runs already
  // sorted one way or the other (along an edge and on while the boundary keeps rising or
  // falling): where those are long, they are merged (a field's few hundred samples of a few
  // dozen edges were sorted anew for every direction).
  // Sorted after those a long lane sees are left out: the others' order is the one sorting all
  // gave (equivalent samples are equal points).
  geometry::sort_by_runs(boundary, by_ordinate, true);
  std::vector<double> rows;
  for (double y = scan.y_min + step / 8; y < scan.y_max; y += step / 4) rows.push_back(y);
  const SpanRows inside = scan.at(rows);
  const auto count = [&](const Span& in) {
    return std::max(1, int(std::ceil((in.x1 - in.x0) / (step / 4))));
  };
  samples.clear();
  if (!skip) {
    std::size_t total = boundary.size();
    for (std::size_t r = 0; r < inside.size(); ++r)
      for (const Span& in : inside[r]) total += std::size_t(count(in));
    samples.reserve(total);
  }
  std::size_t next = 0;  // of boundary
  bool in_order = true;  // the inside's samples ascending (expected: spans are disjoint, ascending)
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (inside[r].empty()) continue;
    const double y = rows[r];
    // The boundary's samples below the row come before all of its own; one on the row (rare)
    // is placed sample by sample; else the row's samples go in as they are made.
    while (next < boundary.size() && boundary[next].y < y) samples.push_back(boundary[next++]);
    if (next < boundary.size() && boundary[next].y == y) {
      for (const Span& in : inside[r]) {
        const int n = count(in);
        for (int i = 0; i < n; ++i) {
          const Point2 p{in.x0 + (in.x1 - in.x0) * (i + 0.5) / n, y};
          if (skip && skip->sees(p)) continue;
          while (next < boundary.size() && !by_ordinate(p, boundary[next]))
            samples.push_back(boundary[next++]);
          in_order = in_order && (samples.empty() || !by_ordinate(p, samples.back()));
          samples.push_back(p);
        }
      }
      continue;
    }
    // The sample before the row's first is below it: only the row's own can be out of order,
    // and within a span they are not (x0 + w (i + 1/2) / n, rounded, does not decrease with i
    // for w > 0; a NaN compares false either way): each span's first is checked.
    double previous_x = -std::numeric_limits<double>::infinity();
    // Samples [first, last) of a span: written at once, the first checked against the last before.
    const auto write = [&](double x0, double width, int n, int first, int last) {
      const std::size_t at = samples.size();
      for (int i = first; i < last; ++i) samples.push_back({x0 + width * (i + 0.5) / n, y});
      in_order = in_order && !(samples[at].x < previous_x);
      previous_x = samples.back().x;
    };
    const std::span<const Span> seen = skip ? skip->at(y) : std::span<const Span>();
    for (const Span& in : inside[r]) {
      const int n = count(in);
      // The span's ends read once: stores into `samples` might alias them (the same arithmetic).
      const double x0 = in.x0, width = in.x1 - in.x0;
      if (seen.empty()) {
        write(x0, width, n, 0, n);
        continue;
      }
      // Left out: the samples within a long lane's reach. A span's abscissae do not decrease with
      // i (above), so those within one range [a, b] are the indices from the first whose
      // abscissa is >= a up to the first whose is > b: found from the index the abscissa t
      // suggests, (t - x0) n / width - 1/2, walked to in the same arithmetic (a step or two).
      const auto x_at = [&](int i) { return x0 + width * (i + 0.5) / n; };
      // The first i in [from, n] where i == n or !below(x_at(i)), below() true then false.
      const auto first_index = [&](int from, double t, auto below) {
        const double guess = (t - x0) / width * n - 0.5;
        int i = !(guess > from) ? from : !(guess < n) ? n : int(guess);
        while (i > from && !below(x_at(i - 1))) --i;
        while (i < n && below(x_at(i))) ++i;
        return i;
      };
      int i = 0;
      for (auto range = std::lower_bound(seen.begin(), seen.end(), x_at(0),
                                         [](const Span&s, double x) { return s.x1 < x; });
           range != seen.end() && i < n; ++range) {
        const int from = first_index(i, range->x0, [&](double x) { return x < range->x0; });
        if (from == n) break;
        const int to = first_index(from, range->x1, [&](double x) { return x <= range->x1; });
        if (from > i) write(x0, width, n, i, from);
        i = to;
      }
      if (i < n) write(x0, width, n, i, n);
    }
  }
  samples.insert(samples.end(), boundary.begin() + std::ptrdiff_t(next), boundary.end());
  if (!in_order)  // not expected; kept as the plain sort
    std::sort(samples.begin(), samples.end(), by_ordinate);
}

}  // namespace detail

namespace {

// Which lanes see which samples: within half a footprint across and within the lane's length.
class SeenCount {
 public:
  SeenCount(const std::vector<Point2>& samples, double footprint_width_m)
      : samples_(samples),
        rows_(samples, footprint_width_m / 4),
        half_(detail::seen_half_width_m(footprint_width_m)),
        count_(samples.size() + 1, 0) {}

  /// f(i) for every sample i the lane sees, in no particular order.
  template <typename F>
  void each_seen_by(const RunLane& lane, F f) const {
    rows_.any_order_in(
        lane.y - half_, lane.y + half_, lane.x0 - detail::kSeenAlongM,
        lane.x1 + detail::kSeenAlongM,
        [&](std::size_t first, std::size_t last) {
          for (std::size_t i = first; i < last; ++i) f(i);
        },
        f);
  }
  void add(const RunLane& lane) {
    each_seen_by(lane, [&](std::size_t i) { ++count_[i]; });
  }
  /// add() for every lane of `lanes`, on counts all 0 (the first lanes added): a run of samples on
  /// one row counted as +1 at its start and -1 past its end (a lone sample as a run of one), the
  /// steps summed once over every sample (the grid's lanes, each marking ~10^3 samples one by one,
  /// were 5 % of the corpus' plans). The steps are kept in the counts themselves (one slot past
  /// the last), summed in place: the counts are add()'s, whatever the order. `unseen`: the
  /// samples no lane sees after it, ascending (found in the same pass).
  void add_all(const std::vector<RunLane>& lanes, std::vector<std::size_t>& unseen) {
    for (const RunLane& lane : lanes)
      rows_.any_order_in(
          lane.y - half_, lane.y + half_, lane.x0 - detail::kSeenAlongM,
          lane.x1 + detail::kSeenAlongM,
          [&](std::size_t first, std::size_t last) {
            ++count_[first];
            --count_[last];
          },
          [&](std::size_t i) {
            ++count_[i];
            --count_[i + 1];
          });
    int running = 0;
    unseen.clear();
    int* const counts = count_.data();  // the size read once, not at every sample
    const std::size_t n = count_.size() - 1;
    for (std::size_t i = 0; i < n; ++i) {
      running += counts[i];
      counts[i] = running;
      if (running == 0) unseen.push_back(i);
    }
    counts[n] = 0;
  }
  void remove(const RunLane& lane) {
    each_seen_by(lane, [&](std::size_t i) { --count_[i]; });
  }
  /// f(i) for every sample i of `subset` from `from` on (indices ascending) the lane sees, in
  /// increasing i: the same as each_seen_by() filtered to those, without walking the others.
  template <typename F>
  void each_of_seen_by(const std::vector<std::size_t>& subset, std::size_t from,
                       const RunLane& lane, F f) const {
    const double y_lo = lane.y - half_, y_hi = lane.y + half_;
    const double x_lo = lane.x0 - detail::kSeenAlongM, x_hi = lane.x1 + detail::kSeenAlongM;
    // Indices ascending are ordinates ascending (the samples are sorted by them).
    auto k = std::lower_bound(subset.begin() + std::ptrdiff_t(from), subset.end(), y_lo,
                              [&](std::size_t i, double y) { return samples_[i].y < y; });
    for (; k != subset.end() && samples_[*k].y <= y_hi; ++k)
      if (samples_[*k].x >= x_lo && samples_[*k].x <= x_hi) f(*k);
  }
  /// The stretch of `subset` (indices ascending) from `from` on whose samples lie within the lane's
  /// reach across (each_seen_by()'s ordinates, lane.y - half to lane.y + half): every sample of
  /// it the lane sees is there.
  std::pair<std::vector<std::size_t>::iterator, std::vector<std::size_t>::iterator> across_reach(
      std::vector<std::size_t>& subset, std::size_t from, const RunLane& lane) const {
    const double y_lo = lane.y - half_, y_hi = lane.y + half_;
    const auto first = std::lower_bound(subset.begin() + std::ptrdiff_t(from), subset.end(), y_lo,
                                        [&](std::size_t i, double y) { return samples_[i].y < y; });
    const auto last = std::upper_bound(first, subset.end(), y_hi,
                                       [&](double y, std::size_t i) { return y < samples_[i].y; });
    return {first, last};
  }
  /// Whether every sample the lane sees is seen by another lane too.
  bool redundant(const RunLane& lane) const {
    bool all = true;
    each_seen_by(lane, [&](std::size_t i) { all &= count_[i] >= 2; });
    return all;
  }
  int count(std::size_t i) const { return count_[i]; }
  const Point2& sample(std::size_t i) const { return samples_[i]; }
  std::size_t size() const { return samples_.size(); }

 private:
  const std::vector<Point2>& samples_;
  detail::SampleRows rows_;  ///< the samples (sorted by ordinate, then abscissa) by row
  double half_;
  std::vector<int> count_;  ///< per sample, and one slot past the last (add_all()'s steps)
};

// Lanes off the grid for what the grid's lanes do not see: for the first unseen sample (lowest,
// then leftmost), of the lanes through it or up to half a footprint from it, the one that sees
// the most unseen samples. `live`: the samples no lane sees yet, ascending (emptied). `reference`:
// the list pruned whole after each lane (lane_runs' tests compare the two).
std::vector<RunLane> coverage_lanes(const LaneScan& scan, SeenCount& seen, const LaneRunSettings& s,
                                    std::size_t& unreachable, std::vector<std::size_t>& live,
                                    bool reference) {
  const double w = s.footprint_width_m, inset = 1e-3 * s.line_spacing_m;
  // The samples still unseen and not given up on, ascending: the first is the next to cover, and
  // a lane's worth is how many of them it sees. Lanes are only added here, so the list only
  // shrinks: it is pruned after each lane (every sample unseen at the start was asked for every
  // lane tried, seen since or not: most of this step's time on traced fields).
  // Given-up samples are passed (`head`), not erased from the front one by one.
  std::vector<RunLane> added;
  std::vector<Span> spans;  // scan.at(y)'s, one buffer for every ordinate asked
  for (std::size_t head = 0; head < live.size();) {
    const Point2 b = seen.sample(live[head]);
    RunLane best{0, 0, 0, -1};
    long best_count = -1;
    for (const double dy : {0.0, inset, -inset, w / 4, -w / 4, w / 2 - inset, -(w / 2 - inset)}) {
      // Inside the area's height (its middle when the area is thinner than two insets).
      const double lo = scan.y_min + inset, hi = scan.y_max - inset;
      const double y = lo <= hi ? std::clamp(b.y + dy, lo, hi) : (scan.y_min + scan.y_max) / 2;
      if (std::abs(y - b.y) > w / 2) continue;
      scan.at(y, spans);
      for (const Span& in : spans) {
        if (b.x < in.x0 - 1e-6 || b.x > in.x1 + 1e-6) continue;
        const RunLane lane{y, in.x0, in.x1, -1};
        long n = 0;
        seen.each_of_seen_by(live, head, lane, [&](std::size_t) { ++n; });
        if (n > best_count) {
          best_count = n;
          best = lane;
        }
      }
    }
    if (best_count <= 0) {  // a point no lane inside reaches (a needle's tip)
      if (reference)
        live.erase(live.begin());
      else
        ++head;
      ++unreachable;
      continue;
    }
    seen.add(best);
    added.push_back(best);
    if (reference) {
      std::erase_if(live, [&](std::size_t i) { return seen.count(i) > 0; });
      continue;
    }
    // Only the samples within the new lane's reach across can be seen now (the others' counts are
    // still 0): the list is pruned there, not walked whole after every lane.
    const auto [first, last] = seen.across_reach(live, head, best);
    live.erase(std::remove_if(first, last, [&](std::size_t i) { return seen.count(i) > 0; }), last);
  }
  live.clear();
  return added;
}

// Runs in one array (run k's lanes from start[k] to start[k + 1]): a vector per run, grown lane
// by lane, was most of a direction's allocations.
struct Chains {
  std::vector<RunLane> lanes;
  std::vector<std::size_t> start{0};
  std::size_t size() const { return start.size() - 1; }
  std::span<const RunLane> operator[](std::size_t k) const {
    return {lanes.data() + start[k], lanes.data() + start[k + 1]};
  }
  void clear() {
    lanes.clear();
    start.assign(1, 0);
  }
  void end_run() { start.push_back(lanes.size()); }
};

// Zigzag chains over the grid's ordinates: each lane linked to at most one lane on the next
// ordinate up, the pairs that overlap most first, when both turns (left ends, right ends) stay
// inside. Coverage lanes stay runs of their own; the order places them. Into `runs` (cleared; the
// thread's buffers kept from one direction to the next).
void chain(const std::vector<RunLane>& lanes, const detail::Turns& turns, Chains& runs) {
  // The grid's lanes by row (each row's a stretch of `grid`, from group[r] to group[r + 1]; one
  // array, not a vector per row).
  thread_local std::vector<std::size_t> grid, group, up, down;
  thread_local std::vector<int> rows;
  grid.clear();
  group.clear();
  rows.clear();
  runs.clear();
  for (std::size_t i = 0; i < lanes.size(); ++i) {
    if (lanes[i].row < 0) {
      runs.lanes.push_back(lanes[i]);
      runs.end_run();
      continue;
    }
    if (rows.empty() || lanes[i].row != rows.back()) {
      rows.push_back(lanes[i].row);
      group.push_back(grid.size());
    }
    grid.push_back(i);
  }
  group.push_back(grid.size());
  const auto by_row = [&](std::size_t r) {
    return std::span<const std::size_t>(grid.data() + group[r], grid.data() + group[r + 1]);
  };
  const std::size_t none = std::numeric_limits<std::size_t>::max();
  up.assign(lanes.size(), none);
  down.assign(lanes.size(), none);
  thread_local std::vector<std::tuple<double, std::size_t, std::size_t>> links;  // every row's
  for (std::size_t r = 0; r + 1 < rows.size(); ++r) {
    if (rows[r + 1] != rows[r] + 1) continue;  // a row left out between: no zigzag across it
    links.clear();
    for (std::size_t u : by_row(r))
      for (std::size_t v : by_row(r + 1)) {
        const RunLane &a = lanes[u], &b = lanes[v];
        const double overlap = std::min(a.x1, b.x1) - std::max(a.x0, b.x0);
        if (overlap <= 0) continue;
        const auto row = std::size_t(a.row);
        if (!turns.inside({a.x0, a.y}, {b.x0, b.y}, row) ||
            !turns.inside({a.x1, a.y}, {b.x1, b.y}, row))
          continue;
        links.push_back({-overlap, u, v});
      }
    std::sort(links.begin(), links.end());
    for (const auto& [negative_overlap, u, v] : links)
      if (up[u] == none && down[v] == none) {
        up[u] = v;
        down[v] = u;
      }
  }
  for (const std::size_t start : grid) {
    if (down[start] != none) continue;
    for (std::size_t i = start; i != none; i = up[i]) runs.lanes.push_back(lanes[i]);
    runs.end_run();
  }
}

// `turn` is rotate()'s by the direction (geometry::Turn: the same bits).
Ring outline(std::span<const RunLane> run, double half_spacing, const geometry::Turn& turn) {
  Ring ring;  // counter-clockwise: up the right ends, down the left ends
  ring.reserve(4 * run.size());
  for (const RunLane& l : run) {
    ring.push_back(turn({l.x1, l.y - half_spacing}));
    ring.push_back(turn({l.x1, l.y + half_spacing}));
  }
  for (auto l = run.rbegin(); l != run.rend(); ++l) {
    ring.push_back(turn({l->x0, l->y + half_spacing}));
    ring.push_back(turn({l->x0, l->y - half_spacing}));
  }
  return ring;
}

// The grid's ordinates (in the frame turned by -angle): on the grid through s.grid_ordinate_m,
// the last at or below half a footprint above the bottom (inside) to the first at or above half a
// footprint below the top, the fewest that reach both edges; else (or none of those) the area's
// own grid.
std::vector<double> grid_ordinates(const LaneScan& scan, const LaneRunSettings& s) {
  std::vector<double> ys;
  if (s.grid_ordinate_m) {
    const double o = *s.grid_ordinate_m, spacing = s.line_spacing_m;
    const double half = s.footprint_width_m / 2;
    double first = std::floor((scan.y_min + half - o) / spacing);
    if (o + first * spacing <= scan.y_min) first += 1;
    double last = std::ceil((scan.y_max - half - o) / spacing);
    if (o + last * spacing >= scan.y_max) last -= 1;
    for (double k = first; k <= last; ++k) ys.push_back(o + k * spacing);
  }
  if (ys.empty())
    ys = line_offsets(scan.y_min, scan.y_max, s.line_spacing_m, s.footprint_width_m, s.placement);
  return ys;
}

// The grid's lanes at `ys`: the intervals inside `area.fly`, joined across the gaps `area.bridge`
// spans.
detail::SpanRows grid_spans(const LaneRunArea& area, const LaneScan& scan,
                            const std::vector<double>& ys, double angle_deg) {
  return area.bridge.empty() ? scan.at(ys)
                             : bridged(scan.at(ys), LaneScan(area.bridge, angle_deg).at(ys));
}

}  // namespace

std::size_t grid_lane_count(const LaneRunArea& area, const LaneRunSettings& s) {
  if (!(s.line_spacing_m > 0) || !(s.footprint_width_m >= s.line_spacing_m))
    throw std::invalid_argument("grid_lane_count: need 0 < spacing <= footprint width");
  const LaneScan scan(area.fly, s.angle_deg);
  if (!(scan.y_max > scan.y_min)) return 0;
  const detail::SpanRows spans = grid_spans(area, scan, grid_ordinates(scan, s), s.angle_deg);
  std::size_t lanes = 0;
  for (std::size_t k = 0; k < spans.size(); ++k) lanes += spans[k].size();
  return lanes;
}

LaneRuns lane_runs(const LaneRunArea& area, const LaneRunSettings& s) {
  std::vector<Point2> samples;
  return lane_runs(area, s, samples);
}

namespace {

// lane_runs(); reference: the straightforward computation its tests compare with (the coverage
// check on every sample, not only on those no long lane sees; `see` scanned even where it is
// `fly`; the unseen samples' list pruned whole after each coverage lane).
LaneRuns runs_of(const LaneRunArea& area, const LaneRunSettings& s, std::vector<Point2>& samples,
                 bool reference) {
  if (!(s.line_spacing_m > 0) || !(s.footprint_width_m >= s.line_spacing_m))
    throw std::invalid_argument("lane_runs: need 0 < spacing <= footprint width");
  const LaneScan scan(area.fly, s.angle_deg);
  LaneRuns out;
  if (!(scan.y_max > scan.y_min)) return out;

  // 1. The grid's lanes, cut where they meet the boundary.
  const std::vector<double> ys = grid_ordinates(scan, s);
  if (ys.empty()) return out;
  const detail::SpanRows cut = grid_spans(area, scan, ys, s.angle_deg);
  std::vector<RunLane> lanes;
  for (std::size_t k = 0; k < ys.size(); ++k) {
    for (const Span& in : cut[k]) {
      lanes.push_back({ys[k], in.x0, in.x1, int(k)});
      out.grid.lanes_m += in.x1 - in.x0;
    }
    if (!cut[k].empty()) {
      out.grid.y_lo_m = std::min(out.grid.y_lo_m, ys[k]);
      out.grid.y_hi_m = std::max(out.grid.y_hi_m, ys[k]);
    }
  }

  // 2. Lanes for the corners the grid misses. The samples a long grid lane sees (longer than the
  // slivers' length, as step 3 tells them) are left out: no decision below turns on them. Such a
  // sample is seen from the start and lanes are only added until step 3, so it is never unseen
  // (coverage lanes and unreachable points only ask the unseen). Step 3 asks a lane L only if it
  // is at most the slivers' length, and asks whether every sample L sees has a count >= 2: a
  // sample the long lane sees does, L and the long one (not L: longer; never dropped: step 3
  // stops at the first lane longer than that length) both counted. A sample's count is the
  // lanes seeing it, whatever the other samples: the samples kept answer as before, the left-out
  // ones would have answered "yes". So the same lanes, the same order, the same runs.
  const double sliver_m = s.sliver_length_footprints * s.footprint_width_m;
  {
    // Not `see.empty() ? scan : LaneScan(...)`: that copies `scan` (every edge) each direction.
    // Nor when `see` is `fly` bit for bit (a plan without no-fly zones): the same scan.
    std::optional<LaneScan> seen_scan;
    if (!area.see.empty() && (reference || !same_bits(area.see, area.fly)))
      seen_scan.emplace(area.see, s.angle_deg);
    detail::LongLaneReach long_lanes(ys, cut, detail::seen_half_width_m(s.footprint_width_m),
                                     sliver_m);
    detail::coverage_samples(seen_scan ? *seen_scan : scan, s.line_spacing_m, samples,
                             reference ? nullptr : &long_lanes);
  }
  SeenCount seen(samples, s.footprint_width_m);
  thread_local std::vector<std::size_t> unseen;
  seen.add_all(lanes, unseen);
  const std::vector<RunLane> more =
      coverage_lanes(scan, seen, s, out.unreachable_points, unseen, reference);
  out.coverage_lanes = more.size();
  lanes.insert(lanes.end(), more.begin(), more.end());

  // 3. Slivers: short lanes whose every sample another lane sees too, shortest first. A grid lane
  // only at the area's edge across the lanes: no lane kept on one of its neighbouring rows
  // overlaps it. Between lanes on both sides, dropping it would leave two spacings between them,
  // the side overlap lost (docs/swath-plan.md: a sliver is a strip narrower than the footprint, not
  // a short lane; lanes across an arm narrower than two footprints are all short).
  std::vector<std::size_t> row_start(ys.size() + 1, 0);  // grid lanes come first, by row
  for (const RunLane& l : lanes)
    if (l.row >= 0) ++row_start[std::size_t(l.row) + 1];
  for (std::size_t k = 0; k < ys.size(); ++k) row_start[k + 1] += row_start[k];
  std::vector<char> keep(lanes.size(), 1);
  const auto edge_across = [&](const RunLane& lane) {
    if (lane.row < 0) return true;
    for (const int r : {lane.row - 1, lane.row + 1}) {
      if (r < 0 || std::size_t(r) >= ys.size()) return true;
      bool overlapped = false;
      for (std::size_t j = row_start[std::size_t(r)]; j < row_start[std::size_t(r) + 1]; ++j)
        overlapped |= keep[j] && std::min(lane.x1, lanes[j].x1) > std::max(lane.x0, lanes[j].x0);
      if (!overlapped) return true;
    }
    return false;
  };
  std::vector<std::size_t> by_length(lanes.size());
  for (std::size_t i = 0; i < lanes.size(); ++i) by_length[i] = i;
  std::stable_sort(by_length.begin(), by_length.end(), [&](std::size_t a, std::size_t b) {
    return lanes[a].x1 - lanes[a].x0 < lanes[b].x1 - lanes[b].x0;
  });
  for (std::size_t i : by_length) {
    if (lanes[i].x1 - lanes[i].x0 > sliver_m) break;
    if (!edge_across(lanes[i]) || !seen.redundant(lanes[i])) continue;
    seen.remove(lanes[i]);
    keep[i] = 0;
  }
  std::vector<RunLane> kept;
  for (std::size_t i = 0; i < lanes.size(); ++i)
    if (keep[i]) kept.push_back(lanes[i]);
  std::stable_sort(kept.begin(), kept.end(), [](const RunLane& a, const RunLane& b) {
    return a.y < b.y || (a.y == b.y && a.x0 < b.x0);
  });

  // 4. Zigzag runs.
  thread_local Chains runs;
  chain(kept, detail::Turns(scan, ys), runs);
  const geometry::Turn turn(s.angle_deg);
  out.runs.reserve(runs.size());
  out.outlines.reserve(runs.size());
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const std::span<const RunLane> run = runs[k];
    Sweep sweep;
    sweep.angle_deg = s.angle_deg;
    sweep.height_m = run.back().y - run.front().y;
    sweep.lines.reserve(run.size());
    for (const RunLane& l : run) sweep.lines.push_back({turn({l.x0, l.y}), turn({l.x1, l.y})});
    out.runs.push_back(std::move(sweep));
    out.outlines.push_back(outline(run, s.line_spacing_m / 2, turn));
  }
  return out;
}

}  // namespace

LaneRuns lane_runs(const LaneRunArea& area, const LaneRunSettings& s,
                   std::vector<Point2>& samples) {
  return runs_of(area, s, samples, false);
}

namespace detail {

LaneRuns lane_runs_on_every_sample(const LaneRunArea& area, const LaneRunSettings& s) {
  std::vector<Point2> samples;
  return runs_of(area, s, samples, true);
}

}  // namespace detail

}  // namespace swath::planning
