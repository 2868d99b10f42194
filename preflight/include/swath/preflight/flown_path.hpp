#pragma once
// The flight a mission file makes an ArduCopter-like autopilot fly (issue 45), rebuilt from the
// file alone: home, the take-off climb, the items in order, and the return to launch or landing.
//
// Model and why:
// - Legs are straight lines in 3-D between item positions (ArduCopter's WPNAV without splines);
//   altitudes are converted to metres above home from each item's own frame (relative, AMSL
//   through the file's home altitude, terrain through the DEM, or as relative without one).
// - Each leg is timed at the speed in force (DO_CHANGE_SPEED 178 with param1 0 or 1, else the
//   file's cruise speed, else the drone's; param1 2 and 3 set the climb and descent speeds, as
//   ArduCopter's ModeAuto::do_change_speed does) with a trapezoidal speed profile: the vehicle
//   stops, accelerating and decelerating at `deceleration_m_s2`, where the path turns sharply (more
//   than `sharp_turn_deg`) or holds, and flies through gentler corners at speed. Climbs and
//   descents take |dz| / vertical speed; a leg takes the longer of its horizontal and vertical
//   times. Two drones' files are thus comparable in time to within the corner rounding, which is
//   not modelled.
// - DO_JUMP is unrolled (ArduPilot counts each jump's repeats over the whole flight, up to
//   kMaxFlownItems items flown; repeating forever is refused); LOITER_TURNS flies to the circle's
//   edge and round it (a polygon whose sides touch the circle, so it contains it) its whole turns.
//   Commands that move nothing (camera, gimbal, ROI, yaw) are passed over; any other command is
//   refused: its flight is not known, so nothing about it can be said to hold.
// - RETURN_TO_LAUNCH climbs to max(current, RTL altitude) (ArduCopter RTL_ALT, 15 m; the file's
//   own, Mission::return_altitude_m, when it gives one: a DJI KMZ's globalRTHHeight), flies home
//   and descends; a mission that ends without RTL or LAND is given one (the vehicle would loiter
//   there until the pilot or the battery failsafe brings it home: checking the way home is safer
//   than ignoring it).
// - Stopping margin: where the vehicle stops (sharp turn, hold, end), it may overrun the waypoint
//   along its incoming direction by v^2 / (2 a) (missions::stopping_distance_m): ArduCopter plans
//   its braking before the waypoint, but a late braking point, a pilot's pause, or a lagging
//   position estimate put it up to this far beyond; the checks treat that segment as part of the
//   flight. v is the fastest it can arrive: a speed cut brakes it at no more than a (v^2 = v0^2 -
//   2 a d over the d flown since, v0 its speed before the cut), never below the speed commanded;
//   a cut takes effect at the waypoint it follows (ArduPilot may start it earlier), a speed raised
//   is reached at once, and after a stop it starts from rest, accelerating at no more than a (at
//   most sqrt(2 a s) over the s flown since: the overrun is never longer than s). A slow approach
//   begun a few decimetres before a stop does not make it slow there.

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "swath/geometry/ground.hpp"
#include "swath/geometry/local_frame.hpp"
#include "swath/missions/mission.hpp"
#include "swath/missions/stopping.hpp"
#include "swath/vehicle/kinematics.hpp"

namespace swath::preflight {

/// A point of the flight: local metres (x east, y north) in the check's common frame, z metres
/// above the drone's home.
struct Point3 {
  double x = 0.0, y = 0.0, z_m = 0.0;
  geometry::Point2 xy() const { return {x, y}; }
};

/// The autopilot's parameters the model needs (defaults: ArduCopter's).
struct FlightModel {
  double speed_m_s = 5.0;                             ///< when the file gives none (WPNAV_SPEED)
  double climb_m_s = vehicle::kDefaultClimb_m_s;      ///< WPNAV_SPEED_UP
  double descent_m_s = vehicle::kDefaultDescent_m_s;  ///< WPNAV_SPEED_DN
  double deceleration_m_s2 = vehicle::kDefaultAccel_m_s2;  ///< WPNAV_ACCEL
  double rtl_altitude_m = 15.0;                            ///< RTL_ALT
  double sharp_turn_deg = 45.0;  ///< a change of course above which the vehicle stops
};

enum class LegKind { climb, cruise, hold, rtl, descent };

/// One piece of the flight, flown in a straight line at constant speed from t_start_s to t_end_s.
struct Leg {
  Point3 from, to;
  double t_start_s = 0.0, t_end_s = 0.0;      ///< from the drone's launch
  double speed_m_s = 0.0;                     ///< horizontal cruise speed in force
  double climb_m_s = 0.0, descent_m_s = 0.0;  ///< vertical speeds in force (DO_CHANGE_SPEED 2, 3)
  LegKind kind = LegKind::cruise;
  std::string place;  ///< the item that flies it ("drone-1.plan: item 7") or "return to launch"
  double trigger_distance_m = 0.0;  ///< DO_SET_CAM_TRIGG_DIST in force (0: off)
  double trigger_interval_s = 0.0;  ///< IMAGE_START_CAPTURE interval in force (0: off)
  /// A trigger item (206 with a distance, 2000 with an interval) ran before this leg: counting
  /// starts anew from its start, with one photo at once (206's param3 1; 2000 always).
  bool trigger_started = false;
  bool photo_at_start = false;
  bool stops_at_end = false;
};

/// The overrun past a waypoint where the vehicle stops.
struct Overrun {
  Point3 from, to;
  std::string place;
};

struct FlownPath {
  std::string source;
  Point3 home;  ///< on the ground
  std::vector<Leg> legs;
  std::vector<Overrun> overruns;
  double duration_s = 0.0;
};

/// Heights of points above the drone's home, metres, for an item in its frame. Without `ground`,
/// terrain-relative altitudes are read as above home (flat ground); AMSL ones need the file's home
/// altitude. With `ground`, home's altitude is the DEM's ground there (the file's where the DEM
/// has none), so AMSL altitudes are measured against the DEM whatever the file's home says.
class HeightConverter {
 public:
  HeightConverter(const missions::Mission& mission, const geometry::Ground* ground);
  double above_home_m(const missions::Item& item) const;
  /// The ground's height above home at `p` (0 without a DEM or outside it).
  double ground_above_home_m(const geometry::GeoPoint& p) const;

 private:
  const missions::Mission& mission_;
  const geometry::Ground* ground_;
  double home_amsl_m_ = 0.0;
  bool home_amsl_known_ = false;
};

/// The flight of `mission` in `frame` (the check's common local frame). Throws base::InputError
/// for an AMSL item when the home's altitude is unknown, and for an item whose flight the model
/// does not know (modelled_command()), a DO_JUMP to no item, or one repeating forever.
FlownPath fly(const missions::Mission& mission, const geometry::LocalFrame& frame,
              const FlightModel& model, const geometry::Ground* ground = nullptr);

/// Does fly() model MAV_CMD `command` (docs/swath-verify.md lists them)?
bool modelled_command(int command);

/// The position at time t_s (before the first leg: home on the ground; after the last: home).
Point3 position_at(const FlownPath& path, double t_s);

}  // namespace swath::preflight
