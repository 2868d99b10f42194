#pragma once
// A drone's mission, item by item as the autopilot gets it (docs/swath-plan.md): take off, set the
// drone's speed, point the camera, fly the lines with the camera triggering on each line only,
// and return to launch (or land).

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "swath/missions/export_types.hpp"
#include "swath/missions/stopping.hpp"
#include "swath/planning/sweep.hpp"
#include "swath/vehicle/kinematics.hpp"

namespace swath::planning {

enum class Firmware { ardupilot, px4 };
enum class Vehicle { multirotor, fixedwing };

/// How photos are taken on the lines (distance, time, hover), as the mission writers take it.
using TriggerMode = missions::TriggerMode;

/// The command a hover shot uses.
enum class CameraCommand {
  digicam,        ///< DO_DIGICAM_CONTROL (203), relay and servo cameras
  image_capture,  ///< IMAGE_START_CAPTURE (2000) with one image, MAVLink cameras
};

struct Triggering {
  TriggerMode mode = TriggerMode::distance;
  CameraCommand command = CameraCommand::digicam;
  /// Keep the camera on through turns that stay inside the area (runs of lines in one cell);
  /// otherwise it is started at each line and stopped at its end.
  bool photos_in_turns = false;
  /// Camera pitch set once at the start, degrees (-90: nadir, 0: level); DO_MOUNT_CONTROL (205)
  /// for ArduPilot, DO_GIMBAL_MANAGER_PITCHYAW (1000) for PX4.
  double gimbal_pitch_deg = -90.0;
  /// Hover mode: how long the drone holds at each photo point, seconds (ArduCopter stops for a
  /// hold of at least 1 s).
  double hover_hold_s = 1.0;
};

/// A planned photo: where, and on which of the drone's lines (0-based, flying order).
struct PhotoPoint {
  geometry::Point2 position;
  int line = 0;
};

enum class ItemKind {
  takeoff,           ///< NAV_TAKEOFF (22) at home to the survey altitude
  waypoint,          ///< NAV_WAYPOINT (16); `value`: hold time, seconds
  change_speed,      ///< DO_CHANGE_SPEED (178); `value`: m/s
  gimbal_pitch,      ///< DO_MOUNT_CONTROL (205) / DO_GIMBAL_MANAGER_PITCHYAW (1000); `value`: deg
  trigger_start,     ///< distance: 206 with `value` m; time: 2000 with `value` s between images
  trigger_stop,      ///< distance: 206 with 0; time: 2001
  camera_shot,       ///< hover: one photo (203 or 2000 with one image)
  land_start,        ///< DO_LAND_START (189): where a fixed-wing landing sequence begins
  land,              ///< NAV_LAND (21) at home
  return_to_launch,  ///< NAV_RETURN_TO_LAUNCH (20)
};

struct MissionItem {
  ItemKind kind = ItemKind::waypoint;
  geometry::Point2 position;  ///< local metres (takeoff and land: home); unused by the others
  double altitude_m = 0.0;    ///< above home
  double value = 0.0;         ///< see ItemKind
  TriggerMode trigger = TriggerMode::distance;     ///< trigger and camera items
  CameraCommand command = CameraCommand::digicam;  ///< camera_shot
  /// Above mean sea level, with terrain (SurveyRequest::terrain) only; NaN otherwise.
  double altitude_amsl_m = std::numeric_limits<double>::quiet_NaN();
};

/// Whether an item is a position the drone flies to (takeoff, waypoint, land).
bool positional(ItemKind kind);

/// The flight-time estimate accelerates at swath::vehicle::kDefaultAccel_m_s2 (ArduCopter's
/// WPNAV_ACCEL, the default of vehicle::Drone::accel_m_s2 and swath plan's) unless told otherwise;
/// climb and descent are the drone's, by default WPNAV_SPEED_UP and _DN (vehicle::Drone). A corner
/// this sharp it stops at (ArduCopter slows to a stop before such turns; gentler ones it flies
/// through).
inline constexpr double kStopTurn_deg = 45.0;

/// Turn angle at b between legs a-b and b-c, degrees in [0, 180].
double turn_deg(geometry::Point2 a, geometry::Point2 b, geometry::Point2 c);

/// How far a multirotor may run past a stop (a hold, a turn sharper than kStopTurn_deg, the last
/// waypoint) along its incoming leg: braking from `speed_m_s` at `accel_m_s2` (ArduCopter's
/// WPNAV_ACCEL, 2.5 m/s² by default), speed² / (2 accel), metres. ArduCopter plans its braking
/// and stopped 0.42 m past in SITL at 5 m/s; this is what a vehicle that starts braking only at
/// the waypoint covers, the bound `swath verify` checks too.
inline double stop_overrun_m(double speed_m_s,
                             double accel_m_s2 = swath::vehicle::kDefaultAccel_m_s2) {
  return speed_m_s * speed_m_s / (2 * accel_m_s2);
}

/// The fastest a multirotor can still fly `distance_m` past the point where its commanded speed
/// dropped from `before_m_s` to `commanded_m_s`, m/s: it brakes at no more than `accel_m_s2`, so
/// v² = before² − 2 a d until the commanded speed is reached (a speed cut a few decimetres before
/// a stop leaves it nearly as fast as before: ArduCopter SITL came 2 to 7 cm inside a zone's
/// clearance at stops whose 0.2 m/s approach began 0.5 m before them).
inline double reachable_speed_m_s(double before_m_s, double commanded_m_s, double distance_m,
                                  double accel_m_s2 = swath::vehicle::kDefaultAccel_m_s2) {
  const double braked_sq = before_m_s * before_m_s - 2 * accel_m_s2 * std::max(distance_m, 0.0);
  return std::max(commanded_m_s, std::sqrt(std::max(braked_sq, 0.0)));
}

/// The slowest approach to a stop beside a no-fly zone, m/s: ArduCopter's least WPNAV_SPEED,
/// 20 cm/s, an overrun of 8 mm at 2.5 m/s².
inline constexpr double kSlowestApproach_m_s = 0.2;

struct MissionSettings {
  double altitude_m = 0.0;                              ///< > 0, above home
  double speed_m_s = 0.0;                               ///< > 0, cruise speed over the whole path
  double climb_speed_m_s = vehicle::kDefaultClimb_m_s;  ///< > 0, vertical, after take-off
  double descent_speed_m_s = vehicle::kDefaultDescent_m_s;  ///< > 0, vertical, landing at home
  double trigger_distance_m = 0.0;                          ///< > 0
  std::optional<double> waypoint_spacing_m;  ///< intermediate waypoints on long lines
  Vehicle vehicle = Vehicle::multirotor;
  Triggering triggering;
  bool land = false;  ///< NAV_LAND (fixed-wing: DO_LAND_START then NAV_LAND) instead of RTL
  /// Line ends (either end) where the drone must stop: a hold of kStopHold_s is written there
  /// (drawn back along the line as free_run_m asks). ArduCopter flies through every waypoint
  /// without a hold, and a turn flown through at a line end beside a no-fly zone swings into the
  /// clearance band (docs/swath-plan.md).
  std::function<bool(geometry::Point2)> stop_at;
  /// From a point along a unit direction, how far the vehicle may fly before it comes within the
  /// clearance of a no-fly zone, metres (+infinity: never). Line ends where a stop would overrun
  /// further (stop_overrun_m) are drawn back along their lines. Empty: nothing is drawn back.
  std::function<double(geometry::Point2, geometry::Point2)> free_run_m;
  /// The drone's acceleration and braking (vehicle::Drone::accel_m_s2): the flight time's legs
  /// and stop_overrun_m(), > 0.
  double accel_m_s2 = swath::vehicle::kDefaultAccel_m_s2;
  /// The slowest a stop beside a no-fly zone is approached at, m/s: kSlowestApproach_m_s, or
  /// what the files' app flies at least (DJI Pilot 2: 1 m/s); the stops are placed for its overrun.
  double slowest_approach_m_s = kSlowestApproach_m_s;
  /// How far an autopilot steering in latitude and longitude strays from the straight leg a -> b,
  /// metres (geometry::AutopilotTrack::bow_m about the drone's home). A leg that strays more than
  /// kMaxBow_m is written as the fewest equal legs that each stray at most kSplitBow_m
  /// (intermediate waypoints, flown through): the track stays with the plan. Empty: never.
  std::function<double(geometry::Point2, geometry::Point2)> bow_m;
  /// The equal legs, at least `pieces` (what bow_m asks), that leg a -> b is written as so that
  /// the track the autopilot flies along each keeps the no-fly zones' clearance wherever the
  /// straight leg keeps it: a long line beside a hole may keep only centimetres more than the
  /// clearance, less than its track strays within kMaxBow_m (at most 1000). Empty: `pieces`.
  std::function<int(geometry::Point2, geometry::Point2, int pieces)> pieces_kept_clear;
};

/// Legs straying less than this are written whole: 25 cm, an east-west leg of 3.4 km at 47
/// degrees, 2.1 km at 70; what is left is within swath verify's check (it measures the track).
inline constexpr double kMaxBow_m = 0.25;
/// What each leg of a split one strays at most.
inline constexpr double kSplitBow_m = 0.05;

/// The hold that makes ArduPilot stop at a waypoint: NAV_WAYPOINT's param1 is whole seconds.
inline constexpr double kStopHold_s = 1.0;

struct DroneMission {
  int drone = 1;  ///< 1-based
  geometry::Point2 home;
  std::vector<SweepLine> lines;        ///< in flight order and direction
  std::vector<MissionItem> items;      ///< what the autopilot gets, in order
  std::vector<geometry::Point2> path;  ///< home -> every waypoint -> home, local metres
  double work_length_m = 0.0;          ///< along the sweep lines (camera over the area)
  double transit_length_m = 0.0;       ///< home legs and the legs between lines
  double path_length_m = 0.0;          ///< work + transit
  /// Climb, the path (accelerating at swath::vehicle::kDefaultAccel_m_s2, stopping at corners
  /// sharper than kStopTurn_deg and for hover holds) and the descent at home; fixed-wing: climb and
  /// path.
  double flight_time_s = 0.0;
  std::size_t waypoint_count = 0;  ///< items with a position (takeoff, waypoints, land)
  /// The ground at home above mean sea level, with terrain (SurveyRequest::terrain); else 0.
  double home_amsl_m = 0.0;
};

/// A flight path over the survey, without the legs to and from home: points, and for each segment
/// between two points whether it lies on a sweep line (camera work) or is a turn or transit.
struct SurveyPath {
  std::vector<geometry::Point2> points;
  std::vector<char> on_line;  ///< points.size() - 1 flags
  double length_m() const;
};

/// Points strictly between a and b that a leg from a to b flies through (empty: straight).
using LegRoute = std::function<std::vector<geometry::Point2>(geometry::Point2, geometry::Point2)>;
/// Whether the straight leg a-b between two lines stays inside the area (photos in turns).
using InsideTest = std::function<bool(geometry::Point2, geometry::Point2)>;

/// The lines in flight order joined by turns (through `route`'s points when given), with
/// intermediate points every `waypoint_spacing_m` at most along the lines.
SurveyPath survey_path(const std::vector<SweepLine>& ordered_lines,
                       std::optional<double> waypoint_spacing_m, const LegRoute& route = {});

/// Cuts a path at increasing distances from its start (each in (0, length)), inserting a point at
/// every cut: consecutive pieces that together are the path.
std::vector<SurveyPath> cut_path(const SurveyPath& path, const std::vector<double>& cuts_m);

/// Turns into transits (camera off) the piece's first and last survey lines where what the piece
/// holds of them meets none of `rings`: a division's or a sortie's cut in a line's turnaround
/// beyond the area leaves the next piece a stub of it outside the area, and the camera takes no
/// photos outside the area except on a line that crosses it.
void transit_stubs_outside(SurveyPath& piece, const std::vector<geometry::Ring>& rings);

/// Builds the mission for a survey path: takeoff at home to the survey altitude, the speed, the
/// gimbal, the path's first point, then every point with the camera on along the lines only
/// (started at each line, stopped at its end; with photos_in_turns kept on through turns that
/// `inside` says stay in the area; hover: a held waypoint and a shot at each photo point), and
/// return to launch or land. The legs from and to home go through `route`'s points when given.
/// settings.waypoint_spacing_m is not used here (survey_path() applies it).
DroneMission mission_for_path(int drone, geometry::Point2 home, const SurveyPath& path,
                              const MissionSettings& settings, const LegRoute& route = {},
                              const InsideTest& inside = {});

/// mission_for_path(survey_path(ordered_lines, settings.waypoint_spacing_m, route), ...).
DroneMission build_mission(int drone, geometry::Point2 home,
                           const std::vector<SweepLine>& ordered_lines,
                           const MissionSettings& settings, const LegRoute& route = {});

/// The planned photo positions of a line of `length_m` from `start` to `end`: the first where the
/// camera starts, then every `trigger_distance_m` (as the autopilot's distance trigger takes them).
std::vector<geometry::Point2> photo_positions(geometry::Point2 start, geometry::Point2 end,
                                              double trigger_distance_m);

/// The photos a mission takes, as the autopilot takes them: one where the trigger starts, then
/// every `trigger_distance_m` flown until it stops (through turns too when it stays on); one at
/// each hover shot. Each names the line it was taken on or after (0-based).
std::vector<PhotoPoint> planned_photos(const DroneMission& mission, double trigger_distance_m);

/// The flight time of a path flown from rest to rest (see DroneMission::flight_time_s): legs at
/// `speed_m_s` with the trapezoid profile between stops (vehicle::rest_to_rest_s at
/// `accel_m_s2`). `hold_s` per point (hover photos).
double path_time_s(const std::vector<geometry::Point2>& path, const std::vector<double>& hold_s,
                   double speed_m_s, Vehicle vehicle,
                   double accel_m_s2 = swath::vehicle::kDefaultAccel_m_s2);

}  // namespace swath::planning
