#pragma once
// Dividing a survey among drones (paper 001 §V-D, docs/swath-plan.md).

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "swath/geometry/polygon.hpp"
#include "swath/planning/mission.hpp"

namespace swath::planning {

enum class DivisionMode { path, region };
enum class Balance { capability, makespan };

/// One drone in the local frame, with what it can fly.
struct DroneResource {
  std::string name;
  geometry::Point2 home;
  double speed_m_s = 5.0;         ///< > 0
  std::optional<double> range_m;  ///< absent when only a capability is known
  double capability = 1.0;        ///< relative share when no range is known, > 0
  /// The longest flight it may make, seconds, climbs, stops and descents included (its charge);
  /// absent: no limit. A share whose measured flight is longer counts as beyond its range.
  std::optional<double> flight_limit_s = std::nullopt;
};

struct DroneWork {
  SurveyPath path;                     ///< its part of the survey, home legs not included
  std::vector<geometry::Ring> region;  ///< region division: its band (counter-clockwise pieces)
  double share = 0.0;                  ///< fraction of the path length (path) or area (region)
  double home_cost_m = 0.0;            ///< there and back to the farthest point of the path / area
  std::optional<double> budget_m;      ///< range - home cost, where the range is known
  /// Its flight time: the measured flight where the division was given a FlightMeasure, else
  /// straight home legs + its part at its speed.
  double estimated_time_s = 0.0;
};

struct DivisionResult {
  std::vector<DroneWork> drones;
  double unflown_path_m = 0.0;           ///< path division: what the fleet's budgets cannot reach
  double makespan_s = 0.0;               ///< the longest estimated_time_s
  double proportional_makespan_s = 0.0;  ///< the same for capability-proportional cuts
  /// Balance::capability: the proportional shares were beyond a drone's range or flight time
  /// limit and were re-cut as Balance::makespan cuts.
  bool recut_within_limits = false;
};

/// A drone's whole flight over a part of the survey, as its mission will fly it.
struct FlightCost {
  double time_s = 0.0;    ///< home legs included, at its speed (with stops, climb, descent), >= 0
  double length_m = 0.0;  ///< home -> part -> home along the routed legs, metres, >= 0
};

/// The exact flight of drone `drone` (index into the fleet) over `part` (its survey path, home legs
/// not included; an empty path is no flight). Balancing on it rather than on straight legs at
/// cruise speed is what brings the longest flight to within a fraction of a percent of the
/// shortest (the estimate ignores stops at corners, climb and descent, routed legs).
using FlightMeasure = std::function<FlightCost(std::size_t drone, const SurveyPath& part)>;

/// Path division (Algorithm 3): cuts the whole survey path into consecutive pieces, one per drone
/// in fleet order. Shares follow the corrected capabilities: budgets (range minus the home cost,
/// twice the distance to the farthest point of the path) where ranges are known, capabilities
/// otherwise. When the budgets add up to less than the path, each drone flies its budget and the
/// rest is unflown. Balance::makespan instead cuts where the longest flight time (home legs
/// included, each at its own speed, within its range) is smallest, by bisection on that time.
/// With `measure`, times (estimated_time_s, makespans, the balance) are the measured flights and
/// a drone's range is checked against the measured length; without it, straight home legs at
/// cruise speed. A drone's flight_limit_s is checked on the measured flight (`measure`, else
/// `limit`: the times stay the straight legs'); proportional pieces beyond a drone's limits are
/// re-cut as the balance cuts (a short fleet: each drone the longest piece within its limits).
/// Throws base::InputError when a drone cannot even fly its home cost.
DivisionResult divide_path(const SurveyPath& path, const std::vector<DroneResource>& drones,
                           Balance balance, const FlightMeasure& measure = {},
                           const FlightMeasure& limit = {});

/// Plans a band for a drone: the band's pieces -> its survey path.
using BandSweep =
    std::function<SurveyPath(const std::vector<geometry::Ring>& band, const DroneResource& drone)>;

/// Region division (Algorithm 4): cuts the area with lines along the sweep (angle_deg, degrees CCW
/// from x) into one band per drone, areas in proportion to the corrected capabilities (home cost:
/// twice the distance to the farthest vertex of the area); each cut found by bisection on the area
/// below it (relative error < 1e-9). Bands are cut from the boustrophedon pieces of the area, so
/// every band piece is met by each lane in one interval. (Balanced on flight times, region
/// division is divide_lanes().) Throws base::InputError as divide_path().
DivisionResult divide_region(const std::vector<geometry::Ring>& rings, double angle_deg,
                             const std::vector<DroneResource>& drones, const BandSweep& sweep_band);

/// A piece of a lane given to a drone by divide_lanes(): `lane` indexes the lanes passed in,
/// `line` is the part of it (the whole lane, or one side of a cut along its length), flown
/// towards +x of the rotated frame.
struct LanePiece {
  std::size_t lane = 0;
  SweepLine line;
};

/// Sweeps one drone's pieces of lanes (index into the fleet, its pieces in lane order) into its
/// survey path (home legs not included).
using LaneSweep =
    std::function<SurveyPath(std::size_t drone, const std::vector<LanePiece>& pieces)>;

/// Region division balanced on measured flight times (docs/swath-plan.md): the undivided plan's
/// lanes
/// (`lanes`, at angle_deg, degrees CCW from x, one grid) in order of their ordinate, then along
/// +x, are one line of length L; n - 1 cuts in [0, L] give each drone a band of lanes, whole ones
/// and at most one cut along its length at each end, so that a drone's time changes with a cut
/// continuously but where its share first reaches into a lane (the turn and stops that costs).
/// The cuts minimise the longest measured flight (bisection on it, each cut the longest share a
/// drone flies within it, found by bisection) for every assignment of drones to bands (every
/// permutation up to 4 drones, interchangeable drones once; beyond that the homes' order across
/// the lanes, the fleet's order and swaps of the best: every pair up to 8 drones, adjacent ones
/// beyond); then, within 2 % of that makespan, the cuts whose longest over shortest flight is
/// smallest (each cut moved to where its two drones' times cross, from several starts). A share
/// over its drone's limits counts as infinitely long. Every lane is flown exactly once: the pieces
/// of a lane add up to it (a lane under a micrometre goes whole to the share holding its start).
/// Regions: a partition of `share_area` (`rings` when empty; outer rings counter-clockwise, holes
/// clockwise), their areas the shares: each row of lanes (rows end halfway between lane
/// ordinates, the first and last reach out to infinity) goes across to the drones of its pieces
/// of lanes, split at a cut along a lane and halfway between the pieces of two drones on a row
/// (the ground between them: a bay, a hole, a gap between cells). With `lane_cell` (the cell of
/// each lane), the lanes are cut in the order and direction given instead (the undivided plan's
/// flight: run after run, so that a share is whole runs and parts of one at either end, and the
/// part of a cut lane a drone gets is the part flown before or after the cut); where that balance
/// leaves the longest flight more than 0.2 % above the shortest, the lanes are balanced by row as
/// well (a share's ends then run across cells side by side instead of reaching into the next cell
/// in the flight order), and the narrowest of the two within 2 % of the shorter makespan is kept
/// (spreads under 0.2 % equal, then the shorter makespan). Where the drones are still more than
/// 2 % apart, the same with the parts of cut lanes taken from their other ends (every lane, by row
/// and in the order given, or every other row's), kept where narrower with a longest flight no
/// longer: a band's zigzag ends at one end of a lane or the other with the parity of its lanes, so
/// its time can jump by a lane's flight where its share first reaches into one. Where they are
/// still more than 2 % apart, bands cut across the lanes are tried: the rows in blocks of two
/// (either parity), or all rows in one block, each block cut by lines perpendicular to the lanes
/// (the band below a cut gets every lane's part on its left, or on its right), so that a band
/// ends in a U over two rows of any length instead of stepping by a lane flown out and back; the
/// narrowest of these whose longest flight is no longer than the division's so far replaces it
/// where narrower (spreads under 0.2 % equal, then the shorter makespan). The regions still
/// split each row at the cuts, so they tile the area, and each lane's pieces still add up to it.
/// `proportional_makespan_s`: cuts in proportion to the corrected capabilities, bands in fleet
/// order; Balance::capability returns those cuts (shares of the lanes' length, the paper's
/// Algorithm 4 on the plan's own lanes: every lane flown, so the side overlap holds across the
/// bands' seams) where every share is within its drone's limits, else the balance's cuts. Home
/// costs and budgets as divide_region(); throws base::InputError as it does.
DivisionResult divide_lanes(const std::vector<geometry::Ring>& rings, double angle_deg,
                            const std::vector<SweepLine>& lanes,
                            const std::vector<DroneResource>& drones, const LaneSweep& sweep,
                            const FlightMeasure& measure,
                            const std::vector<std::size_t>& lane_cell = {},
                            const std::vector<geometry::Ring>& share_area = {},
                            Balance balance = Balance::makespan);

/// Area of `rings` (outer counter-clockwise, holes clockwise) with y <= y_cut in the frame rotated
/// by -angle_deg, m². Exact up to rounding (half-plane clipping of each ring, shoelace).
double area_below(const std::vector<geometry::Ring>& rings, double angle_deg, double y_cut);

/// The area below a cut as an exact function of the cut's ordinate: between consecutive vertex
/// ordinates the area's width along the cut varies linearly, so the area below is a quadratic
/// there. Built in O(n log n); each evaluation O(log n).
class AreaProfile {
 public:
  /// `rings`: outer counter-clockwise, holes clockwise (even-odd); ordinates in the frame rotated
  /// by -angle_deg.
  AreaProfile(const std::vector<geometry::Ring>& rings, double angle_deg);
  double below(double y) const;
  double total() const { return cumulative_.empty() ? 0.0 : cumulative_.back(); }
  double y_min() const { return y_.front(); }
  double y_max() const { return y_.back(); }
  /// The ordinate with `area` below it (bisection to 1e-12 of the height).
  double ordinate_for(double area) const;

 private:
  std::vector<double> y_;           ///< event ordinates, increasing
  std::vector<double> cumulative_;  ///< area below y_[k]
  std::vector<double> width_;       ///< width just above y_[k]
  std::vector<double> slope_;       ///< d width / dy in slab k
};

/// A ring clipped to y0 <= y <= y1 in the frame rotated by -angle_deg, in the input frame.
/// For a ring that every such line meets in one interval the result is one simple ring.
geometry::Ring clip_band(const geometry::Ring& ring, double angle_deg, double y0, double y1);

}  // namespace swath::planning
