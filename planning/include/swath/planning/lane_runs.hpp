#pragma once
// Runs from the lanes (issue 18, docs/swath-plan.md): lay the lanes over the whole area first, cut
// each only where it meets the boundary or a no-fly zone, and chain lanes whose turns stay inside
// into zigzag runs. A notch or reflex vertex that no lane meets makes no cell; a sliver that the
// neighbouring lanes' footprints already cover gets no lane; a corner they miss gets the lane
// that covers the most of what is still unseen.

#include <limits>
#include <optional>
#include <vector>

#include "swath/geometry/polygon.hpp"
#include "swath/planning/sweep.hpp"

namespace swath::planning {

struct LaneRunSettings {
  double angle_deg = 0.0;          ///< lane direction, degrees CCW from the local x axis (east)
  double line_spacing_m = 0.0;     ///< > 0
  double footprint_width_m = 0.0;  ///< across the lanes, >= line_spacing_m
  LinePlacement placement = LinePlacement::centered;
  /// A lane shorter than this many footprint widths is a sliver's: dropped when the other lanes'
  /// footprints cover everything it covers.
  double sliver_length_footprints = 2.0;
  /// Lanes on the grid through this ordinate (metres, in the frame turned by -angle_deg),
  /// `line_spacing_m` apart, instead of the grid placed on this area alone: regions of one area
  /// swept at one direction keep the spacing across their seams. The fewest grid lanes whose
  /// footprints reach both edges (at most one more than the area's own grid); an area that no
  /// grid lane crosses gets its own.
  std::optional<double> grid_ordinate_m;
};

/// Zigzag runs: each a Sweep whose lines lie on consecutive lane ordinates, bottom to top, all
/// flown towards +x of the rotated frame (zigzag() alternates them), and its outline (the lanes'
/// strips, half a spacing either side, as one ring in the input frame).
/// The grid's lanes as laid before any corner or sliver is looked at (in the frame turned by
/// -angle): their lengths summed row by row, lane by lane from 0, and the least and greatest
/// ordinate of a row holding one (+inf and -inf: none). The cells' bound at the same direction is
/// made of these (split_detail::cells_estimate_bound): the runs hand them over instead of the bound
/// scanning the rings again.
struct LaneGridExtent {
  double lanes_m = 0;  ///< metres
  double y_lo_m = std::numeric_limits<double>::infinity();
  double y_hi_m = -std::numeric_limits<double>::infinity();
};

struct LaneRuns {
  std::vector<Sweep> runs;
  std::vector<geometry::Ring> outlines;
  std::size_t coverage_lanes = 0;      ///< lanes added off the grid to cover corners
  std::size_t unreachable_points = 0;  ///< samples of the area to see that no lane inside reaches
  LaneGridExtent grid;                 ///< the grid's lanes (joined across `bridge`), step 1
};

/// The areas lane_runs works with, each as rings (outer counter-clockwise, holes clockwise, no
/// crossings), in the local frame.
struct LaneRunArea {
  /// Where lanes lie and turn: e.g. the field less its no-fly zones grown by the clearance.
  std::vector<geometry::Ring> fly;
  /// What the footprints must see (empty: `fly`): e.g. the field less the zones themselves, so
  /// that lanes beside a zone see the band at the ends of the lanes that stop short of it.
  std::vector<geometry::Ring> see;
  /// Where a lane may cross outside `fly` to join two of its pieces (empty: nowhere): e.g. the
  /// outline grown by --outside-margin, less the grown zones. A lane is the span from its first
  /// piece's start to its last piece's end within one interval of `bridge`; its ends stay in `fly`.
  std::vector<geometry::Ring> bridge;
};

/// Lanes on neighbouring rows are chained when both straight turns (left ends, right ends) stay
/// inside `fly`. Every lane lies inside
/// `fly` but for its bridges; every sample of `see` (its boundary every eighth of a spacing, its
/// inside on a grid a quarter of a spacing apart) lies within half a footprint across of a lane
/// and within its length, unless counted in unreachable_points. O((n + lanes) log + samples x
/// nearby lanes).
LaneRuns lane_runs(const LaneRunArea& area, const LaneRunSettings& settings);
/// The same, with the coverage samples in `samples` (in the frame turned by -angle; whatever it
/// held is replaced, its capacity kept for the next call): those no lane longer than the slivers'
/// length sees, the only ones the coverage check asks.
LaneRuns lane_runs(const LaneRunArea& area, const LaneRunSettings& settings,
                   std::vector<geometry::Point2>& samples);

/// The grid's lanes lane_runs lays first, counted without laying them: per grid ordinate, the
/// intervals of the lane inside `area.fly` (joined across `area.bridge`), i.e. its boundary
/// crossings over two. Where the area is concave a lane position holds several. lane_runs then
/// adds lanes for corners the grid misses and drops slivers; the boustrophedon cells of the same
/// direction lay their lanes on the same grid. O(n log n + crossings log crossings).
std::size_t grid_lane_count(const LaneRunArea& area, const LaneRunSettings& settings);

}  // namespace swath::planning
