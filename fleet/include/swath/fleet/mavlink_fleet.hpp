#pragma once
// swath-fleet's runtime flying multicopters over MAVLink: the fleet's adapter to swath::mavlink's
// drivers (fleet -> mavlink, never the reverse) (docs/swath-fleet.md; `swath-fleet run ...
// --backend mavlink --vehicles V`): one driver per vehicle, chosen by the autopilot its first
// HEARTBEAT names (12: Px4Driver, untested on PX4 and said so on stderr; else CopterDriver for
// ArduCopter), each vehicle steered toward what
// the runtime last asked of it — at a place (GUIDED; from the ground: GUIDED, arm, NAV_TAKEOFF to
// the target's altitude, the drone's layer; then the speed rule: DO_CHANGE_SPEED to cruise,
// answered before the position target goes, as ArduCopter's GUIDED plans a leg with the speed in
// force when its target arrives; then to the approach speed within approach_within_m, which
// ArduCopter's GUIDED applies from the next leg on, not mid-leg), a photo for a sense
// action, or home (RTL, landed and disarmed). The steering is re-applied on every poll from the
// vehicle's reported state, so a lost acknowledgement, a command timed out or a failsafe RTL
// during a link cut is followed by the right command once the vehicle answers again. A step
// (GUIDED, arm, take-off, RTL) rejected three times, or a target outside the fence, refuses the
// vehicle (report().refusal, with its last STATUSTEXT): it is sent nowhere but home after that.
// (PX4: Hold, AUTO.LOITER, for GUIDED, and DO_REPOSITION for the position target.) The drivers'
// connect-time safety warnings (a lost-link failsafe off or unreadable) go to `warn`; they never
// hold the mission back. The fence goes to every vehicle at connect and is read back before it
// may arm (MavlinkFleetSettings::upload_fence). Told home or to land while armed on the ground (an
// abort before it took off), a vehicle is disarmed, not sent to RTL (which climbs to its return
// altitude first).
//
// Clock: the runtime's. advance_to(t) polls every poll_step_s up to t; with wall_clock it first
// waits until t seconds after the first call (a real run), else it does not wait and calls
// `before_poll(t)` (tests step their in-process fake autopilots there). Positions: local metres
// at `origin` (x east, y north), altitudes above each vehicle's home.

#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "swath/fleet/backend.hpp"
#include "swath/fleet/vehicle_address.hpp"
#include "swath/geometry/point.hpp"
#include "swath/mavlink/driver.hpp"
#include "swath/mavlink/link.hpp"
#include "swath/mavlink/signing.hpp"

namespace swath::fleet {

struct MavlinkFleetSettings {
  geometry::GeoPoint origin;  ///< the world's origin (WGS84 degrees)
  /// The world's fence, local metres (x, y), counter-clockwise; empty: none. An inclusion fence
  /// like those of `inclusions_m`.
  std::vector<std::array<double, 2>> fence_m;
  /// The envelope's fence polygons, local metres (x, y). A target outside every inclusion (when
  /// there is one) or inside an exclusion is never sent: the vehicle is refused at once ("target
  /// outside the fence"), before any command for it goes out.
  std::vector<std::vector<std::array<double, 2>>> inclusions_m, exclusions_m;
  /// With a fence: each vehicle gets it with MAVLink's fence protocol when it connects (one
  /// NAV_FENCE_POLYGON_VERTEX_INCLUSION / _EXCLUSION item per vertex, param1 the polygon's vertex
  /// count), reads it back and compares, and enables it (ArduCopter: FENCE_TYPE with its polygon
  /// bit, FENCE_ENABLE 1); none takes off before its fence is verified, and a vehicle whose
  /// upload fails, is refused, or reads back different is refused (report().refusal says why).
  /// false: the fence is only checked here, never uploaded.
  bool upload_fence = true;
  mavlink::DriverSettings
      driver;  ///< for every vehicle; vehicle_sysid and inside_fence are set per vehicle
  bool wall_clock = false;
  double poll_step_s = 0.02;  ///< polls between two advance_to times, s (> 0)
  /// Called before each poll with its time (not with wall_clock): tests step their fakes here.
  std::function<void(double t_s)> before_poll;
  /// end_run() polls until every vehicle is down (disarmed or landed) or this long has passed
  /// on the run's clock, s (>= 0): the return to launch is sent, the vehicles land under the
  /// ground station's heartbeat.
  double end_timeout_s = 600;
  /// Once this returns true, end_run() stops waiting for the vehicles to land as soon as every
  /// one has taken its RTL (`swath-fleet run`: a SIGINT or SIGTERM during the wait); empty: it
  /// waits. The abort's shorter wait (end_abort) is never cut short.
  std::function<bool()> stop_waiting;
  /// After an abort, end_abort() polls until every vehicle told has taken its order (RTL or LAND,
  /// or down) or this long has passed, s (>= 0).
  double abort_timeout_s = 10;
  /// false: a vehicle on the ground whose safety check read its lost-link failsafe as off
  /// (ArduCopter FS_GCS_ENABLE 0, PX4 NAV_DLL_ACT 0) is refused (report().refusal) instead of
  /// taking off, and none takes off before its check has read the parameters (answered or timed
  /// out; unreadable: the warning only). true: `--allow-no-gcs-failsafe`, the warning only.
  bool allow_no_gcs_failsafe = false;
  /// With wall_clock: a thread of the backend's own sends the ground station's HEARTBEAT to every
  /// vehicle whenever the runtime has not polled for heartbeat period (the app's compute() or
  /// the scheduler busy), so that no vehicle's GCS failsafe fires because swath thinks.
  bool keepalive = true;
  /// MAVLink 2 signing (`--signing-key FILE`): every frame sent is signed with this key, and only
  /// frames signed with it are read (mavlink/signing_link.hpp); vehicle i's link id is i.
  std::optional<mavlink::SigningKey> signing_key;
  /// Told each warning about a vehicle (index from 0): its drivers' safety-check findings and
  /// that a PX4 driver, untested, flies it. Empty: written to stderr.
  std::function<void(int drone, const std::string& text)> warn;
};

class MavlinkFleet final : public Backend {
 public:
  /// One vehicle per link (owned), with its system id.
  MavlinkFleet(std::vector<std::unique_ptr<mavlink::Link>> links,
               const std::vector<std::uint8_t>& sysids, MavlinkFleetSettings settings);
  ~MavlinkFleet() override;

  int vehicles() const override { return static_cast<int>(vehicles_.size()); }
  void go_to(int drone, double t_s, const Vec3& to_m, double cruise_m_s, double approach_m_s,
             double approach_within_m) override;
  void act(int drone, const std::string& name, bool sense) override;
  void return_home(int drone, double t_s) override;
  /// Nothing is sent: the vehicle flies on to its last target and holds there (GUIDED), as it
  /// did before the simulated fleet shared this seam; the runtime counts it idle meanwhile.
  void hold(int, double) override {}
  /// LAND where it is (ArduCopter: NAV_LAND).
  void land(int drone, double t_s) override;
  /// A GUIDED target at the vehicle's reported position: it stops and holds there.
  void pause(int drone, double t_s) override;
  /// Polls until every vehicle told to return or land has taken the order, or
  /// settings.abort_timeout_s.
  void end_abort() override;
  void advance_to(double t_s) override;
  VehicleReport report(int drone) const override;
  /// Every airborne vehicle returns to launch; returns once all are down or after
  /// settings.end_timeout_s (on the wall clock in a real run, via before_poll in tests).
  void end_run() override;
  /// Only the vehicle's report says when it arrives.
  double arrival_s(int) const override { return std::numeric_limits<double>::infinity(); }
  bool reports_every_tick() const override { return true; }

  /// The vehicle's driver; null until its first HEARTBEAT came.
  const mavlink::Driver* driver(int drone) const;
  double now_s() const { return now_s_; }

 private:
  struct Vehicle;
  void steer(Vehicle& v);
  void come_down(Vehicle& v);
  void poll(Vehicle& v, int drone);
  void warn(int drone, const std::string& text) const;
  bool all_down() const;
  bool all_told() const;
  Vehicle& at(int drone) const;

  std::vector<std::unique_ptr<Vehicle>> vehicles_;
  MavlinkFleetSettings settings_;
  std::vector<mavlink::MissionItemInt> fence_items_;  // uploaded to every vehicle
  double now_s_ = 0;
  std::optional<std::chrono::steady_clock::time_point> start_;
  // The keep-alive thread (settings.keepalive with wall_clock): see keep_alive().
  void keep_alive();
  std::atomic<std::int64_t> last_poll_ns_{0};  // steady_clock of the runtime's last poll
  std::mutex keepalive_mutex_;
  std::condition_variable keepalive_stop_;
  bool stopping_ = false;
  std::thread keepalive_;
};

/// Opens the links of `urls` and the backend over them. Socket errors throw std::system_error
/// naming the address.
std::unique_ptr<MavlinkFleet> open_mavlink_fleet(const std::vector<VehicleAddress>& urls,
                                                 MavlinkFleetSettings settings);

}  // namespace swath::fleet
