#pragma once
// Concave areas and holes without flying outside (--concave split): boustrophedon cells, each
// swept inside, visited in the order and direction that make the whole path shortest.

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "swath/geometry/visibility.hpp"
#include "swath/planning/sweep.hpp"

namespace swath::planning {

/// How an area is cut into the pieces a zigzag sweeps (each a swappable step of plan_split).
enum class SplitCells {
  /// Lanes first, cut where they meet the boundary, chained into runs (lane_runs.hpp).
  runs,
  /// Boustrophedon cells of the polygon, lanes placed per piece (the first method; a baseline).
  boustrophedon,
  /// Both, per direction: the shorter whole path wins.
  best,
};

/// Whether one split plan flies one direction or a direction per region (issue 18,
/// docs/swath-plan.md).
enum class SplitDirections {
  /// Every lane at the one direction searched (or fixed).
  one,
  /// Also a plan whose regions (one ring cut greedily by chords from reflex vertices along their
  /// edges while the parts, each at its own best direction, shorten the estimate) each fly their
  /// own direction; it wins only where its whole routed path is shorter than the best
  /// one-direction plan's and it sees >= 99.9 % of the area (footprints along each line). Not with
  /// a fixed direction, bridge rings, holes or several pieces: those keep one direction.
  per_region,
};

struct SplitSettings {
  double line_spacing_m = 0.0;
  double footprint_width_m = 0.0;
  LinePlacement placement = LinePlacement::centered;
  double turnaround_m = 0.0;
  /// Fly this direction (degrees CCW from east) instead of searching.
  std::optional<double> fixed_angle_deg;
  /// The scan part of the direction search, degrees; edge directions are always candidates.
  double scan_step_deg = 2.0;
  /// Candidates of each kind (bridged runs, runs, cells; best by a straight-transit estimate)
  /// evaluated with routed transits.
  std::size_t refined_candidates = 3;
  SplitCells cells = SplitCells::best;
  /// The area the footprints must see (rings as plan_split's; empty: the rings lines fly over),
  /// e.g. without the clearance around no-fly zones.
  std::vector<geometry::Ring> seen_rings;
  /// Where lanes may cross outside the rings to join their pieces (--outside-margin: the outline
  /// grown by the margin, less the grown zones); empty: nowhere. Runs only.
  std::vector<geometry::Ring> bridge_rings;
  /// Where no turnaround goes (keep_turnarounds_out()): the no-fly zones grown by the clearance,
  /// each part's outer ring then its holes; empty: anywhere.
  std::vector<geometry::Ring> keep_out_rings;
  SplitDirections directions = SplitDirections::one;
  /// Threads for the direction search (0: the machine's); the plan is the same for any number.
  unsigned threads = 0;
  /// At most this many lanes (0: no limit): a direction, and a kind of candidate at it, whose
  /// grid lanes (lane_runs.hpp grid_lane_count: counted before any is laid) are more is not
  /// tried; none left: LaneLimitExceeded. The plan's lines can still differ from the count by
  /// the lanes added for missed corners and the slivers dropped.
  std::size_t max_lines = 0;
  /// The limit holds for the pass at 90 degrees to a direction too (a crosshatch flies both).
  bool limit_cross_pass = false;
  /// Told the fraction of the search done, in [0, 1], ascending, ending with 1 (null: not told):
  /// the lanes at every direction are a third, the cells where they could rank a sixth, each
  /// candidate refined an equal share of the rest (with SplitDirections::per_region, these make
  /// 85 %, the search for a direction per region the rest). Called one call at a time, from
  /// whichever thread finished a piece.
  std::function<void(double fraction)> progress;
};

/// plan_split's refusal when no direction it would try lays its grid lanes within
/// SplitSettings::max_lines (before any lane is laid or ordered).
class LaneLimitExceeded : public std::runtime_error {
 public:
  LaneLimitExceeded(std::size_t lanes, double angle_deg)
      : std::runtime_error("plan_split: more lanes than the limit at every direction"),
        lanes_(lanes),
        angle_deg_(angle_deg) {}
  /// The fewest grid lanes of any direction tried (with SplitSettings::limit_cross_pass, of the
  /// larger of its two passes), and that direction.
  std::size_t lanes() const { return lanes_; }
  double angle_deg() const { return angle_deg_; }

 private:
  std::size_t lanes_;
  double angle_deg_;
};

struct SplitPlan {
  double angle_deg = 0.0;  ///< chosen line direction, degrees CCW from east, [0, 180)
  /// Boustrophedon cells (counter-clockwise, tiling the area) or runs' outlines (their lanes'
  /// strips, half a spacing either side), local frame.
  std::vector<geometry::Ring> cells;
  SplitCells method = SplitCells::boustrophedon;  ///< which made the plan (never `best`)
  std::vector<SweepLine> lines;                   ///< flight order and direction
  std::vector<std::size_t> line_cell;             ///< cell of each line
  std::size_t candidates = 0;                     ///< directions evaluated
  double path_length_m = 0.0;                     ///< home -> all lines -> home, transits routed
  /// What the choice minimised: the length plus, per transit, its length again for each run or
  /// cell still to be flown whose lanes it crosses (cell_order.hpp).
  double objective_m = 0.0;
  /// A plan with a direction per region (SplitDirections::per_region won): the regions (counter-
  /// clockwise rings, local frame, tiling the area) and each one's line direction (degrees CCW
  /// from east, [0, 180)); `angle_deg` is then the direction of the largest region. Both empty
  /// for a one-direction plan.
  std::vector<geometry::Ring> regions;
  std::vector<double> region_angles_deg;
};

/// Plans the split sweep of an area given as rings (outer counter-clockwise, holes clockwise).
/// Transits and turns are measured along `router` paths. Throws std::invalid_argument on
/// settings out of range.
SplitPlan plan_split(const std::vector<geometry::Ring>& rings, geometry::Point2 home,
                     const SplitSettings& settings, const geometry::VisibilityRouter& router);

/// Sweeps given pieces, each met by every lane at `angle_deg` in one interval (e.g. the band of a
/// region division cut from boustrophedon pieces), as cells with lanes on one grid over them, and
/// orders them as plan_split does. Empty lines when the pieces hold none.
SplitPlan plan_pieces(const std::vector<geometry::Ring>& pieces, double angle_deg,
                      geometry::Point2 home, const SplitSettings& settings,
                      const geometry::VisibilityRouter& router);

/// Orders given runs as plan_split orders its cells (exact where small, transits routed and kept
/// off lanes still to be flown), remembering routed transits from call to call: region division
/// orders each drone's share of the same lanes many times.
class RunOrder {
 public:
  explicit RunOrder(const geometry::VisibilityRouter& router);
  ~RunOrder();
  RunOrder(const RunOrder&) = delete;
  RunOrder& operator=(const RunOrder&) = delete;
  /// `runs`: each a Sweep at `angle_deg` (degrees CCW from east) whose lines lie on consecutive
  /// lane ordinates, bottom to top, all flown towards +x of the rotated frame; `outlines` one ring
  /// per run (reported as the plan's cells). Empty lines when there are no runs.
  SplitPlan operator()(std::vector<geometry::Ring> outlines, std::vector<Sweep> runs,
                       double angle_deg, geometry::Point2 home);

 private:
  struct Memo;
  std::unique_ptr<Memo> memo_;
};

}  // namespace swath::planning
