// Division by lanes (divide_lanes): the lanes of every line cut into bands and balanced between
// drones; along a path and by area in division.cpp.
#include "swath/planning/division.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

#include "swath/base/input_error.hpp"
#include "swath/geometry/decomposition.hpp"
#include "swath/planning/sweep.hpp"

#include "division_shared.hpp"

namespace swath::planning {

namespace {

using division_detail::clip_half;
using division_detail::farthest_fitting;
using division_detail::home_costs;
using division_detail::rotated;
using division_detail::weights;
using geometry::Point2;
using geometry::Ring;

// Which lanes of a line give the band below a cut along them their part at the other end: none
// (the part flown first, or towards -x by row), all, or those of every other row (a serpentine).
enum class LaneFlip { none, all, odd_rows, even_rows };

// Cuts across the lanes instead of along them: the rows of lanes in blocks of `rows` consecutive
// rows (0: no blocks, cuts along the lanes; kAllRows: one block), the first block `offset` rows
// (< rows) shorter; within a block a cut is a line perpendicular to the lanes, the band below it
// gets every lane's part on its left (towards -x) or, `from_right`, on its right. With every
// drone at one home beside long lanes a band cut along them grows in steps of a lane flown out and
// back; a block of two rows cut across lets a band end with a U (out along one row, back along
// the next) of any length, the whole area one block lets every band fly all rows.
struct Across {
  static constexpr std::size_t kAllRows = std::numeric_limits<std::size_t>::max();
  std::size_t rows = 0;
  std::size_t offset = 0;
  bool from_right = false;
};

// The lanes of one grid as one line to cut: lanes by ordinate (rows), then along +x; or, with
// blocks of rows cut across (Across), block after block, position s within a block the abscissa
// X(s) at which the length of the block's lanes on the band's side of it is s, and [a, b] every
// lane's part between X(a) and X(b).
class LaneLine {
 public:
  // `by_row`: lanes by ordinate, then along +x; otherwise in the order given.
  // `flip`: which lanes give the band below a cut along them the part at their other end.
  // `across`: blocks of rows cut across the lanes (the lanes by row; `flip` not used then).
  LaneLine(const std::vector<SweepLine>& lanes, double angle_deg, bool by_row,
           LaneFlip flip = LaneFlip::none, Across across = {})
      : angle_deg_(angle_deg), across_(across.rows > 0), from_right_(across.from_right) {
    by_row = by_row || across_;
    for (std::size_t i = 0; i < lanes.size(); ++i) {
      const Point2 a = rotate(lanes[i].start, -angle_deg), b = rotate(lanes[i].end, -angle_deg);
      const bool forward = a.x <= b.x;
      lanes_.push_back({forward ? lanes[i] : SweepLine{lanes[i].end, lanes[i].start}, i,
                        (a.y + b.y) / 2, std::min(a.x, b.x), std::max(a.x, b.x), 0, 0,
                        !by_row && !forward});
    }
    std::vector<Lane*> sorted;
    for (Lane& l : lanes_) sorted.push_back(&l);
    std::sort(sorted.begin(), sorted.end(), [](const Lane* u, const Lane* v) {
      return std::tie(u->y, u->x0, u->index) < std::tie(v->y, v->x0, v->index);
    });
    for (Lane* l : sorted) {
      // Lanes of one grid share ordinates up to rounding.
      if (row_y_.empty() || l->y - row_y_.back() > 1e-6 * (1 + std::abs(l->y)))
        row_y_.push_back(l->y);
      l->row = row_y_.size() - 1;
    }
    if (by_row)
      std::sort(lanes_.begin(), lanes_.end(), [](const Lane& u, const Lane& v) {
        return std::tie(u.y, u.x0, u.index) < std::tie(v.y, v.x0, v.index);
      });
    for (Lane& l : lanes_)
      if (flip == LaneFlip::all || (flip == LaneFlip::odd_rows && l.row % 2 == 1) ||
          (flip == LaneFlip::even_rows && l.row % 2 == 0))
        l.reversed = !l.reversed;
    for (Lane& l : lanes_) {
      l.start = total_;
      total_ += l.x1 - l.x0;
    }
    if (across_) {
      // Blocks of consecutive rows (the lanes are by row); within one, the summed length on the
      // band's side of an abscissa is piecewise linear between the lanes' ends. Abscissae are u:
      // x, or -x from the right.
      total_ = 0;
      for (std::size_t i = 0; i < lanes_.size();) {
        const auto block_of = [&](std::size_t row) {
          return across.rows == Across::kAllRows
                     ? 0
                     : (row + across.rows - across.offset) / across.rows;
        };
        Block b;
        b.first = i;
        while (i < lanes_.size() && block_of(lanes_[i].row) == block_of(lanes_[b.first].row)) ++i;
        b.last = i;
        for (std::size_t k = b.first; k < b.last; ++k) {
          const auto [u0, u1] = u_of(lanes_[k]);
          b.us.push_back(u0);
          b.us.push_back(u1);
        }
        std::sort(b.us.begin(), b.us.end());
        b.us.erase(std::unique(b.us.begin(), b.us.end()), b.us.end());
        for (const double u : b.us) {
          double side = 0;
          for (std::size_t k = b.first; k < b.last; ++k) {
            const auto [u0, u1] = u_of(lanes_[k]);
            side += std::clamp(u - u0, 0.0, u1 - u0);
          }
          b.side.push_back(side);
        }
        b.start = total_;
        total_ += b.side.back();
        b.end = total_;
        blocks_.push_back(std::move(b));
      }
    }
  }

  // A piece of a lane on its row: the row and its abscissae, increasing.
  struct RowPiece {
    std::size_t row;
    double x0, x1;
  };

  // The pieces of lanes in [a, b] of the line as rows and abscissae (as share() cuts them).
  std::vector<RowPiece> row_pieces(double a, double b) const {
    std::vector<RowPiece> out;
    if (across_) {
      for (const auto& [l, x0, x1] : across_pieces(a, b)) out.push_back({l->row, x0, x1});
      return out;
    }
    for (const Lane& l : lanes_) {
      const double from = std::max(a, l.start), to = std::min(b, l.start + (l.x1 - l.x0));
      if (holds_short(l, a, b)) {
        out.push_back({l.row, l.x0, l.x1});
      } else if (to - from > kShortLane_m) {
        const auto [x0, x1] = along(l, from, to);
        out.push_back({l.row, x0, x1});
      }
    }
    return out;
  }

  std::size_t rows() const { return row_y_.size(); }
  // Where row r's strip starts and ends across the lanes: halfway to the next rows' ordinates,
  // the first and last rows out to infinity.
  double row_lo(std::size_t r) const { return r == 0 ? -kInf : (row_y_[r - 1] + row_y_[r]) / 2; }
  double row_hi(std::size_t r) const {
    return r + 1 >= row_y_.size() ? kInf : (row_y_[r] + row_y_[r + 1]) / 2;
  }

  double total() const { return total_; }

  // The pieces of lanes in [a, b] of the line, in lane order; pieces shorter than a micrometre
  // (a cut at a lane's end) are left out, but a lane that short goes whole to the share that
  // holds its start (holds_short).
  std::vector<LanePiece> share(double a, double b) const {
    std::vector<LanePiece> out;
    if (across_) {
      for (const auto& [l, x0, x1] : across_pieces(a, b)) {
        LanePiece piece{l->index, l->line};
        if (x0 > l->x0) piece.line.start = rotate({x0, l->y}, angle_deg_);
        if (x1 < l->x1) piece.line.end = rotate({x1, l->y}, angle_deg_);
        out.push_back(piece);
      }
      return out;
    }
    for (const Lane& l : lanes_) {
      const double length = l.x1 - l.x0;
      const double from = std::max(a, l.start), to = std::min(b, l.start + length);
      const bool whole_short = holds_short(l, a, b);
      if (!(to - from > kShortLane_m) && !whole_short) continue;
      LanePiece piece{l.index, l.line};
      if (!whole_short && (from > l.start || to < l.start + length)) {
        const auto [x0, x1] = along(l, from, to);
        piece.line.start = x0 == l.x0 ? l.line.start : rotate({x0, l.y}, angle_deg_);
        piece.line.end = x1 == l.x1 ? l.line.end : rotate({x1, l.y}, angle_deg_);
      }
      out.push_back(piece);
    }
    return out;
  }

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  static constexpr double kShortLane_m = 1e-6;  // shorter pieces of a lane are not flown apart
  struct Lane {
    SweepLine line;     // flown towards +x of the rotated frame
    std::size_t index;  // in the lanes given
    double y, x0, x1;   // rotated frame
    std::size_t row;
    double start;   // along the line
    bool reversed;  // the line runs along it towards -x (the order given flies it so)
  };

  // A lane no longer than kShortLane_m belongs whole to the one non-empty share [a, b) that holds
  // its start, the last share [a, total] closed: cut nowhere, flown once.
  bool holds_short(const Lane& l, double a, double b) const {
    return l.x1 - l.x0 <= kShortLane_m && b > a && a <= l.start && (l.start < b || b >= total_);
  }

  // A block of rows cut across: lanes_[first, last), their ends' abscissae u (increasing) and
  // the summed length of its lanes below each (side), its stretch [start, end] of the line.
  struct Block {
    std::size_t first = 0, last = 0;
    std::vector<double> us, side;
    double start = 0, end = 0;
  };

  // Lane l's ends as abscissae u, increasing.
  std::pair<double, double> u_of(const Lane& l) const {
    return from_right_ ? std::make_pair(-l.x1, -l.x0) : std::make_pair(l.x0, l.x1);
  }

  // Within block b: the abscissa u where the summed length of lane below it is s (0 < s < the
  // block's length; past a stretch without lanes).
  static double abscissa(const Block& b, double s) {
    const auto k = static_cast<std::size_t>(std::upper_bound(b.side.begin(), b.side.end(), s) -
                                            b.side.begin() - 1);
    if (k + 1 >= b.us.size()) return b.us.back();
    const double lanes = (b.side[k + 1] - b.side[k]) / (b.us[k + 1] - b.us[k]);  // lanes at u
    return std::min(b.us[k + 1], b.us[k] + (s - b.side[k]) / lanes);
  }

  // Across: each lane's part of [a, b] (b > a): in a block within [a, b] whole, in one that holds
  // a or b its part between the abscissae of a and b; pieces no longer than kShortLane_m left out,
  // a lane that short whole to the share whose [U(a), U(b)) holds its start (a block of only such
  // lanes to the share whose [a, b) holds its start, the last share closed). Neighbouring shares
  // meet at the same abscissa, so the pieces of a lane add up to it.
  struct AcrossPiece {
    const Lane* lane;
    double x0, x1;
  };
  std::vector<AcrossPiece> across_pieces(double a, double b) const {
    std::vector<AcrossPiece> out;
    if (!(b > a)) return out;
    for (const Block& block : blocks_) {
      const bool last = b >= total_;
      if (block.end > block.start ? !(a < block.end && b > block.start)
                                  : !(a <= block.start && (block.start < b || last)))
        continue;
      const double ua = a <= block.start ? -kInf : abscissa(block, a - block.start);
      const double ub = b >= block.end ? kInf : abscissa(block, b - block.start);
      for (std::size_t k = block.first; k < block.last; ++k) {
        const Lane& l = lanes_[k];
        const auto [u0, u1] = u_of(l);
        if (u1 - u0 <= kShortLane_m) {
          if (ua <= u0 && (u0 < ub || last)) out.push_back({&l, l.x0, l.x1});
          continue;
        }
        const double from = std::max(u0, ua), to = std::min(u1, ub);
        if (!(to - from > kShortLane_m)) continue;
        if (from_right_)
          out.push_back({&l, -to, -from});
        else
          out.push_back({&l, from, to});
      }
    }
    return out;
  }

  // The part [from, to] of the line on lane l (from < to) as abscissae, increasing.
  std::pair<double, double> along(const Lane& l, double from, double to) const {
    if (l.reversed) return {l.x1 - (to - l.start), l.x1 - (from - l.start)};
    return {l.x0 + (from - l.start), l.x0 + (to - l.start)};
  }
  double angle_deg_;
  bool across_, from_right_;
  std::vector<Lane> lanes_;
  std::vector<double> row_y_;
  double total_ = 0;
  std::vector<Block> blocks_;  // across
};

// `ring` clipped to a box of the frame rotated by -angle_deg (infinite sides not clipped), in the
// input frame.
Ring clip_box(const Ring& ring, double angle_deg, const std::array<double, 4>& box) {
  Ring r = rotated(ring, -angle_deg);
  if (std::isfinite(box[0])) r = clip_half(r, box[0], false);
  if (std::isfinite(box[1])) r = clip_half(r, box[1], true);
  if (std::isfinite(box[2])) r = clip_half(r, box[2], false, 0);
  if (std::isfinite(box[3])) r = clip_half(r, box[3], true, 0);
  Ring out;
  for (const Point2& p : r)
    if (out.empty() || !(out.back() == p)) out.push_back(rotate(p, angle_deg));
  while (out.size() > 1 && out.back() == out.front()) out.pop_back();
  return out;
}

// Up to this many drones every order of them over the bands is balanced (4! = 24 orders; 6!
// took tens of seconds on split areas); beyond, the heuristic and fleet orders and swaps of the
// best: every pair up to kPairwiseSwapDrones, adjacent ones beyond.
constexpr std::size_t kAllOrdersDrones = 4;
constexpr std::size_t kPairwiseSwapDrones = 8;

// Orders of the drones over the bands (band k flown by order[k]) worth balancing: every
// permutation up to kAllOrdersDrones, drones that `same` says are interchangeable in one order
// only; beyond, the heuristic order and the fleet's.
std::vector<std::vector<std::size_t>> band_orders(
    std::size_t n, const std::function<bool(std::size_t, std::size_t)>& same,
    const std::vector<std::size_t>& heuristic) {
  std::vector<std::vector<std::size_t>> out{heuristic};
  if (n > kAllOrdersDrones) {
    std::vector<std::size_t> fleet(n);
    std::iota(fleet.begin(), fleet.end(), 0);
    if (fleet != heuristic) out.push_back(fleet);
    return out;
  }
  std::vector<std::size_t> p(n);
  std::iota(p.begin(), p.end(), 0);
  do {
    bool canonical = true;  // interchangeable drones in fleet order
    for (std::size_t i = 0; i < n && canonical; ++i)
      for (std::size_t j = i + 1; j < n && canonical; ++j)
        if (p[i] > p[j] && same(p[i], p[j])) canonical = false;
    if (canonical && p != heuristic) out.push_back(p);
  } while (std::next_permutation(p.begin(), p.end()));
  return out;
}

// The state one divide_lanes() call shares between its steps: the lanes as one line, the drones,
// how a share is swept and measured (remembered: the searches ask for the same shares again, a
// greedy pass's last band, the refinement's neighbours).
class LaneDivision {
 public:
  LaneDivision(const std::vector<Ring>& rings, double angle_deg,
               const std::vector<SweepLine>& lanes, const std::vector<DroneResource>& drones,
               const LaneSweep& sweep, const FlightMeasure& measure,
               const std::vector<std::size_t>& lane_cell, const std::vector<Ring>& share_area,
               bool by_row = false, LaneFlip flip = LaneFlip::none, Across across = {})
      : drones_(drones),
        sweep_(sweep),
        measure_(measure),
        angle_deg_(angle_deg),
        pieces_(geometry::boustrophedon_decomposition(share_area.empty() ? rings : share_area,
                                                      angle_deg)
                    .pieces),
        by_cell_(!lane_cell.empty() && lane_cell.size() == lanes.size()),
        line_(lanes, angle_deg, !by_cell_ || by_row, flip, across),
        tolerance_(1e-6 * (1 + line_.total())) {
    std::vector<Point2> vertices;
    for (const Ring& ring : rings) vertices.insert(vertices.end(), ring.begin(), ring.end());
    home_cost_ = home_costs(vertices, drones);
    weights_ = weights(drones, home_cost_, budgets_);
    for (const Ring& ring : share_area.empty() ? rings : share_area)
      total_area_ += geometry::signed_area(ring);
  }

  std::size_t size() const { return drones_.size(); }
  /// Whether the lanes are cut in the flight order of a split area's cells (`lane_cell` given).
  bool by_cell() const { return by_cell_; }
  double total() const { return line_.total(); }
  const DroneResource& drone(std::size_t d) const { return drones_[d]; }
  double angle_deg() const { return angle_deg_; }
  const std::vector<double>& weight() const { return weights_; }

  // Drone d flying [a, b] of the line: its measured time, +inf beyond its range.
  double flight_s(std::size_t d, double a, double b) {
    if (!(b > a)) return 0.0;
    const auto key = std::make_tuple(d, a, b);
    if (const auto it = known_.find(key); it != known_.end()) return it->second;
    const std::vector<LanePiece> share = line_.share(a, b);
    double t = 0.0;
    if (!share.empty()) {
      const FlightCost cost = measure_(d, sweep_(d, share));
      t = over_range(d, cost) ? kInfinity : cost.time_s;
    }
    return known_[key] = t;
  }

  // Each band's flight time for `bounds` (n + 1 of them) in `order`.
  std::vector<double> times_of(const std::vector<std::size_t>& order,
                               const std::vector<double>& bounds) {
    std::vector<double> t(size());
    for (std::size_t k = 0; k < size(); ++k) t[k] = flight_s(order[k], bounds[k], bounds[k + 1]);
    return t;
  }

  // Greedy cuts within `makespan`: each band's drone the longest share it flies in time. The
  // n + 1 bounds; reaching the end of the line means the makespan is feasible.
  std::vector<double> greedy(const std::vector<std::size_t>& order, double makespan) {
    std::vector<double> bounds{0};
    for (std::size_t k = 0; k < size(); ++k) {
      const double start = bounds.back();
      bounds.push_back(farthest_fitting(start, total(), tolerance_, [&](double end) {
        return flight_s(order[k], start, end) <= makespan;
      }));
    }
    return bounds;
  }

  // Greedy from the last band down: each drone the longest share it flies within `makespan`.
  std::vector<double> greedy_down(const std::vector<std::size_t>& order, double makespan) {
    const std::size_t n = size();
    std::vector<double> bounds(n + 1, 0.0);
    bounds[n] = total();
    for (std::size_t k = n; k-- > 1;)  // the band's start
      bounds[k] = farthest_fitting(bounds[k + 1], 0.0, tolerance_, [&](double start) {
        return flight_s(order[k], start, bounds[k + 1]) <= makespan;
      });
    return bounds;
  }

  bool reaches(const std::vector<double>& bounds) const { return bounds.back() >= total(); }

  // Where the flight times of the drones either side of a cut in [a, b] cross: the bracket
  // (lo, hi) with lower(lo) <= upper(lo) and lower(hi) > upper(hi), within the tolerance.
  std::pair<double, double> crossing(std::size_t lower, std::size_t upper, double a, double b) {
    double lo = a, hi = b;  // gap(a) <= 0 <= gap(b)
    while (hi - lo > tolerance_) {
      const double mid = (lo + hi) / 2;
      (flight_s(lower, a, mid) - flight_s(upper, mid, b) <= 0 ? lo : hi) = mid;
    }
    return {lo, hi};
  }

  // The division for `bounds` in `order` and its score: the longest flight with +inf beyond a
  // drone's range (as flight_s), so that cuts over a range never win on time.
  std::pair<DivisionResult, double> result_for(const std::vector<std::size_t>& order,
                                               const std::vector<double>& bounds) {
    DivisionResult r;
    double score_s = 0.0;
    r.drones.resize(size());
    std::vector<std::vector<Ring>> regions = regions_of(bounds);
    for (std::size_t k = 0; k < size(); ++k) {
      const std::size_t d = order[k];
      DroneWork& work = r.drones[d];
      const double a = bounds[k], b = std::max(bounds[k], bounds[k + 1]);
      work.region = std::move(regions[k]);
      double area = 0;
      for (const Ring& piece : work.region) area += geometry::signed_area(piece);
      work.share = total_area_ > 0 ? area / total_area_ : 0;
      const std::vector<LanePiece> share = line_.share(a, b);
      if (!share.empty()) {
        work.path = sweep_(d, share);
        const FlightCost cost = measure_(d, work.path);
        work.estimated_time_s = cost.time_s;
        score_s = std::max(score_s, over_range(d, cost) ? kInfinity : cost.time_s);
      }
      work.home_cost_m = home_cost_[d];
      work.budget_m = budgets_[d];
      r.makespan_s = std::max(r.makespan_s, work.estimated_time_s);
    }
    return {std::move(r), score_s};
  }

 private:
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();

  bool over_range(std::size_t d, const FlightCost& cost) const {
    return division_detail::beyond_limits(drones_[d], cost.length_m, cost.time_s);
  }

  // The bands' regions for `bounds` (n + 1 of them), a partition of the area: each row of lanes
  // (its strip ends halfway between lane ordinates, the first and last reach out to infinity)
  // goes across to the bands of its pieces of lanes, split halfway between consecutive pieces of
  // different bands (at the cut where a lane is cut along its length), the ground between two
  // lanes of a row (a bay, a hole, a comb's gap) to the nearer along the row; strips held by one
  // band whole are joined with their neighbours of the same band. The strips tile the plane, the
  // boustrophedon pieces the area, so the regions' areas add up to it (clipping the cells to the
  // lanes' rows instead lost the cells' ground outside those rows and any ground between cells).
  std::vector<std::vector<Ring>> regions_of(const std::vector<double>& bounds) const {
    const std::size_t n = size();
    struct Owned {
      double x0, x1;
      std::size_t band;
    };
    std::vector<std::vector<Owned>> rows(line_.rows());
    for (std::size_t k = 0; k < n; ++k) {
      const double a = bounds[k], b = std::max(bounds[k], bounds[k + 1]);
      if (!(b > a)) continue;
      for (const LaneLine::RowPiece& p : line_.row_pieces(a, b))
        rows[p.row].push_back({p.x0, p.x1, k});
    }
    std::vector<std::vector<std::array<double, 4>>> boxes(n);            // y0, y1, x0, x1 per band
    std::optional<std::pair<std::size_t, std::array<double, 4>>> whole;  // open run of rows
    auto close_whole = [&] {
      if (whole) boxes[whole->first].push_back(whole->second);
      whole.reset();
    };
    double y0 = -kInfinity;  // a row without pieces (none is expected) goes to the next
    for (std::size_t r = 0; r < rows.size(); ++r) {
      std::vector<Owned>& row = rows[r];
      if (row.empty()) continue;
      std::sort(row.begin(), row.end(), [](const Owned& u, const Owned& v) {
        return std::tie(u.x0, u.x1, u.band) < std::tie(v.x0, v.x1, v.band);
      });
      const double y1 = line_.row_hi(r);
      std::vector<std::pair<double, std::size_t>> starts{{-kInfinity, row.front().band}};
      double reach = row.front().x1;  // the current band's farthest abscissa
      for (std::size_t i = 1; i < row.size(); ++i) {
        if (row[i].band != starts.back().second)
          starts.push_back(
              {std::clamp((reach + row[i].x0) / 2, starts.back().first, kInfinity), row[i].band});
        reach = row[i].band == row[i - 1].band ? std::max(reach, row[i].x1) : row[i].x1;
      }
      if (starts.size() == 1) {
        if (whole && whole->first == starts.front().second) {
          whole->second[1] = y1;
        } else {
          close_whole();
          whole = {starts.front().second, {y0, y1, -kInfinity, kInfinity}};
        }
      } else {
        close_whole();
        for (std::size_t i = 0; i < starts.size(); ++i)
          boxes[starts[i].second].push_back(
              {y0, y1, starts[i].first, i + 1 < starts.size() ? starts[i + 1].first : kInfinity});
      }
      y0 = y1;
    }
    close_whole();
    if (std::isfinite(y0) && !boxes.empty()) {  // rows without pieces at the top (none expected)
      for (auto& band : boxes)
        if (!band.empty() && band.back()[1] == y0) band.back()[1] = kInfinity;
    }
    std::vector<std::vector<Ring>> regions(n);
    for (std::size_t k = 0; k < n; ++k)
      for (const std::array<double, 4>& box : boxes[k])
        for (const Ring& piece : pieces_) {
          Ring clipped = clip_box(piece, angle_deg_, box);
          if (clipped.size() >= 3 && geometry::signed_area(clipped) > 1e-9 * total_area_)
            regions[k].push_back(std::move(clipped));
        }
    return regions;
  }

  const std::vector<DroneResource>& drones_;
  const LaneSweep& sweep_;
  const FlightMeasure& measure_;
  double angle_deg_;
  std::vector<Ring> pieces_;  // of the area the regions tile
  bool by_cell_;
  LaneLine line_;
  double tolerance_;
  double total_area_ = 0;
  std::vector<double> home_cost_;
  std::vector<std::optional<double>> budgets_;
  std::vector<double> weights_;
  std::map<std::tuple<std::size_t, double, double>, double> known_;
};

constexpr double kSlack = 1.02;  // how much longer than the smallest makespan a balance may be
// A spread (longest over shortest flight) this narrow is not worth searching further.
constexpr double kGoodSpread = 1.002;
// The cut lanes' parts from their other ends are tried only above this spread (docs/swath-plan.md
// bound for typical fields): below it they bought little and cost much (the meadow with
// three-quads at 1.012 planned in 339 ms instead of 34 ms, for the same shares).
constexpr double kFlipSpread = 1.02;

// A balance of one order of the drones over the bands.
struct Balanced {
  double makespan_s;
  std::vector<std::size_t> order;
  std::vector<double> bounds;
};

// Step 1: the smallest makespan per order of the drones over the bands (band_orders(), then
// swaps of the best beyond kAllOrdersDrones), by bisection on the makespan with greedy cuts; an
// order whose greedy cuts cannot reach the end within 2 % of the best makespan so far cannot
// compete and costs one greedy pass.
std::vector<Balanced> balance_orders(LaneDivision& ld, double proportional_makespan) {
  const std::size_t n = ld.size();
  // The drones in the order of their homes across the lanes: nearest band first, a good start.
  std::vector<std::size_t> heuristic(n);
  std::iota(heuristic.begin(), heuristic.end(), 0);
  std::stable_sort(heuristic.begin(), heuristic.end(), [&](std::size_t i, std::size_t j) {
    return rotate(ld.drone(i).home, -ld.angle_deg()).y <
           rotate(ld.drone(j).home, -ld.angle_deg()).y;
  });
  std::vector<double> whole(n);
  for (std::size_t d = 0; d < n; ++d) whole[d] = ld.flight_s(d, 0, ld.total());
  const auto same = [&](std::size_t i, std::size_t j) {
    const DroneResource &a = ld.drone(i), &b = ld.drone(j);
    return a.home == b.home && a.speed_m_s == b.speed_m_s && a.range_m == b.range_m &&
           a.flight_limit_s == b.flight_limit_s && a.capability == b.capability &&
           whole[i] == whole[j];
  };
  double best = std::numeric_limits<double>::infinity();
  std::vector<Balanced> found;
  auto balance = [&](const std::vector<std::size_t>& order) {
    double hi = best * kSlack;
    if (!std::isfinite(hi)) {
      hi = proportional_makespan > 0 && std::isfinite(proportional_makespan) ? proportional_makespan
                                                                             : 1.0;
      for (int guard = 0; guard < 40 && !ld.reaches(ld.greedy(order, hi)); ++guard) hi *= 1.5;
    }
    if (!ld.reaches(ld.greedy(order, hi))) return;
    double lo = 0;
    while (hi - lo > 1e-5 * hi) {
      const double mid = (lo + hi) / 2;
      (ld.reaches(ld.greedy(order, mid)) ? hi : lo) = mid;
    }
    std::vector<double> bounds = ld.greedy(order, hi);
    double longest = 0;
    for (std::size_t k = 0; k < n; ++k)
      longest = std::max(longest, ld.flight_s(order[k], bounds[k], bounds[k + 1]));
    best = std::min(best, longest);
    found.push_back({longest, order, std::move(bounds)});
  };
  if (n < 2 || !(ld.total() > 0)) return found;
  std::set<std::vector<std::size_t>> tried;
  for (const auto& order : band_orders(n, same, heuristic)) {
    tried.insert(order);
    balance(order);
  }
  if (n > kAllOrdersDrones && !found.empty()) {
    // Beyond the permutations: swaps of the best order once (every pair, or adjacent ones for
    // large fleets), interchangeable drones not swapped.
    const auto first = std::min_element(
        found.begin(), found.end(),
        [](const Balanced& u, const Balanced& v) { return u.makespan_s < v.makespan_s; });
    const std::vector<std::size_t> start = first->order;
    for (std::size_t i = 0; i + 1 < n; ++i)
      for (std::size_t j = i + 1; j < (n > kPairwiseSwapDrones ? i + 2 : n); ++j) {
        if (same(start[i], start[j])) continue;
        std::vector<std::size_t> order = start;
        std::swap(order[i], order[j]);
        if (tried.insert(order).second) balance(order);
      }
  }
  return found;
}

// Longest over shortest of the flights that fly (1 when none does), and the longest.
std::pair<double, double> spread(const std::vector<double>& t) {
  double longest = 0, shortest = std::numeric_limits<double>::infinity();
  for (const double v : t) {
    longest = std::max(longest, v);
    if (v > 0) shortest = std::min(shortest, v);
  }
  return std::make_pair(std::isfinite(shortest) ? longest / shortest : 1.0, longest);
}

// Cut by cut, the two drones beside a cut brought to where their times cross (either side of a
// jump between them), within `makespan_limit`. relax: each cut to whichever side of the crossing
// makes the longer of its two drones shorter, the narrowest state seen kept (it can pass through
// wider ones); otherwise a cut moves only when the whole spread narrows.
std::pair<std::vector<double>, std::pair<double, double>> refine(
    LaneDivision& ld, const std::vector<std::size_t>& order, std::vector<double> bounds, bool relax,
    double makespan_limit) {
  const std::size_t n = ld.size();
  std::vector<double> times = ld.times_of(order, bounds);
  std::vector<double> kept = bounds;
  std::pair<double, double> kept_spread = spread(times);
  for (int round = 0; round < 8; ++round) {
    bool changed = false;
    for (std::size_t k = 1; k < n; ++k) {
      const double a = bounds[k - 1], b = bounds[k + 1];
      const auto [lo, hi] = ld.crossing(order[k - 1], order[k], a, b);
      double pair_best = std::max(times[k - 1], times[k]);
      for (const double t : {lo, hi}) {
        std::vector<double> trial = times;
        trial[k - 1] = ld.flight_s(order[k - 1], a, t);
        trial[k] = ld.flight_s(order[k], t, b);
        const auto [ratio, longest] = spread(trial);
        const double pair = std::max(trial[k - 1], trial[k]);
        const bool better =
            relax ? pair < pair_best * (1 - 1e-9) : ratio < spread(times).first * (1 - 1e-9);
        if (longest <= makespan_limit && better) {
          times = trial;
          bounds[k] = t;
          pair_best = pair;
          changed = true;
          if (ratio < kept_spread.first * (1 - 1e-9)) {
            kept = bounds;
            kept_spread = {ratio, longest};
          }
        }
      }
    }
    if (!changed) break;
  }
  return std::make_pair(kept, kept_spread);
}

// Step 2: a drone's time jumps where its share first reaches into a lane (the turn to it, the
// stops at its ends, which end of its zigzag it leaves from), so the smallest makespan can leave
// the drone beside a jump well short of the others. For each order within 2 % of the smallest
// makespan, from greedy cuts within a few makespans up to 2 % above it (from the first band and
// from the last), refine(); the narrowest found within 2 % of the smallest makespan (and within
// `cap_s`, seconds) wins. `found`: not empty.
std::pair<std::vector<std::size_t>, std::vector<double>> narrowest(
    LaneDivision& ld, std::vector<Balanced> found,
    double cap_s = std::numeric_limits<double>::infinity()) {
  const std::size_t n = ld.size();
  std::sort(found.begin(), found.end(),
            [](const Balanced& u, const Balanced& v) { return u.makespan_s < v.makespan_s; });
  const double makespan_limit = std::min(found.front().makespan_s * kSlack, cap_s);
  std::vector<std::size_t> best_order = found.front().order;
  std::vector<double> best_bounds = found.front().bounds;
  std::pair<double, double> best_spread{std::numeric_limits<double>::infinity(), 0.0};
  for (const Balanced& candidate : found) {
    if (candidate.makespan_s > makespan_limit || best_spread.first <= kGoodSpread) break;
    const std::vector<std::size_t>& order = candidate.order;
    auto consider = [&](const std::vector<double>& start) {
      if (start.size() != n + 1 || start.back() < ld.total() ||
          spread(ld.times_of(order, start)).second > makespan_limit)
        return;
      for (const bool relax : {false, true}) {
        const auto [bounds, sp] = refine(ld, order, start, relax, makespan_limit);
        if (sp.first < best_spread.first * (1 - 1e-9) ||
            (sp.first <= best_spread.first * (1 + 1e-9) && sp.second < best_spread.second)) {
          best_spread = sp;
          best_order = order;
          best_bounds = bounds;
        }
      }
    };
    consider(candidate.bounds);
    for (const double above : {0.0, 0.005, 0.01, 0.02}) {
      if (best_spread.first <= kGoodSpread) break;
      consider(ld.greedy(order, candidate.makespan_s * (1 + above)));
      consider(ld.greedy_down(order, candidate.makespan_s * (1 + above)));
    }
  }
  return {best_order, best_bounds};
}

}  // namespace

DivisionResult divide_lanes(const std::vector<Ring>& rings, double angle_deg,
                            const std::vector<SweepLine>& lanes,
                            const std::vector<DroneResource>& drones, const LaneSweep& sweep,
                            const FlightMeasure& measure, const std::vector<std::size_t>& lane_cell,
                            const std::vector<Ring>& share_area, Balance balance) {
  LaneDivision ld(rings, angle_deg, lanes, drones, sweep, measure, lane_cell, share_area);
  const std::size_t n = ld.size();
  const double total = ld.total();
  // Proportional: shares of the lanes' length in proportion to the weights, fleet order.
  const std::vector<double>& w = ld.weight();
  const double total_w = std::accumulate(w.begin(), w.end(), 0.0);
  std::vector<std::size_t> fleet(n);
  std::iota(fleet.begin(), fleet.end(), 0);
  std::vector<double> proportional{0};
  for (std::size_t k = 0; k < n; ++k)
    proportional.push_back(k + 1 == n ? total : proportional.back() + w[k] / total_w * total);
  auto [result, result_score] = ld.result_for(fleet, proportional);
  const double proportional_makespan = result.makespan_s;
  result.proportional_makespan_s = proportional_makespan;
  // Capability shares beyond a drone's range or charge (a score of +inf) are re-cut as the
  // balance cuts, within every drone's limits where it can.
  if (balance == Balance::capability && std::isfinite(result_score)) return result;
  const bool recut = balance == Balance::capability;

  // The balance on the line in the given order; for a split area whose flight order leaves the
  // drones more than kGoodSpread apart, on the lanes by row too (the flight order puts a cell's
  // runs end to end, so a share that needs a little more lane must take it from the next cell,
  // transit and all: 1.0204 on the vineyard with three-quads; by row, a share's end runs across
  // the cells side by side). Of the two, the smallest spread within 2 % of the smaller makespan,
  // spreads under kGoodSpread counted as equal and then the shorter makespan.
  std::vector<std::pair<DivisionResult, double>> candidates;
  // cap_s: where the narrowest cuts within 2 % of the line's own makespan are longer, those
  // within cap_s too (a second candidate).
  auto balance_line = [&](LaneDivision& line,
                          double cap_s = std::numeric_limits<double>::infinity()) {
    const std::vector<Balanced> found = balance_orders(line, proportional_makespan);
    if (found.empty()) return;
    const auto [order, bounds] = narrowest(line, found);
    candidates.push_back(line.result_for(order, bounds));
    if (candidates.back().second > cap_s) {
      const auto [capped_order, capped_bounds] = narrowest(line, found, cap_s);
      candidates.push_back(line.result_for(capped_order, capped_bounds));
    }
  };
  auto ratio_of = [](const DivisionResult& r) {
    std::vector<double> t;
    for (const DroneWork& work : r.drones) t.push_back(work.estimated_time_s);
    return spread(t).first;
  };
  balance_line(ld);
  if (ld.by_cell() && (candidates.empty() || ratio_of(candidates.front().first) > kGoodSpread)) {
    LaneDivision rows(rings, angle_deg, lanes, drones, sweep, measure, lane_cell, share_area, true);
    balance_line(rows);
  }
  double best_score = std::numeric_limits<double>::infinity();
  for (const auto& c : candidates) best_score = std::min(best_score, c.second);
  const std::pair<DivisionResult, double>* chosen = nullptr;
  std::pair<double, double> chosen_key{std::numeric_limits<double>::infinity(), 0.0};
  for (const auto& c : candidates) {
    if (!(c.second <= best_score * kSlack)) continue;
    const std::pair<double, double> key{std::max(ratio_of(c.first), kGoodSpread), c.second};
    if (!chosen || key < chosen_key) {
      chosen_key = key;
      chosen = &c;
    }
  }
  if (chosen && chosen->second <= result_score) {
    result = chosen->first;
    result_score = chosen->second;
  }
  // Where the drones are still more than kFlipSpread apart, the same with the lanes' parts taken
  // from their other ends: a band's zigzag ends at one end of a lane or the other with the parity
  // of its lanes, so a share one piece of lane longer can jump by a home leg's length (1.0759 on
  // the corpus's walk 0 with three equal drones: 787, 787, 731 s, the third drone a lane's flight
  // short or one too long). Below a cut along a lane the band's part is then from its other end:
  // every lane's (whole rows), every other row's (a serpentine). A variant is kept only if it is
  // narrower and its longest flight no longer than what it replaces.
  if (balance == Balance::makespan && n > 1 && ratio_of(result) > kFlipSpread) {
    std::vector<std::pair<bool, LaneFlip>> variants;  // (by row, flip)
    if (ld.by_cell()) variants.push_back({false, LaneFlip::all});
    for (const LaneFlip flip : {LaneFlip::all, LaneFlip::odd_rows, LaneFlip::even_rows})
      variants.push_back({true, flip});
    for (const auto& [by_row, flip] : variants) {
      const double ratio = ratio_of(result);
      if (ratio <= kGoodSpread) break;
      LaneDivision line(rings, angle_deg, lanes, drones, sweep, measure, lane_cell, share_area,
                        by_row, flip);
      candidates.clear();
      balance_line(line);
      if (candidates.empty()) continue;
      auto& [r, score] = candidates.front();
      if (score <= result_score && ratio_of(r) < ratio * (1 - 1e-9)) {
        result = std::move(r);
        result_score = score;
      }
    }
  }
  // Where the drones are still more than kFlipSpread apart, bands cut across the lanes (Across):
  // blocks of two rows (from either row's parity, the band below a cut given the lanes' parts on
  // their left or right) or all rows in one block. Cut along the rows only, with every drone at
  // one home beside long lanes, a band's time steps by a lane flown out and back where its share
  // first reaches into one more (walk 0 above: 720 s, then 807 s; 768, 768, 731 s at best); a
  // band ending in a U over two rows grows without that step (764, 764, 764 s). Each variant's
  // narrowest cuts within 2 % of its own makespan, and where those are longer than the division
  // so far, also its narrowest within that (its 2 % often ends a few per cent longer: combs, L/T
  // shapes). Both are needed: refining from greedy cuts can end far below their makespan (the
  // corpus's l-t 0 with four drones: 337.7 s greedy, 300.0 s refined, 1.0006), and a search
  // capped below the greedy makespan finds nothing. The narrowest of all within the division's
  // longest flight so far (spreads under kGoodSpread equal, then the shortest makespan) replaces
  // it where narrower.
  if (balance == Balance::makespan && n > 1 && ratio_of(result) > kFlipSpread) {
    std::vector<Across> variants;
    for (const bool from_right : {false, true})
      for (const std::size_t offset : {0, 1}) variants.push_back({2, offset, from_right});
    for (const bool from_right : {false, true})
      variants.push_back({Across::kAllRows, 0, from_right});
    const double limit_s = result_score;
    std::pair<double, double> best_key{ratio_of(result) * (1 - 1e-9), limit_s};
    for (const Across& across : variants) {
      if (best_key.first <= kGoodSpread) break;
      LaneDivision line(rings, angle_deg, lanes, drones, sweep, measure, lane_cell, share_area,
                        true, LaneFlip::none, across);
      candidates.clear();
      balance_line(line, limit_s);
      for (auto& [r, score] : candidates) {
        const std::pair<double, double> key{std::max(ratio_of(r), kGoodSpread), score};
        if (score <= limit_s && key < best_key) {
          best_key = key;
          result = std::move(r);
          result_score = score;
        }
      }
    }
  }
  result.proportional_makespan_s = proportional_makespan;
  result.recut_within_limits = recut;
  return result;
}

}  // namespace swath::planning
