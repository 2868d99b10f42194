#pragma once
// The whole survey pipeline: area -> imaging -> sweep direction -> lines -> mission -> coverage.

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "swath/geometry/area_facts.hpp"
#include "swath/geometry/field.hpp"
#include "swath/planning/coverage.hpp"
#include "swath/planning/division.hpp"
#include "swath/planning/fleet.hpp"
#include "swath/planning/imaging.hpp"
#include "swath/planning/mission.hpp"

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

enum class Firmware { ardupilot, px4 };
enum class Vehicle { multirotor, fixedwing };

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
  double turnaround_m = 0.0;
  std::optional<double> waypoint_spacing_m;
  StartCorner start = StartCorner::nearest_home;
  std::optional<geometry::GeoPoint> home;  ///< absent: the area's south-west-most vertex
  /// Plan with homes farther than kMaxHomeDistance_m from the area (refused otherwise).
  bool far_home = false;
  ConcaveMode concave = ConcaveMode::split;
  /// Extra no-fly zones (local frame, any orientation); they become holes of the area.
  std::vector<geometry::Ring> exclusions;
  double split_scan_step_deg = 2.0;  ///< split: the scan part of the direction search
  /// Divide the survey among this fleet (absent: one drone).
  std::optional<Fleet> fleet;
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
};

/// Limits that keep the work bounded (plan_survey() refuses beyond them) and the autopilot limit
/// it warns above.
inline constexpr std::size_t kMaxSweepLines = 20'000;
inline constexpr std::size_t kMaxWaypoints = 1'000'000;
inline constexpr std::size_t kAutopilotItemLimit = 700;  ///< ArduPilot's classic mission size
/// Split routes transits around holes on a visibility graph whose size grows with the square of
/// the holes' vertices: 500 holes of 4 vertices plan in ~2 s and 150 MB, 3,000 took 98 s and
/// 5.6 GB. Beyond these, split refuses (hull mode ignores holes and is not limited).
inline constexpr std::size_t kMaxSplitHoles = 500;
/// A home farther than this from the area is refused unless SurveyRequest::far_home.
inline constexpr double kMaxHomeDistance_m = 50'000;
/// Farther than this no home is planned even with far_home: no drone flies that far to a survey,
/// and the local frame the plan is computed in ends beyond it (tangent-plane coordinates stop
/// being invertible towards the horizon; the tests check the round trip at this distance).
inline constexpr double kMaxFarHomeDistance_m = 1'000'000;
/// An area narrower than this at its narrowest (minimum height) is degenerate input.
inline constexpr double kMinAreaWidth_m = 1.0;
inline constexpr std::size_t kMaxSplitHoleVertices = 4'000;

struct SurveyPlan {
  SurveyRequest request;
  geometry::AreaFacts facts;     ///< of the area as given, no-fly zones included as holes
  geometry::Polygon area;        ///< the area to cover: the field minus the no-fly zones
  geometry::Polygon flown_area;  ///< what the sweep covers (the hull for a concave area)
  /// How the area was flown: "convex" (one sweep, strip rule), "hull" or "split".
  std::string handling;
  std::vector<geometry::Ring> cells;  ///< split: the cells; otherwise the flown area's outer ring
  std::size_t direction_candidates = 1;  ///< directions evaluated
  double transit_outside_m = 0.0;        ///< turns and transits (not home legs) outside the area
  /// With a fleet: one mission per drone (`mission` keeps the undivided survey), and the division.
  std::vector<DroneMission> drone_missions;
  std::vector<DroneWork> drone_work;
  std::vector<std::string> drone_names;
  std::vector<double> drone_speeds_m_s;
  DivisionResult division;
  /// --repair: the enclosed areas beyond the largest one (which became the field's outer ring),
  /// counter-clockwise, local frame. Planned with the rest.
  std::vector<geometry::Ring> extra_pieces;
  Imaging imaging;
  geometry::SweepDirection direction;  ///< angle of the lines (local, CCW from east) and height
  Sweep sweep;
  DroneMission mission;
  double speed_m_s = 0.0;
  geometry::GeoPoint home;
  /// Coverage of the area as given by the flown footprints, and the share of swath outside it.
  CoverageMeasure coverage;
  std::vector<std::string> warnings;  ///< one sentence each
};

/// The missions to write: one per drone of the fleet, or the single survey mission.
std::vector<const DroneMission*> missions_of(const SurveyPlan& plan);

/// What the coverage of a plan is measured over: the area, and --repair's extra pieces as further
/// rings (the scanline measure counts by the even-odd rule).
geometry::Polygon measured_area(const SurveyPlan& plan);

/// Plans a survey, divided among a fleet when one is given. Throws base::InputError for an area
/// it refuses (self-intersecting, or non-convex with ConcaveMode::reject), a local-metres area
/// without a geographic frame, or settings out of range; the message names the problem.
SurveyPlan plan_survey(const SurveyRequest& request);

}  // namespace swath::planning
