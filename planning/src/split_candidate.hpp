#pragma once
// Internal to split.cpp and split_regions.cpp: a candidate plan (the cells or runs at one
// direction, swept and ordered), the routed metric, and the steps both files take.
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "swath/geometry/polygon.hpp"
#include "swath/geometry/visibility.hpp"
#include "swath/planning/cell_order.hpp"
#include "swath/planning/split.hpp"
#include "swath/planning/sweep.hpp"

namespace swath::planning::split_detail {

using geometry::Point2;
using Metric = std::function<double(Point2, Point2)>;

struct Candidate {
  double angle_deg;
  SplitCells method = SplitCells::boustrophedon;
  std::vector<geometry::Ring> cells;
  std::vector<Sweep> sweeps;  // per cell, bottom to top
  CellOrder order;
  std::vector<std::vector<std::pair<bool, bool>>> variant_flags;  // per cell, per variant
};

/// The bearing of the line through a and b, degrees in [0, 180).
double line_angle(Point2 a, Point2 b);

/// Sweeps every cell and builds the ordering problem under `metric`.
CellOrderProblem problem_for(Candidate& c, Point2 home, const Metric& metric);

/// The lane runs of `rings` at `angle` as a candidate (bridged: joined across s.bridge_rings);
/// `samples`: lane_runs' buffer for its coverage samples; `grid` (if given): the grid's extent
/// (LaneRuns::grid).
Candidate sweep_runs(const std::vector<geometry::Ring>& rings, double angle, const SplitSettings& s,
                     bool bridged, std::vector<Point2>& samples, bool drop_slivers = true,
                     std::optional<double> grid_ordinate_m = std::nullopt,
                     LaneGridExtent* grid = nullptr);

/// The boustrophedon cells of `rings` at `angle` (degrees) as a candidate, each cell's lines
/// sorted by ordinate (in the frame turned by -angle).
Candidate sweep_cells(const std::vector<geometry::Ring>& rings, double angle,
                      const SplitSettings& s);

/// The straight distance, metres: the estimates' metric.
double straight_m(Point2 a, Point2 b);

// Routed paths and their lengths, memoised: the four variants of a cell share their turns, and
// the ordering asks for the same transits again and again.
class RoutedMetric {
 public:
  explicit RoutedMetric(const geometry::VisibilityRouter& router) : router_(router) {}
  double operator()(Point2 a, Point2 b) { return known(a, b).length_m; }
  const std::vector<Point2>& path(Point2 a, Point2 b) { return known(a, b).path; }

 private:
  struct Route {
    std::vector<Point2> path;  // from the lexicographically smaller end
    double length_m;
  };
  const Route& known(Point2 a, Point2 b) {
    if (std::tie(b.x, b.y) < std::tie(a.x, a.y)) std::swap(a, b);  // the metric is symmetric
    if (!router_.routes()) {
      // Every path is straight (the router's own answer): nothing worth keeping. The length is
      // polyline_length's sum of the one leg.
      straight_.path.assign({a, b});
      straight_.length_m = geometry::distance(a, b);
      return straight_;
    }
    const Key key{a.x, a.y, b.x, b.y};
    // The orderings ask for a transit's length and then for its path (the lanes it crosses):
    // the last answer is kept beside the map (whose entries stay put).
    if (last_ && key == last_key_) return *last_;
    auto it = known_.find(key);
    if (it == known_.end()) {
      std::vector<Point2> path = router_.path(a, b);
      const double length = geometry::polyline_length(path);
      it = known_.emplace(key, Route{std::move(path), length}).first;
    }
    last_key_ = key;
    last_ = &it->second;
    return it->second;
  }
  // Hashed, not ordered: the ordering asks ~10^5 times a plan. Keys compare as the doubles do
  // (no NaN reaches here; -0 and 0 are one key, as in the ordered map before, and hash alike).
  // The doubles' bits mixed inline: std::hash<double> calls out to a byte hash, 2.5 % of a
  // four-drone region division.
  using Key = std::array<double, 4>;
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = 0;
      for (const double v : k)
        h = (h ^ std::bit_cast<std::uint64_t>(v == 0 ? 0.0 : v)) * 0x9e3779b97f4a7c15ull;
      return std::size_t(h ^ (h >> 29));
    }
  };
  const geometry::VisibilityRouter& router_;
  std::unordered_map<Key, Route, KeyHash> known_;
  Key last_key_{};
  const Route* last_ = nullptr;  ///< known_'s entry for last_key_
  Route straight_;               ///< the last straight answer (valid until the next question)
};

/// The candidate's cells in their best order (exact where small), transits routed and kept off
/// lanes still to be flown where that costs less than flying them again, as a plan.
SplitPlan ordered_plan(Candidate& c, Point2 home, RoutedMetric& routed);

/// The best plan with a direction per region (split_regions.cpp), when it beats `single`.
std::optional<SplitPlan> per_region_plan(const std::vector<geometry::Ring>& rings, Point2 home,
                                         const SplitSettings& s, const geometry::Polygon& to_see,
                                         const SplitPlan& single, RoutedMetric& routed);

}  // namespace swath::planning::split_detail
