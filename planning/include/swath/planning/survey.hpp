#pragma once
// The survey: a request, the plan, and plan_survey(), a short pipeline of named steps
// (docs/architecture.md): area -> imaging -> direction -> lanes -> drones -> missions -> sorties ->
// measures. Each step lives in its own file pair (survey_area, imaging, direction, lanes, drones,
// mission, sorties, photos, clearance, checks); this header holds only the data they share.

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "swath/geometry/area_facts.hpp"
#include "swath/geometry/field.hpp"
#include "swath/planning/coverage.hpp"
#include "swath/planning/division.hpp"
#include "swath/planning/imaging.hpp"
#include "swath/planning/mission.hpp"
#include "swath/planning/split.hpp"
#include "swath/planning/terrain.hpp"
#include "swath/vehicle/drone.hpp"

namespace swath::planning {

/// How the sweep direction is chosen.
enum class AngleSearch {
  exact,  ///< exact minimum height (rotating calipers)
  scan,   ///< the paper's scan in `angle_step_deg` steps
  fixed,  ///< `line_bearing_deg` as given
};

/// What a non-convex area (reflex vertices or holes) becomes before sweeping.
enum class ConcaveMode {
  split,   ///< boustrophedon cells swept inside the area, transits routed around holes
  hull,    ///< paper 001: its convex hull (flies over ground outside the area; reported)
  reject,  ///< refuse it
};

/// How the area was flown.
enum class Handling {
  convex,  ///< one sweep, strip rule
  hull,    ///< one sweep over the convex hull
  split,   ///< cells swept inside the area
};
const char* to_string(Handling handling);

struct SurveyRequest {
  geometry::Field field;
  Camera camera;
  std::variant<PhotogrammetryMode, DetectionMode> mode = PhotogrammetryMode{};
  ImageOrientation orientation = ImageOrientation::landscape;
  /// Photogrammetry mode with a detection target too: h_max is reported and flying above it warned.
  std::optional<DetectionMode> pattern;
  AngleSearch angle_search = AngleSearch::exact;
  double angle_step_deg = 0.1;    ///< scan only, in (0, 90]
  double line_bearing_deg = 0.0;  ///< fixed only: compass bearing of the lines
  LinePlacement placement = LinePlacement::centered;
  /// Extension of every line beyond both ends, metres; absent: 0 for multirotors, the roll-out
  /// distance (one turn radius) for fixed-wing.
  std::optional<double> turnaround_m;
  std::optional<double> waypoint_spacing_m;
  StartCorner start = StartCorner::nearest_home;
  std::optional<geometry::GeoPoint> home;  ///< absent: the area's south-west-most vertex
  /// Plan with homes farther than kMaxHomeDistance_m from the area (refused otherwise).
  bool far_home = false;
  ConcaveMode concave = ConcaveMode::split;
  /// Extra no-fly zones, WGS84 (any orientation); they become holes of the area.
  std::vector<std::vector<geometry::GeoPoint>> exclusions;
  /// How messages name each of `exclusions` (swath plan: its file, and its feature where the file
  /// holds several), after "no-fly zone "; one missing: its number, from 1.
  std::vector<std::string> exclusion_names;
  double split_scan_step_deg = 2.0;           ///< split: the scan part of the direction search
  SplitCells split_cells = SplitCells::best;  ///< split: runs from lanes, boustrophedon or both
  /// Split: one direction, or a direction per region where that is shorter. Per region applies to
  /// one drone or path division without --crosshatch (the crosshatch pass and region division cut
  /// the lanes of one direction); otherwise the one-direction plan is kept.
  SplitDirections split_directions = SplitDirections::one;
  /// Split: threads for the direction search (0: the machine's); the plan is the same for any
  /// number (SplitSettings::threads).
  unsigned threads = 0;
  /// Divide the survey among this fleet (absent: one drone).
  std::optional<vehicle::Fleet> fleet;
  /// How messages name the fleet: its file (empty: --drones N, "the fleet").
  std::string fleet_name;
  DivisionMode division = DivisionMode::path;
  Balance balance = Balance::capability;
  /// A fleet that cannot fly the whole path flies what it can instead of refusing.
  bool allow_partial = false;
  /// A self-intersecting outer ring is replaced by the areas it encloses (union of the faces of
  /// its arrangement) instead of refused.
  bool repair = false;
  Firmware firmware = Firmware::ardupilot;
  Vehicle vehicle = Vehicle::multirotor;
  std::optional<double> speed_m_s;  ///< absent: 5 m/s multirotor, 15 m/s fixed wing
  /// The slowest approach to a stop beside a no-fly zone (MissionSettings::slowest_approach_m_s):
  /// swath plan --dji asks DJI's least waypoint speed, 1 m/s, for every file of the plan.
  double slowest_approach_m_s = kSlowestApproach_m_s;
  /// Fly at the imaging altitude above the ground of a DEM (terrain.hpp) instead of above home.
  std::optional<TerrainRequest> terrain;
  /// docs/swath-plan.md: no waypoint and no leg closer than this to a hole or no-fly zone.
  double clearance_m = 5.0;
  /// The same for the outer boundary (lines shortened, transits kept inside by this much).
  double boundary_clearance_m = 0.0;
  /// Split: a lane may cross up to this far outside the outer boundary (never into a no-fly zone
  /// or its clearance) to join its pieces into one line; its ends stay inside. 0: never.
  double outside_margin_m = 0.0;
  /// Camera triggering and the items that command it (docs/swath-plan.md).
  Triggering triggering;
  /// Fly every line a second time at 90° (crosshatch), after the first pass.
  bool crosshatch = false;
  /// Fixed-wing: the bank limit that sets the minimum turn radius r = v² / (g tan(bank)).
  double max_bank_deg = 30.0;
  /// End with a landing at home instead of return-to-launch.
  bool land = false;
  /// Cut each drone's flight into sorties that fit its endurance above the reserve.
  bool sorties = false;
  /// Endurance for sorties and the endurance warning when the fleet does not give one, seconds.
  std::optional<double> endurance_s;
  double reserve = 0.2;  ///< share of the endurance kept in hand, [0, 0.9]
  /// The fence: the area grown by this much, metres; absent: turnaround + half the footprint
  /// width + 10 m (docs/swath-plan.md).
  std::optional<double> fence_margin_m;
  /// Drones of one plan whose paths come within kSeparation_m of each other fly this far apart in
  /// height (altitude layers above the imaging altitude), metres, > 0.
  double layer_spacing_m = 10.0;
  /// No layer above this height above home, metres: a fleet that needs more layers is refused.
  double ceiling_m = 120.0;
  /// Told the fraction done of the split's direction search (the long part of a plan on a
  /// concave area), in [0, 1], as it goes (SplitSettings::progress); null: not told. For the
  /// call of plan_survey() only: the plan's copy of the request has none.
  std::function<void(double fraction)> progress;
};

/// Flight times on one battery the endurance warning assumes when none is given, seconds.
inline constexpr double kTypicalMultirotorEndurance_s = 30 * 60;
inline constexpr double kTypicalFixedWingEndurance_s = 90 * 60;

/// How far apart two drones of one plan stay at every moment (altitude layers, staggered
/// launches), metres.
inline constexpr double kSeparation_m = 10.0;

/// Limits that keep the work bounded (plan_survey() refuses beyond them) and the autopilot limit
/// it warns above. Waypoints and photos bound the memory of the files written (each waypoint
/// ~3.6 KB and each photo ~2.7 KB at the peak, measured: 93,034 items took 340 MB and 2.7 s of
/// CPU, 202,398 photos 543 MB): at the limits a plan stays under 1 GB and 60 s. Both are far
/// above what an autopilot holds (kAutopilotItemLimit) or a camera card takes in one flight.
inline constexpr std::size_t kMaxSweepLines = 20'000;
inline constexpr std::size_t kMaxWaypoints = 100'000;
inline constexpr std::size_t kMaxPhotos = 250'000;
inline constexpr std::size_t kAutopilotItemLimit = 700;  ///< ArduPilot's classic mission size
/// Vertices of one fence polygon an autopilot stores: PX4's limit (ArduPilot holds more).
inline constexpr std::size_t kFenceVertexLimit = 64;
/// Split routes transits around holes on a visibility graph whose size grows with the square of
/// the holes' vertices: 500 holes of 4 vertices plan in ~2 s and 150 MB, 3,000 took 98 s and
/// 5.6 GB. Beyond these, split refuses (hull mode ignores holes and is not limited).
inline constexpr std::size_t kMaxSplitHoles = 500;
inline constexpr std::size_t kMaxSplitHoleVertices = 4'000;
/// A home farther than this from the area is refused unless SurveyRequest::far_home.
inline constexpr double kMaxHomeDistance_m = 50'000;
/// Farther than this no home is planned even with far_home: no drone flies that far to a survey,
/// and the local frame the plan is computed in ends beyond it (tangent-plane coordinates stop
/// being invertible towards the horizon; the tests check the round trip at this distance).
inline constexpr double kMaxFarHomeDistance_m = 1'000'000;
/// An area narrower than this at its narrowest (minimum height) is degenerate input.
inline constexpr double kMinAreaWidth_m = 1.0;
/// Altitude above home above which a warning names the common legal limit (EU, US: 120 m / 400 ft).
inline constexpr double kLegalAltitude_m = 120.0;

/// A battery-sized part of one drone's flight (docs/swath-plan.md).
struct Sortie {
  int number = 1;                  ///< 1-based, in flying order
  DroneMission mission;            ///< home -> resume point -> ... -> home
  geometry::Point2 resume;         ///< where its survey work starts
  std::vector<PhotoPoint> photos;  ///< planned photo positions
  /// Launched this long after the plan's first drone, seconds: after the sortie before it has
  /// landed, and (several drones) when its climb and descent at home miss the lower layers.
  double launch_offset_s = 0.0;
};

/// One drone of the plan: who it is, where it starts, what it flies.
struct DronePlan {
  int number = 1;         ///< 1-based, fleet order
  std::string name;       ///< the fleet's name, "drone-<number>" otherwise
  std::string file_stem;  ///< its files' name: `name` reduced to [A-Za-z0-9._-]
  geometry::Point2 home;  ///< local frame
  geometry::GeoPoint home_geo;
  double speed_m_s = 0.0;
  double climb_speed_m_s = vehicle::Drone{}.climb_speed_m_s;      ///< the fleet's, or the default
  double descent_speed_m_s = vehicle::Drone{}.descent_speed_m_s;  ///< the fleet's, or the default
  double accel_m_s2 = vehicle::Drone{}.accel_m_s2;  ///< the drone's (ArduCopter's WPNAV_ACCEL)
  std::optional<double> endurance_s;                ///< flight time on a full charge, when known
  /// The share of a full charge it takes off with (the fleet's battery_level; 1 otherwise).
  double battery_level = 1.0;
  /// Whether the fleet file gives its battery (battery_level and endurance_s): then no flight of
  /// it is written longer than its charge (a sortie after the first: a full one), else refused.
  bool charge_from_fleet = false;
  /// Its part of the survey (with a fleet: the division's share, budgets and region).
  DroneWork work;
  DroneMission mission;            ///< the whole flight
  std::vector<PhotoPoint> photos;  ///< planned photo positions (same rule as the autopilot)
  std::vector<Sortie> sorties;     ///< with --sorties: the flight cut to fit the battery
  /// Its altitude layer: flown this much above the imaging altitude, metres (>= 0).
  double layer_m = 0.0;
  /// Launched this long after the plan's first drone, seconds (>= 0).
  double launch_offset_s = 0.0;
};

/// What the flown paths keep from the no-fly zones and the boundary (measured over every leg of
/// every flight, home legs included).
struct ClearanceMeasure {
  std::optional<double> no_fly_m;   ///< least distance to a hole or zone; absent: there are none
  double boundary_outside_m = 0.0;  ///< line length outside the outer boundary (--outside-margin)
};

namespace steps {
struct Routes;
}

struct SurveyPlan {
  SurveyRequest request;
  geometry::AreaFacts facts;     ///< of the area as given, no-fly zones included as holes
  geometry::Polygon area;        ///< the area to cover: the field minus the no-fly zones
  geometry::Polygon flown_area;  ///< what the sweep covers (the hull for a concave area)
  Handling handling = Handling::convex;
  /// The rings lines are laid in and turns and transits stay in: the flown area with its holes and
  /// zones grown by the clearance and its outer boundary shrunk by the boundary clearance.
  std::vector<geometry::Ring> planning_rings;
  /// The no-fly zones (holes of the field, then --exclude zones), local frame and as given.
  std::vector<geometry::Ring> no_fly;
  std::vector<std::vector<geometry::GeoPoint>> no_fly_geo;
  /// The zones grown by the clearance, united: each part's outer ring counter-clockwise, then the
  /// holes it encloses clockwise (geometry::grow_keeping_holes()).
  std::vector<geometry::Ring> no_fly_grown;
  /// Inclusion fences: the area (each piece) grown by the fence margin; one ring usually.
  std::vector<geometry::Ring> fence;
  /// Exclusion fences as written, one per no-fly zone (order of no_fly_geo): the zone as given,
  /// or where it has more than kFenceVertexLimit vertices, a polygon of at most that many holding
  /// the zone and reaching at most half the clearance beyond it.
  std::vector<std::vector<geometry::GeoPoint>> exclusion_fences_geo;
  double fence_margin_m = 0.0;
  std::vector<geometry::Ring> cells;  ///< split: the cells; otherwise the flown area's outer ring
  std::optional<SplitCells> split_method;  ///< split: what made the cells (runs or boustrophedon)
  std::size_t direction_candidates = 1;    ///< directions evaluated
  /// Split with a direction per region (SplitPlan::regions): the regions (local frame) and each
  /// one's line direction (degrees CCW from east); empty for a one-direction plan, whose lines all
  /// lie at sweep.angle_deg.
  std::vector<geometry::Ring> regions;
  std::vector<double> region_angles_deg;
  double transit_outside_m = 0.0;  ///< turns and transits (not home legs) outside the area
  /// --repair: the enclosed areas beyond the largest one (which became the field's outer ring),
  /// counter-clockwise, local frame. Planned with the rest.
  std::vector<geometry::Ring> extra_pieces;
  /// Zones cut out across the boundary: the holes the zones leave in the extra pieces (clockwise,
  /// local frame). Not flown (the zones stay no-fly); counted out of the area and its coverage.
  std::vector<geometry::Ring> extra_piece_holes;
  Imaging imaging;
  geometry::SweepDirection direction;  ///< angle of the lines (local, CCW from east) and height
  Sweep sweep;
  /// Split: the cell (index into `cells`) of each of sweep.lines; empty otherwise.
  std::vector<std::size_t> sweep_line_cell;
  std::vector<SweepLine> survey_lines;  ///< every line in flying order, before division
  double speed_m_s = 0.0;               ///< the request's cruise speed
  double turnaround_m = 0.0;
  double turn_radius_m = 0.0;  ///< fixed-wing minimum turn radius; 0 for multirotors
  geometry::GeoPoint home;     ///< the plan's (fleet's) home
  geometry::Point2 home_local;
  std::vector<DronePlan> drones;  ///< one per drone; one without a fleet
  bool divided = false;           ///< the survey is divided among a fleet
  DivisionResult division;        ///< with a fleet: makespan and what stays unflown
  /// Coverage of the area as given by the flown footprints, and the share of swath outside it.
  CoverageMeasure coverage;
  ClearanceMeasure clearance;
  std::optional<TerrainFacts> terrain;  ///< with SurveyRequest::terrain
  std::vector<std::string> warnings;    ///< one sentence each
  /// The routers the steps share (steps::routes_of): built once, by the first step that routes,
  /// from what the steps before `lanes` settle (planning rings, zones, homes); plan_survey drops
  /// them when the plan is done.
  std::shared_ptr<const steps::Routes> routes;
};

/// What the coverage of a plan is measured over: the area, and the extra pieces (--repair's, or
/// the parts zones cut off) and their holes as further rings (the scanline measure counts by the
/// even-odd rule).
geometry::Polygon measured_area(const SurveyPlan& plan);

/// How messages name plan.no_fly[k] (the field's holes first, then the request's exclusions):
/// "hole K" (K from 0, as the area readers count holes), else "no-fly zone NAME" (the exclusion's
/// name, or K from 1).
std::string no_fly_name(const SurveyPlan& plan, std::size_t k);

/// Plans a survey, divided among a fleet when one is given. Throws base::InputError for an area
/// it refuses (self-intersecting, or non-convex with ConcaveMode::reject), a local-metres area
/// without a geographic frame, or settings out of range; the message names the problem.
SurveyPlan plan_survey(const SurveyRequest& request);

/// `seconds` as text a pilot reads: "7 min 05 s" below an hour, "1:07:05" (h:mm:ss) above.
std::string duration_text(double seconds);

}  // namespace swath::planning
